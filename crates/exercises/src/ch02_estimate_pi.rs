//! # Chapter 2, A Simple Monte Carlo Program, "Estimating π": estimate pi by throwing darts
//!
//! The checks of the exercise `crates/exercises/exercises/ch02_estimate_pi.rs`, which states the
//! task.

use crate::check::{self, Arg, CheckResult, Generator};
use rand::RngCore;
use std::f64::consts::PI;

/// The estimator under test: `(n, rng) -> estimate`.
pub trait PiEstimator: Fn(usize, &mut dyn RngCore) -> Option<f64> {}
impl<F: Fn(usize, &mut dyn RngCore) -> Option<f64>> PiEstimator for F {}

/// `estimate` with its calls recorded, so that a panic names the `n` and the generator (where it
/// was, and what it drew) that caused it.
fn recorded(estimate: impl PiEstimator) -> impl Fn(usize, &mut Generator) -> Option<f64> {
    move |n: usize, rng: &mut Generator| {
        let args = [("n", Arg::Count(n)), ("rng", rng.arg())];
        check::calling("estimate_pi", &args, || estimate(n, rng))
    }
}

/// With 1e5 points the estimate is within 4.89 standard errors of pi (false failure 1e-6).
pub fn check_value(estimate: impl PiEstimator) -> CheckResult {
    let estimate = recorded(estimate);
    let n = 100_000;
    let p = PI / 4.0;
    let se = 4.0 * (p * (1.0 - p) / n as f64).sqrt();
    let got = estimate(n, &mut Generator::new(2)).ok_or("estimate_pi(100000) returned None")?;
    check::z_test("estimate_pi with 1e5 points", got, se, PI)
}

/// `n = 0` gives `None`; otherwise the estimate is 4 k / n for a whole number k in [0, n].
pub fn check_lattice(estimate: impl PiEstimator) -> CheckResult {
    let estimate = recorded(estimate);
    if let Some(x) = estimate(0, &mut Generator::new(3)) {
        return Err(format!(
            "estimate_pi(0) returned Some({}); no samples give no estimate (None)",
            check::num(x)
        ));
    }
    let mut rng = Generator::new(4);
    for n in [1usize, 2, 3, 10, 1000] {
        let got = estimate(n, &mut rng).ok_or(format!("estimate_pi({n}) returned None"))?;
        let k = got * n as f64 / 4.0;
        if !(0.0..=n as f64).contains(&k) || (k - k.round()).abs() > 1e-9 {
            return Err(format!(
                "estimate_pi({n}) = {}: that is no count of points inside the circle (0 to {n}) \
                 times the one constant that makes the estimate's mean pi, divided by {n}",
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
        // The fraction inside, with n = 0 handled: the message names the symptom, not the formula.
        let fraction = |n: usize, rng: &mut dyn RngCore| {
            if n == 0 {
                None
            } else {
                without_factor_4(n, rng)
            }
        };
        let err = check_lattice(fraction).unwrap_err();
        assert!(
            err.starts_with("estimate_pi(") && err.contains("that is no count of points"),
            "{err}"
        );
        assert!(
            !err.contains("4 k") && !err.contains("4k"),
            "no formula: {err}"
        );
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

    #[test]
    fn a_panic_names_n_and_how_to_replay_the_generator() {
        // Panics at the 4th point of the 10-point call of the lattice check, after the calls with
        // 1, 2 and 3 points drew 12 values.
        fn panics_at_10(n: usize, rng: &mut dyn RngCore) -> Option<f64> {
            for i in 0..n {
                let _: (f64, f64) = (rng.random(), rng.random());
                assert!(!(n == 10 && i == 3), "point 3 of 10");
            }
            (n > 0).then_some(4.0)
        }
        let report = crate::harness::panic_of(|| check_lattice(panics_at_10));
        // The generator the report names draws the values it shows: the 5th to 8th after 12.
        let mut replayed = check::replay(4, 12);
        let u: Vec<f64> = (0..8).map(|_| replayed.random::<f64>()).collect();
        let call = format!(
            "your code panicked in estimate_pi(n = 10, rng = rtl_exercises::check::replay(4, 12)), \
             which drew 8 uniforms, the last u = {}, {}, {}, {}, at ",
            check::num(u[4]),
            check::num(u[5]),
            check::num(u[6]),
            check::num(u[7])
        );
        assert!(report.starts_with(&call), "{report}\n{call}");
        assert!(report.ends_with(": point 3 of 10"), "{report}");
    }
}
