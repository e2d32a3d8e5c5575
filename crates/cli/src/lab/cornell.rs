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

use super::glue::{self, Settings};
use crate::study::render::{errors, heat, reference_until};
use rtl_mc::RunningStats;
use rtl_render::Color;
use rtl_render::output::{Transfer, to_rgb8};
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

/// A curve of RMSE against seconds for one setting tried.
#[derive(Clone, Debug, Serialize)]
pub struct Curve {
    pub label: String,
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
    pub image_png: Arc<Vec<u8>>,
    pub variance_png: Arc<Vec<u8>>,
}

/// The reference image at one width.
#[derive(Clone)]
pub enum Reference {
    Rendering,
    Ready(Arc<Vec<Color>>),
    Failed(String),
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
    references: Mutex<HashMap<usize, Reference>>,
    /// A reference is being rendered (one at a time: the others are asked for again later).
    reference_busy: AtomicBool,
    reference_dir: PathBuf,
    reference_spp: u64,
}

/// `last_seen_ms` before the first request.
const NEVER: u64 = u64::MAX;

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
    use rtl_render::integrator::Strategy;
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

/// The spp of the best reference cached in `dir` at `width` (`rtl study render`'s file names).
fn cached_reference_spp(dir: &Path, width: usize) -> Option<u64> {
    let prefix = format!("render-reference-{}-{width}-", glue::SCENE);
    std::fs::read_dir(dir)
        .ok()?
        .filter_map(|e| {
            let name = e.ok()?.file_name().into_string().ok()?;
            name.strip_prefix(&prefix)?
                .strip_suffix(".pfm")?
                .parse::<u64>()
                .ok()
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

    /// New settings: the render restarts at once (even with the same settings: a fresh curve).
    pub fn set(&self, s: Settings) -> u64 {
        *self.settings.lock().unwrap() = s;
        self.touch();
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

    fn now_ms(&self) -> u64 {
        self.epoch.elapsed().as_millis() as u64
    }

    /// Forget every curve; the running render's curve starts again with its next pass.
    pub fn clear_curves(&self) {
        self.curves.lock().unwrap().clear();
    }

    /// The state of the reference at `width`, starting its render if there is none and no other
    /// reference is being rendered (then it is asked for again after the next pass). So at most one
    /// thread renders references, and none waits.
    pub fn reference(self: &Arc<Self>, scene: &Arc<Scene>, width: usize) -> Reference {
        let mut refs = self.references.lock().unwrap();
        if let Some(r) = refs.get(&width) {
            return r.clone();
        }
        if self.reference_busy.swap(true, Ordering::SeqCst) {
            return Reference::Rendering;
        }
        refs.insert(width, Reference::Rendering);
        let (me, scene) = (Arc::clone(self), Arc::clone(scene));
        std::thread::spawn(move || {
            let dir = &me.reference_dir;
            let spp = cached_reference_spp(dir, width).unwrap_or(me.reference_spp);
            // A pool of its own: in the render's pool its long passes would hold up the frames
            // (rayon runs one injected job after another); beside it, the two share the cores.
            let result = rayon::ThreadPoolBuilder::new()
                .thread_name(|i| format!("reference-{i}"))
                .build()
                .map_err(anyhow::Error::from)
                .and_then(|pool| {
                    std::fs::create_dir_all(dir)?;
                    // Stopped when nobody watches: the page closed, or went to another bench.
                    let stop = || me.is_idle();
                    pool.install(|| reference_until(dir, glue::SCENE, &scene, width, spp, &stop))
                });
            let mut refs = me.references.lock().unwrap();
            match result {
                Ok(Some(img)) => {
                    refs.insert(width, Reference::Ready(Arc::new(img)));
                }
                // Asked for again (from the start) when the page is back.
                Ok(None) => {
                    refs.remove(&width);
                }
                Err(e) => {
                    refs.insert(width, Reference::Failed(format!("{e:#}")));
                }
            }
            me.reference_busy.store(false, Ordering::SeqCst);
        });
        Reference::Rendering
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
            Some(Reference::Ready(_)) => format!(
                "{}/render-reference-{}-{width}-{}.pfm (rtl study render's)",
                self.reference_dir.display(),
                glue::SCENE,
                cached_reference_spp(&self.reference_dir, width).unwrap_or(self.reference_spp)
            ),
            Some(Reference::Failed(e)) => format!("no reference: {e}"),
        }
    }
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

fn render_generation(bench: &Arc<Bench>, scene: &Arc<Scene>, generation: u64, s: Settings) {
    let r = glue::renderer(scene, &s);
    let (w, h) = (r.camera.width, r.camera.height);
    let mut acc = r.accumulator();
    let mut moments = vec![RunningStats::new(); w * h];
    let mut backup = (acc.clone(), moments.clone());
    let stop = || bench.generation() != generation || bench.is_idle();
    let label = label(&s);
    let mut seconds = 0.0;
    let mut rays = 0u64;
    let mut n = 1u64;
    let mut curve_started = false;
    while !stop() {
        let (k0, k1) = (acc.samples, acc.samples + n);
        backup.0.clone_from(&acc);
        backup.1.clone_from(&moments);
        let t0 = Instant::now();
        let Some(stats) = glue::pass(&r, &mut acc, &mut moments, k0, k1, &stop) else {
            // Stopped half-way: keep the whole passes only (the page may come back).
            std::mem::swap(&mut acc, &mut backup.0);
            std::mem::swap(&mut moments, &mut backup.1);
            if bench.generation() != generation {
                return;
            }
            // Idle: wait for the page, then carry on with this render.
            while bench.is_idle() {
                std::thread::sleep(Duration::from_millis(50));
            }
            continue;
        };
        // Finished just as the settings changed: a pass of the old render, shown to nobody.
        if bench.generation() != generation {
            return;
        }
        let t = t0.elapsed().as_secs_f64();
        seconds += t;
        rays += stats.rays;
        let img = acc.image();
        let rmse = match bench.reference(scene, w) {
            Reference::Ready(reference) if reference.len() == img.len() => {
                Some(errors(&img, &reference).0)
            }
            _ => None,
        };
        if let Some(rmse) = rmse {
            let mut curves = bench.curves.lock().unwrap();
            // A fresh render of a setting tried before replaces its curve.
            if !curve_started {
                curves.retain(|c| c.label != label);
                curve_started = true;
            }
            // Not there at the start, or cleared by the page since: the curve (re)starts here.
            let i = match curves.iter().position(|c| c.label == label) {
                Some(i) => i,
                None => {
                    if curves.len() >= MAX_CURVES {
                        curves.remove(0);
                    }
                    curves.push(Curve {
                        label: label.clone(),
                        width: w,
                        points: Vec::new(),
                    });
                    curves.len() - 1
                }
            };
            let c = &mut curves[i];
            if c.points.len() >= MAX_POINTS {
                let kept: Vec<_> = c.points.iter().copied().step_by(2).collect();
                c.points = kept;
            }
            c.points.push((seconds, acc.samples, rmse));
        }
        let image_png = png(w, h, to_rgb8(&img, Transfer::Gamma2));
        let variance_png = png(w, h, variance_rgb(&moments));
        {
            let mut f = bench.frame.lock().unwrap();
            *f = Frame {
                id: f.id + 1,
                generation,
                width: w,
                height: h,
                spp: acc.samples,
                seconds,
                rays_per_second: rays as f64 / seconds.max(1e-9),
                rmse,
                image_png: Arc::new(image_png),
                variance_png: Arc::new(variance_png),
            };
        }
        // The next pass: about PASS_TIME long, at most twice the last.
        let per_spp = t / (k1 - k0) as f64;
        let fit = (PASS_TIME.as_secs_f64() / per_spp.max(1e-12)).floor() as u64;
        n = fit.clamp(1, n.saturating_mul(2));
    }
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
        let s = Settings {
            width: 16,
            strategy: Strategy::Cosine,
            seed: 1,
            max_depth: 50,
            mixture_weight: 0.5,
        };
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
        // Cleared while it runs: the running render's curve comes back alone, from later passes.
        let spp_at_clear = bench.frame.lock().unwrap().spp;
        bench.clear_curves();
        let back = |curves: &Vec<Curve>| {
            curves.len() == 1
                && curves[0].label == label(&bench.settings())
                && curves[0].points.iter().all(|p| p.1 > spp_at_clear)
        };
        let start = Instant::now();
        while !back(&bench.curves.lock().unwrap()) {
            assert!(
                start.elapsed() < Duration::from_secs(60),
                "the curve did not come back after a clear: {:?}",
                bench.curves.lock().unwrap()
            );
            bench.touch();
            std::thread::sleep(Duration::from_millis(20));
        }
        // Nobody asks: the passes stop.
        bench.last_seen_ms.store(NEVER, Ordering::SeqCst);
        std::thread::sleep(Duration::from_millis(300));
        let spp = bench.frame.lock().unwrap().spp;
        std::thread::sleep(Duration::from_millis(500));
        assert_eq!(bench.frame.lock().unwrap().spp, spp);
        let _ = std::fs::remove_dir_all(dir);
    }

    #[test]
    fn a_reference_stops_when_nobody_watches() {
        let scene = Arc::new(glue::scene().unwrap());
        let dir = std::env::temp_dir().join(format!("rtl-lab-ref-test-{}", std::process::id()));
        let s = Settings {
            width: 16,
            strategy: Strategy::Cosine,
            seed: 1,
            max_depth: 50,
            mixture_weight: 0.5,
        };
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
}
