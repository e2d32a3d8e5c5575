//! # Bug museum, chapter 5, Light Scattering, "The Lambertian surface": the sphere's normal that is not of unit length
//!
//! The checks of the exercise `crates/exercises/exercises/ch05_bug_normal_length.rs`, which holds the
//! bug to find.
//!
//! The check: the normal at points of spheres of radius 0.5, 1, 2 and 100 has unit length and points
//! outwards, and on a sphere of negative radius (the glass bubble of earlier editions of *Ray
//! Tracing in One Weekend*) points inwards; and the
//! Lambertian density built on it integrates to 1 over the sphere of directions (z-test of 1e5
//! uniform directions, false failure 1e-6), which a normal of length r would make r.

use crate::check::{self, Arg, CheckResult};
use glam::DVec3;
use std::f64::consts::{FRAC_1_PI, PI};

/// The Lambertian density max(0, n . d) / pi (given): right only for a unit normal `n`.
pub fn lambertian_pdf(normal: DVec3, direction: DVec3) -> f64 {
    normal.dot(direction).max(0.0) * FRAC_1_PI
}

/// The normal under test: `(center, radius, point on the sphere) -> normal`.
pub trait Normal: Fn(DVec3, f64, DVec3) -> DVec3 {}
impl<F: Fn(DVec3, f64, DVec3) -> DVec3> Normal for F {}

const CENTER: DVec3 = DVec3::new(1.0, -2.0, 0.5);

/// Unit length and the book's sign convention (inwards for a negative radius).
pub fn check_unit(normal: impl Normal) -> CheckResult {
    let mut rng = check::seeded(50);
    for radius in [0.5f64, 1.0, 2.0, 100.0, -0.4] {
        for _ in 0..100 {
            let d = check::uniform_direction(&mut rng);
            let p = CENTER + radius.abs() * d;
            let args = [
                ("center", Arg::Vector(CENTER)),
                ("radius", Arg::Real(radius)),
                ("point", Arg::Vector(p)),
            ];
            let n = check::calling("outward_normal", &args, || normal(CENTER, radius, p));
            if !n.is_finite() || (n.length() - 1.0).abs() > 1e-12 {
                return Err(format!(
                    "the normal at {p} of the sphere of radius {radius} has length {} (it is {n}): \
                     a normal must have unit length",
                    n.length()
                ));
            }
            let want = d * radius.signum();
            if (n - want).length() > 1e-9 {
                let (should, wrong) = if radius < 0.0 {
                    (
                        "inwards, towards the centre: the sphere is a bubble",
                        "outwards",
                    )
                } else {
                    ("outwards, away from the centre", "inwards")
                };
                let how = if n.dot(want) < 0.0 {
                    format!("it points {wrong}")
                } else {
                    format!("it is not along the line from the centre, {want}")
                };
                return Err(format!(
                    "the normal at {p} of the sphere of radius {radius} is {n}: {how}. With a \
                     radius of {radius} it must point {should}"
                ));
            }
        }
    }
    Ok(())
}

/// The Lambertian density on the normal of a radius-2 sphere integrates to 1: E[4 pi p(d)] over
/// 1e5 uniform directions, z-tested against 1.
pub fn check_normalised(normal: impl Normal) -> CheckResult {
    let radius = 2.0;
    let p = CENTER + DVec3::new(0.0, radius, 0.0);
    let args = [
        ("center", Arg::Vector(CENTER)),
        ("radius", Arg::Real(radius)),
        ("point", Arg::Vector(p)),
    ];
    let n = check::calling("outward_normal", &args, || normal(CENTER, radius, p));
    let mut rng = check::seeded(51);
    let values =
        (0..100_000).map(|_| 4.0 * PI * lambertian_pdf(n, check::uniform_direction(&mut rng)));
    check::z_test_mean(
        "the Lambertian density on your normal of a radius-2 sphere, integrated over the sphere",
        values,
        1.0,
    )
    .map_err(|e| {
        let length = n.length();
        if n.is_finite() && (length - 1.0).abs() > 1e-9 {
            format!(
                "{e}\n(a density must integrate to 1; the cosine n . d grows with the length of n, \
                     {}, so the surface would reflect {}x the light it receives)",
                check::sig(length, 6),
                check::sig(length, 4)
            )
        } else {
            format!(
                "{e}\n(the normal there is {n}, of length {})",
                check::num(length)
            )
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checks_reject_the_unscaled_and_the_sign_losing_normal() {
        let unscaled = |c: DVec3, _r: f64, p: DVec3| p - c;
        assert!(check_unit(unscaled).is_err());
        let err = check_normalised(unscaled).unwrap_err();
        assert!(err.contains("standard errors"), "{err}");
        // Wrong: normalize() loses the inward normal of a negative radius.
        let normalised = |c: DVec3, _r: f64, p: DVec3| (p - c).normalize();
        let err = check_unit(normalised).unwrap_err();
        assert!(
            err.contains("of the sphere of radius -0.4 is [")
                && err.contains(
                    "]: it points outwards. With a radius of -0.4 it must point \
                                 inwards, towards the centre"
                ),
            "{err}"
        );
        assert!(
            !err.contains("(p - c") && !err.contains("/ radius"),
            "no formula: {err}"
        );
        assert!(check_normalised(normalised).is_ok());
    }

    #[test]
    fn a_panic_names_the_sphere_and_the_point() {
        let report = crate::harness::panic_of(|| {
            check_normalised(|_: DVec3, r: f64, _: DVec3| -> DVec3 { panic!("radius {r}") })
        });
        assert!(
            report.starts_with(
                "your code panicked in outward_normal(center = [1, -2, 0.5], radius = 2, \
                 point = [1, 0, 0.5]) at "
            ),
            "{report}"
        );
    }
}
