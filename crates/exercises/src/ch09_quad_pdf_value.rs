//! # Chapter 9, Sampling Lights Directly, "A quad light: from area to solid angle": the solid-angle pdf of a quad light
//!
//! The checks of the exercise `crates/exercises/exercises/ch09_quad_pdf_value.rs`, which states the
//! task, and what that exercise is given ([`Quad`]).
//!
//! The check: exact values head-on and oblique, the hard cases (origin in the plane, 1e-9 above it,
//! parallel, behind, from the back side), and a z-test that E[4 pi p(omega)] = 1 over uniform
//! directions: the density integrates to 1 over the sphere.

use crate::check::{self, Arg, CheckResult};
use glam::DVec3;
use std::f64::consts::PI;

/// A parallelogram light: corner `q`, edges `u` and `v`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quad {
    pub q: DVec3,
    pub u: DVec3,
    pub v: DVec3,
}

/// The function under test.
pub trait QuadPdf: Fn(&Quad, DVec3, DVec3) -> f64 {}
impl<F: Fn(&Quad, DVec3, DVec3) -> f64> QuadPdf for F {}

/// The 2 x 2 square in the plane z = -1 centred under the origin (area 4).
const SQUARE: Quad = Quad {
    q: DVec3::new(-1.0, -1.0, -1.0),
    u: DVec3::new(2.0, 0.0, 0.0),
    v: DVec3::new(0.0, 2.0, 0.0),
};

/// `pdf` with each call's arguments recorded, so that a panic report names them.
fn recorded(pdf: impl QuadPdf) -> impl QuadPdf {
    move |quad: &Quad, origin: DVec3, direction: DVec3| {
        let args = [
            ("quad.q", Arg::Vector(quad.q)),
            ("quad.u", Arg::Vector(quad.u)),
            ("quad.v", Arg::Vector(quad.v)),
            ("origin", Arg::Vector(origin)),
            ("direction", Arg::Vector(direction)),
        ];
        check::calling("quad_pdf_value", &args, || pdf(quad, origin, direction))
    }
}

/// Exact values: head-on, oblique, and the misses.
pub fn check_values(pdf: impl QuadPdf) -> CheckResult {
    let pdf = recorded(pdf);
    let o = DVec3::ZERO;
    check::close(
        "quad_pdf_value head-on at distance 1 (1/A)",
        pdf(&SQUARE, o, -DVec3::Z),
        0.25,
        1e-15,
    )?;
    let d = DVec3::new(0.5, 0.25, -1.0);
    let r2 = d.length_squared(); // hits (0.5, 0.25, -1) at distance |d|, cos theta = 1 / |d|
    check::close(
        "quad_pdf_value oblique",
        pdf(&SQUARE, o, d.normalize()),
        r2 * r2.sqrt() / 4.0,
        1e-14,
    )?;
    check::close(
        "quad_pdf_value from the back side",
        pdf(&SQUARE, DVec3::new(0.0, 0.0, -2.0), DVec3::Z),
        0.25,
        1e-15,
    )?;
    // A skewed parallelogram: q = (0, 0, 2), u = (1, 0, 0), v = (1, 1, 1); area |u x v| = sqrt 2.
    let skew = Quad {
        q: DVec3::new(0.0, 0.0, 2.0),
        u: DVec3::X,
        v: DVec3::ONE,
    };
    let target = skew.q + 0.5 * skew.u + 0.5 * skew.v; // (1, 0.5, 2.5)
    let to = target - DVec3::new(0.0, 0.0, 1.0);
    let n = skew.u.cross(skew.v).normalize();
    let want = to.length_squared() / (n.dot(to.normalize()).abs() * 2f64.sqrt());
    check::close(
        "quad_pdf_value of a skewed parallelogram",
        pdf(&skew, DVec3::Z, to.normalize()),
        want,
        1e-13,
    )?;
    let misses = [
        ("pointing away", o, DVec3::Z),
        (
            "beside the square",
            o,
            DVec3::new(1.5, 0.0, -1.0).normalize(),
        ),
        (
            "beside a corner",
            o,
            DVec3::new(1.01, 1.01, -1.0).normalize(),
        ),
        ("parallel to the plane", o, DVec3::X),
        (
            "origin in the plane, along it",
            DVec3::new(0.0, 0.0, -1.0),
            DVec3::X,
        ),
        (
            "origin in the plane, straight down",
            DVec3::new(0.0, 0.0, -1.0),
            -DVec3::Z,
        ),
        (
            "origin in the plane, oblique",
            DVec3::new(0.0, 0.0, -1.0),
            DVec3::new(0.6, 0.0, -0.8),
        ),
    ];
    for (what, origin, d) in misses {
        let got = pdf(&SQUARE, origin, d);
        if got != 0.0 {
            return Err(format!(
                "quad_pdf_value {what} = {}, expected 0 (a miss)",
                check::num(got)
            ));
        }
    }
    let got = pdf(&SQUARE, DVec3::new(0.0, 0.0, -1.0 + 1e-9), -DVec3::Z);
    if !(got.is_finite() && got > 0.0) {
        return Err(format!(
            "quad_pdf_value from 1e-9 above the light = {}, expected small, finite and > 0",
            check::num(got)
        ));
    }
    Ok(())
}

