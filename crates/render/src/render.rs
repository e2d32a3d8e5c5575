//! Rendering in progressive passes over sample ranges `[k0, k1)` into an accumulation buffer.
//!
//! Sample `k` of a pixel depends only on `(seed, pixel, k)`, and each pixel's finite samples are summed
//! in the order of `k`, so rendering `[0, a)` then `[a, b)` gives exactly the sums of `[0, b)`, for any
//! number of threads (rows are shared out by rayon, but no pixel's sum depends on who computed it).

use crate::camera::Camera;
use crate::integrator::{Strategy, radiance};
use crate::lights::Lights;
use crate::sampler::{Ctx, SampleRng, Sampler, Stats, sample_key};
use crate::scene::Scene;
use crate::vec::Color;
use rayon::prelude::*;

/// Settings that change the image.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct RenderSettings {
    pub width: usize,
    pub max_depth: u32,
    pub seed: u64,
    pub strategy: Strategy,
    /// `mixture`'s share of directions drawn from the importance targets' density, `w` in
    /// `p = w p_targets + (1 - w) p_material`, strictly between 0 and 1 (see [`check_mixture_weight`]);
    /// the book's is [`BOOK_MIXTURE_WEIGHT`]. The other strategies ignore it. Left out of the settings'
    /// record (the checkpoint identity) when it is the book's, so records made before it existed
    /// still match.
    #[serde(skip_serializing_if = "is_book_mixture_weight")]
    pub mixture_weight: f64,
}

/// The book's even mixture (book 3, ch. 10): half the directions towards the targets.
pub const BOOK_MIXTURE_WEIGHT: f64 = 0.5;

fn is_book_mixture_weight(w: &f64) -> bool {
    *w == BOOK_MIXTURE_WEIGHT
}

/// Why a mixture weight was refused.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[error(
    "the mixture weight is {0}, not strictly between 0 and 1 (0 would be the 'cosine' strategy, 1 \
     the biased 'light' one)"
)]
pub struct MixtureWeightError(pub f64);

/// `w` if it is a mixture weight `mixture` can use: `0 < w < 1` (NaN is refused). At 1 the targets
/// alone would be sampled, which misses the directions they do not cover (biased, the `light`
/// strategy); at 0 it is the material's density alone (the `cosine` strategy).
pub fn check_mixture_weight(w: f64) -> Result<f64, MixtureWeightError> {
    if w > 0.0 && w < 1.0 {
        Ok(w)
    } else {
        Err(MixtureWeightError(w))
    }
}

/// Per-pixel sums of finite sample values, how many were summed, and how many were dropped as
/// non-finite.
#[derive(Clone, Debug, PartialEq)]
pub struct Accumulator {
    pub width: usize,
    pub height: usize,
    pub sum: Vec<Color>,
    pub count: Vec<u64>,
    pub dropped: Vec<u64>,
    /// Samples per pixel done so far: the range `[0, samples)` when rendered from 0.
    pub samples: u64,
}

impl Accumulator {
    pub fn new(width: usize, height: usize) -> Self {
        let n = width * height;
        Accumulator {
            width,
            height,
            sum: vec![Color::ZERO; n],
            count: vec![0; n],
            dropped: vec![0; n],
            samples: 0,
        }
    }

    /// Add one sample to pixel `i`: summed if every component is finite, otherwise counted as dropped.
    /// Returns whether the sample was kept.
    #[inline]
    pub fn add(sum: &mut Color, count: &mut u64, dropped: &mut u64, value: Color) -> bool {
        // `|value| <= MAX` in every component: `is_finite` by floating-point comparisons (NaN fails
        // them), not by tests of each component's bits
        if value.abs().cmple(Color::splat(f64::MAX)).all() {
            *sum += value;
            *count += 1;
            true
        } else {
            *dropped += 1;
            false
        }
    }

    /// The mean of the finite samples of pixel `i` (black if it has none).
    #[inline]
    pub fn mean(&self, i: usize) -> Color {
        if self.count[i] == 0 {
            Color::ZERO
        } else {
            self.sum[i] / self.count[i] as f64
        }
    }

    /// The image: every pixel's mean, rows from the top.
    pub fn image(&self) -> Vec<Color> {
        (0..self.sum.len()).map(|i| self.mean(i)).collect()
    }

    /// Total number of non-finite samples dropped.
    pub fn total_dropped(&self) -> u64 {
        self.dropped.iter().sum()
    }
}

/// A scene with a camera for one image size, ready to trace samples.
pub struct Renderer<'a> {
    pub scene: &'a Scene,
    pub camera: Camera,
    pub settings: RenderSettings,
    /// The scene's importance targets, built once for the strategy.
    pub lights: Lights,
    /// Whether every dimension after the pixel position is low-discrepancy (`mis`'s option, resolved
    /// once here rather than per sample).
    low_discrepancy: bool,
}

