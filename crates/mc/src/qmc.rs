//! Randomised quasi-Monte Carlo: the average of `f` over an Owen-scrambled Sobol point set.

use crate::estimate::{finite, nonzero, product};
use crate::sequence::{ScrambledSobol2, scrambled_sobol};
use crate::stratified::replicates_ok;
use crate::{Estimate, Interval, McError, Rect, RunningStats};
use rand::Rng;
use std::time::Instant;

fn points_ok(estimator: &'static str, points: u64) -> Result<(), McError> {
    nonzero(estimator, points)?;
    if points > 1 << 32 {
        return Err(McError::TooManyPoints { estimator, points });
    }
    Ok(())
}

// ANCHOR: sobol_estimator
/// Randomised quasi-Monte Carlo on `[a, b]`: `(b - a)` times the mean of `f` over the first `points`
/// points of an Owen-scrambled Sobol sequence. A quasi-random point set has no variance to estimate, so
/// the estimator runs `replicates` (at least 2) independent scrambles, seeded from `rng`, and takes the
/// standard error from their spread (randomised QMC, Owen 1997). For smooth `f` and `points` a power of
/// two the error falls as about `points^(-3/2)`.
pub fn sobol<F, R>(
    f: F,
    domain: Interval,
    points: u64,
    replicates: u32,
    rng: &mut R,
) -> Result<Estimate, McError>
where
    F: Fn(f64) -> f64,
    R: Rng + ?Sized,
{
    points_ok("sobol", points)?;
    replicates_ok("sobol", replicates)?;
    let start = Instant::now();
    let mut stats = RunningStats::new();
    for _ in 0..replicates {
        let seed = rng.next_u64();
        // the mean of f, summed as f / points so that it cannot overflow
        let (mut mean, w) = (0.0, 1.0 / points as f64);
        for i in 0..points {
            let x = domain.lerp(scrambled_sobol(i as u32, 0, seed));
            mean += finite("sobol", x, f(x))? * w;
        }
        let what = "(b - a) times the mean of f";
        stats.push(product("sobol", what, domain, domain.length(), mean)?);
    }
    Ok(Estimate {
        stats,
        samples: points * replicates as u64,
        elapsed: start.elapsed(),
    })
}
// ANCHOR_END: sobol_estimator

/// Randomised quasi-Monte Carlo on a rectangle with the 2D scrambled Sobol points, as [`sobol`].
pub fn sobol_2d<F, R>(
    f: F,
    domain: Rect,
    points: u64,
    replicates: u32,
    rng: &mut R,
) -> Result<Estimate, McError>
where
    F: Fn([f64; 2]) -> f64,
    R: Rng + ?Sized,
{
    points_ok("sobol_2d", points)?;
    replicates_ok("sobol_2d", replicates)?;
    let area = domain.checked_area()?;
    let start = Instant::now();
    let mut stats = RunningStats::new();
    for _ in 0..replicates {
        let seed = rng.next_u64();
        let (mut mean, w) = (0.0, 1.0 / points as f64);
        for [s, t] in ScrambledSobol2::new(seed).take(points as usize) {
            let p = domain.lerp(s, t);
            mean += finite("sobol_2d", p, f(p))? * w;
        }
        let what = "area times the mean of f";
        stats.push(product("sobol_2d", what, domain, area, mean)?);
    }
    Ok(Estimate {
        stats,
        samples: points * replicates as u64,
        elapsed: start.elapsed(),
    })
}
