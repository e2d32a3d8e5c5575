//! The Cornell-box bench: a progressive render in a worker thread, restarted at once when a setting
//! changes, stopped when the page stops asking.
//!
//! The worker renders passes (1 spp first, then passes of about [`PASS_TIME`]) on every core (the
//! global rayon pool). Before each pixel it checks the generation counter, bumped by every change of
//! settings, and whether a request about the render has come in the last [`IDLE_AFTER`]: a new
//! generation or an idle page ends the pass at once. After each pass it publishes a frame: the image (the
//! book's gamma 2), the per-pixel variance of one sample's luminance as `rtl study render`'s heat
//! map (log10 from -4 to 3), and a point `(seconds, RMSE)` of the curve of the current settings,
//! against the reference of `rtl study render` at that width (cached in its directory, or rendered
//! once in the background and cached there).
//!
//! Every setting keeps its curve: a render left for other settings is kept (up to [`SAVED_BYTES`]
//! of them, the least recently left forgotten first) and continues where it stopped when its
//! settings come back, its curve with it. One no longer kept is rendered again from its first
//! sample, which gives the same images (sample `k` of a pixel depends only on the seed, the pixel and
//! `k`): its curve waits until the new render passes the curve's end, then goes on from there.
//!
//! The reference is a render too (`mis`, some 1024 spp): its own noise is where every curve
//! flattens, whatever the strategy: the reference's noise floor ([`Floor`]). The bench measures it
//! with a render of the reference's own strategy under another seed: at the reference's spp that
//! render is the reference's twin, and its mean squared error against the reference is twice the
//! reference's variance (the two are independent and alike); at `k` spp before that, with the
//! render's variance falling at least as 1/k (as 1/k for independent samples, faster for
//! low-discrepancy ones), the reference's variance is at most `MSE k / (spp + k)`. The page's own
//! render gives it when it is that strategy at that width (its passes stop at the reference's spp
//! on the way); otherwise a short render of the bench's ([`NOISE_SPP`], seed 998) does.

use super::glue::{self, Settings};
use crate::study::render::{errors, heat, reference_until};
use rtl_mc::RunningStats;
use rtl_render::Color;
use rtl_render::integrator::{MisOptions, Strategy};
use rtl_render::output::{Transfer, to_rgb8};
use rtl_render::render::Accumulator;
use rtl_render::scene::Scene;
use serde::Serialize;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// The aimed-for length of a pass after the first: several frames a second.
pub const PASS_TIME: Duration = Duration::from_millis(150);
/// No request about the render for this long (the page closed or on another bench): stop.
pub const IDLE_AFTER: Duration = Duration::from_secs(3);
/// The most curves kept for comparison.
pub const MAX_CURVES: usize = 16;
/// The most points of one curve (later points replace every other one).
const MAX_POINTS: usize = 400;
/// Widths the page may ask for.
pub const WIDTHS: (usize, usize) = (16, 600);
/// The memory kept for renders left for other settings (about 100 bytes a pixel: 5 of 600 x 600,
/// 50 of 200 x 200).
pub const SAVED_BYTES: usize = 192 << 20;
/// The most samples per pixel of the bench's own measurement of the reference's noise (when the
/// page does not render the reference's strategy at that width), and the most time it takes.
pub const NOISE_SPP: u64 = 64;
pub const NOISE_TIME: Duration = Duration::from_secs(5);
/// The seed of the references of `rtl study render`: a render with it is the reference itself.
const REFERENCE_SEED: u64 = 999;

/// A curve of RMSE against seconds for one setting tried.
#[derive(Clone, Debug, Serialize)]
pub struct Curve {
    pub label: String,
    /// The strategy's name (`uniform` ... `mis`): the page's colour of the curve.
    pub strategy: &'static str,
    pub width: usize,
    /// `(seconds of rendering, spp, RMSE)`.
    pub points: Vec<(f64, u64, f64)>,
}

/// The latest frame of the render.
#[derive(Default)]
pub struct Frame {
    pub id: u64,
    pub generation: u64,
    pub width: usize,
    pub height: usize,
    pub spp: u64,
    pub seconds: f64,
    pub rays_per_second: f64,
    pub rmse: Option<f64>,
    /// This frame continues a render of these settings left earlier (not a fresh one).
    pub resumed: bool,
    pub image_png: Arc<Vec<u8>>,
    pub variance_png: Arc<Vec<u8>>,
}

/// The reference image at one width.
#[derive(Clone)]
pub enum Reference {
    Rendering,
    /// The image, its samples per pixel, and why it is not in the cache if it could not be
    /// written there.
    Ready(Arc<Vec<Color>>, u64, Option<String>),
    /// Why there is none, and when that was found: asked for again [`RETRY_FAILED`] later, it is
    /// tried again (a damaged cached file removed, a directory made writable: seen within seconds,
    /// without restarting the lab).
    Failed(String, Instant),
}

/// How long a failed reference is shown before it is tried again. Every failure that remains
/// comes before any rendering (reading the cache, making its directory; a render that cannot be
/// cached is used all the same), so a retry costs next to nothing.
pub const RETRY_FAILED: Duration = Duration::from_secs(5);

/// The reference's own noise at a width: the RMSE a render would show against it if the render
/// were exact.
#[derive(Clone, Debug, Serialize)]
pub struct Floor {
    pub width: usize,
    /// Samples per pixel of the reference.
    pub reference_spp: u64,
    /// The square root of the reference's variance, averaged over pixels and channels.
    pub rmse: f64,
    /// Measured at this many samples per pixel (the reference's: a measurement; fewer: at most
    /// about this) ...
    pub measured_spp: u64,
    /// ... of this render (a label).
    pub measured_by: String,
}

