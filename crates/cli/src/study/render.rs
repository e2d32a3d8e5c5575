//! `rtl study render`: what accuracy costs in time for each rendering strategy.
//!
//! 1. A converged reference, rendered once with `mis` under another seed and cached in `DIR` as a PFM
//!    with a `.txt` naming the command and settings that made it.
//! 2. Every strategy (and `mis` with each extra switched off: the ablation rows) rendered
//!    progressively at spp = 1, 4, 16, 64, 256 (1024 with `--max-spp 1024`): wall time (all threads;
//!    the shortest of `--repeat` runs, since the machine is shared),
//!    RMSE and relative MSE against the reference over every pixel and channel (linear radiance; also
//!    the RMSE of the displayed range, both clamped to [0, 1]), rays
//!    per sample -> `DIR/render.csv`, and a log-log plot of RMSE against seconds.
//! 3. Per-pixel variance of one sample's luminance (a heat map per strategy, common log scale).
//! 4. Crops side by side at equal spp and at equal time (PNG, the book's gamma 2).
//! 5. An extrapolation to 600 x 600: the samples and seconds each strategy needs for an RMSE of 0.010,
//!    assuming RMSE ~ c / sqrt(spp) (fitted on the two largest spp) and time ~ pixels x spp (the
//!    per-sample cost measured here) -> `DIR/render-600.csv`.

use crate::csv::CsvTable;
use crate::plot::{Panel, Series, image_grid, loglog};
use anyhow::{Result, bail};
use clap::Args;
use rayon::prelude::*;
use rtl_mc::RunningStats;
use rtl_render::Color;
use rtl_render::integrator::{MisOptions, Strategy};
use rtl_render::output::{Transfer, to_rgb8, write_linear};
use rtl_render::render::{Accumulator, RenderSettings, Renderer};
use rtl_render::sampler::Ctx;
use rtl_render::scene::Scene;
use rtl_render::scenes::find;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(Args)]
pub struct RenderArgs {
    /// Directory for the CSV, the plots and the cached reference (created if missing; default: a
    /// scratch directory, printed; the book's figures are book/src/figures).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Built-in scene to study.
    #[arg(long, default_value = "cornell")]
    pub scene: String,
    /// Image width (default 128; 48 with --quick).
    #[arg(long)]
    pub width: Option<usize>,
    /// Samples per pixel of the reference (default 8192; 1024 with --quick).
    #[arg(long)]
    pub reference_spp: Option<u64>,
    /// Largest spp of the sweep (a power of 4 times 1; default 256, 16 with --quick).
    #[arg(long)]
    pub max_spp: Option<u64>,
    /// Render each sweep this many times and keep the shortest time of each step (the machine is shared:
    /// the minimum is the least disturbed). Default 2; 1 with --quick.
    #[arg(long)]
    pub repeat: Option<u32>,
    /// Redraw the plots and images from the measurements already in the output directory
    /// (render.csv), timing nothing: for a change of labels or layout, or on a busy machine. The
    /// images are rendered again (they depend on the seed and spp only, not on the clock).
    #[arg(long)]
    pub replot: bool,
    /// A small, fast look: 48x48, a 1024-spp reference, up to 16 spp: about 10 s on 2 cores. The full
    /// study takes about a minute (47 s measured) on 2 quiet cores with the reference cached (6 minutes
    /// under a load average of 9), plus about 4 minutes to render the 8192-spp reference once.
    #[arg(long)]
    pub quick: bool,
}

/// The strategies of the study and their labels (`mis-no-*`: one extra switched off).
fn strategies() -> Vec<(String, Strategy)> {
    let all = MisOptions::default();
    let mut v: Vec<(String, Strategy)> = [
        Strategy::Uniform,
        Strategy::Cosine,
        Strategy::Light,
        Strategy::Mixture,
        Strategy::Mis(all),
    ]
    .iter()
    .map(|s| (s.name().to_string(), *s))
    .collect();
    let toggle = |name: &str, on: bool| {
        if on {
            format!("mis-no-{name}")
        } else {
            format!("mis+{name}")
        }
    };
    for (label, o) in [
        (
            toggle("rr", all.russian_roulette),
            MisOptions {
                russian_roulette: !all.russian_roulette,
                ..all
            },
        ),
        (
            toggle("sph-rect", all.spherical_rectangles),
            MisOptions {
                spherical_rectangles: !all.spherical_rectangles,
                ..all
            },
        ),
        (
            toggle("lds", all.low_discrepancy),
            MisOptions {
                low_discrepancy: !all.low_discrepancy,
                ..all
            },
        ),
        (
            toggle("manifold", all.manifold),
            MisOptions {
                manifold: !all.manifold,
                ..all
            },
        ),
        (
            "mis-plain".to_string(),
            MisOptions {
                russian_roulette: false,
                spherical_rectangles: false,
                low_discrepancy: false,
                manifold: false,
            },
        ),
    ] {
        v.push((label.to_string(), Strategy::Mis(o)));
    }
    v
}

