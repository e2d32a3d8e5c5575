//! The lab's one door into the renderer: build the Cornell box, make a renderer for a strategy and its
//! options, and render one progressive pass. Everything the Cornell bench asks of `rtl-render` goes
//! through here, so a change of the integrator's or sampler's API is adapted in this file only.
//!
//! A pass adds samples `[k0, k1)` of every pixel exactly as [`Renderer::render_pass_until`] does
//! (`rtl render` and `rtl study render` call it), so the image after `k` samples is the CLI's image
//! bit for bit (tested below); it also keeps each pixel's running statistics of one sample's
//! luminance, for the variance map of `rtl study render` (the variance of one sample, not of the mean).

use rayon::prelude::*;
use rtl_mc::RunningStats;
use rtl_render::integrator::{MisOptions, Strategy};
use rtl_render::render::{Accumulator, RenderSettings, Renderer};
use rtl_render::sampler::{Ctx, Stats};
use rtl_render::scene::Scene;

use crate::study::render::luminance;

/// The scene of the bench: book 3's final Cornell box.
pub const SCENE: &str = "cornell";

/// The book's `max_depth` of its Cornell box.
pub const BOOK_DEPTH: u32 = 50;

/// The settings the page can switch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    pub width: usize,
    pub strategy: Strategy,
    pub seed: u64,
    pub max_depth: u32,
    /// `mixture`'s share of directions towards the targets, in `(0, 1)` (kept across strategies, used
    /// by `mixture` only).
    pub mixture_weight: f64,
}

/// The Cornell box, as `rtl render cornell` builds it.
pub fn scene() -> anyhow::Result<Scene> {
    let b = rtl_render::scenes::find(SCENE).map_err(anyhow::Error::msg)?;
    Ok((b.build)(&Default::default())
        .map_err(|e| anyhow::anyhow!("scene {SCENE}: {e}"))?
        .scene)
}

/// A strategy by its CLI name, with `mis`'s extras (ignored by the other strategies).
pub fn strategy(name: &str, rr: bool, lds: bool, sph_rect: bool) -> Result<Strategy, String> {
    Ok(match name.parse::<Strategy>()? {
        Strategy::Mis(_) => Strategy::Mis(MisOptions {
            russian_roulette: rr,
            low_discrepancy: lds,
            spherical_rectangles: sph_rect,
            ..MisOptions::DEFAULT
        }),
        other => other,
    })
}

/// `mis`'s extras; the defaults for the other strategies (which ignore them), so that the page's
/// switches keep their places across a change of strategy.
pub fn mis_options(s: Strategy) -> MisOptions {
    match s {
        Strategy::Mis(o) => o,
        _ => MisOptions::DEFAULT,
    }
}

/// The names of the strategies, in the book's order.
pub fn strategy_names() -> Vec<&'static str> {
    Strategy::ALL.iter().map(Strategy::name).collect()
}

/// A renderer of `scene` with `s`.
pub fn renderer<'a>(scene: &'a Scene, s: &Settings) -> Renderer<'a> {
    Renderer::new(
        scene,
        RenderSettings {
            width: s.width,
            max_depth: s.max_depth,
            seed: s.seed,
            strategy: s.strategy,
            mixture_weight: s.mixture_weight,
        },
    )
}

/// Add samples `[k0, k1)` of every pixel to `acc` and the luminance of each sample to `moments` (one
/// per pixel, row-major), in parallel over rows; `None` (and a partial pass: keep a copy) as soon as
/// `stop()` is true.
pub fn pass(
    r: &Renderer,
    acc: &mut Accumulator,
    moments: &mut [RunningStats],
    k0: u64,
    k1: u64,
    stop: &(dyn Fn() -> bool + Sync),
) -> Option<Stats> {
    let w = acc.width;
    let stats = acc
        .sum
        .par_chunks_mut(w)
        .zip(acc.count.par_chunks_mut(w))
        .zip(acc.dropped.par_chunks_mut(w))
        .zip(moments.par_chunks_mut(w))
        .enumerate()
        .map(|(j, (((sum, count), dropped), m))| {
            let mut ctx = Ctx::new();
            for i in 0..w {
                if stop() {
                    return None;
                }
                for k in k0..k1 {
                    let v = r.sample(i, j, k, &mut ctx);
                    if Accumulator::add(&mut sum[i], &mut count[i], &mut dropped[i], v) {
                        m[i].push(luminance(v));
                    } else {
                        ctx.stats.non_finite += 1;
                    }
                }
            }
            Some(ctx.stats)
        })
        .reduce(|| Some(Stats::default()), |a, b| Some(a? + b?))?;
    acc.samples = acc.samples.max(k1);
    Some(stats)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The lab's passes make the CLI's image: the same sums as `render_pass` in the same passes.
    #[test]
    fn passes_match_the_cli() {
        let scene = scene().unwrap();
        for name in ["uniform", "mis"] {
            let s = Settings {
                width: 12,
                strategy: strategy(name, true, true, false).unwrap(),
                seed: 5,
                max_depth: 50,
                mixture_weight: 0.5,
            };
            let r = renderer(&scene, &s);
            let mut cli = r.accumulator();
            r.render_pass(&mut cli, 0, 3, &|| {});
            r.render_pass(&mut cli, 3, 7, &|| {});
            let mut lab = r.accumulator();
            let mut m = vec![RunningStats::new(); lab.sum.len()];
            pass(&r, &mut lab, &mut m, 0, 3, &|| false).unwrap();
            pass(&r, &mut lab, &mut m, 3, 7, &|| false).unwrap();
            assert_eq!(cli.sum, lab.sum, "{name}");
            assert_eq!(cli.count, lab.count);
            assert_eq!(cli.samples, lab.samples);
            let counted: u64 = m.iter().map(|s| s.count()).sum();
            assert_eq!(counted, lab.count.iter().sum::<u64>());
        }
    }

    #[test]
    fn a_stopped_pass_says_so() {
        let scene = scene().unwrap();
        let s = Settings {
            width: 8,
            strategy: Strategy::Cosine,
            seed: 1,
            max_depth: 50,
            mixture_weight: 0.5,
        };
        let r = renderer(&scene, &s);
        let mut acc = r.accumulator();
        let mut m = vec![RunningStats::new(); acc.sum.len()];
        assert!(pass(&r, &mut acc, &mut m, 0, 1, &|| true).is_none());
    }

    /// The references of `rtl study render` are rendered at the scene's depth: the book's, which the
    /// bench takes for theirs.
    #[test]
    fn the_scene_has_the_books_depth() {
        assert_eq!(scene().unwrap().max_depth, BOOK_DEPTH);
    }

    #[test]
    fn strategies_by_name() {
        assert!(strategy("nope", true, true, false).is_err());
        assert_eq!(
            strategy("mis", false, true, false).unwrap(),
            Strategy::Mis(MisOptions {
                russian_roulette: false,
                low_discrepancy: true,
                spherical_rectangles: false,
                manifold: true,
            })
        );
        assert_eq!(strategy_names().len(), Strategy::ALL.len());
    }
}
