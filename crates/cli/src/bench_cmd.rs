//! `rtl bench compare`: the book's C++, Mitsuba 3 (optionally) and `rtl` run one after another on
//! the same scene settings, each measured for speed (samples per second per core) and noise per
//! sample (the noise constant `c = RMSE sqrt(spp)`, from two seeds), and projected to the time each
//! needs for a given per-pixel noise. Only ratios from one run on one machine are figures to quote.

mod book_cpp;
mod machine;
pub(crate) mod noise;
mod targets;

use machine::{cpu_model, num_cores, timed, timed_with_stderr};

use anyhow::{Context, Result, bail};
use book_cpp::{BookProgram, BookSettings, patch_main, samples_taken};
use clap::{Args, Subcommand, ValueEnum};
use noise::{DisplayImage, noise_constant, parse_image, parse_pfm, parse_ppm, seconds_to};
use rtl_render::integrator::Strategy;
use rtl_render::vec::Num;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

#[derive(Args)]
pub struct BenchArgs {
    #[command(subcommand)]
    command: BenchCommand,
}

#[derive(Subcommand)]
enum BenchCommand {
    /// Compare rtl with the book's C++ (and Mitsuba 3) side by side on this machine.
    Compare(Box<CompareArgs>),
    /// The per-pixel noise between two renders of one scene with different seeds, as `compare`
    /// measures it: e.g. the book's program at a target's samples, or `rtl render --time`.
    Noise(NoiseArgs),
    /// Issue 16's three speed targets on this machine: each measured by `compare` with the settings
    /// render-speed.md quotes, then a verdict for each target and tier.
    Targets(Box<targets::TargetsArgs>),
}

#[derive(Args)]
pub struct NoiseArgs {
    /// Two renders: the book's PPM or rtl's `--linear` PFM (both brought to the book's encoding).
    #[arg(num_args = 2, value_names = ["A", "B"], required = true)]
    images: Vec<PathBuf>,
    /// The samples per pixel of each render (for `c = RMSE sqrt(spp)`).
    #[arg(long)]
    spp: u64,
}

/// The scenes all the renderers have.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
enum CompareScene {
    /// Book 3's final Cornell box (the book's src/TheRestOfYourLife/main.cc).
    Cornell,
    /// Book 2's final scene (the book's src/TheNextWeek/main.cc, `final_scene`); no Mitsuba scene.
    Book2Final,
}

#[derive(Args)]
pub struct CompareArgs {
    /// A checkout of RayTracing/raytracing.github.io: its program is built with `g++ -O3` from a
    /// patched copy in the scratch directory (width, spp, depth and a seed set in the copy's main.cc).
    #[arg(long, value_name = "DIR")]
    book: Option<PathBuf>,
    /// A Python with the `mitsuba` and `numpy` packages: Mitsuba's path tracer renders the same
    /// Cornell box.
    #[arg(long, value_name = "PYTHON")]
    mitsuba: Option<PathBuf>,
    /// Mitsuba variant.
    #[arg(long, default_value = "llvm_ad_rgb")]
    mitsuba_variant: String,
    #[arg(long, value_enum, default_value = "cornell")]
    scene: CompareScene,
    /// Image width (the images are square).
    #[arg(long, default_value_t = 600)]
    width: usize,
    /// Samples per pixel of each measured render (a square for the book's stratified Cornell box).
    /// On a shared machine longer renders are steadier: at 16 spp rtl's take a few seconds and a
    /// burst of other load moves a round's ratio; `--spp 64` (the book's renders too) narrowed the
    /// rounds' spread (render-speed.md, "Issue 16, fourteenth round").
    #[arg(long, default_value_t = 16)]
    spp: u64,
    /// Samples per pixel of the book's renders (default: `--spp`; a square for the Cornell box). The
    /// noise constant of a display-encoded image settles only once the noise is small beside the
    /// signal: the book's at 16 spp misjudges its noise at `--target-book-spp`,
    /// and the closer this is to that, the truer the target (equal to it: no extrapolation at all).
    #[arg(long, value_name = "SPP")]
    book_spp: Option<u64>,
    /// Most ray segments per path (the book's `max_depth`): 50 for cornell, 40 for book2-final.
    #[arg(long)]
    max_depth: Option<u32>,
    /// rtl strategies to measure, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "mixture,mis")]
    strategy: Vec<String>,
    /// Threads for rtl and Mitsuba (the book's program has one); rates are divided by it.
    #[arg(long, default_value_t = 1)]
    threads: usize,
    /// Cores the projected times are for (at that many times the per-core rate).
    #[arg(long, default_value_t = 2)]
    cores: usize,
    /// The per-pixel RMSE (display values, gamma 2) to project to; default: the book's noise at
    /// `--target-book-spp`.
    #[arg(long)]
    target_rmse: Option<f64>,
    /// The book's per-pixel RMSE at `--target-book-spp`, measured beforehand (a run with `--book-spp`
    /// equal to `--target-book-spp` prints it as its target): the target, no extrapolation, and the
    /// book's time to it is `--target-book-spp` samples at the rate it runs at now. Needs `--book`.
    #[arg(long, value_name = "RMSE", conflicts_with = "target_rmse")]
    book_noise: Option<f64>,
    /// The book's samples per pixel whose noise is the target (when `--target-rmse` is not given).
    #[arg(long, default_value_t = 1000)]
    target_book_spp: u64,
    /// The image width (square) the times are projected to, e.g. 800 for book 2's final render
    /// measured at 400 (default: `--width`). The noise constant is per pixel, so this assumes it
    /// stays the same at the larger size: pixels are smaller, not different.
    #[arg(long)]
    project_width: Option<usize>,
    /// The two seeds of each renderer's pair of renders, separated by a comma (`--seeds 3,4`).
    #[arg(long, value_delimiter = ',', default_value = "1,2")]
    seeds: Vec<u32>,
    /// Measure everything this many times in turn (book, Mitsuba, rtl, then again in the reverse
    /// order, and so on alternately) and summarise
    /// each renderer's ratios to the book *of the same round* by their median and range: on a
    /// machine whose speed drifts, a ratio taken within one round is what stays put.
    #[arg(long, default_value_t = 1)]
    rounds: usize,
    /// The rtl binary to time (default: this one), e.g. a build of another commit.
    #[arg(long)]
    rtl: Option<PathBuf>,
    /// Intersection tiers to time each strategy in, comma-separated (`portable`, `avx2`, `avx512`,
    /// `auto`; `rtl render --hit-tier`), e.g. `avx2,avx512` for the code a processor without AVX-512
    /// runs beside the best one, in the same rounds. Default: what `rtl render` runs unless told,
    /// unnamed (as an `--rtl` binary from before the flag needs).
    #[arg(long, value_delimiter = ',', value_name = "TIERS")]
    hit_tier: Vec<String>,
    /// Where the patched copy, the builds and the images go.
    #[arg(long, default_value = "target/bench-compare")]
    scratch: PathBuf,
}