fn settings(width: usize, scene: &Scene, seed: u64, strategy: Strategy) -> RenderSettings {
    RenderSettings {
        width,
        max_depth: scene.max_depth,
        seed,
        strategy,
        mixture_weight: rtl_render::render::BOOK_MIXTURE_WEIGHT,
    }
}

/// The largest reference PFM read: 3 floats a pixel, 2^26 pixels (a render of 8192 x 8192).
const MAX_PFM_BYTES: u64 = 12 << 26;

/// Read a colour PFM as written by `write_linear` (rows bottom to top, little-endian): refused, naming
/// the file and what is wrong with it, unless its header is whole (a positive width and height whose
/// pixels fit in the file, a negative scale: little-endian), and every value is radiance (finite and
/// never negative). A cached reference is trusted for every curve measured against it: one with a NaN
/// gave every RMSE as NaN (the lab's curves stayed empty, without a word), and a header of
/// 2147483648 x 2147483648 pixels panicked on allocation.
fn read_pfm(path: &Path) -> Result<(usize, usize, Vec<Color>)> {
    let bytes = rtl_render::limits::read_regular_file(path, "reference image", MAX_PFM_BYTES)
        .map_err(anyhow::Error::msg)?;
    parse_pfm(&bytes).map_err(|e| {
        anyhow::anyhow!(
            "{}: {e} (a damaged reference: remove it, and `rtl study render` or `rtl lab` renders it \
             again)",
            path.display()
        )
    })
}

/// [`read_pfm`]'s reading of the file's `bytes`.
fn parse_pfm(bytes: &[u8]) -> std::result::Result<(usize, usize, Vec<Color>), String> {
    let mut fields = Vec::new();
    let mut pos = 0;
    while fields.len() < 4 {
        while pos < bytes.len() && bytes[pos].is_ascii_whitespace() {
            pos += 1;
        }
        let start = pos;
        while pos < bytes.len() && !bytes[pos].is_ascii_whitespace() {
            pos += 1;
        }
        if start == pos {
            return Err("truncated PFM header".into());
        }
        fields.push(String::from_utf8_lossy(&bytes[start..pos]).into_owned());
    }
    pos += 1;
    if fields[0] != "PF" {
        return Err("not a colour PFM (it does not start with PF)".into());
    }
    let side = |f: &str, what: &str| match f.parse::<usize>() {
        Ok(n) if n > 0 => Ok(n),
        _ => Err(format!(
            "PFM header field `{what}`: expected a positive integer, got {f:?}"
        )),
    };
    let w = side(&fields[1], "width")?;
    let h = side(&fields[2], "height")?;
    match fields[3].parse::<f64>() {
        Ok(scale) if scale < 0.0 && scale.is_finite() => {}
        _ => {
            return Err(format!(
                "PFM header field `scale`: expected a negative number (little-endian, as rtl \
                 writes), got {:?}",
                fields[3]
            ));
        }
    }
    let data = bytes.get(pos..).unwrap_or_default();
    let values = w.checked_mul(h).and_then(|n| n.checked_mul(3));
    if values.and_then(|n| n.checked_mul(4)) != Some(data.len()) {
        return Err(format!(
            "{} bytes of pixel data where {w} x {h} pixels take {}",
            data.len(),
            values.map_or("more than there are".to_string(), |n| format!(
                "{}",
                n as u128 * 4
            ))
        ));
    }
    let f = |i: usize| f32::from_le_bytes(data[4 * i..4 * i + 4].try_into().unwrap()) as f64;
    let mut px = vec![Color::ZERO; w * h];
    for row in 0..h {
        let j = h - 1 - row;
        for i in 0..w {
            let k = 3 * (row * w + i);
            let c = [f(k), f(k + 1), f(k + 2)];
            if let Some(v) = c.iter().find(|v| !(v.is_finite() && **v >= 0.0)) {
                return Err(format!(
                    "pixel (x {i}, y {j}) is {v}: radiance is finite and never negative"
                ));
            }
            px[j * w + i] = Color::new(c[0], c[1], c[2]);
        }
    }
    Ok((w, h, px))
}