/// The reference's variance at a width (mean over pixels and channels), and how it was measured.
#[derive(Clone, Debug)]
struct Noise {
    variance: f64,
    spp: u64,
    by: String,
}

/// A render left for other settings, to be continued.
struct Progress {
    acc: Accumulator,
    moments: Vec<RunningStats>,
    seconds: f64,
    rays: u64,
    /// The size of the next pass.
    next: u64,
    /// How its points go onto its curve.
    join: Join,
}

impl Progress {
    fn bytes(&self) -> usize {
        self.acc.sum.len()
            * (std::mem::size_of::<Color>() + 16 + std::mem::size_of::<RunningStats>())
    }
}

/// What the worker, the watchdog and the request handlers share.
pub struct Bench {
    settings: Mutex<Settings>,
    generation: AtomicU64,
    /// When the bench was made: the origin of `last_seen_ms`.
    epoch: Instant,
    /// Milliseconds after `epoch` of the last request about the render ([`NEVER`]: none yet).
    last_seen_ms: AtomicU64,
    pub frame: Mutex<Frame>,
    pub curves: Mutex<Vec<Curve>>,
    /// Bumped by every clear: a render running through one is not kept for later.
    clears: AtomicU64,
    /// Renders left for other settings, by their label (what tells settings of different images
    /// apart), the most recently left last.
    saved: Mutex<Vec<(String, Progress)>>,
    /// The reference's variance, per width.
    noise: Mutex<HashMap<usize, Noise>>,
    references: Mutex<HashMap<usize, Reference>>,
    /// A reference is being rendered (one at a time: the others are asked for again later).
    reference_busy: AtomicBool,
    reference_dir: PathBuf,
    reference_spp: u64,
}

/// `last_seen_ms` before the first request.
const NEVER: u64 = u64::MAX;

/// Held by the thread that renders a reference: when the thread ends, however it ends, the bench is
/// free to render the next one. If it ends by a panic, the reference at `width` is recorded as
/// failed, so that the page says so and asks again after [`RETRY_FAILED`], rather than waiting for a
/// render that will never finish (and the map of references, if the panic left it poisoned, is
/// usable again).
struct ReferenceThread {
    bench: Arc<Bench>,
    width: usize,
}

impl Drop for ReferenceThread {
    fn drop(&mut self) {
        if std::thread::panicking() {
            let references = &self.bench.references;
            let mut refs = references.lock().unwrap_or_else(|e| e.into_inner());
            let why = "the reference's render stopped on an internal error (a panic: its message \
                       is on the terminal)";
            refs.insert(self.width, Reference::Failed(why.into(), Instant::now()));
            drop(refs);
            references.clear_poison();
        }
        self.bench.reference_busy.store(false, Ordering::SeqCst);
    }
}

