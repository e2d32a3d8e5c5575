//! # Bug museum, chapter 12, after chapter 9, Sampling Lights Directly, "A sphere light: the cone it subtends": the sphere cone's cos theta_max
//!
//! The checks of the exercise `crates/exercises/exercises/ch12_bug_cone_cos_theta_max.rs`, which
//! holds the bug to find.
//!
//! The setting: a sphere light of radius r at distance d is sampled as the cone of directions within
//! theta_max of its centre, uniformly, with density 1 / (2 pi (1 - cos theta_max)) (given).
//!
//! The check: exact values of cos theta_max (d = 2r gives sqrt(3)/2); every direction drawn in your
//! cone (1e4) hits the sphere; and the fraction of 1e6 uniform directions that hit the sphere,
//! z-tested (binomial standard error, false failure 1e-6) against your cone's solid angle / 4 pi.

use crate::check::{self, Arg, CheckResult};
use glam::DVec3;
use rand::{Rng, RngCore};
use std::f64::consts::PI;

/// A direction uniform in the cone of half-angle acos(`cos_max`) around +z (given).
pub fn sample_cone(cos_max: f64, rng: &mut dyn RngCore) -> DVec3 {
    let z = 1.0 - rng.random::<f64>() * (1.0 - cos_max);
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * rng.random::<f64>();
    DVec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// Does the ray from the origin along unit `d` hit the sphere of `radius` centred at (0, 0, distance)?
fn hits(d: DVec3, radius: f64, distance: f64) -> bool {
    let along = d.z * distance;
    along > 0.0 && distance * distance - along * along <= radius * radius
}

/// `cos_theta_max` with its calls recorded, so that a panic names the input that caused it.
fn recorded(cos_theta_max: impl Fn(f64, f64) -> f64) -> impl Fn(f64, f64) -> f64 {
    move |radius, distance| {
        let args = [
            ("radius", Arg::Real(radius)),
            ("distance", Arg::Real(distance)),
        ];
        check::calling("cos_theta_max", &args, || cos_theta_max(radius, distance))
    }
}

/// Exact values: d = 2r gives sqrt(3)/2, d = sqrt(2) r gives sqrt(1/2).
pub fn check_values(cos_theta_max: impl Fn(f64, f64) -> f64) -> CheckResult {
    let cos_theta_max = recorded(cos_theta_max);
    for (r, d, want) in [
        (1.0, 2.0, 0.75f64.sqrt()),
        (0.5, 1.0, 0.75f64.sqrt()),
        (1.0, 2f64.sqrt(), 0.5f64.sqrt()),
    ] {
        check::close(
            &format!("cos_theta_max(radius {r}, distance {d})"),
            cos_theta_max(r, d),
            want,
            1e-12,
        )?;
    }
    Ok(())
}

/// Every direction of the cone hits the sphere, which the cone must just enclose.
pub fn check_cone_hits(cos_theta_max: impl Fn(f64, f64) -> f64) -> CheckResult {
    let cos_theta_max = recorded(cos_theta_max);
    let (r, d) = (1.0, 2.5);
    let c = cos_theta_max(r, d);
    let mut rng = check::seeded(140);
    let misses = (0..10_000)
        .filter(|_| !hits(sample_cone(c, &mut rng), r, d))
        .count();
    if misses > 0 {
        return Err(format!(
            "{misses} of 10000 directions sampled in your cone (cos theta_max = {c:.6}) miss the sphere \
             of radius {r} at distance {d}: the cone is wider than the sphere (theta_max = {:.2} degrees, \
             the sphere's edge is at asin(r/d) = {:.2}), so those samples carry no light and the light \
             is under-weighted",
            c.acos().to_degrees(),
            (r / d).asin().to_degrees()
        ));
    }
    Ok(())
}

/// The fraction of uniform directions that hit the sphere estimates its solid angle / 4 pi.
pub fn check_solid_angle(cos_theta_max: impl Fn(f64, f64) -> f64) -> CheckResult {
    let cos_theta_max = recorded(cos_theta_max);
    let (r, d) = (1.0, 1.5);
    let c = cos_theta_max(r, d);
    let claimed = 2.0 * PI * (1.0 - c) / (4.0 * PI);
    let n = 1_000_000;
    let mut rng = check::seeded(141);
    let hit = (0..n)
        .filter(|_| hits(check::uniform_direction(&mut rng), r, d))
        .count();
    let p = claimed.clamp(1e-12, 1.0 - 1e-12);
    let se = (p * (1.0 - p) / n as f64).sqrt();
    check::z_test(
        "the fraction of 1e6 uniform directions that hit a sphere of radius 1 at distance 1.5, against your cone's solid angle / 4 pi",
        hit as f64 / n as f64,
        se,
        claimed,
    )
    .map_err(|e| {
        format!(
            "{e}\n(your cone's pdf 1 / (2 pi (1 - cos theta_max)) is then off by the factor {:.3}: the light's \
             contribution is scaled by it)",
            (hit as f64 / n as f64) / claimed
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checks_reject_a_missing_square_root_and_the_half_angle_in_radians() {
        let no_sqrt = |r: f64, d: f64| 1.0 - r * r / (d * d);
        assert!(check_values(no_sqrt).is_err());
        let err = check_cone_hits(no_sqrt).unwrap_err();
        assert!(err.contains("miss the sphere"), "{err}");
        assert!(check_solid_angle(no_sqrt).is_err());
        // Wrong: cos of r/d read as the angle (too narrow: every sample hits, the weight is wrong).
        let cos_of_ratio = |r: f64, d: f64| (r / d).cos();
        assert!(check_cone_hits(cos_of_ratio).is_ok());
        assert!(check_solid_angle(cos_of_ratio).is_err());
    }
}
