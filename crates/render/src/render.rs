//! Rendering in progressive passes over sample ranges `[k0, k1)` into an accumulation buffer.
//!
//! Sample `k` of a pixel depends only on `(seed, pixel, k)`, and each pixel's finite samples are summed
//! in the order of `k`, so rendering `[0, a)` then `[a, b)` gives exactly the sums of `[0, b)`, for any
//! number of threads (rows are shared out by rayon, but no pixel's sum depends on who computed it).

use crate::camera::Camera;
use crate::integrator::{Strategy, radiance};
use crate::lights::Lights;
use crate::ray::Ray;
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
    "the mixture weight is {}, not strictly between 0 and 1 (0 would be the 'cosine' strategy, 1 \
     the biased 'light' one)",
    crate::vec::Num(*.0)
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
#[derive(Debug, PartialEq)]
pub struct Accumulator {
    pub width: usize,
    pub height: usize,
    pub sum: Vec<Color>,
    pub count: Vec<u64>,
    pub dropped: Vec<u64>,
    /// Samples per pixel done so far: the range `[0, samples)` when rendered from 0.
    pub samples: u64,
}

impl Clone for Accumulator {
    fn clone(&self) -> Self {
        Accumulator {
            width: self.width,
            height: self.height,
            sum: self.sum.clone(),
            count: self.count.clone(),
            dropped: self.dropped.clone(),
            samples: self.samples,
        }
    }

