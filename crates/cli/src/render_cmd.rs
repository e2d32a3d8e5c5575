//! `rtl render`: render a built-in scene or a scene file to PNG (and linear HDR), with a progress bar,
//! a closing summary, and `--explain` / `--list` / `--stats`.

mod explain;

use crate::progressive::{self, Ending, Plan, Saving};
use anyhow::{Context, Result, bail};
use clap::Args;
use explain::explain;
use indicatif::{ProgressBar, ProgressStyle};
use rtl_render::checkpoint::{Checkpoint, Identity};
use rtl_render::integrator::Strategy;
use rtl_render::limits::{self, MAX_SIDE, MAX_THREADS};
use rtl_render::output::{OutputFile, OutputKind, check_outputs};
use rtl_render::output::{Transfer, write_linear, write_png};
use rtl_render::render::{
    Accumulator, BOOK_MIXTURE_WEIGHT, RenderSettings, Renderer, check_mixture_weight,
};
use rtl_render::sampler::Stats;
use rtl_render::scene::Scene;
use rtl_render::scenes::{BUILT_INS, Built, BuiltIn, SceneOptions, find};
use rtl_render::tier_race::TierRace;
use rtl_render::traversal::{HitTier, HitTierError};
use rtl_render::vec::Num;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// How often a checkpoint is saved unless `--checkpoint-every` says otherwise.
const CHECKPOINT_EVERY: Duration = Duration::from_secs(5);

#[derive(Args)]
pub struct RenderArgs {
    /// A built-in scene name (see `--list`) or a path to a scene file (`.toml`).
    pub scene: Option<std::ffi::OsString>,
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
    /// Worker threads, 1 to 1024 (default: all cores).
    #[arg(long)]
    pub threads: Option<usize>,
    /// How diffuse bounces choose directions: uniform, cosine, light (biased), mixture (the book's),
    /// mis (next-event estimation + MIS, the best we have).
    #[arg(long, default_value = "mis", value_parser = parse_strategy)]
    pub strategy: Strategy,
    /// `mixture`'s share of directions drawn towards the importance targets, strictly between 0 and
    /// 1 (default: the book's 0.5).
    #[arg(long, value_name = "W")]
    pub mixture_weight: Option<f64>,
    /// `mis` without Russian roulette.
    #[arg(long)]
    pub no_rr: bool,
    /// `mis` with spherical-rectangle sampling of rectangular lights (off by default: it does not pay
    /// on the Cornell box).
    #[arg(long)]
    pub sph_rect: bool,
    /// `mis` with independent random numbers instead of low-discrepancy samples.
    #[arg(long)]
    pub no_lds: bool,
    /// `mis` without manifold next-event estimation through dielectric spheres (light reaching a
    /// medium or surface inside a glass ball then comes only by material sampling).
    #[arg(long)]
    pub no_manifold: bool,
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
    /// How often to save the checkpoint (`5s`, `1m`, ...; default 5s), with `--checkpoint` or
    /// `--resume`.
    #[arg(long, value_parser = progressive::parse_duration)]
    pub checkpoint_every: Option<Duration>,
    /// Continue the render saved in FILE (same scene and settings; `--spp` is the total wanted). FILE is
    /// kept up to date unless `--checkpoint` names another.
    #[arg(long, value_name = "FILE")]
    pub resume: Option<PathBuf>,
    /// Render samples K .. K+spp of every pixel (a part of a render split over processes or machines).
    #[arg(long, default_value_t = 0, value_name = "K")]
    pub sample_offset: u64,
    /// The intersection code to run: portable, avx2, avx512, or auto (time avx2 and avx512 on the
    /// render's first passes and keep the faster; where the processor does not run both, the best
    /// it runs, said in a note). Default: the best this processor runs, but auto
    /// on an Intel processor with AVX-512, where which is faster depends on the model; `--explain`
    /// names it. Every tier finds the same hits, so the image is the same bit for bit: this is for
    /// timing the tiers side by side, or the one a processor without AVX-512 runs.
    #[arg(long, value_name = "TIER", value_parser = parse_hit_tier)]
    pub hit_tier: Option<TierChoice>,
    /// Trace one path at a time, where 32 would be traced side by side in the vector lanes (in a
    /// scene of one small group, on a processor with AVX2: the book's one-sample strategies, and
    /// `mis` where the scene has no media). The
    /// image is the same bit for bit: this is for timing what the lanes buy.
    #[arg(long)]
    pub no_lanes: bool,
}

