//! What the unbiasedness tests of `mis`'s variants share: an image made by a variant through the
//! renderer's own sample loop, the region means of a batch of images, and the regions where two
//! estimators disagree (Welch's t-test of the batch means, Bonferroni over the regions).
//!
//! A test file that uses it also declares `mod batch_means;`.

use crate::batch_means::{mean_var, welch_p};
use rtl_render::Color;
use rtl_render::integrator::{MisOptions, MisVariant, Strategy, radiance_mis_variant};
use rtl_render::render::{BOOK_MIXTURE_WEIGHT, RenderSettings, Renderer};
use rtl_render::sampler::{Ctx, SampleRng, Sampler, sample_key};
use rtl_render::scene::Scene;

/// The settings of a render `width` wide with paths of at most `max_depth` segments.
pub fn settings(width: usize, max_depth: u32, seed: u64, strategy: Strategy) -> RenderSettings {
    RenderSettings {
        width,
        max_depth,
        seed,
        strategy,
        mixture_weight: BOOK_MIXTURE_WEIGHT,
    }
}

/// The image of `spp` samples a pixel by `mis` (default options) as `variant` computes it, through
/// the renderer's sample loop: the same generator, sampler and camera ray for `(seed, pixel, k)`.
pub fn render_variant(
    scene: &Scene,
    width: usize,
    max_depth: u32,
    spp: u64,
    seed: u64,
    variant: MisVariant,
) -> Vec<Color> {
    let options = MisOptions::DEFAULT;
    let r = Renderer::new(
        scene,
        settings(width, max_depth, seed, Strategy::Mis(options)),
    );
    let (w, h) = (r.camera.width, r.camera.height);
    let mut ctx = Ctx::new();
    let mut img = vec![Color::ZERO; w * h];
    for j in 0..h {
        for i in 0..w {
            let pixel = (j * w + i) as u64;
            let key = sample_key(seed, pixel, u64::MAX);
            for k in 0..spp {
                ctx.rng = SampleRng::for_sample(seed, pixel, k);
                ctx.sampler = Sampler::new(options.low_discrepancy, key, k);
                let ray = r.camera.ray(i, j, key, k, &mut ctx);
                let v = radiance_mis_variant(
                    scene, &r.lights, ray, max_depth, options, variant, &mut ctx,
                );
                assert!(v.is_finite());
                img[j * w + i] += v / spp as f64;
            }
        }
    }
    img
}

/// Per region of a `grid` x `grid` division of images `width` wide, its mean radiance (the mean of
/// the three channels) in each of `batches` images, `image(first_seed + b)` for batch `b`.
pub fn region_means(
    width: usize,
    grid: usize,
    batches: u64,
    first_seed: u64,
    image: impl Fn(u64) -> Vec<Color>,
) -> Vec<Vec<f64>> {
    let cell = width / grid;
    let mut out = vec![Vec::new(); grid * grid];
    for b in 0..batches {
        let img = image(first_seed + b);
        let h = img.len() / width;
        for (r, o) in out.iter_mut().enumerate() {
            let (ci, cj) = (r % grid, r / grid);
            let (rows, cols) = (
                cj * h / grid..(cj + 1) * h / grid,
                ci * cell..(ci + 1) * cell,
            );
            let n = (rows.len() * cols.len()) as f64;
            let mut sum = 0.0;
            for j in rows {
                for i in cols.clone() {
                    sum += img[j * width + i].element_sum() / 3.0;
                }
            }
            o.push(sum / n);
        }
    }
    out
}

/// The regions (of a `grid` x `grid` division) whose means differ at a family-wise false-failure
/// rate of 1e-6 (Bonferroni over the regions).
pub fn disagreements(a: &[Vec<f64>], b: &[Vec<f64>], grid: usize) -> Vec<String> {
    let alpha = 1e-6 / (grid * grid) as f64;
    a.iter()
        .zip(b)
        .enumerate()
        .filter_map(|(r, (x, y))| {
            let p = welch_p(x, y);
            (p < alpha).then(|| {
                format!(
                    "region ({}, {}): {:.5} vs {:.5}, p = {p:.2e}",
                    r % grid,
                    r / grid,
                    mean_var(x).0,
                    mean_var(y).0
                )
            })
        })
        .collect()
}
