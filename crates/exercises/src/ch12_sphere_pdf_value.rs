//! # Chapter 12, after chapter 9, Sampling Lights Directly, "A sphere light: the cone it subtends": the pdf of directions towards a sphere light
//!
//! The checks of the exercise `crates/exercises/exercises/ch12_sphere_pdf_value.rs`, which states the
//! task.
//!
//! The check: the solid angle at distances 1e2 .. 1e9 within 1e-6 relative of a series expansion,
//! finite positive pdfs far away, inside, on and 1e-4 above the sphere, 0 on a miss, a positive pdf
//! for at least 99.9% of the directions drawn in the cone from just above, and a z-test that the
//! density integrates to 1 over the sphere (E[4 pi p] = 1 over uniform directions).

use crate::check::{self, Arg, CheckResult};
use glam::DVec3;
use rand::Rng;
use std::f64::consts::PI;

/// 1 - sqrt(1 - x) by its series x/2 + x^2/8 + x^3/16 + 5x^4/128 + 7x^5/256 (x <= 1e-4: error < 1e-22).
fn one_minus_sqrt_series(x: f64) -> f64 {
    x / 2.0 + x * x / 8.0 + x.powi(3) / 16.0 + 5.0 * x.powi(4) / 128.0 + 7.0 * x.powi(5) / 256.0
}

/// The solid angle of the unit sphere from distance `d` > 1: by the series far away, where it is
/// exact, and by the direct formula nearby, where it does not cancel badly.
fn exact_solid_angle(d: f64) -> f64 {
    let x = 1.0 / (d * d);
    2.0 * PI
        * if x <= 1e-4 {
            one_minus_sqrt_series(x)
        } else {
            1.0 - (1.0 - x).sqrt()
        }
}

/// Solid angles: far away (against the series), nearby (against the direct formula), inside and on.
pub fn check_solid_angle(omega: impl Fn(f64, f64) -> f64) -> CheckResult {
    let omega = |radius: f64, distance: f64| {
        let args = [
            ("radius", Arg::Real(radius)),
            ("distance", Arg::Real(distance)),
        ];
        check::calling("sphere_solid_angle", &args, || omega(radius, distance))
    };
    for d in [1e2, 1e4, 1e6, 1e9] {
        let want = exact_solid_angle(d);
        check::close(
            &format!("sphere_solid_angle(1, {})", check::num(d)),
            omega(1.0, d),
            want,
            1e-6,
        )?;
        // The same geometry scaled: radius 1e-3 at distance 1e-3 d.
        check::close(
            &format!("sphere_solid_angle(0.001, {})", check::num(d * 1e-3)),
            omega(1e-3, d * 1e-3),
            want,
            1e-6,
        )?;
    }
    for d in [2.0, 1.0 + 1e-4] {
        check::close(
            &format!("sphere_solid_angle(1, {d})"),
            omega(1.0, d),
            exact_solid_angle(d),
            1e-12,
        )?;
    }
    for (what, d) in [
        ("inside", 0.5),
        ("at the centre", 0.0),
        ("on the sphere", 1.0),
    ] {
        check::close(
            &format!("sphere_solid_angle {what}"),
            omega(1.0, d),
            4.0 * PI,
            1e-15,
        )?;
    }
    Ok(())
}

/// The function under test.
pub trait SpherePdf: Fn(DVec3, f64, DVec3, DVec3) -> f64 {}
impl<F: Fn(DVec3, f64, DVec3, DVec3) -> f64> SpherePdf for F {}

/// A direction uniform in the cone from `origin` around the centre, of half-angle theta_max (the
/// sampler a sphere light uses; the check's own).
fn cone_direction(center: DVec3, radius: f64, origin: DVec3, rng: &mut impl Rng) -> DVec3 {
    let axis = center - origin;
    let dist = axis.length();
    let sin2 = (radius / dist).powi(2);
    let cos_max = (1.0 - sin2).max(0.0).sqrt();
    let z = 1.0 - rng.random::<f64>() * (1.0 - cos_max);
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * rng.random::<f64>();
    let w = axis / dist;
    let (u, v) = w.any_orthonormal_pair();
    (r * phi.cos() * u + r * phi.sin() * v + z * w).normalize()
}

/// `pdf` with each call's arguments recorded, so that a panic report names them.
fn recorded(pdf: impl SpherePdf) -> impl SpherePdf {
    move |center: DVec3, radius: f64, origin: DVec3, direction: DVec3| {
        let args = [
            ("center", Arg::Vector(center)),
            ("radius", Arg::Real(radius)),
            ("origin", Arg::Vector(origin)),
            ("direction", Arg::Vector(direction)),
        ];
        check::calling("sphere_pdf_value", &args, || {
            pdf(center, radius, origin, direction)
        })
    }
}

