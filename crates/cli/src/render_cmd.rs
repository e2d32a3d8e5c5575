//! `rtl render`: render a built-in scene or a scene file to PNG (and linear HDR), with a progress bar,
//! a closing summary, and `--explain` / `--list` / `--stats`.

use crate::progressive::{self, Ending, Plan, Saving};
use anyhow::{Context, Result, bail};
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use rtl_render::checkpoint::{Checkpoint, Identity, scene_hash};
use rtl_render::integrator::Strategy;
use rtl_render::output::{Transfer, write_linear, write_png};
use rtl_render::render::{RenderSettings, Renderer};
use rtl_render::scene::Scene;
use rtl_render::scenes::{BUILT_INS, Built, BuiltIn, SceneOptions, find};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

#[derive(Args)]
pub struct RenderArgs {
    /// A built-in scene name (see `--list`) or a path to a scene file (`.toml`).
    pub scene: Option<String>,
    /// List the built-in scenes and exit.
    #[arg(long)]
    pub list: bool,
    /// Samples per pixel (exactly this many); default: the scene's.
    #[arg(long)]
    pub spp: Option<u64>,
    /// Image width in pixels; the height follows from the scene's aspect ratio. Default: the book's.
    #[arg(long)]
    pub width: Option<usize>,
    /// Most intersections a path may have. Default: the scene's.
    #[arg(long)]
    pub max_depth: Option<u32>,
    /// Seed of every random number: the same seed gives the same image for any thread count.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Worker threads (default: all cores).
    #[arg(long)]
    pub threads: Option<usize>,
    /// How diffuse bounces choose directions: uniform, cosine, light (biased), mixture (the book's),
    /// mis (next-event estimation + MIS, the best we have).
    #[arg(long, default_value = "mis", value_parser = parse_strategy)]
    pub strategy: Strategy,
    /// `mis` without Russian roulette.
    #[arg(long)]
    pub no_rr: bool,
    /// `mis` with area sampling of rectangular lights instead of spherical rectangles.
    #[arg(long)]
    pub no_sph_rect: bool,
    /// `mis` with spherical-rectangle sampling of rectangular lights (off by default: it does not pay
    /// on the Cornell box).
    #[arg(long, conflicts_with = "no_sph_rect")]
    pub sph_rect: bool,
    /// `mis` with independent random numbers instead of low-discrepancy samples.
    #[arg(long)]
    pub no_lds: bool,
    /// Output PNG (default: `<scene>.png`).
    #[arg(short = 'o', long = "output")]
    pub output: Option<PathBuf>,
    /// Also write the linear mean radiance per pixel: `.pfm` or `.exr`.
    #[arg(long)]
    pub linear: Option<PathBuf>,
    /// Encode the PNG with the sRGB transfer function instead of the book's gamma 2.
    #[arg(long)]
    pub srgb: bool,
    /// Print which effects the scene calls for and which are skipped, then exit.
    #[arg(long)]
    pub explain: bool,
    /// Image for the earth texture (book 2's `earthmap.jpg`), for `earth` and `book2-final`.
    #[arg(long)]
    pub texture: Option<PathBuf>,
    /// Print the render's counters (rays, random numbers, lens/time samples, medium and texture evaluations).
    #[arg(long)]
    pub stats: bool,
    /// Time budget (`90s`, `2m`, `1h30m`, plain seconds): render as many whole passes as fit, then stop
    /// and write the image with the samples it has. With `--spp`, stop at whichever comes first.
    #[arg(long, value_parser = progressive::parse_duration)]
    pub time: Option<Duration>,
    /// Save the accumulation (a checkpoint, or a part for `rtl merge`) to FILE every few seconds, on
    /// Ctrl-C and at the end.
    #[arg(long, visible_alias = "part", value_name = "FILE")]
    pub checkpoint: Option<PathBuf>,
    /// How often to save the checkpoint (`5s`, `1m`, ...).
    #[arg(long, default_value = "5s", value_parser = progressive::parse_duration)]
    pub checkpoint_every: Duration,
    /// Continue the render saved in FILE (same scene and settings; `--spp` is the total wanted). FILE is
    /// kept up to date unless `--checkpoint` names another.
    #[arg(long, value_name = "FILE")]
    pub resume: Option<PathBuf>,
    /// Render samples K .. K+spp of every pixel (a part of a render split over processes or machines).
    #[arg(long, default_value_t = 0, value_name = "K")]
    pub sample_offset: u64,
}