/// One renderer's measurement.
struct Measured {
    name: String,
    /// Samples per second on one core.
    per_core: f64,
    c: f64,
    mean: f64,
    /// The samples per pixel `c` was measured at.
    spp: u64,
    note: String,
}

/// A noise constant measured at `measured` spp is taken as it is up to this many times that (and
/// flagged beyond). In display values `c` settles only once the noise is small beside the signal:
/// with few samples the square root and the clamp at 1 squeeze a pixel's errors (`c` too low), and
/// while a rare bright path is in some pixels' samples and not in others' the square root of their
/// means spreads more than it will (`c` too high). Book 2's final scene in the book's program, at
/// 200 x 200: 0.78 at 16 spp, 1.23 at 256, 1.10 at 10,000; `rtl`'s `mis` 0.19, 0.22, 0.23 (16, 256,
/// 1024).
const FAR_BELOW: f64 = 4.0;

/// The most rounds a comparison may measure (each runs every renderer twice, seconds at least).
const MAX_ROUNDS: usize = 1000;

/// Whether a constant measured at `measured` spp is projected far beyond it (`needed` spp).
fn measured_far_below(measured: u64, needed: f64) -> bool {
    needed > FAR_BELOW * measured as f64
}

pub fn run(args: BenchArgs) -> Result<()> {
    match args.command {
        BenchCommand::Compare(a) => compare(*a),
        BenchCommand::Targets(a) => targets::run(*a),
        BenchCommand::Noise(a) => {
            println!("{}", noise_of(&a)?);
            Ok(())
        }
    }
}

/// `rtl bench noise`: the per-pixel RMSE of one render (`RMS(a - b) / sqrt(2)`), its noise constant
/// and the two images' mean display values.
fn noise_of(a: &NoiseArgs) -> Result<String> {
    if a.spp == 0 {
        bail!("--spp must be positive");
    }
    let (pa, pb) = (&a.images[0], &a.images[1]);
    if let (Ok(ca), Ok(cb)) = (pa.canonicalize(), pb.canonicalize())
        && ca == cb
    {
        bail!(
            "{} and {}: the same file twice; its noise against itself is 0 (give two renders of \
             one scene with different seeds)",
            pa.display(),
            pb.display()
        );
    }
    let load = |path: &PathBuf| -> Result<DisplayImage> {
        Ok(parse_image(&read(path)?, &path.display().to_string())?)
    };
    let (x, y) = (load(pa)?, load(pb)?);
    let (c, _) = pair_constant(&x, &y, a.spp)?;
    // (equal images are two renders with the same seed, or of a scene without noise)
    let same = if c == 0.0 {
        " (the two images are equal: the same seed twice, or a scene without noise?)"
    } else {
        ""
    };
    Ok(format!(
        "{}x{}, {} spp: per-pixel RMSE {:.5}, c {:.4}, mean display values {:.4} and {:.4}{same}",
        x.width,
        x.height,
        a.spp,
        c / (a.spp as f64).sqrt(),
        c,
        x.mean(),
        y.mean()
    ))
}

fn validate(a: &CompareArgs) -> Result<()> {
    for (flag, zero) in [
        ("--width", a.width == 0),
        ("--spp", a.spp == 0),
        ("--threads", a.threads == 0),
        ("--cores", a.cores == 0),
        ("--rounds", a.rounds == 0),
    ] {
        if zero {
            bail!("{flag} must be positive, got 0");
        }
    }
    // What `rtl render` would refuse, refused here, before the book's program is built and run with
    // it: that program holds width, samples and depth in a C++ `int`, and renders whatever it is given
    // (`--width 1000000000` built it and ran it without end; rtl's own render refused at once).
    let limits = [
        (
            "--width",
            a.width as u64,
            rtl_render::limits::MAX_SIDE as u64,
        ),
        (
            "--threads",
            a.threads as u64,
            rtl_render::limits::MAX_THREADS as u64,
        ),
        ("--rounds", a.rounds as u64, MAX_ROUNDS as u64),
    ];
    for (flag, value, most) in limits {
        if value > most {
            bail!("{flag} {value}: must be at most {most}");
        }
    }
    if let Some(d) = a.max_depth
        && let Some(problem) = rtl_render::limits::max_depth_problem(d)
    {
        bail!("--max-depth {d}: the maximum depth {problem}");
    }
    if a.book.is_some() {
        let (flag, spp) = match a.book_spp {
            Some(n) => ("--book-spp", n),
            None => ("--spp", a.spp),
        };
        if spp > i32::MAX as u64 {
            bail!(
                "{flag} {spp}: the book's program counts samples in a C++ int, at most {}",
                i32::MAX
            );
        }
        if a.target_rmse.is_none() && a.book_noise.is_none() && a.target_book_spp == 0 {
            bail!(
                "--target-book-spp must be positive, got 0 (the target is the book's noise at that \
                 many samples)"
            );
        }
    }
    if let Some(w) = a.project_width
        && (w == 0 || w > rtl_render::limits::MAX_SIDE)
    {
        bail!(
            "--project-width must be in 1..={}, got {w}",
            rtl_render::limits::MAX_SIDE
        );
    }
    if a.seeds.len() != 2 || a.seeds[0] == a.seeds[1] {
        bail!("--seeds: give two different seeds, got {:?}", a.seeds);
    }
    if let Some(t) = a.target_rmse
        && !(t > 0.0 && t.is_finite())
    {
        bail!("--target-rmse must be positive, got {}", Num(t));
    }
    if let Some(t) = a.book_noise {
        if !(t > 0.0 && t.is_finite()) {
            bail!("--book-noise must be positive, got {}", Num(t));
        }
        if a.book.is_none() {
            bail!(
                "--book-noise: the book's code is not run (no --book), so it has no rate to go with it"
            );
        }
    }
    if a.target_rmse.is_none() && a.book.is_none() {
        bail!("--target-rmse is needed when the book's code is not run (no --book)");
    }
    if let Some(book) = &a.book {
        let program = program(a.scene);
        let main = book.join(program.dir()).join("main.cc");
        if !main.is_file() {
            bail!(
                "--book {}: no {} (expected a checkout of RayTracing/raytracing.github.io: \
                 git clone --depth 1 https://github.com/RayTracing/raytracing.github.io)",
                book.display(),
                main.display()
            );
        }
        if a.book_spp == Some(0) {
            bail!("--book-spp must be positive");
        }
        let (flag, spp) = match a.book_spp {
            Some(n) => ("--book-spp", n),
            None => ("--spp", a.spp),
        };
        if samples_taken(program, spp) != spp {
            bail!(
                "{flag} {spp}: the book's Cornell box stratifies into a square number of samples; give a square (16, 64, ...)"
            );
        }
    }
    if a.book_spp.is_some() && a.book.is_none() {
        bail!("--book-spp: the book's code is not run (no --book)");
    }
    if a.mitsuba.is_some() && a.scene != CompareScene::Cornell {
        bail!("--mitsuba: only the cornell scene is written for Mitsuba");
    }
    for s in &a.strategy {
        s.parse::<Strategy>()
            .map_err(|e| anyhow::anyhow!("--strategy: {e}"))?;
    }
    for t in &a.hit_tier {
        crate::render_cmd::parse_hit_tier(t).map_err(|e| anyhow::anyhow!("--hit-tier: {e}"))?;
    }
    Ok(())
}

