//! Stratified ("jittered") sampling: one uniform sample in each of `n` equal cells of the domain.

use crate::estimate::{finite, nonzero, product, sample_count};
use crate::{Estimate, Interval, McError, Rect, RunningStats};
use rand::Rng;
use std::time::Instant;

pub(crate) fn replicates_ok(estimator: &'static str, replicates: u32) -> Result<(), McError> {
    if replicates < 2 {
        Err(McError::TooFewReplicates {
            estimator,
            replicates,
        })
    } else {
        Ok(())
    }
}

// ANCHOR: jittered
/// Jittered sampling on `[a, b]`: split it into `strata` equal cells and take one uniform sample in
/// each, `x_k = a + (b - a)(k + u_k) / strata`. Each replicate estimate `(b - a) mean f(x_k)` is
/// unbiased; for a smooth `f` its error falls as `strata^(-3/2)` instead of `strata^(-1/2)`.
///
/// The samples of one replicate are not independent, so the variance of `f(x_k)` says nothing about
/// the error. The estimator therefore runs `replicates` (at least 2) independent jittered sets and
/// takes the standard error from their spread; it evaluates `f` `strata * replicates` times.
pub fn jittered<F, R>(
    f: F,
    domain: Interval,
    strata: u64,
    replicates: u32,
    rng: &mut R,
) -> Result<Estimate, McError>
where
    F: Fn(f64) -> f64,
    R: Rng + ?Sized,
{
    nonzero("jittered", strata)?;
    replicates_ok("jittered", replicates)?;
    let samples = sample_count("jittered", strata, replicates as u64, 1)?;
    let start = Instant::now();
    let mut stats = RunningStats::new();
    let width = 1.0 / strata as f64;
    for _ in 0..replicates {
        // the mean of f over the strata, summed as f / strata so that it cannot overflow
        let mut mean = 0.0;
        for k in 0..strata {
            let x = domain.lerp((k as f64 + rng.random::<f64>()) * width);
            mean += finite("jittered", x, f(x))? * width;
        }
        let what = "(b - a) times the mean of f";
        stats.push(product("jittered", what, domain, domain.length(), mean)?);
    }
    Ok(Estimate {
        stats,
        samples,
        elapsed: start.elapsed(),
    })
}
// ANCHOR_END: jittered

/// Jittered sampling on a rectangle: an `nx` by `ny` grid of cells with one uniform sample in each (the
/// book's `sqrt_N` by `sqrt_N` grid for estimating pi), repeated `replicates` times for the standard
/// error as in [`jittered`].
pub fn jittered_2d<F, R>(
    f: F,
    domain: Rect,
    (nx, ny): (u64, u64),
    replicates: u32,
    rng: &mut R,
) -> Result<Estimate, McError>
where
    F: Fn([f64; 2]) -> f64,
    R: Rng + ?Sized,
{
    nonzero("jittered_2d", nx.min(ny))?;
    replicates_ok("jittered_2d", replicates)?;
    let samples = sample_count("jittered_2d", nx, ny, replicates as u64)?;
    let area = domain.checked_area()?;
    let start = Instant::now();
    let mut stats = RunningStats::new();
    let (wx, wy) = (1.0 / nx as f64, 1.0 / ny as f64);
    for _ in 0..replicates {
        let mut mean = 0.0;
        for i in 0..nx {
            for j in 0..ny {
                let s = (i as f64 + rng.random::<f64>()) * wx;
                let t = (j as f64 + rng.random::<f64>()) * wy;
                let p = domain.lerp(s, t);
                mean += finite("jittered_2d", p, f(p))? * wx * wy;
            }
        }
        let what = "area times the mean of f";
        stats.push(product("jittered_2d", what, domain, area, mean)?);
    }
    Ok(Estimate {
        stats,
        samples,
        elapsed: start.elapsed(),
    })
}