/// The cached reference, or a new one.
pub(crate) fn reference(
    dir: &Path,
    name: &str,
    scene: &Scene,
    width: usize,
    spp: u64,
) -> Result<Vec<Color>> {
    Ok(reference_until(dir, name, scene, width, spp, &|| false)?
        .expect("a reference that is never stopped is made")
        .pixels)
}

/// A reference image, and why it is not in the cache if it could not be written there.
pub(crate) struct ReferenceImage {
    pub pixels: Vec<Color>,
    /// The reason the render could not be cached (it is used all the same).
    pub not_cached: Option<String>,
}

/// [`reference()`] that gives up as soon as `stop()` is true (asked before each pixel of each pass):
/// then `None`, and nothing is written. Unstopped, the same passes as [`reference()`], so the same
/// image bit for bit. A render that cannot be cached (a full disk, a read-only directory) is
/// returned all the same, with the reason: minutes of rendering are not thrown away for it.
pub(crate) fn reference_until(
    dir: &Path,
    name: &str,
    scene: &Scene,
    width: usize,
    spp: u64,
    stop: &(dyn Fn() -> bool + Sync),
) -> Result<Option<ReferenceImage>> {
    let path = dir.join(format!("render-reference-{name}-{width}-{spp}.pfm"));
    if path.exists() {
        let (w, h, px) = read_pfm(&path)?;
        let camera = &Renderer::new(scene, settings(width, scene, 999, Strategy::default())).camera;
        if (w, h) == (camera.width, camera.height) {
            eprintln!("reference: cached {}", path.display());
            return Ok(Some(ReferenceImage {
                pixels: px,
                not_cached: None,
            }));
        }
        eprintln!(
            "reference: {} is {w}x{h}, not {}x{}: rendering it again",
            path.display(),
            camera.width,
            camera.height
        );
    }
    let strategy = Strategy::Mis(MisOptions::default());
    eprintln!("reference: {name} {width} wide, {spp} spp with mis (seed 999) ...");
    let start = Instant::now();
    let r = Renderer::new(scene, settings(width, scene, 999, strategy));
    let mut acc = r.accumulator();
    let mut k = 0;
    while k < spp {
        let k1 = (k + 256).min(spp);
        if r.render_pass_until(&mut acc, k, k1, &|| {}, stop).is_none() {
            eprintln!("\nreference: stopped at {k}/{spp} spp, nothing written");
            return Ok(None);
        }
        k = k1;
        eprint!("\r  {k}/{spp} spp ");
    }
    eprintln!();
    let img = acc.image();
    let not_cached = write_linear(&path, acc.width, acc.height, &img).err();
    if let Some(e) = &not_cached {
        eprintln!("reference: not cached ({e}); used all the same");
    } else if let Err(e) = std::fs::write(
        path.with_extension("txt"),
        format!(
            "Reference for `rtl study render`: `rtl render {name} --width {width} --spp {spp} \
             --strategy mis --seed 999 --linear {}` (linear radiance, {} s on {} threads).\n",
            path.file_name().unwrap().to_string_lossy(),
            start.elapsed().as_secs(),
            rayon::current_num_threads()
        ),
    ) {
        eprintln!(
            "reference: its note {} not written: {e}",
            path.with_extension("txt").display()
        );
    }
    Ok(Some(ReferenceImage {
        pixels: img,
        not_cached,
    }))
}

/// RMSE and relative MSE (`(x - r)^2 / (r^2 + 0.01)`, pbrt's guard) over every pixel and channel.
pub(crate) fn errors(img: &[Color], reference: &[Color]) -> (f64, f64) {
    let (mut se, mut rel) = (0.0, 0.0);
    for (x, r) in img.iter().zip(reference) {
        let d = *x - *r;
        se += d.length_squared();
        rel += (d * d / (*r * *r + Color::splat(0.01))).element_sum();
    }
    let n = 3.0 * img.len() as f64;
    ((se / n).sqrt(), rel / n)
}

pub(crate) fn luminance(c: Color) -> f64 {
    0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z
}

