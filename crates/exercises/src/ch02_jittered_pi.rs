//! # Chapter 2, A Simple Monte Carlo Program, "Stratified samples (jittering)": estimate pi with one point per grid cell
//!
//! The checks of the exercise `crates/exercises/exercises/ch02_jittered_pi.rs`, which states the
//! task.

use crate::check::{self, Arg, CheckResult, Generator};
use rand::RngCore;
use statrs::distribution::{ChiSquared, ContinuousCDF};
use std::f64::consts::PI;

/// Unbiased (mean of 400 estimates of 16 x 16 points z-tested against pi) and of variance below
/// the variance of 256 independent points.
pub fn check_jittered_pi(estimate: impl Fn(usize, &mut dyn RngCore) -> Option<f64>) -> CheckResult {
    let estimate = |k: usize, rng: &mut Generator| {
        let args = [("sqrt_n", Arg::Count(k)), ("rng", rng.arg())];
        check::calling("jittered_pi", &args, || estimate(k, rng))
    };
    if let Some(x) = estimate(0, &mut Generator::new(5)) {
        return Err(format!(
            "jittered_pi(0) returned Some({}); no samples give no estimate (None)",
            check::num(x)
        ));
    }
    let (k, reps) = (16usize, 400usize);
    let mut rng = Generator::new(6);
    let mut values = Vec::with_capacity(reps);
    for _ in 0..reps {
        values.push(estimate(k, &mut rng).ok_or("jittered_pi(16) returned None")?);
    }
    let (mean, se) = check::mean_and_std_error(values.iter().copied());
    check::z_test(
        "mean of 400 jittered estimates of pi (16 x 16 points each)",
        mean,
        se,
        PI,
    )?;
    // Under "no better than independent points" (variance sigma0^2), (reps - 1) s^2 / sigma0^2 is
    // chi-square with reps - 1 degrees of freedom; stratification must put it below the 1e-6 quantile.
    let p = PI / 4.0;
    let sigma0_sq = 16.0 * p * (1.0 - p) / (k * k) as f64;
    let s_sq = se * se * reps as f64;
    let stat = (reps - 1) as f64 * s_sq / sigma0_sq;
    let bound = ChiSquared::new((reps - 1) as f64)
        .expect("dof > 0")
        .inverse_cdf(check::Z_FALSE_FAILURE);
    if stat < bound {
        Ok(())
    } else {
        Err(format!(
            "jittered_pi: variance {} is not below the {} of independent points (ratio {:.2}); are \
             the points stratified, one per cell?",
            check::sig(s_sq, 3),
            check::sig(sigma0_sq, 3),
            s_sq / sigma0_sq
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::Rng;

    #[test]
    fn check_rejects_unstratified_points_and_cell_centres() {
        // Wrong: independent points, not one per cell (unbiased, but no variance reduction).
        let plain = |k: usize, rng: &mut dyn RngCore| {
            let inside = (0..k * k)
                .filter(|_| {
                    let (x, y): (f64, f64) =
                        (rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0));
                    x * x + y * y < 1.0
                })
                .count();
            (k > 0).then(|| 4.0 * inside as f64 / (k * k) as f64)
        };
        let err = check_jittered_pi(plain).unwrap_err();
        assert!(err.contains("variance"), "{err}");
        // Wrong: cell centres without jitter (zero variance, but biased).
        let centres = |k: usize, _: &mut dyn RngCore| {
            let cell = 2.0 / k as f64;
            let inside = (0..k * k)
                .filter(|m| {
                    let x = -1.0 + cell * ((m / k) as f64 + 0.5);
                    let y = -1.0 + cell * ((m % k) as f64 + 0.5);
                    x * x + y * y < 1.0
                })
                .count();
            (k > 0).then(|| 4.0 * inside as f64 / (k * k) as f64)
        };
        assert!(check_jittered_pi(centres).is_err());
    }

    #[test]
    fn a_panic_names_the_grid_and_how_to_replay_the_generator() {
        // Panics in the third estimate of 16 x 16 points, at its first draw; each estimate before
        // it drew 2 values per point.
        let calls = std::cell::Cell::new(0);
        let report = crate::harness::panic_of(move || {
            check_jittered_pi(|k: usize, rng: &mut dyn RngCore| {
                if k > 0 {
                    calls.set(calls.get() + 1);
                }
                let x: f64 = rng.random();
                assert!(calls.get() < 3, "the third estimate");
                for _ in 1..2 * k * k {
                    let _: f64 = rng.random();
                }
                (k > 0).then_some(PI + x - x)
            })
        });
        let mut replayed = check::replay(6, 2 * 2 * 256);
        let u = check::num(replayed.random::<f64>());
        assert!(
            report.starts_with(&format!(
                "your code panicked in jittered_pi(sqrt_n = 16, rng = \
                 rtl_exercises::check::replay(6, 1024)), which drew u = {u}, at "
            )),
            "{report}"
        );
    }
}