/// A number for a label: the shortest decimal that reads back as `x` (`0.2`, `0.0001`), or in
/// scientific notation when that decimal would be long (`1e-320` rather than 0.000...0001).
fn readable(x: f64) -> String {
    if x == 0.0 || (1e-4..1e6).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// A label of the settings, for a curve's legend.
pub fn label(s: &Settings) -> String {
    let name = match s.strategy {
        Strategy::Mis(o) => {
            let mut l = String::from("mis");
            for (on, what) in [
                (o.russian_roulette, "rr"),
                (o.low_discrepancy, "lds"),
                (o.spherical_rectangles, "sph-rect"),
            ] {
                if on {
                    l.push('+');
                    l.push_str(what);
                }
            }
            l
        }
        // The weight only where it is not the book's 50/50.
        Strategy::Mixture if s.mixture_weight != rtl_render::render::BOOK_MIXTURE_WEIGHT => {
            format!("mixture w={}", readable(s.mixture_weight))
        }
        other => other.name().to_string(),
    };
    // The depth only where it is not the book's, but always apart: curves are kept by label.
    let depth = if s.max_depth == glue::BOOK_DEPTH {
        String::new()
    } else {
        format!(" depth {}", s.max_depth)
    };
    format!("{name} seed {} {}px{depth}", s.seed, s.width)
}

/// Whether `s` renders as the references of `rtl study render` do (`mis` with its default extras at
/// the book's depth, as `study::render::reference_until`), under another seed: a render
/// independent of the reference and alike.
fn renders_like_the_reference(s: &Settings) -> bool {
    s.strategy == Strategy::Mis(MisOptions::default())
        && s.max_depth == glue::BOOK_DEPTH
        && s.seed != REFERENCE_SEED
}

/// The reference's variance from the mean squared error `mse` against it of a render like it (and
/// independent of it) at `k` spp, for a reference of `spp`: the render's variance at `k`, at least
/// the reference's times `spp / k`, plus the reference's.
fn reference_variance(mse: f64, k: u64, spp: u64) -> f64 {
    mse * k as f64 / (spp + k) as f64
}

/// The spp of the best reference cached in `dir` at `width` (`rtl study render`'s file names): of
/// the regular files (or links to one) so named, with a number of samples `--reference-spp` would
/// take (1 to [`super::MAX_REFERENCE_SPP`]). A name is no promise: a dangling link named for 2^64 - 1
/// spp had the lab render a reference that never ends.
fn cached_reference_spp(dir: &Path, width: usize) -> Option<u64> {
    let prefix = format!("render-reference-{}-{width}-", glue::SCENE);
    std::fs::read_dir(dir)
        .ok()?
        .filter_map(|e| {
            let e = e.ok()?;
            let name = e.file_name().into_string().ok()?;
            let spp = name
                .strip_prefix(&prefix)?
                .strip_suffix(".pfm")?
                .parse::<u64>()
                .ok()?;
            let file = std::fs::metadata(e.path()).ok()?.is_file();
            (file && (1..=super::MAX_REFERENCE_SPP).contains(&spp)).then_some(spp)
        })
        .max()
}

impl Bench {
    pub fn new(initial: Settings, reference_dir: PathBuf, reference_spp: u64) -> Bench {
        Bench {
            settings: Mutex::new(initial),
            generation: AtomicU64::new(1),
            epoch: Instant::now(),
            last_seen_ms: AtomicU64::new(NEVER),
            frame: Mutex::new(Frame::default()),
            curves: Mutex::new(Vec::new()),
            clears: AtomicU64::new(0),
            saved: Mutex::new(Vec::new()),
            noise: Mutex::new(HashMap::new()),
            references: Mutex::new(HashMap::new()),
            reference_busy: AtomicBool::new(false),
            reference_dir,
            reference_spp,
        }
    }

    pub fn settings(&self) -> Settings {
        *self.settings.lock().unwrap()
    }

    pub fn generation(&self) -> u64 {
        self.generation.load(Ordering::SeqCst)
    }

    /// New settings: the render switches to them at once (continuing their render if one was left
    /// earlier). Settings that render the same image (the same label: the mixture weight with
    /// another strategy, say) are kept for later but change nothing now.
    pub fn set(&self, s: Settings) -> u64 {
        self.touch();
        let mut current = self.settings.lock().unwrap();
        let same = label(&current) == label(&s);
        *current = s;
        if same {
            return self.generation();
        }
        self.generation.fetch_add(1, Ordering::SeqCst) + 1
    }

    /// The page is watching: keep rendering.
    pub fn touch(&self) {
        self.last_seen_ms.store(self.now_ms(), Ordering::SeqCst);
    }

    /// No request about the render for [`IDLE_AFTER`] (the page closed or is on another bench).
    pub fn is_idle(&self) -> bool {
        let last = self.last_seen_ms.load(Ordering::SeqCst);
        last == NEVER || self.now_ms().saturating_sub(last) > IDLE_AFTER.as_millis() as u64
    }

    /// Whether the bench is using the cores: the render (its page watching) or a reference.
    pub fn is_busy(&self) -> bool {
        !self.is_idle() || self.reference_busy.load(Ordering::SeqCst)
    }

    fn now_ms(&self) -> u64 {
        self.epoch.elapsed().as_millis() as u64
    }

    /// Forget every curve and every render left for later, and start the current render again from
    /// its first sample: a clean slate.
    pub fn clear_curves(&self) -> u64 {
        self.clears.fetch_add(1, Ordering::SeqCst);
        self.saved.lock().unwrap().clear();
        self.curves.lock().unwrap().clear();
        self.touch();
        self.generation.fetch_add(1, Ordering::SeqCst) + 1
    }

    /// Keep `p`, the render of `s` left for other settings, forgetting the least recently left ones
    /// beyond [`SAVED_BYTES`]; not if the curves were cleared since `clears` (the render began).
    fn save(&self, s: Settings, p: Progress, clears: u64) {
        let mut saved = self.saved.lock().unwrap();
        if p.acc.samples == 0 || self.clears.load(Ordering::SeqCst) != clears {
            return;
        }
        let key = label(&s);
        saved.retain(|(k, _)| *k != key);
        saved.push((key, p));
        while saved.len() > 1 && saved.iter().map(|(_, p)| p.bytes()).sum::<usize>() > SAVED_BYTES {
            saved.remove(0);
        }
    }

    /// The render of `s` left earlier, if it is kept.
    fn take_saved(&self, s: &Settings) -> Option<Progress> {
        let mut saved = self.saved.lock().unwrap();
        let key = label(s);
        let i = saved.iter().position(|(k, _)| *k == key)?;
        Some(saved.remove(i).1)
    }

    /// A measurement of the reference's variance at `width` by a render of `spp`: kept if it has
    /// more samples than the one before.
    fn record_noise(&self, width: usize, variance: f64, spp: u64, by: String) {
        let mut noise = self.noise.lock().unwrap();
        if noise.get(&width).is_none_or(|n| n.spp < spp) {
            noise.insert(width, Noise { variance, spp, by });
        }
    }

    /// The reference's noise floor at every width that has a reference and a measurement.
    pub fn floors(&self) -> Vec<Floor> {
        let noise = self.noise.lock().unwrap();
        let refs = self.references.lock().unwrap();
        let mut floors: Vec<Floor> = refs
            .iter()
            .filter_map(|(&width, r)| {
                let Reference::Ready(_, spp, _) = r else {
                    return None;
                };
                let n = noise.get(&width)?;
                Some(Floor {
                    width,
                    reference_spp: *spp,
                    rmse: n.variance.sqrt(),
                    measured_spp: n.spp,
                    measured_by: n.by.clone(),
                })
            })
            .collect();
        floors.sort_by_key(|f| f.width);
        floors
    }

    /// The samples per pixel of the reference at `width`: the one in use, or the one that will be.
    pub fn reference_spp(&self, width: usize) -> u64 {
        match self.references.lock().unwrap().get(&width) {
            Some(Reference::Ready(_, spp, _)) => *spp,
            _ => cached_reference_spp(&self.reference_dir, width).unwrap_or(self.reference_spp),
        }
    }

    /// Add a point of the render of `s` to its curve; `join` is the render's way onto a curve kept
    /// from before.
    fn add_point(&self, s: &Settings, point: (f64, u64, f64), join: &mut Join) {
        let label = label(s);
        let mut curves = self.curves.lock().unwrap();
        let i = match curves.iter().position(|c| c.label == label) {
            Some(i) => i,
            None => {
                if curves.len() >= MAX_CURVES {
                    curves.remove(0);
                }
                curves.push(Curve {
                    label,
                    strategy: s.strategy.name(),
                    width: s.width,
                    points: Vec::new(),
                });
                curves.len() - 1
            }
        };
        let c = &mut curves[i];
        let (seconds, spp, rmse) = point;
        let last = c.points.last().copied();
        let offset = match (join.offset, last) {
            (_, None) => *join.offset.get_or_insert(0.0),
            // The curve goes on only past its end (a render again from the first sample repeats
            // the images of the curve's points), later in time by as much as it has already taken.
            (None, Some((t, k, _))) => {
                if spp <= k {
                    (join.base, join.base_spp) = (seconds, spp);
                    return;
                }
                // When this render passed the curve's end, at the pace of its last pass.
                let f = (k - join.base_spp) as f64 / (spp - join.base_spp) as f64;
                let passed = join.base + (seconds - join.base) * f;
                *join.offset.get_or_insert(t - passed)
            }
            (Some(o), Some((_, k, _))) => {
                if spp <= k {
                    return;
                }
                o
            }
        };
        if c.points.len() >= MAX_POINTS {
            let kept: Vec<_> = c.points.iter().copied().step_by(2).collect();
            c.points = kept;
        }
        c.points.push((seconds + offset, spp, rmse));
    }

    /// The state of the reference at `width`, starting its render if there is none and no other
    /// reference is being rendered (then it is asked for again after the next pass). So at most one
    /// thread renders references, and none waits.
    pub fn reference(self: &Arc<Self>, scene: &Arc<Scene>, width: usize) -> Reference {
        let mut refs = self.references.lock().unwrap();
        match refs.get(&width) {
            Some(Reference::Failed(_, at)) if at.elapsed() >= RETRY_FAILED => {}
            Some(r) => return r.clone(),
            None => {}
        }
        if self.reference_busy.swap(true, Ordering::SeqCst) {
            return Reference::Rendering;
        }
        refs.insert(width, Reference::Rendering);
        let (me, scene) = (Arc::clone(self), Arc::clone(scene));
        let spawned = std::thread::Builder::new()
            .name("reference".into())
            .spawn(move || me.render_reference(&scene, width));
        match spawned {
            Ok(_) => Reference::Rendering,
            // No thread (the process's or the system's limit): shown as the page shows any
            // failure, and tried again later like one.
            Err(e) => {
                let failed = Reference::Failed(
                    format!("cannot start the reference's thread: {e}"),
                    Instant::now(),
                );
                refs.insert(width, failed.clone());
                self.reference_busy.store(false, Ordering::SeqCst);
                failed
            }
        }
    }

    /// The reference's thread: render it at `width` (or read it from the cache), record it, and
    /// measure its noise where that is not known.
    fn render_reference(self: &Arc<Self>, scene: &Scene, width: usize) {
        let _done = ReferenceThread {
            bench: Arc::clone(self),
            width,
        };
        let dir = &self.reference_dir;
        let spp = cached_reference_spp(dir, width).unwrap_or(self.reference_spp);
        // Stopped when nobody watches: the page closed, or went to another bench.
        let stop = || self.is_idle();
        // A pool of its own: in the render's pool its long passes would hold up the frames
        // (rayon runs one injected job after another); beside it, the two share the cores.
        let pool = rayon::ThreadPoolBuilder::new()
            .thread_name(|i| format!("reference-{i}"))
            .build()
            .map_err(anyhow::Error::from);
        let result = pool
            .as_ref()
            .map_err(|e| anyhow::anyhow!("{e:#}"))
            .and_then(|pool| {
                std::fs::create_dir_all(dir).map_err(|e| {
                    anyhow::anyhow!("cannot create the directory {}: {e}", dir.display())
                })?;
                pool.install(|| reference_until(dir, glue::SCENE, scene, width, spp, &stop))
            });
        let mut ready = None;
        {
            let mut refs = self.references.lock().unwrap();
            match result {
                Ok(Some(img)) => {
                    let pixels = Arc::new(img.pixels);
                    ready = Some(Arc::clone(&pixels));
                    refs.insert(width, Reference::Ready(pixels, spp, img.not_cached));
                }
                // Asked for again (from the start) when the page is back.
                Ok(None) => {
                    refs.remove(&width);
                }
                Err(e) => {
                    refs.insert(width, Reference::Failed(format!("{e:#}"), Instant::now()));
                }
            }
        }
        // The reference's noise: measured here unless it is known or the render will measure
        // it (it renders like the reference at this width, and has not passed its spp).
        let measured = self.noise.lock().unwrap().contains_key(&width);
        let current = self.settings();
        let by_render = current.width == width
            && renders_like_the_reference(&current)
            && self.frame.lock().unwrap().spp < spp;
        if let (Some(reference), false, false, Ok(pool)) = (ready, measured, by_render, &pool) {
            pool.install(|| self.measure_noise(scene, width, &reference, spp, &stop));
        }
    }

    /// Render the reference's strategy at `width` under seed 998 (the reference's is 999, the
    /// page's 1), for up to [`NOISE_SPP`] samples or [`NOISE_TIME`], and record the reference's
    /// variance its error gives.
    fn measure_noise(
        &self,
        scene: &Scene,
        width: usize,
        reference: &[Color],
        spp: u64,
        stop: &(dyn Fn() -> bool + Sync),
    ) {
        let s = Settings {
            width,
            strategy: Strategy::Mis(MisOptions::default()),
            seed: 998,
            max_depth: glue::BOOK_DEPTH,
            mixture_weight: rtl_render::render::BOOK_MIXTURE_WEIGHT,
        };
        let r = glue::renderer(scene, &s);
        let mut acc = r.accumulator();
        let mut moments = vec![RunningStats::new(); acc.sum.len()];
        let start = Instant::now();
        let most = NOISE_SPP.min(spp);
        while acc.samples < most && start.elapsed() < NOISE_TIME {
            let (k0, k1) = (acc.samples, (acc.samples + 8).min(most));
            if glue::pass(&r, &mut acc, &mut moments, k0, k1, stop).is_none() {
                return;
            }
        }
        let img = acc.image();
        if acc.samples > 0 && img.len() == reference.len() {
            let rmse = errors(&img, reference).0;
            let v = reference_variance(rmse * rmse, acc.samples, spp);
            self.record_noise(width, v, acc.samples, label(&s));
        }
    }

    /// A description of the reference at `width` for the page.
    pub fn reference_note(&self, width: usize) -> String {
        match self.references.lock().unwrap().get(&width) {
            None if self.reference_busy.load(Ordering::SeqCst) => {
                "waiting: a reference at another width is being rendered".into()
            }
            None => "not asked for yet".into(),
            Some(Reference::Rendering) => format!(
                "rendering the reference ({} spp of mis, seed 999) in {}: curves start when it is done",
                cached_reference_spp(&self.reference_dir, width).unwrap_or(self.reference_spp),
                self.reference_dir.display()
            ),
            Some(Reference::Ready(_, spp, None)) => format!(
                "a {spp}-spp render with mis (seed 999), {}/render-reference-{}-{width}-{spp}.pfm (rtl study render's)",
                self.reference_dir.display(),
                glue::SCENE,
            ),
            Some(Reference::Ready(_, spp, Some(e))) => format!(
                "a {spp}-spp render with mis (seed 999), kept in memory only (not cached: {e})"
            ),
            Some(Reference::Failed(e, _)) => format!(
                "no reference: {e} (tried again {} s after, while this page is open)",
                RETRY_FAILED.as_secs()
            ),
        }
    }
}

/// How a render's points go onto its curve: `offset` is added to its seconds, once known (0 on a
/// curve of its own; at its first point past the end of a curve kept from an earlier render of the
/// same settings, what makes it follow that curve in time); `base` and `base_spp` are its seconds
/// and spp at its last point before that end.
struct Join {
    offset: Option<f64>,
    base: f64,
    base_spp: u64,
}

fn png(width: usize, height: usize, rgb: Vec<u8>) -> Vec<u8> {
    let mut out = Vec::new();
    let img = image::RgbImage::from_raw(width as u32, height as u32, rgb).expect("w * h * 3 bytes");
    img.write_to(&mut std::io::Cursor::new(&mut out), image::ImageFormat::Png)
        .expect("PNG into memory");
    out
}

/// The variance map: log10 of each pixel's variance of one sample's luminance, from -4 to 3.
fn variance_rgb(moments: &[RunningStats]) -> Vec<u8> {
    let (lo, hi) = (-4.0f64, 3.0f64);
    moments
        .iter()
        .flat_map(|m| {
            let v = m.variance().unwrap_or(0.0);
            heat((v.max(1e-12).log10() - lo) / (hi - lo))
        })
        .collect()
}

/// The render worker: forever, render the current settings while the page watches.
pub fn worker(bench: Arc<Bench>, scene: Arc<Scene>) {
    loop {
        if bench.is_idle() {
            std::thread::sleep(Duration::from_millis(50));
            continue;
        }
        let generation = bench.generation();
        let settings = bench.settings();
        render_generation(&bench, &scene, generation, settings);
    }
}

/// Render `s` (continuing its render left earlier, if kept) until the settings change; then keep
/// it for later.
fn render_generation(bench: &Arc<Bench>, scene: &Arc<Scene>, generation: u64, s: Settings) {
    let clears = bench.clears.load(Ordering::SeqCst);
    let r = glue::renderer(scene, &s);
    let (w, h) = (r.camera.width, r.camera.height);
    let mut p = bench.take_saved(&s).unwrap_or_else(|| Progress {
        acc: r.accumulator(),
        moments: vec![RunningStats::new(); w * h],
        seconds: 0.0,
        rays: 0,
        next: 1,
        join: Join {
            offset: None,
            base: 0.0,
            base_spp: 0,
        },
    });
    let resumed = p.acc.samples > 0;
    let mut backup = (p.acc.clone(), p.moments.clone());
    let stop = || bench.generation() != generation || bench.is_idle();
    let by = label(&s);
    // Like the reference: a pass ends at the reference's spp, where the render is its twin.
    let twin_at = renders_like_the_reference(&s).then(|| bench.reference_spp(w));
    loop {
        if bench.generation() != generation {
            break;
        }
        if bench.is_idle() {
            // Wait for the page, then carry on with this render.
            std::thread::sleep(Duration::from_millis(50));
            continue;
        }
        let (k0, mut k1) = (p.acc.samples, p.acc.samples + p.next);
        if let Some(spp) = twin_at.filter(|&spp| k0 < spp) {
            k1 = k1.min(spp);
        }
        backup.0.clone_from(&p.acc);
        backup.1.clone_from(&p.moments);
        let t0 = Instant::now();
        let Some(stats) = glue::pass(&r, &mut p.acc, &mut p.moments, k0, k1, &stop) else {
            // Stopped half-way: keep the whole passes only.
            std::mem::swap(&mut p.acc, &mut backup.0);
            std::mem::swap(&mut p.moments, &mut backup.1);
            continue;
        };
        let t = t0.elapsed().as_secs_f64();
        p.seconds += t;
        p.rays += stats.rays;
        // The next pass: about PASS_TIME long, at most twice the last.
        let per_spp = t / (k1 - k0) as f64;
        let fit = (PASS_TIME.as_secs_f64() / per_spp.max(1e-12)).floor() as u64;
        p.next = fit.clamp(1, p.next.saturating_mul(2));
        // Finished just as the settings changed: a pass kept for later, shown to nobody.
        if bench.generation() != generation {
            break;
        }
        let img = p.acc.image();
        let rmse = match bench.reference(scene, w) {
            Reference::Ready(reference, spp, _) if reference.len() == img.len() => {
                let rmse = errors(&img, &reference).0;
                if twin_at.is_some() && p.acc.samples <= spp {
                    let v = reference_variance(rmse * rmse, p.acc.samples, spp);
                    bench.record_noise(w, v, p.acc.samples, by.clone());
                }
                Some(rmse)
            }
            _ => None,
        };
        if let Some(rmse) = rmse {
            bench.add_point(&s, (p.seconds, p.acc.samples, rmse), &mut p.join);
        }
        let image_png = png(w, h, to_rgb8(&img, Transfer::Gamma2));
        let variance_png = png(w, h, variance_rgb(&p.moments));
        {
            let mut f = bench.frame.lock().unwrap();
            *f = Frame {
                id: f.id + 1,
                generation,
                width: w,
                height: h,
                spp: p.acc.samples,
                seconds: p.seconds,
                rays_per_second: p.rays as f64 / p.seconds.max(1e-9),
                rmse,
                resumed,
                image_png: Arc::new(image_png),
                variance_png: Arc::new(variance_png),
            };
        }
    }
    bench.save(s, p, clears);
}

#[cfg(test)]
mod tests {
    use super::*;
    use rtl_render::integrator::Strategy;

    #[test]
    fn every_setting_has_a_label_of_its_own() {
        let s = Settings {
            width: 16,
            strategy: Strategy::Cosine,
            seed: 1,
            max_depth: glue::BOOK_DEPTH,
            mixture_weight: 0.5,
        };
        let others = [
            Settings { width: 32, ..s },
            Settings { seed: 2, ..s },
            Settings { max_depth: 5, ..s },
            Settings {
                strategy: Strategy::Uniform,
                ..s
            },
            Settings {
                strategy: glue::strategy("mis", true, false, false).unwrap(),
                ..s
            },
            Settings {
                strategy: glue::strategy("mis", false, false, false).unwrap(),
                ..s
            },
            Settings {
                strategy: Strategy::Mixture,
                ..s
            },
            Settings {
                strategy: Strategy::Mixture,
                mixture_weight: 0.2,
                ..s
            },
        ];
        let mut labels: Vec<String> = others.iter().map(label).collect();
        labels.push(label(&s));
        assert_eq!(label(&others[6]), "mixture seed 1 16px");
        assert_eq!(label(&others[7]), "mixture w=0.2 seed 1 16px");
        let tiny = Settings {
            mixture_weight: 1e-320,
            ..others[7]
        };
        assert_eq!(label(&tiny), "mixture w=1e-320 seed 1 16px");
        for (x, text) in [
            (0.999, "0.999"),
            (0.0001, "0.0001"),
            (0.00005, "5e-5"),
            (1.5e-7, "1.5e-7"),
            (f64::MIN_POSITIVE, "2.2250738585072014e-308"),
            (5e-324, "5e-324"),
        ] {
            assert_eq!(readable(x), text);
        }
        let n = labels.len();
        labels.sort();
        labels.dedup();
        assert_eq!(labels.len(), n, "{labels:?}");
    }

    #[test]
    fn a_setting_change_restarts_and_idleness_stops() {
        let scene = Arc::new(glue::scene().unwrap());
        let dir = std::env::temp_dir().join(format!("rtl-lab-test-{}", std::process::id()));
        let s = cosine_16();
        let bench = Arc::new(Bench::new(s, dir.clone(), 16));
        {
            let b = Arc::clone(&bench);
            let sc = Arc::clone(&scene);
            std::thread::spawn(move || worker(b, sc));
        }
        let wait_for = |what: &dyn Fn(&Frame) -> bool| {
            let start = Instant::now();
            while start.elapsed() < Duration::from_secs(60) {
                bench.touch();
                if what(&bench.frame.lock().unwrap()) {
                    return true;
                }
                std::thread::sleep(Duration::from_millis(20));
            }
            false
        };
        let g = bench.set(s);
        assert!(wait_for(&|f| f.generation == g && f.spp >= 2));
        assert!(wait_for(&|f| f.generation == g && f.rmse.is_some()));
        let g2 = bench.set(Settings {
            strategy: Strategy::Uniform,
            ..s
        });
        assert!(g2 > g);
        assert!(wait_for(&|f| f.generation == g2 && f.rmse.is_some()));
        assert!(
            bench
                .curves
                .lock()
                .unwrap()
                .iter()
                .any(|c| c.label == label(&bench.settings()))
        );
        // Back to cosine: its render continues where it stopped, and so does its curve.
        let cosine_spp = bench
            .curves
            .lock()
            .unwrap()
            .iter()
            .find(|c| c.label == label(&s))
            .map(|c| c.points.last().unwrap().1);
        let g3 = bench.set(s);
        assert!(wait_for(&|f| f.generation == g3));
        let f = bench.frame.lock().unwrap();
        assert!(f.resumed && f.spp > cosine_spp.unwrap_or(2), "{}", f.spp);
        drop(f);
        // The same settings again change nothing.
        assert_eq!(bench.set(s), g3);
        // Cleared while it runs: every curve goes, and the render starts again from its first sample.
        let g4 = bench.clear_curves();
        assert!(g4 > g3);
        assert!(wait_for(&|f| f.generation == g4 && f.rmse.is_some()));
        let curves = bench.curves.lock().unwrap().clone();
        assert_eq!(curves.len(), 1, "{curves:?}");
        assert_eq!(curves[0].label, label(&s));
        assert!(!bench.frame.lock().unwrap().resumed);
        assert!(curves[0].points[0].1 <= 2, "{curves:?}");
        // Nobody asks: the passes stop.
        bench.last_seen_ms.store(NEVER, Ordering::SeqCst);
        std::thread::sleep(Duration::from_millis(300));
        let spp = bench.frame.lock().unwrap().spp;
        std::thread::sleep(Duration::from_millis(500));
        assert_eq!(bench.frame.lock().unwrap().spp, spp);
        let _ = std::fs::remove_dir_all(dir);
    }

    /// A curve is continued, never replaced: a render again from the first sample adds nothing until
    /// it passes the curve's end, then follows it in time.
    #[test]
    fn a_curve_kept_from_before_is_joined_past_its_end() {
        let s = Settings {
            width: 16,
            strategy: Strategy::Light,
            seed: 1,
            max_depth: 50,
            mixture_weight: 0.5,
        };
        let bench = Bench::new(s, std::env::temp_dir(), 16);
        let fresh = || Join {
            offset: None,
            base: 0.0,
            base_spp: 0,
        };
        let mut first = fresh();
        for (t, k) in [(0.1, 1), (0.3, 4), (1.0, 16)] {
            bench.add_point(&s, (t, k, 1.0 / k as f64), &mut first);
        }
        // Rendered again: 1, 4 and 8 spp (skipped: the curve has them, or has passed them), then 32
        // spp at 1.5 s of its own. From 8 spp at 0.8 s to 32 at 1.5 s, it passed the curve's end (16
        // spp) at 0.8 + 0.7 / 3: its later points go 1.0 - that later than its own seconds.
        let mut again = fresh();
        for (t, k) in [(0.05, 1), (0.2, 4), (0.8, 8), (1.5, 32), (2.0, 64)] {
            bench.add_point(&s, (t, k, 1.0 / k as f64), &mut again);
        }
        let curves = bench.curves.lock().unwrap();
        assert_eq!(curves.len(), 1);
        let spp: Vec<u64> = curves[0].points.iter().map(|p| p.1).collect();
        assert_eq!(spp, [1, 4, 16, 32, 64]);
        let t: Vec<f64> = curves[0].points.iter().map(|p| p.0).collect();
        let shift = 1.0 - (0.8 + 0.7 / 3.0);
        assert!((t[3] - (1.5 + shift)).abs() < 1e-12, "{t:?}");
        assert!((t[4] - (2.0 + shift)).abs() < 1e-12, "{t:?}");
        assert_eq!(curves[0].strategy, "light");
    }

    /// A render like the reference at the reference's spp is its twin: MSE = 2 variances; before,
    /// its variance is (for 1/k) spp / k times the reference's.
    #[test]
    fn the_reference_variance_from_a_render_like_it() {
        let v = 1e-5;
        assert!((reference_variance(2.0 * v, 1024, 1024) - v).abs() < 1e-18);
        let k = 64;
        let mse = v * 1024.0 / k as f64 + v;
        assert!((reference_variance(mse, k, 1024) - v).abs() < 1e-18);
        let s = Settings {
            width: 64,
            strategy: Strategy::default(),
            seed: 1,
            max_depth: glue::BOOK_DEPTH,
            mixture_weight: 0.2,
        };
        assert!(renders_like_the_reference(&s));
        assert!(!renders_like_the_reference(&Settings { seed: 999, ..s }));
        assert!(!renders_like_the_reference(&Settings { max_depth: 5, ..s }));
        let no_rr = glue::strategy("mis", false, true, false).unwrap();
        assert!(!renders_like_the_reference(&Settings {
            strategy: no_rr,
            ..s
        }));
    }

    #[test]
    fn a_reference_stops_when_nobody_watches() {
        let scene = Arc::new(glue::scene().unwrap());
        let dir = std::env::temp_dir().join(format!("rtl-lab-ref-test-{}", std::process::id()));
        let s = cosine_16();
        // Far more samples than a test could wait for: only a stop ends it.
        let bench = Arc::new(Bench::new(s, dir.clone(), 1 << 40));
        bench.touch();
        assert!(matches!(bench.reference(&scene, 16), Reference::Rendering));
        std::thread::sleep(Duration::from_millis(200));
        assert!(
            bench.reference_busy.load(Ordering::SeqCst),
            "still rendering"
        );
        bench.last_seen_ms.store(NEVER, Ordering::SeqCst);
        let start = Instant::now();
        while bench.reference_busy.load(Ordering::SeqCst) {
            assert!(
                start.elapsed() < Duration::from_secs(60),
                "the reference went on"
            );
            std::thread::sleep(Duration::from_millis(20));
        }
        // Forgotten, to be asked for again; nothing written.
        assert!(bench.references.lock().unwrap().get(&16).is_none());
        let written = std::fs::read_dir(&dir).map_or(0, |d| d.count());
        assert_eq!(written, 0);
        let _ = std::fs::remove_dir_all(dir);
    }

    /// A reference thread that panics (here while it holds the map of references) leaves the bench
    /// free, the reference failed with a message, and the map usable; then it is not tried again
    /// before [`RETRY_FAILED`].
    #[test]
    fn a_panic_in_the_reference_thread_frees_the_bench() {
        let scene = Arc::new(glue::scene().unwrap());
        let dir = std::env::temp_dir().join(format!("rtl-lab-ref-panic-{}", std::process::id()));
        let bench = Arc::new(Bench::new(cosine_16(), dir.clone(), 4));
        bench.reference_busy.store(true, Ordering::SeqCst);
        bench
            .references
            .lock()
            .unwrap()
            .insert(16, Reference::Rendering);
        let me = Arc::clone(&bench);
        let thread = std::thread::spawn(move || {
            let _done = ReferenceThread {
                bench: Arc::clone(&me),
                width: 16,
            };
            let _held = me.references.lock().unwrap();
            panic!("a bug in the reference's render");
        });
        assert!(thread.join().is_err());
        assert!(!bench.reference_busy.load(Ordering::SeqCst));
        assert!(!bench.references.is_poisoned());
        match bench.reference(&scene, 16) {
            Reference::Failed(why, _) => assert!(why.contains("panic"), "{why}"),
            _ => panic!("not recorded as failed"),
        }
        assert!(
            bench.reference_note(16).contains("panic"),
            "{}",
            bench.reference_note(16)
        );
        assert!(
            !bench.reference_busy.load(Ordering::SeqCst),
            "tried again at once"
        );
        let _ = std::fs::remove_dir_all(dir);
    }

    /// Wait (at most a minute) until the reference at `width` is no longer being rendered.
    fn settled(bench: &Arc<Bench>, scene: &Arc<Scene>, width: usize) -> Reference {
        let start = Instant::now();
        loop {
            let r = bench.reference(scene, width);
            if !matches!(r, Reference::Rendering) {
                return r;
            }
            assert!(start.elapsed() < Duration::from_secs(60), "no reference");
            std::thread::sleep(Duration::from_millis(20));
        }
    }

    /// `cosine` at 16 pixels wide: the tests' render that takes next to no time.
    fn cosine_16() -> Settings {
        Settings {
            width: 16,
            strategy: Strategy::Cosine,
            seed: 1,
            max_depth: 50,
            mixture_weight: 0.5,
        }
    }

    fn tiny_reference_bench(dir: &Path) -> Arc<Bench> {
        let s = cosine_16();
        let bench = Arc::new(Bench::new(s, dir.to_path_buf(), 1));
        bench.touch();
        bench
    }

    /// A cached reference counts by its name only if it is a file and its spp one `--reference-spp`
    /// takes: a dangling link named for 2^64 - 1 spp, a directory, and a file named for two million
    /// are passed over for the file of 64 beside them (the dangling link had the lab render a
    /// reference that never ends).
    #[test]
    fn cached_references_are_files_of_a_number_of_samples_the_flag_takes() {
        let dir = std::env::temp_dir().join(format!("rtl-lab-names-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let name = |spp: &str| dir.join(format!("render-reference-cornell-16-{spp}.pfm"));
        assert_eq!(cached_reference_spp(&dir, 16), None);
        std::os::unix::fs::symlink(dir.join("gone"), name("18446744073709551615")).unwrap();
        std::fs::create_dir(name("5000")).unwrap();
        std::fs::write(name("2000000"), b"PF\n").unwrap();
        assert_eq!(cached_reference_spp(&dir, 16), None);
        std::fs::write(name("64"), b"PF\n").unwrap();
        assert_eq!(cached_reference_spp(&dir, 16), Some(64));
        std::fs::write(name("1000000"), b"PF\n").unwrap();
        assert_eq!(cached_reference_spp(&dir, 16), Some(1_000_000));
        assert_eq!(cached_reference_spp(&dir, 32), None);
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// A damaged cached reference fails, and is tried again once removed, without restarting the
    /// lab (it had kept showing the failure until the lab was restarted).
    #[test]
    fn a_failed_reference_is_tried_again() {
        let scene = Arc::new(glue::scene().unwrap());
        let dir = std::env::temp_dir().join(format!("rtl-lab-retry-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let damaged = dir.join("render-reference-cornell-16-1.pfm");
        std::fs::write(&damaged, b"PF\n16 16\n-1.0\nshort").unwrap();
        let bench = tiny_reference_bench(&dir);
        let Reference::Failed(e, _) = settled(&bench, &scene, 16) else {
            panic!("a damaged reference was used");
        };
        assert!(e.contains("render-reference-cornell-16-1.pfm"), "{e}");
        assert!(bench.reference_note(16).contains("tried again"));
        // Shown as it is until RETRY_FAILED has passed, even once the cause is gone.
        std::fs::remove_file(&damaged).unwrap();
        assert!(matches!(bench.reference(&scene, 16), Reference::Failed(..)));
        // Then tried again: rendered (1 spp) and cached.
        if let Some(Reference::Failed(_, at)) = bench.references.lock().unwrap().get_mut(&16) {
            *at = Instant::now() - RETRY_FAILED;
        }
        let Reference::Ready(img, 1, None) = settled(&bench, &scene, 16) else {
            panic!("not tried again, or not cached");
        };
        assert_eq!(img.len(), 16 * 16);
        assert!(damaged.is_file());
        let _ = std::fs::remove_dir_all(dir);
    }

    /// A reference that cannot be written to the cache is used all the same, and the page says
    /// it is in memory only (it had been thrown away after its whole render).
    #[test]
    fn a_reference_that_cannot_be_cached_is_used() {
        let scene = Arc::new(glue::scene().unwrap());
        let dir = std::env::temp_dir().join(format!("rtl-lab-uncached-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        // (a directory where the image's temporary file goes: the write fails, even for root)
        let temp = format!(
            ".render-reference-cornell-16-1.pfm.tmp{}",
            std::process::id()
        );
        std::fs::create_dir_all(dir.join(temp).join("x")).unwrap();
        let bench = tiny_reference_bench(&dir);
        let Reference::Ready(img, 1, Some(e)) = settled(&bench, &scene, 16) else {
            panic!("not kept, or said to be cached");
        };
        assert_eq!(img.len(), 16 * 16);
        assert!(e.contains("render-reference-cornell-16-1.pfm"), "{e}");
        assert!(bench.reference_note(16).contains("memory only"));
        let _ = std::fs::remove_dir_all(dir);
    }
}