/// E[4 pi p(omega)] = 1 over 1e5 uniform directions (z-test), for the square and a skewed quad.
pub fn check_normalised(pdf: impl QuadPdf) -> CheckResult {
    let pdf = recorded(pdf);
    let skew = Quad {
        q: DVec3::new(-0.5, 1.0, 0.2),
        u: DVec3::new(1.0, 0.3, 0.0),
        v: DVec3::new(0.4, 0.5, 1.5),
    };
    let mut rng = check::seeded(90);
    for (what, quad, origin) in [
        ("square", SQUARE, DVec3::ZERO),
        ("skewed quad", skew, DVec3::new(0.1, 0.0, 0.4)),
    ] {
        let mut values = Vec::with_capacity(100_000);
        for _ in 0..100_000 {
            let d = check::uniform_direction(&mut rng);
            let p = pdf(&quad, origin, d);
            if !(p >= 0.0 && p.is_finite()) {
                let why = if p < 0.0 {
                    "a density is never negative"
                } else {
                    "a density is a finite number >= 0"
                };
                return Err(format!(
                    "quad_pdf_value({quad:?}, {origin}, {d}) = {}: {why}",
                    check::num(p)
                ));
            }
            values.push(4.0 * PI * p);
        }
        check::z_test_mean(
            &format!("integral over the sphere of the {what}'s pdf"),
            values,
            1.0,
        )?;
    }
    Ok(())
}

/// All of this exercise's checks.
pub fn check_quad_pdf(pdf: impl QuadPdf) -> CheckResult {
    check_values(&pdf)?;
    check_normalised(&pdf)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A correct hit test, returning `(t, |cos theta|, area)` on a hit.
    fn hit(quad: &Quad, origin: DVec3, d: DVec3) -> Option<(f64, f64, f64)> {
        let n = quad.u.cross(quad.v);
        let denom = n.dot(d);
        if denom == 0.0 {
            return None;
        }
        let t = n.dot(quad.q - origin) / denom;
        let p = origin + t * d - quad.q;
        let w = n / n.length_squared();
        let (a, b) = (w.dot(p.cross(quad.v)), w.dot(quad.u.cross(p)));
        ((0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b) && t >= 0.0)
            .then(|| (t, denom.abs() / n.length(), n.length()))
    }

    #[test]
    fn checks_reject_wrong_pdfs() {
        // Wrong: the area density 1/A, not converted to solid angle.
        let area_measure =
            |q: &Quad, o: DVec3, d: DVec3| hit(q, o, d).map_or(0.0, |(_, _, a)| 1.0 / a);
        assert!(check_values(area_measure).is_err());
        assert!(check_normalised(area_measure).is_err());
        // Wrong: forgets the cosine.
        let no_cos = |q: &Quad, o: DVec3, d: DVec3| hit(q, o, d).map_or(0.0, |(t, _, a)| t * t / a);
        assert!(check_normalised(no_cos).is_err());
        // Wrong: counts a hit at t = 0 (origin in the light's plane) and returns infinity for it.
        let t_zero = |q: &Quad, o: DVec3, d: DVec3| {
            hit(q, o, d).map_or(0.0, |(t, c, a)| {
                if t == 0.0 {
                    f64::INFINITY
                } else {
                    t * t / (c * a)
                }
            })
        };
        assert!(check_values(t_zero).is_err());
        // Wrong: the signed cosine, negative where the light faces away from the origin.
        let signed = |q: &Quad, o: DVec3, d: DVec3| {
            hit(q, o, d).map_or(0.0, |(t, _, a)| {
                let n = q.u.cross(q.v);
                t * t * n.length() / (n.dot(d) * a)
            })
        };
        let err = check_normalised(signed).unwrap_err();
        assert!(err.ends_with(": a density is never negative"), "{err}");
    }

    #[test]
    fn a_panic_names_the_quad_the_origin_and_the_direction() {
        // Panics from the light's plane, the first such case being "origin in the plane, along it".
        let report = crate::harness::panic_of(|| {
            check_values(|q: &Quad, o: DVec3, d: DVec3| {
                assert!(o.z != q.q.z, "origin in the plane");
                hit(q, o, d).map_or(0.0, |(t, c, a)| t * t / (c * a))
            })
        });
        assert!(
            report.starts_with(
                "your code panicked in quad_pdf_value(quad.q = [-1, -1, -1], quad.u = [2, 0, 0], \
                 quad.v = [0, 2, 0], origin = [0, 0, -1], direction = [1, 0, 0]) at "
            ),
            "{report}"
        );
    }
}
