//! # Bug museum, chapter 12, after chapter 9, Sampling Lights Directly, "A sphere light: the cone it subtends": the sphere cone's cos theta_max
//!
//! The checks of the exercise `crates/exercises/exercises/ch12_bug_cone_cos_theta_max.rs`, which
//! holds the bug to find.
//!
//! The setting: a sphere light of radius r at distance d is sampled as the cone of directions within
//! theta_max of its centre, uniformly, with density 1 / (2 pi (1 - cos theta_max)) (given).
//!
//! The check: exact values of cos theta_max (d = 2r gives sqrt(3)/2); every direction drawn in your
//! cone (1e4) hits the sphere; and your cone's solid angle / 4 pi against the fraction of 1e6
//! uniform directions that hit the sphere (a z-test at the binomial standard error of your cone's
//! fraction, false failure 1e-6).
//!
//! What the museum's bug does: 1 - r^2/d^2 is cos^2 theta_max, smaller than cos theta_max, so the
//! cone is wider than the sphere, its solid angle 2 pi (1 - cos^2 theta_max) is (1 + cos theta_max)
//! times the sphere's (1.14 at r/d = 0.99, 1.87 at r/d = 1/2, 2 far away), and a fraction
//! cos theta_max / (1 + cos theta_max) of its directions miss the light (12 %, 46 %, 50 %). Samples
//! weighted by the cone's own density still estimate the light without bias (the misses carry
//! nothing, the hits (1 + cos theta_max) times the light), only with more variance, worst far away;
//! but the sphere's density as the book evaluates it, 0 off the sphere, disagrees with the directions
//! drawn.

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
    let n = 10_000;
    let (mut misses, mut widest_hit) = (0, 0.0f64);
    for _ in 0..n {
        let dir = sample_cone(c, &mut rng);
        if hits(dir, r, d) {
            widest_hit = widest_hit.max(dir.z.clamp(-1.0, 1.0).acos());
        } else {
            misses += 1;
        }
    }
    if misses > 0 {
        return Err(format!(
            "{misses} of {n} directions sampled in your cone miss the sphere of radius {r} at \
             distance {d}: your cone (cos theta_max = {}, theta_max = {:.2} degrees) is wider than \
             the sphere (the sampled directions that hit it all lie within {:.2} degrees of its \
             centre). \
             Those samples find no light: they are wasted, and the sphere's density, 0 off the \
             sphere, says they cannot be drawn",
            check::sig(c, 6),
            c.acos().to_degrees(),
            widest_hit.to_degrees()
        ));
    }
    Ok(())
}

/// Your cone's solid angle / 4 pi against the fraction of uniform directions that hit the sphere.
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
    let hit_fraction = hit as f64 / n as f64;
    // The binomial standard error of the hit fraction if your cone were the sphere's.
    let p = claimed.clamp(1e-12, 1.0 - 1e-12);
    let se = (p * (1.0 - p) / n as f64).sqrt();
    let z = (hit_fraction - claimed) / se;
    if z.abs() < check::z_critical() {
        return Ok(());
    }
    let ratio = claimed / hit_fraction;
    let what = if !ratio.is_finite() || ratio <= 0.0 {
        "no cone at all".to_string()
    } else if ratio > 1.0 {
        format!(
            "wider than the sphere: {:.0} % of its directions miss the light, and its density \
             1 / (2 pi (1 - cos theta_max)) is {} times too small for those that hit it",
            100.0 * (1.0 - 1.0 / ratio),
            check::sig(ratio, 3)
        )
    } else {
        format!(
            "narrower than the sphere: the light's edge is never sampled, and the light comes out \
             {} times as bright as it is",
            check::sig(ratio, 3)
        )
    };
    Err(format!(
        "your cone (cos theta_max = {}) covers {} of the sphere of directions, but a fraction {} of \
         1e6 uniform directions hit the sphere of radius {r} at distance {d} ({z:.1} standard \
         errors of {} away): your cone's solid angle is {} times the sphere's. It is {what}",
        check::sig(c, 6),
        check::sig(claimed, 5),
        check::sig(hit_fraction, 5),
        check::sig(se, 3),
        check::sig(ratio, 4),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checks_reject_a_missing_square_root_and_the_half_angle_in_radians() {
        let no_sqrt = |r: f64, d: f64| 1.0 - r * r / (d * d);
        assert!(check_values(no_sqrt).is_err());
        // r/d = 0.4: cos theta_max = sqrt(0.84) = 0.9165, so a fraction 0.9165 / 1.9165 = 0.478 of
        // the cone misses (binomial standard error 0.005), and the misses lie beyond 23.58 degrees.
        let err = check_cone_hits(no_sqrt).unwrap_err();
        let misses: f64 = err.split(' ').next().unwrap().parse().unwrap();
        assert!((misses / 1e4 - 0.478).abs() < 0.03, "{err}");
        assert!(
            err.contains(
                "(cos theta_max = 0.84, theta_max = 32.86 degrees) is wider than the sphere"
            ),
            "{err}"
        );
        assert!(err.contains("within 23.5"), "{err}");
        assert!(
            !err.contains("asin") && !err.contains("r/d"),
            "no formula: {err}"
        );
        // r/d = 2/3: cos theta_max = sqrt(5)/3 = 0.745, the cone 1.745 times the sphere's solid
        // angle, 42.7 % of it missing.
        let err = check_solid_angle(no_sqrt).unwrap_err();
        assert!(
            err.contains("your cone's solid angle is 1.7")
                && err.contains("It is wider than the sphere: 43 %"),
            "{err}"
        );
        assert!(
            err.contains("covers 0.22222 of the sphere of directions, but a fraction 0.12"),
            "the hit fraction is the measurement, your cone the claim: {err}"
        );
        // Wrong: cos of r/d read as the angle (too narrow: every sample hits, the weight is wrong).
        let cos_of_ratio = |r: f64, d: f64| (r / d).cos();
        assert!(check_cone_hits(cos_of_ratio).is_ok());
        let err = check_solid_angle(cos_of_ratio).unwrap_err();
        assert!(err.contains("narrower than the sphere"), "{err}");
    }
}