impl<'a> Renderer<'a> {
    ///
    /// Panics if `settings.mixture_weight` is refused by [`check_mixture_weight`] (callers check
    /// their users' input first, with its flag or field in the message).
    pub fn new(scene: &'a Scene, settings: RenderSettings) -> Self {
        if let Err(e) = check_mixture_weight(settings.mixture_weight) {
            panic!("RenderSettings: {e}");
        }
        let camera = Camera::new(&scene.camera, settings.width, scene.features.motion);
        let options = settings.strategy.mis_options();
        let spherical_rectangles = options.is_some_and(|o| o.spherical_rectangles);
        Renderer {
            scene,
            camera,
            settings,
            lights: Lights::new(scene, spherical_rectangles),
            low_discrepancy: options.is_some_and(|o| o.low_discrepancy),
        }
    }

    pub fn accumulator(&self) -> Accumulator {
        Accumulator::new(self.camera.width, self.camera.height)
    }

    /// The scramble key of a pixel's sub-pixel sequence.
    #[inline]
    fn pixel_key(&self, pixel: u64) -> u64 {
        sample_key(self.settings.seed, pixel, u64::MAX)
    }

    /// The value of sample `k` of pixel `(i, j)`: a function of `(seed, pixel, k)` only.
    #[inline]
    pub fn sample(&self, i: usize, j: usize, k: u64, ctx: &mut Ctx) -> Color {
        let pixel = (j * self.camera.width + i) as u64;
        ctx.rng = SampleRng::for_sample(self.settings.seed, pixel, k);
        let pixel_key = self.pixel_key(pixel);
        ctx.sampler = Sampler::new(self.low_discrepancy, pixel_key, k);
        let ray = self.camera.ray(i, j, pixel_key, k, ctx);
        let value = radiance(
            self.scene,
            &self.lights,
            ray,
            self.settings.max_depth,
            self.settings.strategy,
            self.settings.mixture_weight,
            ctx,
        );
        ctx.stats.samples += 1;
        ctx.stats.random_numbers += ctx.rng.drawn;
        value
    }

    /// Add samples `k0..k1` of every pixel to `acc`, in parallel over rows; `on_row` is called after each
    /// row (for progress). Returns the counters of this pass.
    pub fn render_pass(
        &self,
        acc: &mut Accumulator,
        k0: u64,
        k1: u64,
        on_row: &(dyn Fn() + Sync),
    ) -> Stats {
        self.render_pass_until(acc, k0, k1, on_row, &|| false)
            .expect("a pass that is never stopped finishes")
    }

    /// [`Renderer::render_pass`] that gives up as soon as `stop()` is true (asked before each pixel):
    /// then it returns `None`, and `acc` holds the pass for some pixels only (keep a copy to go back
    /// to). Whole passes are what a checkpoint or a stopped render keeps.
    pub fn render_pass_until(
        &self,
        acc: &mut Accumulator,
        k0: u64,
        k1: u64,
        on_row: &(dyn Fn() + Sync),
        stop: &(dyn Fn() -> bool + Sync),
    ) -> Option<Stats> {
        assert_eq!(
            (acc.width, acc.height),
            (self.camera.width, self.camera.height),
            "accumulator of another size"
        );
        let w = acc.width;
        let stats = acc
            .sum
            .par_chunks_mut(w)
            .zip(acc.count.par_chunks_mut(w))
            .zip(acc.dropped.par_chunks_mut(w))
            .enumerate()
            .map(|(j, ((sum, count), dropped))| {
                let mut ctx = Ctx::new();
                for i in 0..w {
                    if stop() {
                        return None;
                    }
                    for k in k0..k1 {
                        let v = self.sample(i, j, k, &mut ctx);
                        if !Accumulator::add(&mut sum[i], &mut count[i], &mut dropped[i], v) {
                            ctx.stats.non_finite += 1;
                        }
                    }
                }
                on_row();
                Some(ctx.stats)
            })
            .reduce(|| Some(Stats::default()), |a, b| Some(a? + b?))?;
        acc.samples = acc.samples.max(k1);
        Some(stats)
    }
}

/// Render samples `[0, spp)` in one go (in the current rayon pool).
pub fn render(scene: &Scene, settings: RenderSettings, spp: u64) -> (Accumulator, Stats) {
    let r = Renderer::new(scene, settings);
    let mut acc = r.accumulator();
    let stats = r.render_pass(&mut acc, 0, spp, &|| {});
    (acc, stats)
}
