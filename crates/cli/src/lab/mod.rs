//! `rtl lab`: a local web page on which a reader watches estimators, samplers and the Cornell box
//! converge, and switches strategies live. Three benches:
//!
//! 1. Monte Carlo (book chapters 2-4): the integrals and estimators of `rtl study mc`, one N at a
//!    time: the estimate and its 95% band, RMS error against N and against time ([`mc`]);
//! 2. sampling (chapters 3, 7): a density and a method, the histogram against the density, the
//!    u-error, ns per sample and the chi-square p-value, on a line and on the sphere ([`sampling`]);
//! 3. the Cornell box (chapters 5-13): a progressive render with the strategy and its extras
//!    switchable, the variance map, and RMSE against time, one curve per setting ([`cornell`],
//!    through the renderer's door [`glue`]).
//!
//! All computation is in our crates, through the same functions as `rtl study` and `rtl render`;
//! the page (HTML, CSS and JavaScript of our own, plots drawn as SVG by its script) is embedded in the
//! binary and loads nothing from anywhere else.
//!
//! **Why no HTTP crate.** The lab serves one reader on one machine: a handful of small requests a
//! second, each with no body. Its server ([`http`]) is a few hundred lines on `std::net`, one thread
//! per connection and `Connection: close`, with every read bounded in size and time; tiny_http, which
//! it used at first, buffered what a client declared and could be made to abort or to stop listening,
//! and axum would bring tokio and hyper (minutes of compiling on a two-core machine) for concurrency
//! the lab does not need. The render runs on rayon's pool either way.

mod cornell;
mod glue;
mod http;
mod mc;
mod params;
mod sampling;
mod server;

use anyhow::{Context, Result};
use clap::Args;
use std::net::{IpAddr, Ipv4Addr, SocketAddr, TcpListener};
use std::path::{Path, PathBuf};
use std::sync::Arc;

#[derive(Args)]
pub struct LabArgs {
    /// The Cornell box's width (and height) when the page opens: the page's own range.
    #[arg(long, default_value_t = 200,
          value_parser = clap::value_parser!(u64).range(cornell::WIDTHS.0 as u64..=cornell::WIDTHS.1 as u64))]
    pub width: u64,
    /// Port to listen on; 0 picks a free one.
    #[arg(long, default_value_t = 8017)]
    pub port: u16,
    /// Address to listen on. The default, 127.0.0.1, is this machine only; any other address lets
    /// other machines drive the lab (and use its cores).
    #[arg(long, default_value_t = IpAddr::V4(Ipv4Addr::LOCALHOST))]
    pub bind: IpAddr,
    /// Directory of the references of `rtl study render` (`render-reference-cornell-W-SPP.pfm`): the
    /// Cornell bench reads the one at its width, or renders one and caches it there.
    #[arg(long, default_value = "book/src/figures")]
    pub reference_dir: PathBuf,
    /// Samples per pixel of a reference the lab renders itself (none cached at that width).
    #[arg(long, default_value_t = 1024, value_parser = clap::value_parser!(u64).range(1..=MAX_REFERENCE_SPP))]
    pub reference_spp: u64,
    /// The built book (`mdbook build book`), which the benches link to under /book/.
    #[arg(long, default_value = "book/book")]
    pub book_dir: PathBuf,
}

/// The most samples per pixel of a reference: what `--reference-spp` takes, and what a cached
/// reference's file name may say.
pub const MAX_REFERENCE_SPP: u64 = 1_000_000;

/// The Cornell bench's settings when the page opens: `mis` with its default extras.
fn initial_settings(width: usize) -> glue::Settings {
    glue::Settings {
        width,
        strategy: rtl_render::integrator::Strategy::default(),
        seed: 1,
        max_depth: glue::BOOK_DEPTH,
        mixture_weight: rtl_render::render::BOOK_MIXTURE_WEIGHT,
    }
}

