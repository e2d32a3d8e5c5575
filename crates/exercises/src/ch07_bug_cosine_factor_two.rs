//! # Bug museum, chapter 7: the cosine warp's factor 2
//!
//! The checks of the exercise `crates/exercises/exercises/ch07_bug_cosine_factor_two.rs`, which holds
//! the bug to find.
//!
//! The check: unit directions above the horizon at the corners of [0, 1)^2; the mean of cos theta
//! over 1e5 directions z-tested against 2/3, its value under the density cos theta / pi (false failure
//! 1e-6); and the chi-square test of chapter 7's exercise against cos theta / pi.

use crate::ch07_cosine_direction;
use crate::check::{self, CheckResult};
use glam::DVec3;
use rand::Rng;

/// Unit, upper-hemisphere directions at the corners of [0, 1)^2.
pub fn check_corners(sample: impl Fn(f64, f64) -> DVec3) -> CheckResult {
    ch07_cosine_direction::check_corners(sample)
}

/// E[cos theta] = integral of cos theta (cos theta / pi) d omega = 2/3: z-test of 1e5 directions.
pub fn check_mean_cosine(sample: impl Fn(f64, f64) -> DVec3) -> CheckResult {
    let mut rng = check::seeded(71);
    let zs: Vec<f64> = (0..100_000)
        .map(|_| sample(rng.random(), rng.random()).normalize_or_zero().z)
        .collect();
    let (mean, _) = check::mean_and_std_error(zs.iter().copied());
    check::z_test_mean("the mean of cos theta over your directions", zs, 2.0 / 3.0).map_err(|e| {
        let lean = if mean < 2.0 / 3.0 {
            "they lean towards the horizon: the disc point was pushed outwards before it was lifted"
        } else {
            "they crowd around the normal"
        };
        format!(
            "{e}\n(under cos theta / pi the mean of cos theta is 2/3; yours is {mean:.4}: {lean})"
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
        assert!(err.contains("horizon"), "{err}");
        assert!(check_distribution(factor_two).is_err());
    }
}