fn program(scene: CompareScene) -> BookProgram {
    match scene {
        CompareScene::Cornell => BookProgram::Cornell,
        CompareScene::Book2Final => BookProgram::Book2Final,
    }
}

fn compare(mut a: CompareArgs) -> Result<()> {
    measure(&mut a).map(drop)
}

/// What a comparison measured: each round's rows (the book's first when it ran, then Mitsuba's,
/// then rtl's strategies, each in its tiers), the per-pixel RMSE the times are projected to, and
/// the pixels they are for.
struct Comparison {
    rounds: Vec<Vec<Measured>>,
    target: f64,
    pixels: usize,
}

/// Runs the comparison `a` and prints its tables (`a.scratch` made absolute).
fn measure(a: &mut CompareArgs) -> Result<Comparison> {
    validate(a)?;
    if let Some(py) = &a.mitsuba {
        check_mitsuba(py, &a.mitsuba_variant)?;
    }
    let depth = a.max_depth.unwrap_or(match a.scene {
        CompareScene::Cornell => 50,
        CompareScene::Book2Final => 40,
    });
    std::fs::create_dir_all(&a.scratch)
        .with_context(|| format!("--scratch {}: cannot create it", a.scratch.display()))?;
    // The programs run with their own directory as the working directory, so every path handed to
    // them must be absolute (a relative default such as target/bench-compare would not be found).
    a.scratch = std::fs::canonicalize(&a.scratch)
        .with_context(|| format!("--scratch {}: cannot resolve it", a.scratch.display()))?;
    let cpu = cpu_model();
    println!("CPU: {cpu} ({} logical cores)", num_cores());
    println!(
        "scene {:?}, {w}x{w}, {} spp per render, max depth {depth}, seeds {:?}, rtl/Mitsuba threads {}",
        a.scene,
        a.spp,
        a.seeds,
        a.threads,
        w = a.width
    );
    if let (Some(_), Some(n)) = (&a.book, a.book_spp) {
        println!("the book's renders: {n} spp each");
    }
    let mut rounds = Vec::with_capacity(a.rounds);
    for r in 0..a.rounds {
        if a.rounds > 1 {
            eprintln!("round {} of {}", r + 1, a.rounds);
        }
        rounds.push(measure_round(a, depth, r)?);
    }
    let book_c = a.book.as_ref().map(|_| rounds[0][0].c);
    let target = match (a.book_noise.or(a.target_rmse), book_c) {
        (Some(t), _) => t,
        (None, Some(c)) => c / (a.target_book_spp as f64).sqrt(),
        (None, None) => unreachable!("validated"),
    };
    let side = a.project_width.unwrap_or(a.width);
    let pixels = side * side;
    for (r, rows) in rounds.iter().enumerate() {
        println!();
        if a.rounds > 1 {
            println!("round {} of {}", r + 1, a.rounds);
        }
        print_table(a, rows, target, pixels, side);
    }
    if a.rounds > 1 && a.book.is_some() {
        println!();
        println!(
            "over {} rounds, each renderer's ratio to the book's C++ measured in the same round: \
             median (lowest-highest)",
            a.rounds
        );
        println!(
            "{:<nw$} {:>14} {:>26} {:>26}",
            "renderer",
            "samples/s/core",
            "samples/s vs book",
            "time to target vs book",
            nw = name_width(&rounds[0])
        );
        for i in 1..rounds[0].len() {
            let rate = Spread::of(rounds.iter().map(|rows| rows[i].per_core));
            let by_rate = rate_ratio(&rounds, i);
            let by_time = Spread::of(rounds.iter().map(|rows| {
                book_seconds(a, &rows[0], target, pixels)
                    / seconds_to(rows[i].c, target, pixels, rows[i].per_core, a.cores)
            }));
            println!(
                "{:<nw$} {:>14.0} {:>26} {:>26}",
                rounds[0][i].name,
                rate.median,
                by_rate.ratio(),
                by_time.ratio(),
                nw = name_width(&rounds[0])
            );
        }
    }
    println!();
    println!(
        "vs book: samples/s per core / time to the target (both as ratios to the book's C++). samples/s per core is samples per \
         second of processor time (user + system, all threads: the process for the book and rtl, `mi.render` for Mitsuba), \
         the projection assumes that rate on each of the cores; every image is encoded as the book's write_color does \
         (sqrt, clamp, 8 bits) before c is measured. The book's main.cc was patched in a copy under {}.",
        a.scratch.display()
    );
    Ok(Comparison {
        rounds,
        target,
        pixels,
    })
}