/// Per-pixel variance of one sample's luminance from `spp` samples (its own loop over samples, in
/// parallel over rows).
fn pixel_variance(r: &Renderer, spp: u64) -> Vec<f64> {
    let (w, h) = (r.camera.width, r.camera.height);
    (0..h)
        .into_par_iter()
        .flat_map_iter(|j| {
            let mut ctx = Ctx::new();
            (0..w)
                .map(|i| {
                    let mut stats = RunningStats::new();
                    for k in 0..spp {
                        let v = r.sample(i, j, k, &mut ctx);
                        if v.is_finite() {
                            stats.push(luminance(v));
                        }
                    }
                    stats.variance().unwrap_or(0.0)
                })
                .collect::<Vec<_>>()
        })
        .collect()
}

/// A colour map from 0 (dark blue) through green to 1 (yellow-white).
pub(crate) fn heat(t: f64) -> [u8; 3] {
    let t = t.clamp(0.0, 1.0);
    let stops = [
        (0.0, [0.05, 0.03, 0.25]),
        (0.35, [0.2, 0.3, 0.7]),
        (0.6, [0.1, 0.7, 0.5]),
        (0.85, [0.9, 0.85, 0.2]),
        (1.0, [1.0, 1.0, 0.9]),
    ];
    let mut c = stops[0].1;
    for w in stops.windows(2) {
        let ((t0, a), (t1, b)) = (w[0], w[1]);
        if t >= t0 && t <= t1 {
            let f = (t - t0) / (t1 - t0);
            c = [
                a[0] + f * (b[0] - a[0]),
                a[1] + f * (b[1] - a[1]),
                a[2] + f * (b[2] - a[2]),
            ];
        }
    }
    [
        (c[0] * 255.0) as u8,
        (c[1] * 255.0) as u8,
        (c[2] * 255.0) as u8,
    ]
}

/// How much to enlarge a picture of `width` pixels so that it is at least 360 pixels wide.
fn panel_scale(width: usize) -> usize {
    360usize.div_ceil(width.max(1)).max(2)
}

/// The crop `[x0, x0 + cw) x [y0, y0 + ch)` of an image as gamma-2 RGB bytes.
fn crop(img: &[Color], w: usize, (x0, y0, cw, ch): (usize, usize, usize, usize)) -> Vec<u8> {
    let mut px = Vec::with_capacity(cw * ch);
    for y in y0..y0 + ch {
        for x in x0..x0 + cw {
            px.push(img[y * w + x]);
        }
    }
    to_rgb8(&px, Transfer::Gamma2)
}

struct Row {
    label: String,
    biased: bool,
    /// Mean radiance of the image over the reference's, minus 1: a biased strategy's stays away from 0.
    mean_bias: f64,
    spp: u64,
    seconds: f64,
    rmse: f64,
    rel_mse: f64,
    rmse_display: f64,
    rays_per_sample: f64,
}

/// Whether a strategy is a biased estimator of the image: `light` samples only towards the importance
/// targets, so light arriving from anywhere else is never found (its error stops falling, and the
/// renderer's tests reject it against the unbiased strategies).
fn biased(s: Strategy) -> bool {
    matches!(s, Strategy::Light)
}

/// The label of a strategy in plots and tables: biased ones say so.
fn shown(label: &str) -> String {
    match strategies().into_iter().find(|(l, _)| l == label) {
        Some((_, s)) if biased(s) => format!("{label} (biased: misses indirect light)"),
        _ => label.to_string(),
    }
}

