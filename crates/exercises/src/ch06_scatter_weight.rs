//! # Chapter 6, Playing with Importance Sampling, "The strategies": one bounce of `ray_color`
//!
//! The checks of the exercise `crates/exercises/exercises/ch06_scatter_weight.rs`, which states the
//! task.
//!
//! The check: exact values with dyadic inputs, every degenerate density, and a white-furnace test: a
//! Lambertian surface (s = cos/pi) of albedo 0.75 under uniform incoming radiance 1, with directions
//! drawn uniformly on the hemisphere (p = 1/(2 pi)), must return 0.75 on average (z-test, 1e5 samples).

use crate::check::{self, Arg, CheckResult};
use glam::DVec3;
use rand::Rng;
use std::f64::consts::PI;

/// The function under test.
pub trait Contribution: Fn(DVec3, DVec3, f64, f64, DVec3) -> DVec3 {}
impl<F: Fn(DVec3, DVec3, f64, f64, DVec3) -> DVec3> Contribution for F {}

/// `contribution` with each call's arguments recorded, so that a panic report names them.
fn recorded(contribution: impl Contribution) -> impl Contribution {
    move |e: DVec3, a: DVec3, s: f64, p: f64, li: DVec3| {
        let args = [
            ("emitted", Arg::Vector(e)),
            ("attenuation", Arg::Vector(a)),
            ("scattering_pdf", Arg::Real(s)),
            ("pdf_value", Arg::Real(p)),
            ("incoming", Arg::Vector(li)),
        ];
        check::calling("scatter_contribution", &args, || {
            contribution(e, a, s, p, li)
        })
    }
}

/// Exact values and every degenerate density.
pub fn check_cases(contribution: impl Contribution) -> CheckResult {
    let contribution = recorded(contribution);
    let e = DVec3::new(0.25, 0.5, 1.0);
    let a = DVec3::new(0.5, 0.75, 1.0);
    let li = DVec3::new(2.0, 4.0, 8.0);
    let want = e + a * li * (0.25 / 0.125);
    let got = contribution(e, a, 0.25, 0.125, li);
    if got != want {
        return Err(format!(
            "scatter_contribution(s = 1/4, p = 1/8) = {got}, expected {want}"
        ));
    }
    let degenerate = [
        ("p = 0", 0.25, 0.0),
        ("p = -0", 0.25, -0.0),
        ("p < 0", 0.25, -0.5),
        ("p = NaN", 0.25, f64::NAN),
        ("p = inf", 0.25, f64::INFINITY),
        ("s = NaN", f64::NAN, 0.5),
        ("s = inf", f64::INFINITY, 0.5),
        ("s < 0", -0.25, 0.5),
        ("s / p overflows", 1e300, 1e-300),
    ];
    for (what, s, p) in degenerate {
        let got = contribution(e, a, s, p, li);
        if got != e {
            return Err(format!(
                "scatter_contribution with {what} = {got}, expected the emission {e} only"
            ));
        }
    }
    // s = 0 (a direction the surface does not scatter into) is a valid zero contribution.
    let got = contribution(e, a, 0.0, 0.5, li);
    if got != e {
        return Err(format!(
            "scatter_contribution with s = 0 = {got}, expected {e}"
        ));
    }
    Ok(())
}

/// White furnace: albedo 0.75, L_i = 1, uniform hemisphere sampling; the mean is 0.75 (z-test).
pub fn check_furnace(contribution: impl Contribution) -> CheckResult {
    let contribution = recorded(contribution);
    let albedo = 0.75;
    let mut rng = check::seeded(60);
    let mut values = Vec::with_capacity(100_000);
    for _ in 0..100_000 {
        let cos = rng.random::<f64>(); // z of a uniform hemisphere direction is uniform in [0, 1)
        let s = cos.max(0.0) / PI;
        let l = contribution(
            DVec3::ZERO,
            DVec3::splat(albedo),
            s,
            1.0 / (2.0 * PI),
            DVec3::ONE,
        );
        if !l.is_finite() {
            return Err(format!("scatter_contribution returned {l} in the furnace"));
        }
        values.push(l.x);
    }
    check::z_test_mean("white furnace, albedo 0.75", values, albedo)
}

/// All of this exercise's checks.
pub fn check_scatter(contribution: impl Contribution) -> CheckResult {
    check_cases(&contribution)?;
    check_furnace(&contribution)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checks_reject_wrong_contributions() {
        // Wrong: the book's plain formula divides by p = 0 and lets NaN through.
        let unguarded = |e: DVec3, a: DVec3, s: f64, p: f64, li: DVec3| e + a * s * li / p;
        assert!(check_cases(unguarded).is_err());
        // Wrong: multiplies by the pdf instead of dividing.
        let multiplies = |e: DVec3, a: DVec3, s: f64, p: f64, li: DVec3| {
            if p > 0.0 && p.is_finite() && s.is_finite() {
                e + a * s * li * p
            } else {
                e
            }
        };
        assert!(check_furnace(multiplies).is_err());
    }
}