/// What a round runs: one renderer's pair of renders.
enum Job<'a> {
    Book(&'a Path),
    Mitsuba(&'a Path),
    Rtl(&'a str, Option<&'a str>),
}

/// The order in which round `round` runs its `n` jobs: as listed in even rounds, the reverse in odd
/// ones. A shared machine's speed drifts within a run (the book's two renders took 10.9 and 9.7 s
/// in one round); alternating the order keeps the drift from always favouring the renderers that
/// run last, and the median over rounds takes both orders.
fn round_order(n: usize, round: usize) -> Vec<usize> {
    if round.is_multiple_of(2) {
        (0..n).collect()
    } else {
        (0..n).rev().collect()
    }
}

/// One round: the book's program, Mitsuba and each rtl strategy, one after another (in
/// [`round_order`]); the rows in the listed order, the book's first.
fn measure_round(a: &CompareArgs, depth: u32, round: usize) -> Result<Vec<Measured>> {
    let mut jobs = Vec::new();
    if let Some(book) = &a.book {
        jobs.push(Job::Book(book));
    }
    if let Some(py) = &a.mitsuba {
        jobs.push(Job::Mitsuba(py));
    }
    for s in &a.strategy {
        if a.hit_tier.is_empty() {
            jobs.push(Job::Rtl(s, None));
        }
        for t in &a.hit_tier {
            jobs.push(Job::Rtl(s, Some(t)));
        }
    }
    let mut rows: Vec<Option<Measured>> = jobs.iter().map(|_| None).collect();
    for i in round_order(jobs.len(), round) {
        rows[i] = Some(match jobs[i] {
            Job::Book(book) => run_book(a, book, depth)?,
            Job::Mitsuba(py) => run_mitsuba(a, py, depth)?,
            Job::Rtl(s, t) => run_rtl(a, s, t, depth)?,
        });
    }
    Ok(rows.into_iter().flatten().collect())
}

/// The table of one round: rates, noise constants and projected times, and the ratios to the book
/// (the first row) when it ran.
fn print_table(a: &CompareArgs, rows: &[Measured], target: f64, pixels: usize, side: usize) {
    println!(
        "target: per-pixel RMSE {target:.5} (display values, gamma 2){}; times for {side} x {side} pixels",
        if a.book_noise.is_some() {
            format!(
                ", the book's C++ at {} spp (--book-noise, measured there)",
                a.target_book_spp
            )
        } else if a.target_rmse.is_none() {
            format!(
                ", the book's C++ at {} spp (its noise constant measured at {} spp)",
                a.target_book_spp,
                a.book_spp.unwrap_or(a.spp)
            )
        } else {
            String::new()
        }
    );
    println!(
        "{:<nw$} {:>14} {:>8} {:>8} {:>11} {:>14} {:>10}  note",
        "renderer",
        "samples/s/core",
        "c",
        "mean",
        "spp needed",
        format!("s on {} cores", a.cores),
        "vs book",
        nw = name_width(rows)
    );
    let book_rate = a.book.as_ref().map(|_| rows[0].per_core);
    let book_secs = book_rate.map(|_| book_seconds(a, &rows[0], target, pixels));
    let mut flagged = Vec::new();
    for (i, m) in rows.iter().enumerate() {
        let is_book = i == 0 && book_rate.is_some();
        // the book's noise measured at its target spp: that many samples, by definition
        let measured_there = is_book && a.book_noise.is_some();
        let needed = if measured_there {
            a.target_book_spp as f64
        } else {
            noise::spp_to(m.c, target)
        };
        let secs = match book_secs {
            Some(s) if is_book => s,
            _ => seconds_to(m.c, target, pixels, m.per_core, a.cores),
        };
        let vs = match (book_rate, book_secs) {
            (Some(r), Some(s)) => format!("{:.2}x/{:.1}x", m.per_core / r, s / secs),
            _ => "-".into(),
        };
        let far = !measured_there && measured_far_below(m.spp, needed);
        if far {
            flagged.push((is_book, m.spp));
        }
        println!(
            "{:<nw$} {:>14.0} {:>8.4} {:>8.4} {:>10.0}{} {:>14.1} {:>10}  {}",
            m.name,
            m.per_core,
            m.c,
            m.mean,
            needed,
            if far { '*' } else { ' ' },
            secs,
            vs,
            m.note,
            nw = name_width(rows)
        );
    }
    if !flagged.is_empty() {
        println!(
            "* c measured at fewer than 1/{FAR_BELOW} of the samples it is projected to. In display values the \
             noise constant settles only once the noise is small beside the signal (the square root and \
             the clamp at 1 squeeze a noisy pixel's errors at first), so such a projection can be off, \
             mostly short."
        );
        if let Some(&(_, spp)) = flagged.iter().find(|&&(book, _)| book) {
            println!(
                "  The book's (at {spp} spp): the target is not the book's noise at {} spp but an \
                 extrapolation; measure it there (--book-spp, then --book-noise) or nearer.",
                a.target_book_spp
            );
        }
        if flagged.iter().any(|&(book, _)| !book) {
            println!("  rtl's or Mitsuba's: measure nearer the spp needed with --spp.");
        }
    }
}

/// The book's seconds to `target` on `a.cores` cores: `--target-book-spp` samples a pixel when its
/// noise there was measured (`--book-noise`), else projected from its noise constant like the others'.
fn book_seconds(a: &CompareArgs, book: &Measured, target: f64, pixels: usize) -> f64 {
    match a.book_noise {
        Some(_) => a.target_book_spp as f64 * pixels as f64 / (book.per_core * a.cores as f64),
        None => seconds_to(book.c, target, pixels, book.per_core, a.cores),
    }
}

/// The width of the tables' first column: the longest renderer's name, at least 22.
fn name_width(rows: &[Measured]) -> usize {
    rows.iter().map(|m| m.name.len()).max().unwrap_or(0).max(22)
}

/// Renderer `i`'s samples per second over the book's (row 0), each taken within one round.
fn rate_ratio(rounds: &[Vec<Measured>], i: usize) -> Spread {
    Spread::of(
        rounds
            .iter()
            .map(|rows| rows[i].per_core / rows[0].per_core),
    )
}

/// The median and range of a few measurements (the rounds of a comparison).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Spread {
    median: f64,
    lowest: f64,
    highest: f64,
}