/// Why the lab could not start.
#[derive(Debug, thiserror::Error)]
pub enum LabError {
    #[error(
        "port {port} on {addr} is in use (another `rtl lab`?): choose another with --port, or --port 0 for a free one"
    )]
    PortInUse { addr: IpAddr, port: u16 },
    #[error("cannot listen on {addr}:{port}: {source}")]
    Listen {
        addr: IpAddr,
        port: u16,
        source: std::io::Error,
    },
    /// `--reference-dir` is (or lies under) something other than a directory: the lab had started,
    /// rendered a reference for the page and then shown `no reference: File exists (os error 17)`.
    #[error(
        "--reference-dir {}: {} is not a directory (the lab reads and caches its references there)",
        dir.display(),
        file.display()
    )]
    ReferenceDir { dir: PathBuf, file: PathBuf },
    /// Less memory than the lab may come to need: under `ulimit -v 100000` it started, then a
    /// page's request for a 600-pixel render aborted it half-way through an allocation.
    #[error(
        "the lab may need {} of {} (its saved renders, a render and a reference of {side} x {side}, \
         and {threads} threads with their stacks and malloc arenas), but {available}",
        rtl_render::limits::Bytes(*needed),
        available.limit.counts()
    )]
    Memory {
        needed: u64,
        side: usize,
        threads: usize,
        available: rtl_render::limits::Available,
    },
}

/// What the lab may come to need at once, checked against each memory limit before it starts
/// ([`rtl_render::limits::Need::exceeds`]): the renders it keeps to go back to
/// ([`cornell::SAVED_BYTES`]), the render and a reference at the largest width the page offers
/// (an accumulation each, with the pass's copy and the noise measurement's moments: three at the
/// render's bytes a pixel), and the threads that render: two pools of the cores (the render's and
/// the reference's) and the render thread. (The connections' threads allocate little and share
/// the arenas of those.)
fn check_memory() -> Result<(), LabError> {
    use rtl_render::limits::{self, Need};
    let side = cornell::WIDTHS.1;
    let pixels = (side * side) as u64;
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let threads = 2 * cores + 1;
    let need = Need::all(cornell::SAVED_BYTES as u64 + 3 * pixels * limits::RENDER_BYTES_PER_PIXEL)
        .plus(limits::threads_need(threads))
        .plus(limits::PROCESS_BASE);
    match need.exceeds(&limits::memory_limits()) {
        None => Ok(()),
        Some(s) => Err(LabError::Memory {
            needed: s.needed,
            side,
            threads,
            available: s.available,
        }),
    }
}

/// Refuse a `--reference-dir` that is, or lies under, a file (or a device): it could never be
/// created, and a reference rendered for it could not be cached. One that does not exist yet is
/// created when the first reference is.
fn check_reference_dir(dir: &Path) -> Result<(), LabError> {
    let mut p = dir;
    loop {
        if p.exists() {
            return if p.is_dir() {
                Ok(())
            } else {
                Err(LabError::ReferenceDir {
                    dir: dir.to_path_buf(),
                    file: p.to_path_buf(),
                })
            };
        }
        match p.parent() {
            Some(q) if !q.as_os_str().is_empty() => p = q,
            _ => return Ok(()),
        }
    }
}

pub fn run(args: LabArgs) -> Result<()> {
    check_reference_dir(&args.reference_dir)?;
    check_memory()?;
    let listener = TcpListener::bind(SocketAddr::new(args.bind, args.port)).map_err(|e| {
        if e.kind() == std::io::ErrorKind::AddrInUse {
            LabError::PortInUse {
                addr: args.bind,
                port: args.port,
            }
        } else {
            LabError::Listen {
                addr: args.bind,
                port: args.port,
                source: e,
            }
        }
    })?;
    let port = listener.local_addr()?.port();
    let hosts = if args.bind.is_loopback() {
        ["127.0.0.1", "localhost", "[::1]"]
            .iter()
            .map(|h| format!("{h}:{port}"))
            .collect()
    } else {
        eprintln!(
            "warning: --bind {}: the lab is reachable from other machines, and anyone who reaches it \
             can make this machine render",
            args.bind
        );
        Vec::new()
    };
    let scene = Arc::new(glue::scene().context("building the Cornell box")?);
    let bench = Arc::new(cornell::Bench::new(
        initial_settings(args.width as usize),
        args.reference_dir.clone(),
        args.reference_spp,
    ));
    {
        let (b, s) = (Arc::clone(&bench), Arc::clone(&scene));
        std::thread::Builder::new()
            .name("render".into())
            .spawn(move || cornell::worker(b, s))?;
    }
    let shown = match args.bind {
        a if a.is_unspecified() => IpAddr::V4(Ipv4Addr::LOCALHOST),
        a => a,
    };
    let url = match shown {
        IpAddr::V6(a) => format!("http://[{a}]:{port}/"),
        IpAddr::V4(a) => format!("http://{a}:{port}/"),
    };
    println!("rtl lab: open {url} (Ctrl-C to stop)");
    server::serve(
        listener,
        Arc::new(server::App::new(bench, hosts, args.book_dir)),
    );
    Ok(())
}