/// `--hit-tier`: one tier, or a race of two.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TierChoice {
    Fixed(HitTier),
    /// `auto`: AVX2 and AVX-512 timed on the first passes where the processor runs both.
    Race,
}

/// A tier that this processor runs, by its key, or `auto` (also `rtl bench compare --hit-tier`'s
/// check of each tier it will pass on).
pub(crate) fn parse_hit_tier(s: &str) -> Result<TierChoice, String> {
    if s == "auto" {
        return Ok(TierChoice::Race);
    }
    match s.parse::<HitTier>().and_then(HitTier::runnable) {
        Ok(t) => Ok(TierChoice::Fixed(t)),
        Err(HitTierError::Unknown(s)) => Err(format!(
            "unknown intersection tier '{s}' (portable, avx2, avx512 or auto)"
        )),
        Err(e) => Err(e.to_string()),
    }
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
    /// Where a scene file gives the width (`FILE:LINE:COL: field `render.width``), for messages.
    width_at: Option<String>,
    spp: u64,
    /// The image files a scene file's textures were read from (inputs no output may overwrite).
    texture_files: Vec<PathBuf>,
}

/// Whether the scene argument names a scene file rather than a built-in scene: one ending in
/// `.toml`, or a file that is not named as a built-in is. A built-in's bare name is the built-in even
/// if a file of that name is in the directory (say the checkpoint of `rtl render cornell --checkpoint
/// cornell`, which `--resume cornell` then read as a scene file); `./cornell` names the file.
fn names_a_file(arg: &str) -> bool {
    arg.ends_with(".toml") || (find(arg).is_err() && Path::new(arg).is_file())
}