pub fn run(args: RenderArgs) -> Result<()> {
    let b = find(&args.scene).map_err(anyhow::Error::msg)?;
    let scene = (b.build)(&Default::default())
        .map_err(|e| anyhow::anyhow!("scene {}: {e}", b.name))?
        .scene;
    let width = args.width.unwrap_or(if args.quick { 48 } else { 128 });
    let ref_spp = args
        .reference_spp
        .unwrap_or(if args.quick { 1024 } else { 8192 });
    let max_spp = args.max_spp.unwrap_or(if args.quick { 16 } else { 256 });
    let repeat = args.repeat.unwrap_or(if args.quick { 1 } else { 2 });
    if repeat == 0 {
        bail!("--repeat 0: each timing needs at least one run");
    }
    if width < 2 {
        bail!("--width {width}: the study needs an image at least 2 pixels wide");
    }
    if ref_spp == 0 {
        bail!("--reference-spp 0: the reference needs at least one sample per pixel");
    }
    // The sweep is 1, 4, 16, ... spp; the crops are taken at 16.
    if max_spp < 16 || !max_spp.is_power_of_two() || !max_spp.trailing_zeros().is_multiple_of(2) {
        bail!("--max-spp {max_spp}: must be a power of 4, at least 16 (16, 64, 256, ...)");
    }
    // The sweep multiplies by 4 up to --max-spp: past 4^30 that would overflow u64.
    if max_spp > 1 << 60 {
        bail!("--max-spp {max_spp}: at most 4^30 = {}", 1u64 << 60);
    }
    let r = Renderer::new(&scene, settings(width, &scene, 1, Strategy::Cosine));
    rtl_render::limits::check_image(
        r.camera.width,
        r.camera.height,
        rayon::current_num_threads(),
        0,
        &rtl_render::limits::memory_limits(),
    )
    .map_err(|e| anyhow::anyhow!("--width {width}: {e}"))?;
    // (made only once every flag is checked, so that a refused command leaves nothing behind)
    let out_dir = super::out_dir(args.out.clone(), "render")?;
    let mut threads = rayon::current_num_threads();
    if args.replot {
        let (rows, csv_width, csv_threads, csv_ref_spp) = read_rows(&out_dir.join("render.csv"))?;
        threads = csv_threads;
        let mut images = Vec::new();
        for (label, strategy) in strategies() {
            if ["uniform", "cosine", "mixture", "mis"].contains(&label.as_str()) {
                let r = Renderer::new(&scene, settings(csv_width, &scene, 1, strategy));
                let mut acc = r.accumulator();
                r.render_pass(&mut acc, 0, 16, &|| {});
                images.push((label, acc.image()));
            }
        }
        let height = images[0].1.len() / csv_width;
        return figures(
            &args,
            &out_dir,
            b,
            &scene,
            rows,
            images,
            (csv_width, height),
            threads,
            csv_ref_spp,
            false,
        );
    }
    let reference = reference(&out_dir, b.name, &scene, width, ref_spp)?;
    let mut spps = vec![1u64];
    while spps.last().unwrap() * 4 <= max_spp {
        spps.push(spps.last().unwrap() * 4);
    }

    // 2. The sweep: progressive passes, so the time to N spp is the sum of the passes up to N.
    let mut rows: Vec<Row> = Vec::new();
    let mut images: Vec<(String, Vec<Color>)> = Vec::new(); // at 16 spp, for the equal-spp crops
    for (label, strategy) in strategies() {
        let r = Renderer::new(&scene, settings(width, &scene, 1, strategy));
        let mut best: Vec<f64> = vec![f64::INFINITY; spps.len()];
        let mut rays = vec![0u64; spps.len()];
        for _ in 0..repeat {
            let mut acc: Accumulator = r.accumulator();
            let (mut seconds, mut total_rays, mut k0) = (0.0, 0u64, 0u64);
            for (n, &spp) in spps.iter().enumerate() {
                let start = Instant::now();
                let stats = r.render_pass(&mut acc, k0, spp, &|| {});
                seconds += start.elapsed().as_secs_f64();
                total_rays += stats.rays;
                k0 = spp;
                best[n] = best[n].min(seconds);
                rays[n] = total_rays;
                if spp == 16 {
                    images.retain(|(l, _)| l != &label);
                    images.push((label.clone(), acc.image()));
                }
            }
        }
        // The images are the same in every repetition (same seed): errors from a fresh pass per step.
        let mut acc = r.accumulator();
        let mut k0 = 0;
        for (n, &spp) in spps.iter().enumerate() {
            r.render_pass(&mut acc, k0, spp, &|| {});
            k0 = spp;
            let img = acc.image();
            let (rmse, rel_mse) = errors(&img, &reference);
            let clamp =
                |v: &[Color]| -> Vec<Color> { v.iter().map(|c| c.min(Color::ONE)).collect() };
            let rmse_display = errors(&clamp(&img), &clamp(&reference)).0;
            let samples = (acc.width * acc.height) as u64 * spp;
            let seconds = best[n];
            eprintln!("{label:>16} {spp:>5} spp {seconds:>8.3} s  RMSE {rmse:.5}");
            let mean = |v: &[Color]| v.iter().map(|c| c.element_sum()).sum::<f64>();
            rows.push(Row {
                label: label.clone(),
                biased: biased(strategy),
                mean_bias: mean(&img) / mean(&reference) - 1.0,
                spp,
                seconds,
                rmse,
                rel_mse,
                rmse_display,
                rays_per_sample: rays[n] as f64 / samples as f64,
            });
        }
    }
    let mut csv = String::from(
        "strategy,spp,seconds,rmse,rel_mse,rmse_display,rays_per_sample,width,height,threads,reference_spp,biased,mean_bias\n",
    );
    let height = reference.len() / width;
    for r in &rows {
        writeln!(
            csv,
            "{},{},{:.6},{:.6e},{:.6e},{:.6e},{:.4},{width},{height},{threads},{ref_spp},{},{:.5}",
            r.label,
            r.spp,
            r.seconds,
            r.rmse,
            r.rel_mse,
            r.rmse_display,
            r.rays_per_sample,
            r.biased,
            r.mean_bias
        )?;
    }
    std::fs::write(out_dir.join("render.csv"), csv)?;
    figures(
        &args,
        &out_dir,
        b,
        &scene,
        rows,
        images,
        (width, height),
        threads,
        ref_spp,
        true,
    )
}