impl Spread {
    /// Of a non-empty list; the median of an even count is the mean of the middle two.
    fn of(values: impl Iterator<Item = f64>) -> Spread {
        let mut v: Vec<f64> = values.collect();
        assert!(!v.is_empty(), "a spread of no values");
        v.sort_by(f64::total_cmp);
        let n = v.len();
        let median = if n % 2 == 1 {
            v[n / 2]
        } else {
            (v[n / 2 - 1] + v[n / 2]) / 2.0
        };
        Spread {
            median,
            lowest: v[0],
            highest: v[n - 1],
        }
    }

    /// As a ratio: `2.90x (2.79-3.31x)`.
    fn ratio(&self) -> String {
        format!(
            "{:.2}x ({:.2}-{:.2}x)",
            self.median, self.lowest, self.highest
        )
    }
}

/// An image to compare (the book's PPM or rtl's PFM): a regular file of at most 1 GiB, so that a device
/// or a pipe named by mistake is refused, not read without end.
fn read(path: &Path) -> Result<Vec<u8>> {
    rtl_render::limits::read_regular_file(path, "image", 1 << 30).map_err(anyhow::Error::msg)
}

fn pair_constant(a: &DisplayImage, b: &DisplayImage, spp: u64) -> Result<(f64, f64)> {
    let c = noise_constant(a, b, spp)?;
    Ok((c, 0.5 * (a.mean() + b.mean())))
}

fn run_book(a: &CompareArgs, book: &Path, depth: u32) -> Result<Measured> {
    let program = program(a.scene);
    let src_dir = book.join(program.dir());
    let dir = a.scratch.join("book");
    std::fs::create_dir_all(&dir)?;
    let main_path = src_dir.join("main.cc");
    let src = String::from_utf8(read(&main_path)?)
        .with_context(|| format!("{} is not UTF-8", main_path.display()))?;
    let book_spp = a.book_spp.unwrap_or(a.spp);
    let mut images = Vec::new();
    let (mut secs, mut wall) = (0.0, 0.0);
    for &seed in &a.seeds {
        let settings = BookSettings {
            width: a.width,
            spp: book_spp,
            max_depth: depth,
            seed,
        };
        let patched = patch_main(&src, &main_path.display().to_string(), program, &settings)?;
        let cc = dir.join(format!("main-{seed}.cc"));
        std::fs::write(&cc, patched)?;
        let exe = dir.join(format!("book-{seed}"));
        eprintln!("building the book's program: g++ -O3 {}", cc.display());
        timed(
            Command::new("g++")
                .arg("-O3")
                // The book's headers are read from the checkout, not copied.
                .arg("-I")
                .arg(&src_dir)
                .arg("-I")
                .arg(book.join("src"))
                .arg("-o")
                .arg(&exe)
                .arg(&cc),
            "g++ (is it installed?)",
        )?;
        eprintln!("running the book's program, seed {seed}");
        let (ppm, s) = timed(
            Command::new(&exe)
                .current_dir(&dir)
                .env("RTW_IMAGES", book.join("images"))
                .stderr(Stdio::null()),
            "the book's program",
        )?;
        let ppm_path = dir.join(format!("book-{seed}.ppm"));
        std::fs::write(&ppm_path, &ppm)?;
        let img = parse_ppm(&ppm, &ppm_path.display().to_string())?;
        if (img.width, img.height) != (a.width, a.width) {
            bail!(
                "{}: the book's program wrote {}x{}, expected {}x{}",
                ppm_path.display(),
                img.width,
                img.height,
                a.width,
                a.width
            );
        }
        eprintln!(
            "  {:.2} s processor time, {:.2} s wall",
            s.cpu.unwrap_or(f64::NAN),
            s.wall
        );
        images.push(img);
        secs += s.seconds();
        wall += s.wall;
    }
    let samples = (a.width * a.width) as f64 * book_spp as f64 * 2.0;
    let (c, mean) = pair_constant(&images[0], &images[1], book_spp)?;
    Ok(Measured {
        name: "book C++ (g++ -O3)".into(),
        per_core: samples / secs,
        c,
        mean,
        spp: book_spp,
        note: format!(
            "1 thread, {book_spp} spp, {secs:.1} s processor time ({wall:.1} s wall) for both renders, main.cc patched"
        ),
    })
}

/// Whether `python` imports what the Mitsuba script needs (`drjit`, `mitsuba`, `numpy`) and has
/// `variant`: asked before any render, so that a missing package is named at once rather than
/// after the book's renders.
fn check_mitsuba(python: &Path, variant: &str) -> Result<()> {
    let out = Command::new(python)
        .args([
            "-c",
            "import sys, drjit, mitsuba, numpy; mitsuba.set_variant(sys.argv[1])",
        ])
        .arg(variant)
        .stdin(Stdio::null())
        .output()
        .with_context(|| format!("--mitsuba {}: cannot run it", python.display()))?;
    if !out.status.success() {
        let stderr = String::from_utf8_lossy(&out.stderr);
        let last = stderr.lines().rev().find(|l| !l.trim().is_empty());
        bail!(
            "--mitsuba {}: that Python cannot import mitsuba, drjit and numpy with variant '{variant}' \
             (--mitsuba-variant): {}",
            python.display(),
            last.unwrap_or("it failed and said nothing")
        );
    }
    Ok(())
}

fn run_mitsuba(a: &CompareArgs, python: &Path, depth: u32) -> Result<Measured> {
    let dir = a.scratch.join("mitsuba");
    std::fs::create_dir_all(&dir)?;
    let script = dir.join("cornell_mitsuba.py");
    std::fs::write(&script, include_str!("bench_cmd/cornell_mitsuba.py"))?;
    eprintln!(
        "running Mitsuba ({}), seeds {:?}",
        a.mitsuba_variant, a.seeds
    );
    let prefix = dir.join("mitsuba");
    let (out, _) = timed(
        Command::new(python)
            .arg(&script)
            .arg(&a.mitsuba_variant)
            .arg(a.width.to_string())
            .arg(a.spp.to_string())
            .arg(depth.to_string())
            .arg(a.threads.to_string())
            .arg(&prefix)
            .args(a.seeds.iter().map(|s| s.to_string())),
        "Mitsuba (is `mitsuba` installed in that Python?)",
    )?;
    let text = String::from_utf8_lossy(&out);
    let field = |k: usize| -> Vec<f64> {
        text.lines()
            .filter_map(|l| l.split_whitespace().nth(k).and_then(|t| t.parse().ok()))
            .collect()
    };
    let (times, cpu) = (field(3), field(5));
    if times.len() != 2 || cpu.len() != 2 {
        bail!("Mitsuba: expected two `seed S seconds T cpu C` lines, got:\n{text}");
    }
    let mut images = Vec::new();
    for &seed in &a.seeds {
        let path = PathBuf::from(format!("{}-{seed}.pfm", prefix.display()));
        images.push(parse_pfm(&read(&path)?, &path.display().to_string())?);
    }
    let (c, mean) = pair_constant(&images[0], &images[1], a.spp)?;
    // The first render compiles the kernels: the second one is the rate.
    let samples = (a.width * a.width) as f64 * a.spp as f64;
    Ok(Measured {
        name: format!("Mitsuba {}", a.mitsuba_variant),
        per_core: samples / cpu[1],
        c,
        mean,
        spp: a.spp,
        note: format!(
            "{} threads, path (max_depth {depth}), second render {:.1} s processor time ({:.1} s wall; the first, compiling its kernels, {:.1} s wall)",
            a.threads, cpu[1], times[1], times[0]
        ),
    })
}