/// Hard cases: hits far away, misses, inside, on and just above the sphere.
pub fn check_values(pdf: impl SpherePdf) -> CheckResult {
    let pdf = recorded(pdf);
    let c = DVec3::new(0.0, 0.0, 0.0);
    for d in [3.0, 1e2, 1e4, 1e6, 1e9] {
        let origin = DVec3::new(0.0, 0.0, -d);
        let got = pdf(c, 1.0, origin, DVec3::Z);
        let want = 1.0 / exact_solid_angle(d);
        check::close(
            &format!("sphere_pdf_value towards the centre from {}", check::num(d)),
            got,
            want,
            1e-6,
        )?;
        let miss = pdf(c, 1.0, origin, DVec3::new(0.0, 0.8, 0.6));
        let behind = pdf(c, 1.0, origin, -DVec3::Z);
        if miss != 0.0 || behind != 0.0 {
            return Err(format!(
                "sphere_pdf_value from {}: a miss gave {}, pointing away {}; expected 0",
                check::num(d),
                check::num(miss),
                check::num(behind)
            ));
        }
    }
    let mut rng = check::seeded(120);
    for (what, origin) in [("inside", DVec3::new(0.2, -0.3, 0.1)), ("at the centre", c)] {
        for _ in 0..100 {
            let d = check::uniform_direction(&mut rng);
            let got = pdf(c, 1.0, origin, d);
            check::close(
                &format!("sphere_pdf_value from {what} the sphere, towards {d}"),
                got,
                1.0 / (4.0 * PI),
                1e-15,
            )?;
        }
    }
    // On the sphere (to rounding: |origin| may be 1 +- 1 ulp): finite and >= 0 whichever side.
    for origin in [
        DVec3::Z,
        DVec3::new(0.0, 0.6, 0.8),
        DVec3::new(0.48, 0.6, 0.64),
    ] {
        for _ in 0..100 {
            let d = check::uniform_direction(&mut rng);
            let p = pdf(c, 1.0, origin, d);
            if !(p.is_finite() && p >= 0.0) {
                return Err(format!(
                    "sphere_pdf_value from {origin} on the sphere towards {d} = {}",
                    check::num(p)
                ));
            }
        }
    }
    // From 1e-4 above the surface: finite, and > 0 for >= 99.9% of the directions in the cone.
    let origin = DVec3::new(0.0, 0.0, 1.0 + 1e-4);
    let mut positive = 0;
    for _ in 0..10_000 {
        let d = cone_direction(c, 1.0, origin, &mut rng);
        let p = pdf(c, 1.0, origin, d);
        if !(p.is_finite() && p >= 0.0) {
            return Err(format!(
                "sphere_pdf_value from 1e-4 above the sphere towards {d} = {}",
                check::num(p)
            ));
        }
        positive += usize::from(p > 0.0);
    }
    if positive < 9990 {
        return Err(format!(
            "sphere_pdf_value from 1e-4 above: only {positive} of 10000 directions in the cone hit"
        ));
    }
    Ok(())
}

/// E[4 pi p] = 1 over 1e5 uniform directions, from outside (z-test) and inside (exactly).
pub fn check_normalised(pdf: impl SpherePdf) -> CheckResult {
    let pdf = recorded(pdf);
    let mut rng = check::seeded(121);
    let center = DVec3::new(1.0, -2.0, 0.5);
    for (what, origin) in [
        ("from outside", center + DVec3::new(2.0, 1.0, -2.0)),
        ("from inside", center + DVec3::new(0.0, 0.5, 0.0)),
    ] {
        let values: Vec<f64> = (0..100_000)
            .map(|_| 4.0 * PI * pdf(center, 1.0, origin, check::uniform_direction(&mut rng)))
            .collect();
        check::z_test_mean(
            &format!("integral over the sphere of the sphere light's pdf {what}"),
            values,
            1.0,
        )?;
    }
    Ok(())
}

/// All of this exercise's checks.
pub fn check_sphere_pdf(omega: impl Fn(f64, f64) -> f64, pdf: impl SpherePdf) -> CheckResult {
    check_solid_angle(omega)?;
    check_values(&pdf)?;
    check_normalised(&pdf)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Correct apart from the solid angle it divides by.
    fn pdf_with(omega: impl Fn(f64, f64) -> f64) -> impl SpherePdf {
        move |c: DVec3, r: f64, o: DVec3, d: DVec3| {
            let oc = c - o;
            if oc.length() <= r {
                return 1.0 / omega(r, oc.length());
            }
            let along = oc.dot(d);
            if along <= 0.0 || (oc - along * d).length() > r {
                0.0
            } else {
                1.0 / omega(r, oc.length())
            }
        }
    }

    #[test]
    fn checks_reject_the_cancelling_formula_and_a_wrong_inside() {
        // Wrong: 2 pi (1 - sqrt(1 - r^2/d^2)) as written, which cancels far away.
        let naive = |r: f64, d: f64| {
            if d <= r {
                4.0 * PI
            } else {
                2.0 * PI * (1.0 - (1.0 - r * r / (d * d)).sqrt())
            }
        };
        assert!(check_solid_angle(naive).is_err());
        assert!(check_values(pdf_with(naive)).is_err());
        // Wrong: from inside the formula is used anyway (sin^2 > 1 gives NaN).
        let no_inside = |r: f64, d: f64| {
            let sin2 = (r / d).powi(2);
            2.0 * PI * sin2 / (1.0 + (1.0 - sin2).sqrt())
        };
        assert!(check_solid_angle(no_inside).is_err());
        assert!(check_values(pdf_with(no_inside)).is_err());
        // Wrong: the hemisphere 2 pi sin^2 theta_max (drops the 1 / (1 + cos)): does not integrate to 1.
        let no_cos = |r: f64, d: f64| {
            if d <= r {
                4.0 * PI
            } else {
                2.0 * PI * (r / d).powi(2)
            }
        };
        assert!(check_normalised(pdf_with(no_cos)).is_err());
    }
}