fn parse_strategy(s: &str) -> Result<Strategy, String> {
    s.parse()
}

/// A scene to render, whichever way it was named.
struct Loaded {
    name: String,
    description: String,
    built: Built,
    width: usize,
    spp: u64,
}

fn load(arg: &str, opts: &SceneOptions) -> Result<Loaded> {
    if arg.ends_with(".toml") || Path::new(arg).is_file() {
        return load_file(Path::new(arg));
    }
    let b: &BuiltIn = find(arg).map_err(anyhow::Error::msg)?;
    let built = (b.build)(opts).map_err(|e| anyhow::anyhow!("scene {}: {e}", b.name))?;
    Ok(Loaded {
        name: b.name.into(),
        description: b.description.into(),
        built,
        width: b.width,
        spp: b.spp,
    })
}

/// A scene file (`.toml`).
fn load_file(path: &Path) -> Result<Loaded> {
    let file = rtl_render::scene_file::load_file(path)?;
    let name = path
        .file_stem()
        .map_or("scene".into(), |s| s.to_string_lossy().into_owned());
    let description = match &file.description {
        Some(d) => format!("{d} (scene file {})", path.display()),
        None => format!("scene file {}", path.display()),
    };
    Ok(Loaded {
        name,
        description,
        built: file.built,
        width: file.width.unwrap_or(400),
        spp: file.spp.unwrap_or(100),
    })
}

fn list() {
    println!("Built-in scenes (rtl render NAME):");
    for b in BUILT_INS {
        println!(
            "  {:<18} {} [{} wide, {} spp]",
            b.name, b.description, b.width, b.spp
        );
    }
}

fn yes_no(on: bool, yes: &str, no: &str) -> String {
    if on {
        format!("used    {yes}")
    } else {
        format!("skipped {no}")
    }
}

fn explain(l: &Loaded, scene: &Scene, settings: &RenderSettings, spp: u64) {
    let f = scene.features;
    println!("scene {}: {}", l.name, l.description);
    println!(
        "  lens / defocus blur : {}",
        yes_no(
            f.defocus,
            "(thin lens: 2 random numbers per camera ray)",
            "(pinhole camera: no lens samples drawn)"
        )
    );
    println!(
        "  motion blur / time  : {}",
        yes_no(
            f.motion,
            "(something moves: 1 time sample per camera ray)",
            "(nothing moves: no time samples drawn)"
        )
    );
    println!(
        "  participating media : {}",
        yes_no(
            f.media > 0,
            &format!("({} constant media)", f.media),
            "(no media: nothing tested or sampled for them)"
        )
    );
    println!(
        "  textures            : {}",
        yes_no(
            f.textures > 0,
            &format!("({} non-constant textures)", f.textures),
            "(plain colours only: no texture lookups)"
        )
    );
    println!(
        "  emitters            : {}",
        if f.emitters == 0 {
            "none (light comes from the background)".to_string()
        } else {
            format!(
                "{} ({})",
                f.emitters,
                if f.one_sided_emitters {
                    "one-sided"
                } else {
                    "two-sided"
                }
            )
        }
    );
    println!(
        "  importance targets  : {}",
        if f.targets == 0 {
            "none".to_string()
        } else {
            format!(
                "{} listed; {}",
                f.targets,
                match settings.strategy {
                    Strategy::Uniform | Strategy::Cosine => format!(
                        "not used by the '{}' strategy (book-2 scattering)",
                        settings.strategy.name()
                    ),
                    Strategy::Light => "sampled alone: biased (indirect light is missed)".into(),
                    Strategy::Mixture => "mixed 50/50 with the material's density".into(),
                    Strategy::Mis(_) => "emitters by next-event estimation, the others \
                        mixed with the material's density"
                        .into(),
                }
            )
        }
    );
    let background = match scene.background {
        rtl_render::scene::Background::Solid(c) => format!("solid ({}, {}, {})", c.x, c.y, c.z),
        rtl_render::scene::Background::Sky => "book 1's sky gradient".to_string(),
    };
    println!("  background          : {background}");
    println!(
        "  strategy            : {} ({})",
        settings.strategy.name(),
        settings.strategy.description()
    );
    println!(
        "  max depth           : {} intersections per path",
        settings.max_depth
    );
    println!(
        "  image               : {} wide, {spp} samples per pixel, seed {}",
        settings.width, settings.seed
    );
}