    /// Field by field, into the buffers `self` has: the derived `clone_from` (`*self =
    /// source.clone()`) made a third accumulation before it dropped the old one, 40 bytes a pixel
    /// more at the peak of every pass of a long render (which copies the accumulation into the
    /// one the pass works on).
    fn clone_from(&mut self, source: &Self) {
        self.width = source.width;
        self.height = source.height;
        self.sum.clone_from(&source.sum);
        self.count.clone_from(&source.count);
        self.dropped.clone_from(&source.dropped);
        self.samples = source.samples;
    }
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
    /// Whether paths are traced side by side in the vector lanes, their rays intersected eight at
    /// a time ([`crate::paths8`], [`crate::mis8`]): the same image, sooner.
    paths_in_lanes: bool,
    /// The `mixture` strategy's density in the lanes, where the paths are traced in them.
    mixture8: Option<crate::mixture8::Mixture8>,
    /// The quads whose Lambertian vertex `mixture` computes in the lanes ([`crate::vertex8`]).
    quad_surfaces: Option<crate::vertex8::QuadSurfaces>,
    /// The glass spheres whose vertex is computed in the lanes ([`crate::glass8`]).
    glass_spheres: Option<crate::glass8::GlassSpheres>,
    /// The targets of `mis`'s Lambertian vertex in the lanes ([`crate::mis_vertex8`]).
    mis_lanes: Option<crate::mis_vertex8::MisLanes>,
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
        let lights = Lights::new(scene, spherical_rectangles);
        let paths_in_lanes = crate::paths8::applies(scene, settings.strategy)
            || crate::mis8::applies(scene, settings.strategy);
        let mixture8 = (paths_in_lanes && settings.strategy == Strategy::Mixture)
            .then(|| crate::mixture8::Mixture8::new(&lights.all, settings.mixture_weight))
            .flatten();
        let mis_lanes = (paths_in_lanes && options.is_some())
            .then(|| crate::mis_vertex8::MisLanes::new(&lights))
            .flatten();
        let quad_surfaces = (mixture8.is_some() || mis_lanes.is_some())
            .then(|| crate::vertex8::QuadSurfaces::new(scene, crate::scene::GroupId(0)))
            .flatten();
        let glass_spheres = quad_surfaces
            .as_ref()
            .and_then(|_| crate::glass8::GlassSpheres::new(scene, crate::scene::GroupId(0)));
        Renderer {
            scene,
            camera,
            settings,
            lights,
            low_discrepancy: options.is_some_and(|o| o.low_discrepancy),
            paths_in_lanes,
            mixture8,
            quad_surfaces,
            glass_spheres,
            mis_lanes,
        }
    }

    /// Whether every dimension after the pixel position is a padded Sobol pair (`mis`'s option).
    pub(crate) fn low_discrepancy(&self) -> bool {
        self.low_discrepancy
    }

    /// Whether paths are traced side by side in the lanes ([`crate::paths8`], [`crate::mis8`]): in a
    /// scene whose rays meet a small group (no tree), on a processor with AVX2 or AVX-512, for the
    /// book's one-sample strategies and for `mis` where the scene has no media.
    pub fn paths_in_lanes(&self) -> bool {
        self.paths_in_lanes
    }

    /// The `mixture` strategy's density at Lambertian points, in the lanes ([`crate::mixture8`]), if
    /// the paths are traced in them and the targets allow it.
    pub fn mixture_in_lanes(&self) -> Option<&crate::mixture8::Mixture8> {
        self.mixture8.as_ref()
    }

    /// The quads whose Lambertian vertex is computed in the lanes, whole ([`crate::vertex8`]): for
    /// `mixture` where its density is in the lanes and the scene's small group has Lambertian quads
    /// of a constant albedo.
    pub fn lambertian_vertex_in_lanes(&self) -> Option<&crate::vertex8::QuadSurfaces> {
        self.quad_surfaces
            .as_ref()
            .filter(|_| self.mixture8.is_some())
    }

    /// `mis`'s Lambertian vertex in the lanes ([`crate::mis_vertex8`]): the quads and the targets,
    /// where `mis` traces its paths in the lanes, the scene has one emitter and non-emitting
    /// targets, and its small group has Lambertian quads of a constant albedo.
    pub fn mis_vertex_in_lanes(
        &self,
    ) -> Option<(&crate::vertex8::QuadSurfaces, &crate::mis_vertex8::MisLanes)> {
        Some((self.quad_surfaces.as_ref()?, self.mis_lanes.as_ref()?))
    }

    /// This renderer with `m` as the targets of `mis`'s Lambertian vertex in the lanes: for the
    /// tests that show a wrong one is caught.
    #[doc(hidden)]
    pub fn with_mis_vertex_in_lanes(mut self, m: Option<crate::mis_vertex8::MisLanes>) -> Self {
        self.mis_lanes = m;
        self
    }

    /// This renderer with the Lambertian vertex built lane by lane after the traversal (only the
    /// mixture's directions in the lanes): the same image, for tests and for measuring what the
    /// vertex in the lanes buys.
    #[doc(hidden)]
    pub fn without_lambertian_vertex_in_lanes(mut self) -> Self {
        self.quad_surfaces = None;
        self.glass_spheres = None;
        self
    }

    /// The glass spheres whose vertex is computed in the lanes, whole ([`crate::glass8`]): where
    /// the Lambertian vertex is ([`Renderer::lambertian_vertex_in_lanes`]: the lanes then hold the
    /// paths' rays and throughputs) and the scene's small group has static spheres of a dielectric.
    pub fn glass_vertex_in_lanes(&self) -> Option<&crate::glass8::GlassSpheres> {
        self.glass_spheres
            .as_ref()
            .filter(|_| self.lambertian_vertex_in_lanes().is_some())
    }

    /// This renderer with the glass vertex computed one path at a time: the same image, for tests
    /// and for measuring what the glass vertex in the lanes buys.
    #[doc(hidden)]
    pub fn without_glass_vertex_in_lanes(mut self) -> Self {
        self.glass_spheres = None;
        self
    }

    /// This renderer with `g` as the glass spheres of the vertex in the lanes: for the tests that
    /// show a wrong one is caught.
    #[doc(hidden)]
    pub fn with_glass_vertex_in_lanes(mut self, g: Option<crate::glass8::GlassSpheres>) -> Self {
        self.glass_spheres = g;
        self
    }

    /// This renderer with `m` as the mixture's density in the lanes (where the paths are traced in
    /// them): for the tests that show a wrong one is caught.
    #[doc(hidden)]
    pub fn with_mixture_in_lanes(mut self, m: Option<crate::mixture8::Mixture8>) -> Self {
        if self.paths_in_lanes {
            self.mixture8 = m;
        }
        self
    }

    /// Trace one path at a time even where [`Renderer::paths_in_lanes`] would trace 32: the same
    /// image (for tests and for measuring what the lanes buy).
    pub fn one_path_at_a_time(mut self) -> Self {
        self.paths_in_lanes = false;
        self.mixture8 = None;
        self.quad_surfaces = None;
        self.glass_spheres = None;
        self.mis_lanes = None;
        self
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
        let ray = self.start_sample(i, j, k, ctx);
        let value = radiance(
            self.scene,
            &self.lights,
            ray,
            self.settings.max_depth,
            self.settings.strategy,
            self.settings.mixture_weight,
            ctx,
        );
        Self::finish_sample(ctx);
        value
    }

    /// Sample `k` of pixel `(i, j)` begun: `ctx` set to its numbers, and its camera ray.
    #[inline]
    pub(crate) fn start_sample(&self, i: usize, j: usize, k: u64, ctx: &mut Ctx) -> Ray {
        let pixel = (j * self.camera.width + i) as u64;
        self.start_sample_keyed(i, j, k, self.pixel_key(pixel), ctx)
    }

    /// [`Renderer::start_sample`] with the pixel's scramble key already made (once per pixel).
    #[inline]
    pub(crate) fn start_sample_keyed(
        &self,
        i: usize,
        j: usize,
        k: u64,
        pixel_key: u64,
        ctx: &mut Ctx,
    ) -> Ray {
        let pixel = (j * self.camera.width + i) as u64;
        ctx.rng = SampleRng::for_sample(self.settings.seed, pixel, k);
        ctx.sampler = Sampler::new(self.low_discrepancy, pixel_key, k);
        self.camera.ray(i, j, pixel_key, k, ctx)
    }

    /// The scramble key of pixel `(i, j)`'s sub-pixel sequence.
    #[inline]
    pub(crate) fn pixel_key_of(&self, i: usize, j: usize) -> u64 {
        self.pixel_key((j * self.camera.width + i) as u64)
    }

    /// The counters of a sample whose path has ended.
    #[inline]
    pub(crate) fn finish_sample(ctx: &mut Ctx) {
        ctx.stats.samples += 1;
        ctx.stats.random_numbers += ctx.rng.drawn;
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
                // (only x86-64 has the lanes: `paths_in_lanes` is false elsewhere)
                #[cfg(target_arch = "x86_64")]
                if self.paths_in_lanes {
                    let stats = if matches!(self.settings.strategy, Strategy::Mis(_)) {
                        crate::mis8::render_row(self, j, k0, k1, sum, count, dropped, stop)
                    } else {
                        crate::paths8::render_row(self, j, k0, k1, sum, count, dropped, stop)
                    };
                    if stats.is_some() {
                        on_row();
                    }
                    return stats;
                }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clone_from_copies_into_the_buffers_it_has() {
        let mut a = Accumulator::new(5, 3);
        a.sum[7] = Color::new(1.0, 2.0, 3.0);
        a.count[7] = 4;
        a.dropped[2] = 1;
        a.samples = 5;
        let mut b = Accumulator::new(5, 3);
        let buffers = |x: &Accumulator| {
            (
                x.sum.as_ptr() as usize,
                x.count.as_ptr() as usize,
                x.dropped.as_ptr() as usize,
            )
        };
        let before = buffers(&b);
        b.clone_from(&a);
        assert_eq!(b, a);
        // no new accumulation at the peak of a pass: the same three buffers, overwritten
        assert_eq!(buffers(&b), before);
        assert_eq!(a.clone(), a);
    }
}