/// rtl's pair of renders with `strategy`, in intersection tier `tier` if one is named.
fn run_rtl(a: &CompareArgs, strategy: &str, tier: Option<&str>, depth: u32) -> Result<Measured> {
    let exe = match &a.rtl {
        Some(p) => p.clone(),
        None => std::env::current_exe().context("cannot find the rtl binary itself")?,
    };
    let dir = a.scratch.join("rtl");
    std::fs::create_dir_all(&dir)?;
    // The flag's names are rtl's scene names.
    let scene = a.scene.to_possible_value().expect("no skipped scene");
    let scene = scene.get_name();
    let mut images = Vec::new();
    let mut raced = Vec::new();
    let (mut secs, mut wall) = (0.0, 0.0);
    let name = match tier {
        Some(t) => format!("rtl --strategy {strategy} --hit-tier {t}"),
        None => format!("rtl --strategy {strategy}"),
    };
    let stem = format!(
        "{scene}-{strategy}{}",
        tier.map_or(String::new(), |t| format!("-{t}"))
    );
    for &seed in &a.seeds {
        let png = dir.join(format!("{stem}-{seed}.png"));
        let pfm = dir.join(format!("{stem}-{seed}.pfm"));
        let mut cmd = Command::new(&exe);
        cmd.arg("render")
            .arg(scene)
            .args(["--width", &a.width.to_string()])
            .args(["--spp", &a.spp.to_string()])
            .args(["--max-depth", &depth.to_string()])
            .args(["--seed", &seed.to_string()])
            .args(["--threads", &a.threads.to_string()])
            .args(["--strategy", strategy])
            .arg("-o")
            .arg(&png)
            .arg("--linear")
            .arg(&pfm)
            .stdout(Stdio::null());
        if let Some(t) = tier {
            cmd.args(["--hit-tier", t]);
        }
        if a.scene == CompareScene::Book2Final
            && let Some(book) = &a.book
        {
            let earth = book.join("images/earthmap.jpg");
            if earth.is_file() {
                cmd.arg("--texture").arg(earth);
            }
        }
        eprintln!("running {name}, seed {seed}");
        let (_, said, s) = timed_with_stderr(&mut cmd, "rtl render")?;
        eprintln!(
            "  {:.2} s processor time, {:.2} s wall",
            s.cpu.unwrap_or(f64::NAN),
            s.wall
        );
        // where the render raced the intersection tiers, which won (`rtl render`'s own words)
        for line in said.lines().filter(|l| l.starts_with("intersection:")) {
            eprintln!("  {line}");
            raced.push(line.to_string());
        }
        secs += s.seconds();
        wall += s.wall;
        images.push(parse_pfm(&read(&pfm)?, &pfm.display().to_string())?);
    }
    let samples = (a.width * a.width) as f64 * a.spp as f64 * 2.0;
    let (c, mean) = pair_constant(&images[0], &images[1], a.spp)?;
    Ok(Measured {
        name,
        per_core: samples / secs,
        c,
        mean,
        spp: a.spp,
        note: format!(
            "{} threads, {secs:.1} s processor time ({wall:.1} s wall) for both renders{}",
            a.threads,
            race_note(&raced)
        ),
    })
}