pub fn run(args: RenderArgs) -> Result<()> {
    if args.list {
        list();
        return Ok(());
    }
    let Some(scene_arg) = args.scene.as_deref() else {
        bail!("name a scene to render (rtl render --list shows the built-in ones) or a scene file");
    };
    let opts = SceneOptions {
        texture: args.texture.clone(),
    };
    let loaded = load(scene_arg, &opts)?;
    let scene = &loaded.built.scene;
    let width = args.width.unwrap_or(loaded.width);
    if width == 0 {
        bail!("--width must be at least 1");
    }
    // With only a time budget, render until the time is up.
    let spp = match (args.spp, args.time) {
        (Some(n), _) => n,
        (None, Some(_)) => u64::MAX / 2 - args.sample_offset.min(u64::MAX / 2),
        (None, None) => loaded.spp,
    };
    if spp == 0 {
        bail!("--spp must be at least 1");
    }
    let end = args
        .sample_offset
        .checked_add(spp)
        .context("--sample-offset plus --spp is too large")?;
    let settings = RenderSettings {
        width,
        max_depth: args.max_depth.unwrap_or(scene.max_depth),
        seed: args.seed,
        strategy: match args.strategy {
            Strategy::Mis(mut o) => {
                o.russian_roulette &= !args.no_rr;
                o.spherical_rectangles =
                    (o.spherical_rectangles || args.sph_rect) && !args.no_sph_rect;
                o.low_discrepancy &= !args.no_lds;
                Strategy::Mis(o)
            }
            other => other,
        },
    };
    if args.explain {
        explain(&loaded, scene, &settings, args.spp.unwrap_or(loaded.spp));
        return Ok(());
    }
    for n in &loaded.built.notices {
        eprintln!("note: {n}");
    }
    let threads = args.threads.unwrap_or(0);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .context("cannot start the thread pool")?;
    let output = args
        .output
        .clone()
        .unwrap_or_else(|| PathBuf::from(format!("{}.png", loaded.name)));

    let renderer = Renderer::new(scene, settings);
    let mut acc = renderer.accumulator();
    let (w, h) = (acc.width, acc.height);
    let identity = Identity {
        scene: loaded.name.clone(),
        scene_hash: scene_hash(scene),
        settings: format!("{settings:?}"),
        width: w,
        height: h,
    };
    let start = args.sample_offset;
    acc.samples = start;
    if let Some(path) = &args.resume {
        let ck = Checkpoint::read(path)?;
        let diffs = ck
            .identity
            .differences(&identity, "the checkpoint", "this render");
        if !diffs.is_empty() {
            bail!(
                "{} is a checkpoint of another render: {}",
                path.display(),
                diffs.join("; ")
            );
        }
        if ck.start != start {
            bail!(
                "{} holds samples from {} on, but --sample-offset is {start}",
                path.display(),
                ck.start
            );
        }
        if ck.acc.samples > end {
            bail!(
                "{} already holds {} spp, more than the {spp} asked for (--spp is the total)",
                path.display(),
                ck.spp()
            );
        }
        if ck.rtl_version != env!("CARGO_PKG_VERSION") {
            eprintln!(
                "note: {} was written by rtl {}, this is {}",
                path.display(),
                ck.rtl_version,
                env!("CARGO_PKG_VERSION")
            );
        }
        eprintln!("resuming {} at {} spp", path.display(), ck.spp());
        acc = ck.acc;
    }
    if let Some(c) = &args.checkpoint
        && c.exists()
        && args.resume.as_ref() != Some(c)
    {
        bail!(
            "{} exists: continue it with --resume {0}, or remove it to start afresh",
            c.display()
        );
    }
    let saving = args
        .checkpoint
        .clone()
        .or_else(|| args.resume.clone())
        .map(|path| Saving {
            path,
            every: args.checkpoint_every,
            identity: identity.clone(),
        });
    let plan = Plan {
        start,
        end,
        budget: args.time,
        pass_time: args
            .checkpoint_every
            .clamp(Duration::from_millis(20), Duration::from_secs(1)),
        saving,
        progress_by_time: args.time.is_some() && args.spp.is_none(),
    };
    let bar = match args.time {
        Some(t) if plan.progress_by_time => ProgressBar::new(t.as_millis() as u64),
        _ => {
            let b = ProgressBar::new(h as u64 * spp);
            b.set_position(h as u64 * (acc.samples - start));
            b
        }
    };
    bar.set_style(
        ProgressStyle::with_template(
            "{spinner} {prefix} [{elapsed_precise}] {wide_bar} {percent:>3}% ETA {eta} {msg}",
        )
        .expect("valid progress template"),
    );
    bar.set_prefix(format!("{} {w}x{h}", loaded.name));
    progressive::catch_interrupts()?;
    let start_time = Instant::now();
    let (stats, ending) = progressive::run(&renderer, &pool, &mut acc, &plan, &bar)?;
    bar.finish_and_clear();
    let secs = start_time.elapsed().as_secs_f64();
    let spp = acc.samples - start;
    match ending {
        Ending::Done => {}
        Ending::OutOfTime => eprintln!("time budget spent: stopping at {spp} spp"),
        Ending::Interrupted => eprintln!("stopped at {spp} spp (whole passes only)"),
    }
    if spp == 0 {
        eprintln!("warning: no pass finished: the image is black");
    }

    // The checkpoint first (it holds the work; `rtl merge FILE` makes the image again), then the image
    // even if the checkpoint could not be written.
    let saved = plan.saving.as_ref().map(|s| s.save(&acc, start));
    let image = acc.image();
    let transfer = if args.srgb {
        Transfer::Srgb
    } else {
        Transfer::Gamma2
    };
    write_png(&output, w, h, &image, transfer).map_err(anyhow::Error::msg)?;
    if let Some(lin) = &args.linear {
        write_linear(lin, w, h, &image).map_err(anyhow::Error::msg)?;
    }
    if let (Some(s), Some(saved)) = (&plan.saving, saved) {
        saved?;
        eprintln!(
            "checkpoint {}: samples {start}..{} ({spp} spp)",
            s.path.display(),
            acc.samples
        );
    }
    let samples = stats.samples as f64;
    eprintln!(
        "{}: {w}x{h}, {spp} spp{}, {} threads, {:.2} s, {:.0}k samples/s, {:.2}M rays/s, {} non-finite samples dropped -> {}{}",
        loaded.name,
        if start > 0 {
            format!(" (samples {start}..{})", acc.samples)
        } else {
            String::new()
        },
        pool.current_num_threads(),
        secs,
        samples / secs / 1e3,
        stats.rays as f64 / secs / 1e6,
        stats.non_finite,
        output.display(),
        args.linear
            .as_ref()
            .map(|p| format!(", {}", p.display()))
            .unwrap_or_default()
    );
    if args.stats {
        println!("samples              {}", stats.samples);
        println!(
            "rays                 {} ({:.2} per sample)",
            stats.rays,
            stats.rays as f64 / samples
        );
        println!(
            "random numbers       {} ({:.2} per sample)",
            stats.random_numbers,
            stats.random_numbers as f64 / samples
        );
        println!("lens samples         {}", stats.lens_samples);
        println!("time samples         {}", stats.time_samples);
        println!("medium evaluations   {}", stats.medium_evaluations);
        println!("texture evaluations  {}", stats.texture_evaluations);
        println!("non-finite dropped   {}", stats.non_finite);
        println!("wall time            {secs:.3} s");
        println!("samples/s            {:.0}", samples / secs);
        println!("rays/s               {:.0}", stats.rays as f64 / secs);
    }
    if ending == Ending::Interrupted {
        std::process::exit(130);
    }
    Ok(())
}
