//! # Chapter 5, Light Scattering, "The Lambertian surface": the scattering pdf of a Lambertian surface
//!
//! The checks of the exercise `crates/exercises/exercises/ch05_lambertian_pdf.rs`, which states the
//! task.
//!
//! The check: exact values (1/pi along the normal, 1/(2 pi) at 60 degrees, 0 when grazing and below),
//! never negative nor NaN, and a z-test (1e5 uniform directions, for a few normals) that
//! E[4 pi s(d)] = 1, i.e. the density integrates to 1 over the sphere.

use crate::check::{self, Arg, CheckResult};
use glam::DVec3;
use std::f64::consts::{FRAC_1_PI, PI};

/// Exact values, including grazing and below the surface.
pub fn check_values(pdf: impl Fn(DVec3, DVec3) -> f64) -> CheckResult {
    let pdf = |n: DVec3, d: DVec3| {
        let args = [("normal", Arg::Vector(n)), ("direction", Arg::Vector(d))];
        check::calling("lambertian_scattering_pdf", &args, || pdf(n, d))
    };
    let n = DVec3::new(0.0, 0.6, 0.8);
    let t = DVec3::new(1.0, 0.0, 0.0); // perpendicular to n: grazing
    let c60 = 0.5 * n + (0.75f64).sqrt() * t;
    let cases = [
        ("along the normal", n, FRAC_1_PI),
        ("at 60 degrees", c60, 0.5 * FRAC_1_PI),
        ("grazing", t, 0.0),
        ("just below the surface", (t - 1e-9 * n).normalize(), 0.0),
        ("opposite the normal", -n, 0.0),
    ];
    for (what, d, want) in cases {
        let got = pdf(n, d);
        check::close(
            &format!("lambertian_scattering_pdf {what}"),
            got,
            want,
            1e-15,
        )?;
    }
    Ok(())
}

/// Never negative or NaN, and E[4 pi s(d)] = 1 over uniform directions (z-test, 1e5 samples).
pub fn check_normalised(pdf: impl Fn(DVec3, DVec3) -> f64) -> CheckResult {
    let pdf = |n: DVec3, d: DVec3| {
        let args = [("normal", Arg::Vector(n)), ("direction", Arg::Vector(d))];
        check::calling("lambertian_scattering_pdf", &args, || pdf(n, d))
    };
    let mut rng = check::seeded(50);
    for normal in [DVec3::Z, -DVec3::X, DVec3::new(1.0, -2.0, 2.0) / 3.0] {
        let mut values = Vec::with_capacity(100_000);
        for _ in 0..100_000 {
            let d = check::uniform_direction(&mut rng);
            let s = pdf(normal, d);
            if s.is_nan() || s < 0.0 {
                return Err(format!(
                    "lambertian_scattering_pdf({normal}, {d}) = {}, must be >= 0",
                    check::num(s)
                ));
            }
            values.push(4.0 * PI * s);
        }
        check::z_test_mean(
            &format!("integral of the Lambertian pdf around {normal}"),
            values,
            1.0,
        )?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checks_reject_wrong_densities() {
        // Wrong: two-sided |cos| / pi integrates to 2 and is positive below the surface.
        let two_sided = |n: DVec3, d: DVec3| n.dot(d).abs() / PI;
        assert!(check_values(two_sided).is_err());
        assert!(check_normalised(two_sided).is_err());
        // Wrong: cos / pi unclamped goes negative.
        let unclamped = |n: DVec3, d: DVec3| n.dot(d) / PI;
        assert!(check_values(unclamped).is_err());
        assert!(check_normalised(unclamped).is_err());
        // Wrong: the hemisphere's 1/(2 pi) normalisation with a cosine.
        let half = |n: DVec3, d: DVec3| n.dot(d).max(0.0) / (2.0 * PI);
        assert!(check_normalised(half).is_err());
    }
}