/// Rows of a render.csv written by an earlier run, with its width, thread count and reference spp.
fn read_rows(path: &Path) -> Result<(Vec<Row>, usize, usize, u64)> {
    let table = CsvTable::read(path)?;
    let col = |name: &str| table.column(name);
    let (c_label, c_spp, c_sec, c_rmse, c_rel, c_disp, c_rays, c_w, c_t, c_ref) = (
        col("strategy")?,
        col("spp")?,
        col("seconds")?,
        col("rmse")?,
        col("rel_mse")?,
        col("rmse_display")?,
        col("rays_per_sample")?,
        col("width")?,
        col("threads")?,
        col("reference_spp")?,
    );
    let c_bias = col("mean_bias").ok();
    let (mut rows, mut width, mut threads, mut ref_spp) = (Vec::new(), 0, 0, 0);
    for row in table.rows() {
        let label = row.text(c_label).to_string();
        let strategy = strategies()
            .into_iter()
            .find(|(l, _)| *l == label)
            .ok_or_else(|| row.invalid(c_label, format!("unknown strategy `{label}`")))?
            .1;
        width = row.value::<usize>(c_w)?;
        threads = row.value::<usize>(c_t)?;
        ref_spp = row.value::<u64>(c_ref)?;
        rows.push(Row {
            label,
            biased: biased(strategy),
            mean_bias: match c_bias {
                Some(c) => row.value::<f64>(c)?,
                None => f64::NAN,
            },
            spp: row.value::<u64>(c_spp)?,
            seconds: row.value::<f64>(c_sec)?,
            rmse: row.value::<f64>(c_rmse)?,
            rel_mse: row.value::<f64>(c_rel)?,
            rmse_display: row.value::<f64>(c_disp)?,
            rays_per_sample: row.value::<f64>(c_rays)?,
        });
    }
    if width < 2 {
        bail!(
            "{}: no measurements to replot (width {width})",
            path.display()
        );
    }
    Ok((rows, width, threads, ref_spp))
}

