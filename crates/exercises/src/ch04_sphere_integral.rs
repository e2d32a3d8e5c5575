//! # Chapter 4, Monte Carlo Integration on the Sphere of Directions, "A density over directions": integrate cos^2 theta
//!
//! The checks of the exercise `crates/exercises/exercises/ch04_sphere_integral.rs`, which states the
//! task.
//!
//! The check: unit length (to 1e-12) at u = 0 and u = 1 - 2^-53; a chi-square test of 1e5 directions
//! in 16 x 9 equal-area (phi, z) cells; and a z-test of the estimate with its exact variance
//! 16 pi^2 (1/5 - 1/9) / n.

use crate::check::{self, Arg, CheckResult, Generator, SphereBins, U_MAX};
use glam::DVec3;
use rand::{Rng, RngCore};
use std::f64::consts::PI;

/// Unit length at the corners of [0, 1)^2, and a chi-square test of 1e5 directions.
pub fn check_uniform_sphere(sample: impl Fn(f64, f64) -> DVec3) -> CheckResult {
    let sample = |u1: f64, u2: f64| {
        let args = [("u1", Arg::Real(u1)), ("u2", Arg::Real(u2))];
        check::calling("uniform_sphere", &args, || sample(u1, u2))
    };
    for u1 in [0.0, 0.5, U_MAX] {
        for u2 in [0.0, 0.25, U_MAX] {
            check::unit(&format!("uniform_sphere({u1}, {u2})"), sample(u1, u2))?;
        }
    }
    let bins = SphereBins {
        n_phi: 16,
        n_z: 9,
        z_min: -1.0,
        z_max: 1.0,
        pole: "+z",
    };
    let n = 100_000;
    let mut rng = check::seeded(40);
    let dirs: Vec<DVec3> = (0..n).map(|_| sample(rng.random(), rng.random())).collect();
    let observed = bins.histogram("uniform_sphere", dirs)?;
    let expected = bins.expected(n, |_| 1.0 / (4.0 * PI), |_, _| true, 4);
    check::chi_square("uniform_sphere", &observed, &expected, &bins)
}

/// z-test of the estimate from 1e5 directions against 4 pi / 3; `None` for `n = 0`.
pub fn check_estimate(estimate: impl Fn(usize, &mut dyn RngCore) -> Option<f64>) -> CheckResult {
    let estimate = |n: usize, rng: &mut Generator| {
        let args = [("n", Arg::Count(n)), ("rng", rng.arg())];
        check::calling("estimate_cos_sq", &args, || estimate(n, rng))
    };
    if let Some(x) = estimate(0, &mut Generator::new(41)) {
        return Err(format!(
            "estimate_cos_sq(0) returned Some({}); no samples give no estimate (None)",
            check::num(x)
        ));
    }
    let n = 100_000;
    let got =
        estimate(n, &mut Generator::new(42)).ok_or("estimate_cos_sq(100000) returned None")?;
    let se = (16.0 * PI * PI * (1.0 / 5.0 - 1.0 / 9.0) / n as f64).sqrt();
    check::z_test("integral of cos^2 over the sphere", got, se, 4.0 * PI / 3.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checks_reject_wrong_samplers_and_estimators() {
        // Wrong: theta uniform in [0, pi] crowds the poles.
        let theta_uniform = |u1: f64, u2: f64| {
            let (theta, phi) = (PI * u1, 2.0 * PI * u2);
            DVec3::new(
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                theta.cos(),
            )
        };
        let err = check_uniform_sphere(theta_uniform).unwrap_err();
        // theta uniform puts too many directions near the poles, too few at the equator (the
        // three rings there fall short alike: which one is named depends on the seed).
        assert!(
            ["[-0.333, -0.111]", "[-0.111, 0.111]", "[0.111, 0.333]"]
                .iter()
                .any(|ring| err.contains(&format!("\ntoo few at cos theta in {ring}: ")))
                && (err.contains("\ntoo many opposite +z: cos theta in [-1, -0.778]: ")
                    || err.contains("\ntoo many near +z: cos theta in [0.778, 1]: ")),
            "{err}"
        );
        // Wrong: forgets to divide by the pdf (estimates the mean of cos^2, 1/3).
        let mean_only = |n: usize, rng: &mut dyn RngCore| {
            (n > 0).then(|| {
                (0..n)
                    .map(|_| (1.0 - 2.0 * rng.random::<f64>()).powi(2))
                    .sum::<f64>()
                    / n as f64
            })
        };
        assert!(check_estimate(mean_only).is_err());
    }

    #[test]
    fn a_panic_names_the_input_of_either_function() {
        // The estimate panics at once for n > 0, before drawing.
        let report = crate::harness::panic_of(|| {
            check_estimate(|n: usize, _: &mut dyn RngCore| {
                assert!(n == 0, "no estimate yet");
                None
            })
        });
        assert!(
            report.starts_with(
                "your code panicked in estimate_cos_sq(n = 100000, rng = \
                 rtl_exercises::check::seeded(42)), which drew nothing from rng, at "
            ),
            "{report}"
        );
        // The sampler panics at u1 = 1 - 2^-53 of the corners.
        let report = crate::harness::panic_of(|| {
            check_uniform_sphere(|u1: f64, _: f64| {
                assert!(u1 < 0.75, "u1 near 1");
                DVec3::Z
            })
        });
        assert!(
            report.starts_with(
                "your code panicked in uniform_sphere(u1 = 0.9999999999999999, u2 = 0) at "
            ),
            "{report}"
        );
    }
}