fn load(arg: &str, opts: &SceneOptions) -> Result<Loaded> {
    if names_a_file(arg) {
        return load_file(Path::new(arg));
    }
    let b: &BuiltIn = find(arg).map_err(anyhow::Error::msg)?;
    // (a built-in fails to build only on the image of `--texture`, which its error names first)
    let flag = if opts.texture.is_some() {
        "--texture "
    } else {
        ""
    };
    let built = (b.build)(opts).map_err(|e| anyhow::anyhow!("scene {}: {flag}{e}", b.name))?;
    Ok(Loaded {
        name: b.name.into(),
        description: b.description.into(),
        built,
        width: b.width,
        width_at: None,
        spp: b.spp,
        texture_files: Vec::new(),
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
        width_at: file
            .width_at
            .map(|(line, col)| format!("{}:{line}:{col}: field `render.width`", path.display())),
        spp: file.spp.unwrap_or(100),
        texture_files: file.texture_files,
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

/// Everything `rtl render` was asked for, resolved from the flags and the scene and checked, before any
/// work starts.
struct Job {
    loaded: Loaded,
    settings: RenderSettings,
    /// Samples `[start, end)` of every pixel.
    start: u64,
    end: u64,
    threads: usize,
    output: PathBuf,
    /// Where the accumulation is saved (`--checkpoint`, else `--resume`).
    saving: Option<PathBuf>,
}

/// Resolve and check every flag against the scene: what is accepted renders, the rest is refused here,
/// naming the flag, the value and the limit.
fn settings(args: &RenderArgs, scene_arg: &str) -> Result<Job> {
    if let Some(t) = &args.texture {
        let takes = !names_a_file(scene_arg)
            && matches!(find(scene_arg).map(|b| b.name), Ok("earth" | "book2-final"));
        if !takes {
            bail!(
                "--texture {}: only the built-in scenes `earth` and `book2-final` take an image (for \
                 their earth), not '{scene_arg}'; a scene file names its own image textures",
                t.display()
            );
        }
    }
    if !matches!(args.strategy, Strategy::Mis(_)) {
        let switches = [
            (args.no_rr, "--no-rr"),
            (args.sph_rect, "--sph-rect"),
            (args.no_lds, "--no-lds"),
            (args.no_manifold, "--no-manifold"),
        ];
        if let Some((_, flag)) = switches.iter().find(|(on, _)| *on) {
            bail!(
                "{flag}: only the 'mis' strategy has this switch, not '{}'",
                args.strategy.name()
            );
        }
    }
    let opts = SceneOptions {
        texture: args.texture.clone(),
    };
    let file = Path::new(scene_arg);
    // (the checkpoint this render writes or resumes, however its path is written: `./cornell`)
    let same = |p: &Option<PathBuf>| p.as_deref().is_some_and(|p| same_file(p, file));
    let ours = same(&args.resume) || same(&args.checkpoint);
    if !names_a_file(scene_arg) && file.is_file() && !ours {
        eprintln!(
            "note: '{scene_arg}' is the built-in scene; to render the file of that name here, \
             write ./{scene_arg}"
        );
    }
    let loaded = load(scene_arg, &opts)?;
    let scene = &loaded.built.scene;
    let width = args.width.unwrap_or(loaded.width);
    if !(1..=MAX_SIDE).contains(&width) {
        bail!("--width {width}: the width must be 1 to {MAX_SIDE} pixels");
    }
    if args.spp == Some(0) {
        bail!("--spp 0: the samples per pixel must be at least 1");
    }
    if args.time.is_some_and(|t| t.is_zero()) {
        bail!("--time 0: the time budget must be positive");
    }
    if let Some(every) = args.checkpoint_every {
        if every.is_zero() {
            bail!("--checkpoint-every 0: the interval must be positive");
        }
        if args.checkpoint.is_none() && args.resume.is_none() {
            bail!(
                "--checkpoint-every: there is no checkpoint to save (give --checkpoint FILE or \
                 --resume FILE); without one it would be ignored"
            );
        }
    }
    let max_depth = args.max_depth.unwrap_or(scene.max_depth);
    if let Some(problem) = limits::max_depth_problem(max_depth) {
        bail!("--max-depth {max_depth}: the maximum depth {problem}");
    }
    let threads = match args.threads {
        None => 0,
        Some(t) if (1..=MAX_THREADS).contains(&t) => t,
        Some(t) => bail!(
            "--threads {t}: the number of threads must be 1 to {MAX_THREADS} (leave it out for all \
             cores)"
        ),
    };
    let mixture_weight = match (args.mixture_weight, args.strategy) {
        (None, _) => BOOK_MIXTURE_WEIGHT,
        (Some(w), Strategy::Mixture) if loaded.built.scene.features.targets == 0 => bail!(
            "--mixture-weight {}: {} lists no importance targets (`lights`), so 'mixture' has \
             nothing to mix the material's density with and the weight would be ignored",
            Num(w),
            loaded.name
        ),
        (Some(w), Strategy::Mixture) => match check_mixture_weight(w) {
            Ok(w) => w,
            Err(e) => bail!("--mixture-weight {}: {e}", Num(w)),
        },
        (Some(w), s) => bail!(
            "--mixture-weight {}: only the 'mixture' strategy has a mixture weight, not '{}'",
            Num(w),
            s.name()
        ),
    };
    // With only a time budget, render until the time is up.
    let spp = match (args.spp, args.time) {
        (Some(n), _) => n,
        (None, Some(_)) => u64::MAX - args.sample_offset,
        (None, None) => loaded.spp,
    };
    let start = args.sample_offset;
    if spp == 0 {
        bail!(
            "--sample-offset {start}: no sample index is left after it (they end at {})",
            u64::MAX
        );
    }
    let Some(end) = start.checked_add(spp) else {
        bail!(
            "--sample-offset {start} plus --spp {spp} is past the last sample index {}",
            u64::MAX
        );
    };
    let settings = RenderSettings {
        width,
        max_depth,
        seed: args.seed,
        strategy: match args.strategy {
            Strategy::Mis(mut o) => {
                o.russian_roulette &= !args.no_rr;
                o.spherical_rectangles |= args.sph_rect;
                o.low_discrepancy &= !args.no_lds;
                o.manifold &= !args.no_manifold;
                Strategy::Mis(o)
            }
            other => other,
        },
        mixture_weight,
    };
    let output = args
        .output
        .clone()
        .unwrap_or_else(|| PathBuf::from(format!("{}.png", loaded.name)));
    let saving = args.checkpoint.clone().or_else(|| args.resume.clone());
    let job = Job {
        loaded,
        settings,
        start,
        end,
        threads,
        output,
        saving,
    };
    if !args.explain {
        check_job_outputs(args, &job, scene_arg)?;
    }
    Ok(job)
}

/// Every file the render will write: named right, in a directory that exists and can be written, each
/// its own file, and none of them an input.
fn check_job_outputs(args: &RenderArgs, job: &Job, scene_arg: &str) -> Result<()> {
    let mut outputs = vec![OutputFile {
        flag: if args.output.is_some() {
            "-o"
        } else {
            "the default output"
        },
        path: job.output.clone(),
        kind: OutputKind::Png,
    }];
    if let Some(lin) = &args.linear {
        outputs.push(OutputFile {
            flag: "--linear",
            path: lin.clone(),
            kind: OutputKind::Linear,
        });
    }
    if let Some(path) = &job.saving {
        outputs.push(OutputFile {
            flag: if args.checkpoint.is_some() {
                "--checkpoint"
            } else {
                "--resume"
            },
            path: path.clone(),
            kind: OutputKind::Checkpoint,
        });
    }
    let mut inputs = Vec::new();
    if names_a_file(scene_arg) {
        inputs.push(("the scene file".to_string(), PathBuf::from(scene_arg)));
    }
    for t in &job.loaded.texture_files {
        inputs.push((format!("the scene's texture {}", t.display()), t.clone()));
    }
    if let Some(t) = &args.texture {
        inputs.push(("--texture".to_string(), t.clone()));
    }
    // `--resume r.ck --checkpoint ./r.ck` goes on saving where it reads, as `--checkpoint r.ck` does
    let resumed_in_place = |c: &Path| args.resume.as_deref().is_some_and(|r| same_file(c, r));
    if let (Some(c), Some(r)) = (&args.checkpoint, &args.resume)
        && !resumed_in_place(c)
    {
        inputs.push(("--resume".to_string(), r.clone()));
    }
    check_output_files(&outputs, &inputs)?;
    if let Some(c) = &args.checkpoint
        && c.exists()
        && !resumed_in_place(c)
    {
        bail!(
            "{} exists: continue it with --resume {0}, or remove it to start afresh",
            c.display()
        );
    }
    Ok(())
}

/// Whether `a` and `b` name the same file (`r.ck` and `./r.ck`): by their canonical paths where both
/// exist, else as written.
fn same_file(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(x), Ok(y)) => x == y,
        _ => a == b,
    }
}

/// [`check_outputs`], and first that no output's name ends in a `/`: `-o out.png/` passed its checks
/// (its file name is `out.png`) and failed only at the end, on renaming the image into place, the
/// render's work lost (and with `--linear out.pfm/` the PNG written, the PFM not).
pub(crate) fn check_output_files(
    outputs: &[OutputFile],
    inputs: &[(String, PathBuf)],
) -> Result<()> {
    for o in outputs {
        let text = o.path.as_os_str().as_encoded_bytes();
        let ends_in_separator = text
            .last()
            .is_some_and(|b| std::path::is_separator(char::from(*b)))
            || text == b"."
            || (text.ends_with(b".")
                && text
                    .get(text.len().wrapping_sub(2))
                    .is_some_and(|b| std::path::is_separator(char::from(*b))));
        // (`out.png/.` and `out.png/..` name directories too, though their file name reads `out.png`)
        let last_is_a_name = matches!(
            o.path.components().next_back(),
            Some(std::path::Component::Normal(_))
        );
        if ends_in_separator || !last_is_a_name {
            bail!(
                "{} {}: that names a directory, not a file (a file's name cannot end in `{}`, `.` or \
                 `..`)",
                o.flag,
                o.path.display(),
                std::path::MAIN_SEPARATOR
            );
        }
    }
    check_outputs(outputs, inputs)?;
    Ok(())
}

/// What the render needs, counted before anything is allocated: refused if a side is too long or
/// it does not fit in what each memory limit leaves ([`limits::check_image`]): its buffers, a
/// checkpoint to resume, `workers` threads and the Ctrl-C handler's, with their stacks and malloc
/// arenas.
fn check_size(
    args: &RenderArgs,
    loaded: &Loaded,
    w: usize,
    h: usize,
    workers: usize,
) -> Result<()> {
    // (a file that cannot be read is refused by name when it is opened)
    let resume_bytes = args
        .resume
        .as_ref()
        .and_then(|p| std::fs::metadata(p).ok())
        .map_or(0, |m| m.len());
    limits::check_image(w, h, workers + 1, resume_bytes, &limits::memory_limits()).map_err(
        |e| {
            let from = match (args.width, &loaded.width_at) {
                (Some(width), _) => format!("--width {width}"),
                (None, Some(at)) => format!("{at}: the width {}", loaded.width),
                (None, None) => "the scene's width".to_string(),
            };
            let threads = match args.threads {
                Some(t) => format!(", with --threads {t}"),
                None => String::new(),
            };
            anyhow::anyhow!("{from} and the scene's aspect ratio{threads}: {e}")
        },
    )?;
    Ok(())
}

/// The worker threads of the render's pool: `--threads` (`requested`), or where it is left out
/// (0) as many as rayon would start: `RAYON_NUM_THREADS` (or the older `RAYON_RS_NUM_CPUS`) if set
/// to a number above 0, otherwise one for each processor the process may use.
fn worker_threads(requested: usize) -> usize {
    if requested > 0 {
        return requested;
    }
    ["RAYON_NUM_THREADS", "RAYON_RS_NUM_CPUS"]
        .iter()
        .find_map(|name| {
            std::env::var(name)
                .ok()
                .and_then(|v| v.parse::<usize>().ok())
                .filter(|&n| n > 0)
        })
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
}

/// The accumulation to continue: empty at sample `start`, or the `--resume` checkpoint's after checking
/// that it is of this render.
fn open_or_resume(
    args: &RenderArgs,
    job: &Job,
    renderer: &Renderer,
    identity: &Identity,
) -> Result<Accumulator> {
    let (w, h) = (renderer.camera.width, renderer.camera.height);
    let Some(path) = &args.resume else {
        let mut acc = Accumulator::new(w, h);
        acc.samples = job.start;
        return Ok(acc);
    };
    let ck = Checkpoint::read(path)?;
    let diffs = ck
        .identity
        .differences(identity, "the checkpoint", "this render");
    if !diffs.is_empty() {
        bail!(
            "{} is a checkpoint of another render: {}",
            path.display(),
            diffs.join("; ")
        );
    }
    if ck.start != job.start {
        bail!(
            "{} holds samples from {} on, but --sample-offset is {}",
            path.display(),
            ck.start,
            job.start
        );
    }
    if ck.acc.samples > job.end {
        bail!(
            "{} already holds {} spp, more than the {} asked for (--spp is the total)",
            path.display(),
            ck.spp(),
            job.end - job.start
        );
    }
    if ck.rtl_version != env!("CARGO_PKG_VERSION") {
        eprintln!(
            "note: {} was written by rtl {}, this is {}",
            path.display(),
            rtl_render::text::shown(&ck.rtl_version),
            env!("CARGO_PKG_VERSION")
        );
    }
    eprintln!("resuming {} at {} spp", path.display(), ck.spp());
    Ok(ck.acc)
}

/// The progress bar: samples done of those asked for, or milliseconds of the budget.
fn progress_bar(args: &RenderArgs, job: &Job, plan: &Plan, acc: &Accumulator) -> ProgressBar {
    let h = acc.height as u64;
    let bar = match args.time {
        Some(t) if plan.progress_by_time => {
            ProgressBar::new(u64::try_from(t.as_millis()).unwrap_or(u64::MAX))
        }
        _ => {
            let b = ProgressBar::new(h.saturating_mul(job.end - job.start));
            b.set_position(h.saturating_mul(acc.samples - job.start));
            b
        }
    };
    bar.set_style(
        ProgressStyle::with_template(
            "{spinner} {prefix} [{elapsed_precise}] {wide_bar} {percent:>3}% ETA {eta} {msg}",
        )
        .expect("valid progress template"),
    );
    bar.set_prefix(format!("{} {}x{}", job.loaded.name, acc.width, acc.height));
    bar
}

pub fn run(args: RenderArgs) -> Result<()> {
    if args.list {
        list();
        return Ok(());
    }
    let Some(scene_arg) = args.scene.as_deref() else {
        bail!("name a scene to render (rtl render --list shows the built-in ones) or a scene file");
    };
    // Read as UTF-8 here rather than by the argument parser, whose message names no argument.
    let Some(scene_arg) = scene_arg.to_str() else {
        bail!(
            "SCENE '{}': this path is not UTF-8, and rtl reads scene names, scene files and the \
             names inside them as UTF-8; rename the file",
            Path::new(scene_arg).display()
        );
    };
    let mut race = match args.hit_tier {
        Some(TierChoice::Fixed(tier)) => {
            tier.select().context("--hit-tier")?;
            None
        }
        Some(TierChoice::Race) => {
            let race = TierRace::on_this_processor(true);
            if race.is_none() {
                eprintln!("note: {}", nothing_to_race(HitTier::current()));
            }
            race
        }
        None => TierRace::on_this_processor(false),
    };
    let job = settings(&args, scene_arg)?;
    let scene = &job.loaded.built.scene;
    if args.explain {
        explain(
            &job.loaded,
            scene,
            &job.settings,
            args.spp.unwrap_or(job.loaded.spp),
            args.no_lanes,
            race.as_ref(),
        );
        return Ok(());
    }
    let renderer = Renderer::new(scene, job.settings);
    let renderer = if args.no_lanes {
        renderer.one_path_at_a_time()
    } else {
        renderer
    };
    let (w, h) = (renderer.camera.width, renderer.camera.height);
    let workers = worker_threads(job.threads);
    check_size(&args, &job.loaded, w, h, workers)?;
    let identity = Identity::new(&job.loaded.name, scene, &job.settings, w, h);
    let mut acc = open_or_resume(&args, &job, &renderer, &identity)?;
    for n in &job.loaded.built.notices {
        eprintln!("note: {n}");
    }
    if let Some(n) = without_targets(job.settings.strategy, scene) {
        eprintln!("note: {n}");
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(workers)
        .build()
        .context("cannot start the thread pool")?;
    // Every worker allocates once, and so has its malloc arena, before the render allocates the
    // pass's copy of the accumulation: glibc maps twice an arena's size while it makes one, and
    // the check counts one such making at a time (limits::threads_need), not one for each worker
    // at once beside the render's buffers.
    pool.broadcast(|_| drop(std::hint::black_box(Box::new(0u64))));
    let checkpoint_every = args.checkpoint_every.unwrap_or(CHECKPOINT_EVERY);
    let plan = Plan {
        start: job.start,
        end: job.end,
        budget: args.time,
        pass_time: checkpoint_every.clamp(Duration::from_millis(20), Duration::from_secs(1)),
        saving: job.saving.clone().map(|path| Saving {
            path,
            every: checkpoint_every,
            identity: identity.clone(),
        }),
        progress_by_time: args.time.is_some() && args.spp.is_none(),
    };
    let bar = progress_bar(&args, &job, &plan, &acc);
    progressive::catch_interrupts()?;
    let start_time = Instant::now();
    let (stats, ending) = progressive::run(&renderer, &pool, &mut acc, &plan, &bar, &mut race)?;
    bar.finish_and_clear();
    let secs = start_time.elapsed().as_secs_f64();
    if let Some(r) = &race {
        say_race(r, args.hit_tier == Some(TierChoice::Race));
    }
    report(
        &args,
        &job,
        &plan,
        acc,
        &stats,
        ending,
        secs,
        pool.current_num_threads(),
    )
}

/// What `--hit-tier auto` does on a processor that does not run both AVX2 and AVX-512: it runs
/// `tier`, the best this processor runs, with no race.
/// What to tell a user whose image came out black in every pixel though the scene has `emitters`
/// (with none the scene file's loader has said so already): a one-sided quad light facing away from
/// everything the camera sees renders so, with exit code 0 and nothing else to tell it from a
/// render of the dark.
fn all_black(image: &[rtl_render::vec::Color], emitters: usize) -> Option<String> {
    (emitters > 0 && image.iter().all(|c| *c == rtl_render::vec::Color::ZERO)).then(|| {
        "every pixel is black: no light reached the camera. A quad light shines only to the side \
         its normal u x v points to: is it facing away from what it should light?"
            .to_string()
    })
}

/// What to tell a user who asked for a strategy that aims at the importance targets, of a scene that
/// lists none: it samples the material's density alone, so the image is `cosine`'s.
fn without_targets(strategy: Strategy, scene: &Scene) -> Option<String> {
    (matches!(strategy, Strategy::Mixture | Strategy::Light) && scene.features.targets == 0).then(
        || {
            format!(
                "this scene lists no importance targets (`lights`), so '{}' samples the \
                 material's density alone: the image is the 'cosine' strategy's",
                strategy.name()
            )
        },
    )
}

fn nothing_to_race(tier: HitTier) -> String {
    format!(
        "--hit-tier auto: this processor does not run both avx2 and avx512, so there is no race \
         to time; {} runs (the best it runs)",
        tier.key()
    )
}

/// How the race of the intersection tiers went (the image is the same whichever won); a render too
/// short to finish it is told so only if `asked` for the race.
fn say_race(r: &TierRace, asked: bool) {
    if let Some(line) = race_line(r, asked) {
        eprintln!("{line}");
    }
}

/// [`say_race`]'s line (`rtl bench compare` reads the winner from it).
pub(crate) fn race_line(r: &TierRace, asked: bool) -> Option<String> {
    let [a, b] = r.tiers();
    match r.outcome() {
        Some(o) => Some(format!(
            "intersection: {} ran after the first passes, {:.2}x as fast as {} there, timed side by \
             side (--hit-tier {} fixes it)",
            o.winner.key(),
            1.0 / o.time_ratio,
            o.loser.key(),
            o.winner.key()
        )),
        None if !asked => None,
        None => Some(format!(
            "intersection: the render ended before the race of {} and {} did (five passes); \
             --hit-tier names one",
            a.key(),
            b.key()
        )),
    }
}

/// Save the checkpoint and the images, then say what was done.
#[allow(clippy::too_many_arguments)]
fn report(
    args: &RenderArgs,
    job: &Job,
    plan: &Plan,
    acc: Accumulator,
    stats: &Stats,
    ending: Ending,
    secs: f64,
    threads: usize,
) -> Result<()> {
    let start = job.start;
    let spp = acc.samples - start;
    match ending {
        Ending::Done => {}
        Ending::OutOfTime => eprintln!("time budget spent: stopping at {spp} spp"),
        Ending::Interrupted => eprintln!("stopped at {spp} spp (whole passes only)"),
    }
    // The checkpoint first (it holds the work; `rtl merge FILE` makes the image again), then the image
    // even if the checkpoint could not be written.
    let saved = plan.saving.as_ref().map(|s| s.save(&acc, start));
    if spp == 0 {
        if let Some(saved) = saved {
            saved?;
        }
        if ending == Ending::Interrupted {
            eprintln!("no pass finished: no image written");
            std::process::exit(130);
        }
        bail!(
            "no pass finished within --time {:?}: no image written (a pass of one sample per pixel \
             takes longer; give more time)",
            args.time.unwrap_or_default()
        );
    }
    let (w, h, end) = (acc.width, acc.height, acc.samples);
    let image = acc.image();
    // The accumulation is saved and its image made: the encodings are made without it (40 bytes a
    // pixel), so that the output needs less than the passes did (limits::RENDER_BYTES_PER_PIXEL).
    drop(acc);
    let transfer = if args.srgb {
        Transfer::Srgb
    } else {
        Transfer::Gamma2
    };
    write_png(&job.output, w, h, &image, transfer).map_err(anyhow::Error::msg)?;
    if let Some(lin) = &args.linear {
        write_linear(lin, w, h, &image).map_err(anyhow::Error::msg)?;
    }
    if let (Some(s), Some(saved)) = (&plan.saving, saved) {
        saved?;
        eprintln!(
            "checkpoint {}: samples {start}..{} ({spp} spp)",
            s.path.display(),
            end
        );
    }
    let samples = stats.samples as f64;
    eprintln!(
        "{}: {w}x{h}, {spp} spp{}, {threads} threads, {secs:.2} s, {:.0}k samples/s, {:.2}M rays/s, {} non-finite samples dropped -> {}{}",
        job.loaded.name,
        if start > 0 {
            format!(" (samples {start}..{end})")
        } else {
            String::new()
        },
        samples / secs / 1e3,
        stats.rays as f64 / secs / 1e6,
        stats.non_finite,
        job.output.display(),
        args.linear
            .as_ref()
            .map(|p| format!(", {}", p.display()))
            .unwrap_or_default()
    );
    if let Some(n) = all_black(&image, job.loaded.built.scene.features.emitters) {
        eprintln!("note: {n}");
    }
    if args.stats {
        // (a resume of a finished render renders no sample: 0 per sample, not NaN)
        println!("samples              {}", stats.samples);
        println!(
            "rays                 {} ({:.2} per sample)",
            stats.rays,
            stats.rays as f64 / samples.max(1.0)
        );
        println!(
            "random numbers       {} ({:.2} per sample)",
            stats.random_numbers,
            stats.random_numbers as f64 / samples.max(1.0)
        );
        println!("lens samples         {}", stats.lens_samples);
        println!("time samples         {}", stats.time_samples);
        println!("medium evaluations   {}", stats.medium_evaluations);
        println!("texture evaluations  {}", stats.texture_evaluations);
        println!("manifold connections {}", stats.manifold_connections);
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

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;
    use proptest::prelude::*;
    use proptest::strategy::Strategy as _;

    #[derive(Parser)]
    struct Cli {
        #[command(flatten)]
        args: RenderArgs,
    }

    #[test]
    fn auto_with_nothing_to_race_names_the_tier_that_runs() {
        let avx2 = nothing_to_race(HitTier::Avx2);
        assert!(avx2.contains("no race") && avx2.ends_with("avx2 runs (the best it runs)"));
        let portable = nothing_to_race(HitTier::Portable);
        assert!(portable.ends_with("portable runs (the best it runs)"));
    }

    /// Flag values from every class: zero, one, ordinary, the limits and one past them, the type's
    /// maximum, negative and not a number at all.
    fn value() -> impl proptest::strategy::Strategy<Value = String> {
        prop_oneof![
            Just("0".to_string()),
            Just("1".to_string()),
            Just("16".to_string()),
            Just("1024".to_string()),
            Just("1025".to_string()),
            Just("10000".to_string()),
            Just("10001".to_string()),
            Just("65536".to_string()),
            Just("65537".to_string()),
            Just("4294967296".to_string()),
            Just("18446744073709551615".to_string()),
            Just("-1".to_string()),
            Just("nan".to_string()),
            Just("1e300".to_string()),
            (0u64..100).prop_map(|x| x.to_string()),
        ]
    }

    fn duration() -> impl proptest::strategy::Strategy<Value = String> {
        prop_oneof![
            Just("0".to_string()),
            Just("0s".to_string()),
            Just("1ms".to_string()),
            Just("5s".to_string()),
            Just("1e30".to_string()),
            Just("100000000000000d".to_string()),
            Just("-3".to_string()),
            Just("inf".to_string()),
        ]
    }

    /// Removes its directory when dropped, so a case that returns early leaves nothing behind.
    struct RemoveDirOnDrop(std::path::PathBuf);

    impl Drop for RemoveDirOnDrop {
        fn drop(&mut self) {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }

    proptest! {
        // A fixed seed: the same cases every run (a failure found once is also kept in
        // proptest-regressions/).
        #![proptest_config(ProptestConfig {
            cases: 256,
            rng_seed: proptest::test_runner::RngSeed::Fixed(12),
            ..ProptestConfig::default()
        })]

        /// Whatever the flags, settings are refused naming a flag, or accepted within every limit,
        /// and the image they describe is sized without a panic.
        #[test]
        fn every_flag_combination_is_refused_naming_a_flag_or_accepted_within_the_limits(
            flags in proptest::collection::vec(
                (
                    prop_oneof![
                        Just("--width"), Just("--spp"), Just("--max-depth"), Just("--threads"),
                        Just("--sample-offset"), Just("--seed"),
                    ],
                    value(),
                ),
                0..4,
            ),
            times in proptest::collection::vec(
                (prop_oneof![Just("--time"), Just("--checkpoint-every")], duration()),
                0..2,
            ),
        ) {
            let dir = std::env::temp_dir().join(format!("rtl-props-{}", std::process::id()));
            std::fs::create_dir_all(&dir).unwrap();
            // Removed however the case ends (nothing is written into it: no render runs).
            let _cleanup = RemoveDirOnDrop(dir.clone());
            let out = dir.join("x.png").display().to_string();
            let mut argv = vec!["rtl".to_string(), "cornell".into(), "-o".into(), out];
            let mut seen = Vec::new();
            for (flag, v) in flags.iter().chain(times.iter()) {
                if seen.contains(flag) {
                    continue;
                }
                seen.push(*flag);
                argv.push(flag.to_string());
                argv.push(v.clone());
            }
            // clap refuses what does not parse as the flag's type, naming it: nothing to check here.
            let Ok(cli) = Cli::try_parse_from(&argv) else {
                return Ok(());
            };
            match settings(&cli.args, "cornell") {
                Err(e) => {
                    let msg = format!("{e:#}");
                    prop_assert!(
                        seen.iter().any(|f| msg.contains(f)),
                        "{argv:?}: {msg}"
                    );
                }
                Ok(job) => {
                    prop_assert!((1..=MAX_SIDE).contains(&job.settings.width));
                    prop_assert!(limits::max_depth_problem(job.settings.max_depth).is_none());
                    prop_assert!(job.start < job.end);
                    prop_assert!(job.threads <= MAX_THREADS);
                    let r = Renderer::new(&job.loaded.built.scene, job.settings);
                    // A refusal names --width (the only flag that sizes the image; --threads is
                    // named too where it is given).
                    let workers = worker_threads(job.threads);
                    if let Err(e) = check_size(&cli.args, &job.loaded, r.camera.width, r.camera.height, workers) {
                        let msg = format!("{e:#}");
                        prop_assert!(
                            msg.contains("--width") || msg.contains("the scene's width"),
                            "{msg}"
                        );
                    }
                }
            }
        }
    }
}