/// What the note of a renderer's row says of the tier races its renders ran (`intersection: avx512
/// ran after the first passes, 1.27x as fast as avx2 there, ...`): the winners, in the renders' order.
fn race_note(lines: &[String]) -> String {
    let winners: Vec<&str> = lines
        .iter()
        .filter_map(|l| l.strip_prefix("intersection: "))
        .filter_map(|l| l.split_once(" ran after"))
        .map(|(tier, _)| tier)
        .collect();
    if winners.is_empty() {
        String::new()
    } else {
        format!("; tiers raced, won by {}", winners.join(", "))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rtl_render::traversal::HitTier;

    #[test]
    fn the_note_names_each_race_s_winner_and_nothing_without_races() {
        use rtl_render::tier_race::TierRace;
        // `rtl render`'s own lines: a race that AVX-512 won, one that AVX2 won, one cut short.
        let race = |secs: [f64; 2], passes: usize| {
            let mut r = TierRace::new(HitTier::Avx2, HitTier::Avx512);
            for _ in 0..passes {
                let t = if r.tier() == HitTier::Avx2 {
                    secs[0]
                } else {
                    secs[1]
                };
                r.record(t, 1);
            }
            crate::render_cmd::race_line(&r, true).expect("a line, as asked")
        };
        let said = [race([1.0, 0.8], 5), race([1.0, 1.2], 5)];
        assert_eq!(race_note(&said), "; tiers raced, won by avx512, avx2");
        assert_eq!(race_note(&[]), "");
        assert_eq!(
            race_note(&[race([1.0, 0.8], 3)]),
            "",
            "unfinished: no winner"
        );
    }

    #[test]
    fn rounds_alternate_their_order_and_run_every_job_once() {
        assert_eq!(round_order(4, 0), [0, 1, 2, 3]);
        assert_eq!(round_order(4, 1), [3, 2, 1, 0]);
        assert_eq!(round_order(4, 2), [0, 1, 2, 3]);
        assert_eq!(round_order(1, 1), [0]);
        assert!(round_order(0, 3).is_empty());
        for n in 0..6 {
            for r in 0..4 {
                let mut o = round_order(n, r);
                o.sort();
                assert_eq!(o, (0..n).collect::<Vec<_>>(), "round {r} of {n} jobs");
            }
        }
    }

    #[test]
    fn ratios_are_taken_within_a_round_then_summarised() {
        let s = Spread::of([3.0, 1.0, 2.0].into_iter());
        assert_eq!((s.median, s.lowest, s.highest), (2.0, 1.0, 3.0));
        assert_eq!(Spread::of([4.0, 1.0, 2.0, 3.0].into_iter()).median, 2.5);
        assert_eq!(s.ratio(), "2.00x (1.00-3.00x)");
        // The machine drifts between rounds: the book at 100, 50, 90 samples/s, rtl at 300, 200, 180.
        // Within each round rtl is 3x, 4x, 2x as fast: the median ratio is 3x. The ratio of the
        // medians (200 / 90 = 2.2x) mixes rounds, which is what the summary must not do.
        let m = |per_core: f64| Measured {
            name: String::new(),
            per_core,
            c: 0.3,
            mean: 0.2,
            spp: 16,
            note: String::new(),
        };
        let rounds: Vec<Vec<Measured>> = [(100.0, 300.0), (50.0, 200.0), (90.0, 180.0)]
            .into_iter()
            .map(|(b, r)| vec![m(b), m(r)])
            .collect();
        let within = rate_ratio(&rounds, 1);
        assert_eq!(
            (within.median, within.lowest, within.highest),
            (3.0, 2.0, 4.0)
        );
        let mixed = Spread::of(rounds.iter().map(|r| r[1].per_core)).median
            / Spread::of(rounds.iter().map(|r| r[0].per_core)).median;
        assert!(
            (mixed - within.median).abs() > 0.5,
            "the check tells the two apart"
        );
    }

    fn try_parse(args: &[&str]) -> Result<CompareArgs, clap::Error> {
        #[derive(clap::Parser)]
        struct Cli {
            #[command(flatten)]
            compare: CompareArgs,
        }
        let mut all = vec!["compare"];
        all.extend(args);
        <Cli as clap::Parser>::try_parse_from(all).map(|c| c.compare)
    }

    fn parse(args: &[&str]) -> CompareArgs {
        try_parse(args).unwrap()
    }

    /// The parser's own refusal (flags that conflict).
    fn parse_err(args: &[&str]) -> String {
        try_parse(args).err().expect("parsed").to_string()
    }

    #[test]
    fn the_books_measured_noise_is_reached_at_its_own_spp() {
        let book = Measured {
            name: String::new(),
            per_core: 250_000.0,
            c: 0.8,
            mean: 0.2,
            spp: 16,
            note: String::new(),
        };
        let mut a = parse(&["--target-rmse", "0.01", "--target-book-spp", "10000"]);
        // projected from its constant: (0.8 / 0.01)^2 = 6400 spp
        let projected = book_seconds(&a, &book, 0.01, 1000);
        assert!(
            (projected - 6400.0 * 1000.0 / 500_000.0).abs() < 1e-9,
            "{projected}"
        );
        // measured at 10,000 spp: that many, whatever the constant at 16 spp says
        a.target_rmse = None;
        a.book_noise = Some(0.01);
        let measured = book_seconds(&a, &book, 0.01, 1000);
        assert!(
            (measured - 10_000.0 * 1000.0 / 500_000.0).abs() < 1e-9,
            "{measured}"
        );
    }

    /// `rtl bench noise` reads either format and measures as `compare` does.
    #[test]
    fn the_noise_of_two_renders_is_read_from_either_format() {
        let dir = std::env::temp_dir().join(format!("rtl-bench-noise-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        // one pixel: display values 64/256 and 128/256 in every channel, so RMSE (1/4) / sqrt(2)
        let a = dir.join("a.ppm");
        std::fs::write(&a, "P3\n1 1\n255\n64 64 64\n").unwrap();
        // a PFM of linear 0.25 (display sqrt = 0.5, i.e. 128/256), little-endian
        let b = dir.join("b.pfm");
        let mut pfm = b"PF\n1 1\n-1.0\n".to_vec();
        for _ in 0..3 {
            pfm.extend(0.25f32.to_le_bytes());
        }
        std::fs::write(&b, pfm).unwrap();
        let args = |spp| NoiseArgs {
            images: vec![a.clone(), b.clone()],
            spp,
        };
        let out = noise_of(&args(4)).unwrap();
        let rmse = 0.25 / std::f64::consts::SQRT_2;
        assert!(
            out.contains(&format!("RMSE {rmse:.5}, c {:.4}", rmse * 2.0)),
            "{out}"
        );
        assert!(out.contains("0.2500 and 0.5000"), "{out}");
        assert!(
            noise_of(&args(0))
                .unwrap_err()
                .to_string()
                .contains("--spp")
        );
        std::fs::write(&b, "GIF89a").unwrap();
        let e = noise_of(&args(4)).unwrap_err().to_string();
        assert!(e.contains("PPM") && e.contains("PFM"), "{e}");
        std::fs::write(&b, "P3\n2 1\n255\n0 0 0 0 0 0\n").unwrap();
        let e = noise_of(&args(4)).unwrap_err().to_string();
        assert!(e.contains("differ in size"), "{e}");
        // A device or a directory is refused before a byte is read, naming it.
        for not_a_file in ["/dev/zero", "/"] {
            let e = noise_of(&NoiseArgs {
                images: vec![a.clone(), not_a_file.into()],
                spp: 4,
            })
            .unwrap_err()
            .to_string();
            assert!(
                e.contains(not_a_file) && e.contains("not a regular file"),
                "{e}"
            );
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_constant_projected_far_beyond_its_samples_is_flagged() {
        assert!(!measured_far_below(16, 64.0));
        assert!(measured_far_below(16, 64.5));
        assert!(!measured_far_below(10000, 10000.0));
    }

    #[cfg(unix)]
    #[test]
    fn a_python_without_mitsuba_is_refused_before_any_render() {
        use std::os::unix::fs::PermissionsExt;
        let dir = std::env::temp_dir().join(format!("rtl-bench-mitsuba-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        // Stand-ins for a Python: one that lacks numpy, one that has everything.
        let fake = |name: &str, body: &str| {
            let path = dir.join(name);
            std::fs::write(&path, format!("#!/bin/sh\n{body}\n")).unwrap();
            std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o755)).unwrap();
            path
        };
        let lacking = fake(
            "lacking",
            "echo 'Traceback (most recent call last):' >&2; \
             echo \"ModuleNotFoundError: No module named 'numpy'\" >&2; exit 1",
        );
        let e = check_mitsuba(&lacking, "llvm_ad_rgb")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("--mitsuba "), "{e}");
        assert!(
            e.contains("No module named 'numpy'") && e.contains("llvm_ad_rgb"),
            "{e}"
        );
        let good = fake("good", "exit 0");
        assert!(check_mitsuba(&good, "llvm_ad_rgb").is_ok());
        let missing = dir.join("no-such-python");
        let e = check_mitsuba(&missing, "llvm_ad_rgb").unwrap_err();
        assert!(format!("{e:#}").contains("no-such-python"), "{e:#}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn bad_settings_are_refused_before_any_work() {
        let err = |args: &[&str]| validate(&parse(args)).unwrap_err().to_string();
        assert!(err(&[]).contains("--target-rmse is needed"));
        assert!(err(&["--target-rmse", "0"]).contains("--target-rmse must be positive"));
        assert!(err(&["--target-rmse", "0.01", "--seeds", "3,3"]).contains("--seeds"));
        let e = err(&["--target-rmse", "0.01", "--strategy", "mis,fast"]);
        assert!(e.contains("--strategy") && e.contains("fast"), "{e}");
        let e = err(&["--target-rmse", "0.01", "--hit-tier", "avx2,sse9"]);
        assert!(e.contains("--hit-tier") && e.contains("sse9"), "{e}");
        // every tier this processor runs is taken, one it does not is refused by name
        for t in HitTier::ALL {
            let v = validate(&parse(&["--target-rmse", "0.01", "--hit-tier", t.key()]));
            match (t.available(), v) {
                (true, Ok(())) => {}
                (false, Err(e)) => assert!(e.to_string().contains(t.key()), "{e}"),
                (run, v) => panic!("{t:?} (runs here: {run}): {v:?}"),
            }
        }
        // each zero named alone, as the flag the user gave
        for flag in ["--width", "--spp", "--threads", "--cores", "--rounds"] {
            let e = err(&["--target-rmse", "0.01", flag, "0"]);
            assert_eq!(e, format!("{flag} must be positive, got 0"));
        }
        let e = err(&["--book-noise", "0.01"]);
        assert!(e.contains("--book-noise") && e.contains("no --book"), "{e}");
        assert!(
            parse_err(&["--book-noise", "0.01", "--target-rmse", "0.01"]).contains("--target-rmse")
        );
        let e = err(&["--target-rmse", "0.01", "--book-spp", "1024"]);
        assert!(e.contains("--book-spp") && e.contains("no --book"), "{e}");
        for w in ["0", "65537"] {
            let e = err(&["--target-rmse", "0.01", "--project-width", w]);
            assert!(e.contains("--project-width") && e.contains(w), "{e}");
        }
        assert!(validate(&parse(&["--target-rmse", "0.01", "--project-width", "800"])).is_ok());
        // past rtl render's limits, each named with its value (the book's program ran first with
        // them, and `--rounds 100000000000` aborted allocating the rounds)
        for (flag, value, words) in [
            ("--width", "65537", "at most 65536"),
            ("--threads", "1025", "at most 1024"),
            ("--rounds", "100000000000", "at most 1000"),
            ("--max-depth", "0", "at least 1"),
            ("--max-depth", "10001", "at most 10000"),
        ] {
            let e = err(&["--target-rmse", "0.01", flag, value]);
            assert!(
                e.starts_with(&format!("{flag} {value}: ")) && e.contains(words),
                "{e}"
            );
        }
        let dir = std::env::temp_dir().join(format!("rtl-bench-no-book-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let e = err(&["--book", dir.to_str().unwrap()]);
        assert!(e.contains("src/TheRestOfYourLife/main.cc"), "{e}");
        assert!(e.contains("git clone"), "how to get the book's code: {e}");
        // A checkout that looks like the book's, with a spp the book cannot stratify.
        let main = dir.join("src/TheRestOfYourLife");
        std::fs::create_dir_all(&main).unwrap();
        std::fs::write(main.join("main.cc"), "int main() {}\n").unwrap();
        let e = err(&["--book", dir.to_str().unwrap(), "--spp", "20"]);
        assert!(e.contains("--spp 20"), "{e}");
        assert!(validate(&parse(&["--book", dir.to_str().unwrap(), "--spp", "16"])).is_ok());
        // The book's own spp is checked in its place; rtl's then need not be a square.
        let book = |spp: &str| {
            parse(&[
                "--book",
                dir.to_str().unwrap(),
                "--spp",
                "20",
                "--book-spp",
                spp,
            ])
        };
        let e = validate(&book("20")).unwrap_err().to_string();
        assert!(e.contains("--book-spp 20"), "{e}");
        let e = validate(&book("0")).unwrap_err().to_string();
        assert!(e.contains("--book-spp must be positive"), "{e}");
        assert!(validate(&book("1024")).is_ok());
        // the book's program counts samples in an int, and its noise at no samples is no target
        let e = validate(&book("4294967296")).unwrap_err().to_string();
        assert!(
            e.contains("--book-spp 4294967296") && e.contains("C++ int"),
            "{e}"
        );
        let e = err(&["--book", dir.to_str().unwrap(), "--spp", "4294967296"]);
        assert!(
            e.contains("--spp 4294967296") && e.contains("C++ int"),
            "{e}"
        );
        let e = err(&["--book", dir.to_str().unwrap(), "--target-book-spp", "0"]);
        assert!(e.contains("--target-book-spp must be positive"), "{e}");
        let noise = |r: &str| parse(&["--book", dir.to_str().unwrap(), "--book-noise", r]);
        let e = validate(&noise("0")).unwrap_err().to_string();
        assert!(e.contains("--book-noise must be positive"), "{e}");
        assert!(validate(&noise("0.0123")).is_ok());
        let e = err(&[
            "--target-rmse",
            "0.01",
            "--scene",
            "book2-final",
            "--mitsuba",
            "python3",
        ]);
        assert!(e.contains("only the cornell scene"), "{e}");
        assert!(validate(&parse(&["--target-rmse", "0.01"])).is_ok());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
