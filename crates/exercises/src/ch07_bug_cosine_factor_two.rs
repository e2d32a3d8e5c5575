//! # Bug museum, chapter 7, Generating Random Directions, "Cosine-weighted": the cosine warp's factor 2
//!
//! The checks of the exercise `crates/exercises/exercises/ch07_bug_cosine_factor_two.rs`, which holds
//! the bug to find.
//!
//! The check: unit directions above the horizon at the corners of [0, 1)^2; the mean of cos theta
//! over 1e5 directions z-tested against 2/3, its value under the density cos theta / pi (false failure
//! 1e-6); and the chi-square test of chapter 7's exercise against cos theta / pi.
//!
//! A failing mean names the factor-2 bug only when the mean matches that bug's own: the disc point at
//! radius 2 sqrt(u2), lifted to z = sqrt(1 - u2) and normalised, has
//! cos theta = sqrt((1 - u2) / (1 + 3 u2)), so P(cos theta <= t) = 4 t^2 / (1 + 3 t^2) and
//! E[cos theta] = integral from 0 to 1 of (1 - t^2) / (1 + 3 t^2) dt = 4 pi / (9 sqrt 3) - 1/3 = 0.4728
//! ([`FACTOR_TWO_MEAN_COSINE`]); a mean that the z-test cannot tell from it gets the specific
//! diagnosis, any other a general one.

use crate::ch07_cosine_direction;
use crate::check::{self, CheckResult};
use glam::DVec3;
use rand::Rng;
use std::f64::consts::PI;

/// E[cos theta] under the factor-2 bug: 4 pi / (9 sqrt 3) - 1/3 (about 0.4728).
pub const FACTOR_TWO_MEAN_COSINE: f64 = 4.0 * PI / (9.0 * 1.732_050_807_568_877_2) - 1.0 / 3.0;

/// Unit, upper-hemisphere directions at the corners of [0, 1)^2.
pub fn check_corners(sample: impl Fn(f64, f64) -> DVec3) -> CheckResult {
    ch07_cosine_direction::check_corners(sample)
}

/// E[cos theta] = integral of cos theta (cos theta / pi) d omega = 2/3: z-test of 1e5 directions.
/// A failure names the factor-2 bug only if the mean is also within the z-test's reach of
/// [`FACTOR_TWO_MEAN_COSINE`].
pub fn check_mean_cosine(sample: impl Fn(f64, f64) -> DVec3) -> CheckResult {
    let sample = ch07_cosine_direction::recorded(sample);
    let mut rng = check::seeded(71);
    let zs: Vec<f64> = (0..100_000)
        .map(|_| sample(rng.random(), rng.random()).normalize_or_zero().z)
        .collect();
    let (mean, se) = check::mean_and_std_error(zs.iter().copied());
    check::z_test_mean("the mean of cos theta over your directions", zs, 2.0 / 3.0).map_err(|e| {
        let like_factor_two = ((mean - FACTOR_TWO_MEAN_COSINE) / se).abs() < check::z_critical();
        let why = if like_factor_two {
            format!(
                "what directions give whose disc point can lie outside the unit disc before it is \
                 lifted, {}: how far from the centre can yours get?",
                check::sig(FACTOR_TWO_MEAN_COSINE, 4)
            )
        } else if mean < 2.0 / 3.0 {
            "they lean towards the horizon".to_string()
        } else {
            "they crowd around the normal".to_string()
        };
        format!(
            "{e}\n(under cos theta / pi the mean of cos theta is 2/3; yours is {}: {why})",
            check::sig(mean, 4)
        )
    })
}

/// Chi-square test of 1e5 directions against cos theta / pi.
pub fn check_distribution(sample: impl Fn(f64, f64) -> DVec3) -> CheckResult {
    ch07_cosine_direction::check_distribution(sample)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn checks_reject_the_books_old_factor_two() {
        let factor_two = |u1: f64, u2: f64| {
            let phi = 2.0 * PI * u1;
            DVec3::new(
                phi.cos() * 2.0 * u2.sqrt(),
                phi.sin() * 2.0 * u2.sqrt(),
                (1.0 - u2).sqrt(),
            )
            .normalize()
        };
        let err = check_mean_cosine(factor_two).unwrap_err();
        assert!(
            err.contains("disc point can lie outside the unit disc"),
            "{err}"
        );
        // the symptom, not the fix (the hints give that)
        assert!(!err.contains("2 sqrt"), "{err}");
        assert!(check_distribution(factor_two).is_err());
    }

    #[test]
    fn the_factor_two_diagnosis_is_given_only_for_the_factor_two_mean() {
        assert!((FACTOR_TWO_MEAN_COSINE - 0.472_799_717_437_43).abs() < 1e-12);
        // Another mistake that leans to the horizon: uniform directions (mean 1/2). The mean fails,
        // but it is not the factor-2 bug's, so the diagnosis is the general one.
        let uniform = |u1: f64, u2: f64| {
            let phi = 2.0 * PI * u1;
            let r = (1.0 - u2 * u2).sqrt();
            DVec3::new(phi.cos() * r, phi.sin() * r, u2)
        };
        let err = check_mean_cosine(uniform).unwrap_err();
        assert!(err.contains("lean towards the horizon"), "{err}");
        assert!(!err.contains("outside the unit disc"), "{err}");
    }

    #[test]
    fn a_panic_in_the_mean_names_the_uniforms() {
        let report = crate::harness::panic_of(|| {
            check_mean_cosine(|u1: f64, u2: f64| -> DVec3 { panic!("{u1} {u2}") })
        });
        let mut rng = check::seeded(71);
        let (u1, u2): (f64, f64) = (rng.random(), rng.random());
        let (u1, u2) = (check::num(u1), check::num(u2));
        assert!(
            report.starts_with(&format!(
                "your code panicked in random_cosine_direction(u1 = {u1}, u2 = {u2}) at "
            )) && report.ends_with(&format!(": {u1} {u2}")),
            "{report}"
        );
    }
}
