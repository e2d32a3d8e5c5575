//! # Chapter 2, A Simple Monte Carlo Program, "Estimating π": estimate pi by throwing darts
//!
//! The checks of the exercise `crates/exercises/exercises/ch02_estimate_pi.rs`, which states the
//! task.

use crate::check::{self, Arg, CheckResult};
use rand::RngCore;
use std::f64::consts::PI;

/// The estimator under test: `(n, rng) -> estimate`.
pub trait PiEstimator: Fn(usize, &mut dyn RngCore) -> Option<f64> {}
impl<F: Fn(usize, &mut dyn RngCore) -> Option<f64>> PiEstimator for F {}

/// `estimate` with its calls recorded, so that a panic names the `n` that caused it.
fn recorded(estimate: impl PiEstimator) -> impl PiEstimator {
    move |n: usize, rng: &mut dyn RngCore| {
        check::calling("estimate_pi", &[("n", Arg::Count(n))], || estimate(n, rng))
    }
}

/// With 1e5 points the estimate is within 4.89 standard errors of pi (false failure 1e-6).
pub fn check_value(estimate: impl PiEstimator) -> CheckResult {
    let estimate = recorded(estimate);
    let n = 100_000;
    let p = PI / 4.0;
    let se = 4.0 * (p * (1.0 - p) / n as f64).sqrt();
    let got = estimate(n, &mut check::seeded(2)).ok_or("estimate_pi(100000) returned None")?;
    check::z_test("estimate_pi with 1e5 points", got, se, PI)
}

/// `n = 0` gives `None`; otherwise the estimate is 4 k / n for a whole number k in [0, n].
pub fn check_lattice(estimate: impl PiEstimator) -> CheckResult {
    let estimate = recorded(estimate);
    if let Some(x) = estimate(0, &mut check::seeded(3)) {
        return Err(format!(
            "estimate_pi(0) returned Some({}); no samples give no estimate (None)",
            check::num(x)
        ));
    }
    let mut rng = check::seeded(4);
    for n in [1usize, 2, 3, 10, 1000] {
        let got = estimate(n, &mut rng).ok_or(format!("estimate_pi({n}) returned None"))?;
        let k = got * n as f64 / 4.0;
        if !(0.0..=n as f64).contains(&k) || (k - k.round()).abs() > 1e-9 {
            return Err(format!(
                "estimate_pi({n}) = {} is not 4 k / {n} for a count k in 0..={n}",
                check::num(got)
            ));
        }
    }
    Ok(())
}

/// All of this exercise's checks.
pub fn check_estimate_pi(estimate: impl PiEstimator) -> CheckResult {
    check_lattice(&estimate)?;
    check_value(&estimate)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::Rng;

    /// Wrong: forgets the factor 4 (estimates pi/4); and returns NaN for n = 0.
    fn without_factor_4(n: usize, rng: &mut dyn RngCore) -> Option<f64> {
        let inside = (0..n)
            .filter(|_| {
                let (x, y): (f64, f64) = (rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0));
                x * x + y * y < 1.0
            })
            .count();
        Some(inside as f64 / n as f64)
    }

    #[test]
    fn checks_reject_a_wrong_estimator() {
        assert!(check_value(without_factor_4).is_err());
        assert!(check_lattice(without_factor_4).is_err());
        // Wrong: the circle of radius 1/2 (x^2 + y^2 < 0.5^2 read as < 0.5).
        let half = |n: usize, rng: &mut dyn RngCore| {
            let inside = (0..n)
                .filter(|_| {
                    let (x, y): (f64, f64) =
                        (rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0));
                    x * x + y * y < 0.5
                })
                .count();
            (n > 0).then(|| 4.0 * inside as f64 / n as f64)
        };
        assert!(check_value(half).is_err());
    }
}
