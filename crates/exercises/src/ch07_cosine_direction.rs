//! # Chapter 7, Generating Random Directions, "Cosine-weighted": a cosine-weighted direction and its pdf
//!
//! The checks of the exercise `crates/exercises/exercises/ch07_cosine_direction.rs`, which states the
//! task.
//!
//! The check: unit length to 1e-12 and z >= 0 at u = 0 and u = 1 - 2^-53 (where z = sqrt(2^-53) is
//! tiny but must not underflow the length); exact pdf values; and a chi-square test of 1e5 directions
//! in 16 x 10 cells of (phi, z) on the hemisphere, against n (delta phi / 2 pi) (z_hi^2 - z_lo^2), the
//! exact integral of the density over each cell.

use crate::check::{self, Arg, CheckResult, SphereBins, U_MAX};
use glam::DVec3;
use rand::Rng;
use std::f64::consts::FRAC_1_PI;

/// `sample` with its call recorded, so that a panic names the (u1, u2) that caused it.
pub(crate) fn recorded(sample: impl Fn(f64, f64) -> DVec3) -> impl Fn(f64, f64) -> DVec3 {
    move |u1, u2| {
        let args = [("u1", Arg::Real(u1)), ("u2", Arg::Real(u2))];
        check::calling("random_cosine_direction", &args, || sample(u1, u2))
    }
}

/// Unit, upper-hemisphere directions at the corners of [0, 1)^2.
pub fn check_corners(sample: impl Fn(f64, f64) -> DVec3) -> CheckResult {
    let sample = recorded(sample);
    for u1 in [0.0, 0.25, U_MAX] {
        for u2 in [0.0, 0.5, U_MAX] {
            let d = sample(u1, u2);
            let u = |x: f64| {
                if x == U_MAX {
                    "1 - 2^-53".to_string()
                } else {
                    check::num(x)
                }
            };
            let what = format!("random_cosine_direction(u1 = {}, u2 = {})", u(u1), u(u2));
            check::unit(&what, d)?;
            if d.z.is_nan() || d.z < 0.0 {
                return Err(format!("{what} = {d} is below the horizon"));
            }
        }
    }
    Ok(())
}

/// Chi-square test of 1e5 directions against the cosine density.
pub fn check_distribution(sample: impl Fn(f64, f64) -> DVec3) -> CheckResult {
    let bins = SphereBins::hemisphere();
    let sample = recorded(sample);
    let n = 100_000;
    let mut rng = check::seeded(70);
    let dirs: Vec<DVec3> = (0..n).map(|_| sample(rng.random(), rng.random())).collect();
    let observed = bins.histogram("random_cosine_direction", dirs)?;
    let expected: Vec<f64> = (0..bins.n_z * bins.n_phi)
        .map(|c| {
            let (lo, hi) = bins.z_range(c / bins.n_phi);
            n as f64 * (hi * hi - lo * lo) / bins.n_phi as f64
        })
        .collect();
    check::chi_square("random_cosine_direction", &observed, &expected, &bins)
}

/// Exact values of the pdf: 1/pi at the pole, 1/(2 pi) at 60 degrees, 0 at and below the horizon.
pub fn check_pdf(pdf: impl Fn(f64) -> f64) -> CheckResult {
    for (c, want) in [
        (1.0, FRAC_1_PI),
        (0.5, 0.5 * FRAC_1_PI),
        (1e-300, 1e-300 * FRAC_1_PI),
        (0.0, 0.0),
        (-1e-12, 0.0),
        (-1.0, 0.0),
    ] {
        let got = check::calling("cosine_pdf_value", &[("cos_theta", Arg::Real(c))], || {
            pdf(c)
        });
        if got.is_nan() || got < 0.0 {
            return Err(format!(
                "cosine_pdf_value({}) = {}; a density is never negative or NaN",
                check::num(c),
                check::num(got)
            ));
        }
        check::close(
            &format!("cosine_pdf_value({})", check::num(c)),
            got,
            want,
            1e-15,
        )?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn checks_reject_wrong_warps_and_pdfs() {
        // Wrong: the factor-2 bug phi = pi u1 covers half the hemisphere.
        let half_circle = |u1: f64, u2: f64| {
            let phi = PI * u1;
            DVec3::new(
                phi.cos() * u2.sqrt(),
                phi.sin() * u2.sqrt(),
                (1.0 - u2).sqrt(),
            )
        };
        assert!(check_distribution(half_circle).is_err());
        // Wrong: radius u2 instead of sqrt(u2) (and then not of unit length).
        let no_sqrt = |u1: f64, u2: f64| {
            let phi = 2.0 * PI * u1;
            DVec3::new(phi.cos() * u2, phi.sin() * u2, (1.0 - u2).sqrt())
        };
        assert!(check_corners(no_sqrt).is_err());
        assert!(check_distribution(no_sqrt).is_err());
        // Wrong: z = 1 - u2 instead of sqrt(1 - u2): directions lean to the horizon, and the failure
        // says where.
        let linear_z = |u1: f64, u2: f64| {
            let phi = 2.0 * PI * u1;
            DVec3::new(phi.cos() * u2.sqrt(), phi.sin() * u2.sqrt(), 1.0 - u2)
        };
        let err = check_distribution(linear_z).unwrap_err();
        assert!(
            err.contains("\ntoo many near the horizon: cos theta in [0, 0.1]: ")
                && err.contains("1,000 expected")
                && err.contains("\ntoo few at cos theta in ["),
            "{err}"
        );
        // Wrong: uniform hemisphere z = u2 is not cosine-weighted.
        let uniform = |u1: f64, u2: f64| {
            let phi = 2.0 * PI * u1;
            let r = (1.0 - u2 * u2).sqrt();
            DVec3::new(phi.cos() * r, phi.sin() * r, u2)
        };
        assert!(check_distribution(uniform).is_err());
        // Wrong: the factor-2 bug in the pdf (cos / (2 pi)), and an unclamped cosine.
        assert!(check_pdf(|c: f64| c.max(0.0) / (2.0 * PI)).is_err());
        assert!(check_pdf(|c: f64| c / PI).is_err());
    }

    #[test]
    fn a_panic_names_the_uniforms_drawn() {
        // Panics only where u1 > 0.9999, which 1e5 draws reach about 10 times.
        let report = crate::harness::panic_of(|| {
            check_distribution(|u1: f64, _: f64| {
                assert!(u1 <= 0.9999, "u1 = {u1}");
                DVec3::Z
            })
        });
        let (call, message) = report.split_once(") at ").expect(&report);
        let u1 = call
            .strip_prefix("your code panicked in random_cosine_direction(u1 = ")
            .and_then(|rest| rest.split_once(", u2 = "))
            .map(|(u1, _)| u1.parse::<f64>().unwrap());
        assert!(u1.is_some_and(|u1| u1 > 0.9999), "{report}");
        assert!(
            message.ends_with(&format!("u1 = {}", u1.unwrap())),
            "{report}"
        );
    }
}