/// Plots, heat maps, crops and the extrapolation from the sweep's `rows` and its 16-spp `images`.
#[allow(clippy::too_many_arguments)]
fn figures(
    args: &RenderArgs,
    out_dir: &Path,
    b: &rtl_render::scenes::BuiltIn,
    scene: &Scene,
    rows: Vec<Row>,
    images: Vec<(String, Vec<Color>)>,
    (width, height): (usize, usize),
    threads: usize,
    ref_spp: u64,
    write_equal_time_csv: bool,
) -> Result<()> {
    let labels: Vec<String> = strategies().into_iter().map(|(l, _)| l).collect();
    let series = |filter: &dyn Fn(&str) -> bool| -> Vec<Series> {
        labels
            .iter()
            .filter(|l| filter(l))
            .map(|l| Series {
                label: shown(l),
                points: rows
                    .iter()
                    .filter(|r| &r.label == l)
                    .map(|r| (r.seconds, r.rmse))
                    .collect(),
            })
            .collect()
    };
    loglog(
        &out_dir.join("render-study-rmse-time.png"),
        &format!(
            "{} {width}x{height}: RMSE against a {ref_spp}-spp reference ({threads} threads)",
            b.name
        ),
        "seconds",
        "RMSE (linear radiance)",
        &series(&|l: &str| !l.starts_with("mis-") && !l.starts_with("mis+")),
        false,
    )?;
    loglog(
        &out_dir.join("render-study-mis-ablation.png"),
        &format!("{} {width}x{height}: mis with each extra toggled", b.name),
        "seconds",
        "RMSE (linear radiance)",
        &series(&|l: &str| l.starts_with("mis")),
        false,
    )?;

    // 3. Per-pixel variance heat maps (uniform, cosine, mixture, mis), one log scale for all.
    let heat_spp = if args.quick { 16 } else { 64 };
    let main = [
        Strategy::Uniform,
        Strategy::Cosine,
        Strategy::Mixture,
        Strategy::Mis(MisOptions::default()),
    ];
    let variances: Vec<Vec<f64>> = main
        .iter()
        .map(|&s| {
            pixel_variance(
                &Renderer::new(scene, settings(width, scene, 3, s)),
                heat_spp,
            )
        })
        .collect();
    let (lo, hi) = (-4.0f64, 3.0f64); // log10 of the variance
    let panels: Vec<_> = variances
        .iter()
        .map(|v| {
            let rgb: Vec<u8> = v
                .iter()
                .flat_map(|&x| heat(((x.max(1e-12)).log10() - lo) / (hi - lo)))
                .collect();
            (width, height, rgb)
        })
        .zip(main.iter())
        .map(|((w, h, rgb), s)| Panel {
            width: w,
            height: h,
            rgb,
            label: s.name().to_string(),
        })
        .collect();
    image_grid(
        &out_dir.join("render-study-variance.png"),
        &format!(
            "variance of one sample's luminance per pixel ({heat_spp} spp): log scale, 1e-4 dark to 1e3 bright"
        ),
        &panels,
        panel_scale(width),
        2,
    )?;
    let mut vcsv = String::from("strategy,mean_pixel_variance,median_pixel_variance\n");
    for (s, v) in main.iter().zip(&variances) {
        let mut sorted = v.clone();
        sorted.sort_by(f64::total_cmp);
        writeln!(
            vcsv,
            "{},{:.6e},{:.6e}",
            s.name(),
            v.iter().sum::<f64>() / v.len() as f64,
            sorted[sorted.len() / 2]
        )?;
    }
    std::fs::write(out_dir.join("render-variance.csv"), vcsv)?;

    // 4. Crops: the lower half (box, sphere, caustic, floor), at equal spp and at equal time.
    let region = (0, height / 2, width, height / 2);
    let main_labels = ["uniform", "cosine", "mixture", "mis"];
    let panels: Vec<_> = main_labels
        .iter()
        .map(|l| {
            let img = &images.iter().find(|(n, _)| n == l).unwrap().1;
            Panel {
                width: region.2,
                height: region.3,
                rgb: crop(img, width, region),
                label: format!("{l}: 16 spp"),
            }
        })
        .collect();
    image_grid(
        &out_dir.join("render-study-equal-spp.png"),
        &format!(
            "{} {width}x{height}, lower half: equal samples, 16 per pixel",
            b.name
        ),
        &panels,
        panel_scale(width),
        2,
    )?;
    // Equal time: the time mis took for 16 spp (or the largest spp in a quick run); each strategy gets
    // as many samples as fit in it at its measured cost per spp.
    let budget = rows
        .iter()
        .find(|r| r.label == "mis" && r.spp == 16)
        .map(|r| r.seconds)
        .unwrap_or(1.0);
    let mut panels = Vec::new();
    let mut note = String::from("strategy,spp_at_equal_time,seconds_budget\n");
    for l in main_labels {
        let last = rows.iter().rfind(|r| r.label == l).unwrap();
        let per_spp = last.seconds / last.spp as f64;
        let spp = ((budget / per_spp).floor() as u64).max(1);
        let strategy = strategies().into_iter().find(|(n, _)| n == l).unwrap().1;
        let r = Renderer::new(scene, settings(width, scene, 1, strategy));
        let mut acc = r.accumulator();
        r.render_pass(&mut acc, 0, spp, &|| {});
        panels.push(Panel {
            width: region.2,
            height: region.3,
            rgb: crop(&acc.image(), width, region),
            label: format!("{l}: {spp} spp"),
        });
        writeln!(note, "{l},{spp},{budget:.4}")?;
    }
    image_grid(
        &out_dir.join("render-study-equal-time.png"),
        &format!(
            "{} {width}x{height}, lower half: equal time, {budget:.2} s each (what mis takes for 16 spp)",
            b.name
        ),
        &panels,
        panel_scale(width),
        2,
    )?;
    if write_equal_time_csv {
        std::fs::write(out_dir.join("render-equal-time.csv"), note)?;
    }

    // 5. Extrapolation to 600 x 600 and an RMSE of 0.010.
    let target = 0.010;
    let mut table = String::from(
        "strategy,c_rmse_times_sqrt_spp,spp_for_rmse_0.010,seconds_600x600_2_threads,us_per_sample\n",
    );
    println!("To reach RMSE {target} at 600x600 (RMSE ~ c/sqrt(spp), time ~ pixels x spp):");
    println!(
        "{:>16} {:>10} {:>12} {:>12}",
        "strategy", "c", "spp", "seconds"
    );
    for l in &labels {
        let mine: Vec<&Row> = rows.iter().filter(|r| &r.label == l).collect();
        let tail = &mine[mine.len().saturating_sub(2)..];
        let c = tail
            .iter()
            .map(|r| r.rmse * (r.spp as f64).sqrt())
            .sum::<f64>()
            / tail.len() as f64;
        let last = mine.last().unwrap();
        let per_sample = last.seconds / ((width * height) as f64 * last.spp as f64);
        let spp = (c / target).powi(2).ceil();
        let seconds = per_sample * 600.0 * 600.0 * spp;
        if last.biased {
            // its error stops falling: no number of samples reaches the target
            let off = if last.mean_bias.is_finite() {
                format!(
                    ": mean radiance {:+.1}% off the reference",
                    100.0 * last.mean_bias
                )
            } else {
                String::from(": its error stops falling")
            };
            println!("{l:>16} {c:>10.4} {:>12} {:>12}   biased{off}", "-", "-");
            writeln!(table, "{l},{c:.5},biased,biased,{:.4}", per_sample * 1e6)?;
            continue;
        }
        println!("{l:>16} {c:>10.4} {spp:>12.0} {seconds:>12.1}");
        writeln!(
            table,
            "{l},{c:.5},{spp:.0},{seconds:.2},{:.4}",
            per_sample * 1e6
        )?;
    }
    std::fs::write(out_dir.join("render-600.csv"), table)?;
    eprintln!("wrote {}", out_dir.display());
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::parse_pfm;
    use rtl_render::output::write_linear;

    fn pfm(header: &str, values: &[f32]) -> Vec<u8> {
        let mut b = header.as_bytes().to_vec();
        for v in values {
            b.extend_from_slice(&v.to_le_bytes());
        }
        b
    }

    #[test]
    fn a_reference_as_written_is_read_back() {
        let dir = std::env::temp_dir().join(format!("rtl-read-pfm-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("r.pfm");
        let img: Vec<rtl_render::Color> = (0..6)
            .map(|i| rtl_render::Color::new(i as f64, 0.5, 0.25))
            .collect();
        write_linear(&path, 3, 2, &img).unwrap();
        let (w, h, px) = super::read_pfm(&path).unwrap();
        assert_eq!((w, h), (3, 2));
        assert_eq!(px, img);
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// A damaged reference is refused, saying what is wrong, rather than trusted (a NaN made every
    /// RMSE NaN) or allocated (a header of 2^31 x 2^31 pixels panicked on a capacity overflow).
    #[test]
    fn a_damaged_reference_is_refused_not_trusted_nor_allocated() {
        let ok = [0.5f32; 12];
        assert!(parse_pfm(&pfm("PF\n2 2\n-1.0\n", &ok)).is_ok());
        for (bytes, words) in [
            (pfm("PF\n2147483648 2147483648\n-1.0\n", &[]), "pixel data"),
            (pfm("PF\n4294967296 4294967296\n-1.0\n", &[]), "pixel data"),
            (pfm("PF\n0 2\n-1.0\n", &[]), "`width`"),
            (pfm("PF\n2 -2\n-1.0\n", &ok), "`height`"),
            (pfm("PF\n2 2\n1.0\n", &ok), "`scale`"),
            (pfm("PF\n2 2\nnan\n", &ok), "`scale`"),
            (pfm("PF\n2 2\n-1.0\n", &ok[..11]), "pixel data"),
            (pfm("PF\n2 2\n-1.0\n", &[0.5; 13]), "pixel data"),
            (pfm("Pf\n2 2\n-1.0\n", &ok), "not a colour PFM"),
            (pfm("PF\n2 2", &[]), "truncated"),
        ] {
            let e = parse_pfm(&bytes).unwrap_err();
            assert!(e.contains(words), "{e}");
        }
        for bad in [f32::NAN, f32::INFINITY, -1.0] {
            let mut v = ok;
            v[7] = bad;
            let e = parse_pfm(&pfm("PF\n2 2\n-1.0\n", &v)).unwrap_err();
            // value 7 is pixel 2 of the file's rows (bottom to top): x 0 of the top row
            assert!(
                e.contains("pixel (x 0, y 0)") && e.contains("finite"),
                "{e}"
            );
        }
    }
}
