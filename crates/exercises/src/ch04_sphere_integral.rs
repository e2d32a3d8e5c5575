//! # Chapter 4, "Monte Carlo Integration on the Sphere of Directions": integrate cos^2 theta
//!
//! **Task.** Two functions:
//!
//! - [`uniform_sphere`]: a direction uniform on the unit sphere (density 1/(4 pi) w.r.t. solid angle)
//!   from two uniforms: z = 1 - 2 u1 (uniform in [-1, 1], since d omega = dz d phi), phi = 2 pi u2,
//!   x = r cos phi, y = r sin phi with r = sqrt(1 - z^2) (clamp 1 - z^2 at 0 so rounding never gives
//!   a NaN).
//! - [`estimate_cos_sq`]: the Monte Carlo estimate of the integral of cos^2 theta = z^2 over the
//!   sphere, (1/n) sum f(d) / p(d) = (1/n) sum 4 pi z^2, whose exact value is 4 pi / 3. `None` for
//!   `n = 0`.
//!
//! The check: unit length (to 1e-12) at u = 0 and u = 1 - 2^-53; a chi-square test of 1e5 directions
//! in 16 x 9 equal-area (phi, z) cells; and a z-test of the estimate with its exact variance
//! 16 pi^2 (1/5 - 1/9) / n.

use crate::check::{self, CheckResult, SphereBins, U_MAX};
use glam::DVec3;
use rand::{Rng, RngCore};
use std::f64::consts::PI;

// ANCHOR: exercise
/// A direction uniform on the unit sphere, density 1/(4 pi) per steradian, from `u1`, `u2` in [0, 1).
pub fn uniform_sphere(u1: f64, u2: f64) -> DVec3 {
    #[cfg(feature = "solutions")]
    return solution::uniform_sphere(u1, u2);
    #[cfg(not(feature = "solutions"))]
    {
        let _ = (u1, u2);
        todo!("ch04 uniform_sphere: z = 1 - 2 u1, phi = 2 pi u2")
    }
}

/// The estimate of the integral of cos^2 theta over the sphere (exactly 4 pi / 3) from `n` uniform
/// directions; `None` when `n = 0`.
pub fn estimate_cos_sq<R: Rng + ?Sized>(n: usize, rng: &mut R) -> Option<f64> {
    #[cfg(feature = "solutions")]
    return solution::estimate_cos_sq(n, rng);
    #[cfg(not(feature = "solutions"))]
    {
        let _ = (n, rng);
        todo!("ch04 estimate_cos_sq: average cos^2 / (1 / (4 pi)) over uniform directions")
    }
}
// ANCHOR_END: exercise

/// Unit length at the corners of [0, 1)^2, and a chi-square test of 1e5 directions.
pub fn check_uniform_sphere(sample: impl Fn(f64, f64) -> DVec3) -> CheckResult {
    for u1 in [0.0, 0.5, U_MAX] {
        for u2 in [0.0, 0.25, U_MAX] {
            check::unit(&format!("uniform_sphere({u1}, {u2})"), sample(u1, u2))?;
        }
    }
    let bins = SphereBins {
        n_phi: 16,
        n_z: 9,
        z_min: -1.0,
        z_max: 1.0,
    };
    let n = 100_000;
    let mut rng = check::seeded(40);
    let dirs: Vec<DVec3> = (0..n).map(|_| sample(rng.random(), rng.random())).collect();
    let observed = bins.histogram("uniform_sphere", dirs)?;
    let expected = bins.expected(n, |_| 1.0 / (4.0 * PI), |_, _| true, 4);
    check::chi_square("uniform_sphere", &observed, &expected)
}

/// z-test of the estimate from 1e5 directions against 4 pi / 3; `None` for `n = 0`.
pub fn check_estimate(estimate: impl Fn(usize, &mut dyn RngCore) -> Option<f64>) -> CheckResult {
    if let Some(x) = estimate(0, &mut check::seeded(41)) {
        return Err(format!(
            "estimate_cos_sq(0) returned Some({x}); no samples give no estimate (None)"
        ));
    }
    let n = 100_000;
    let got = estimate(n, &mut check::seeded(42)).ok_or("estimate_cos_sq(100000) returned None")?;
    let se = (16.0 * PI * PI * (1.0 / 5.0 - 1.0 / 9.0) / n as f64).sqrt();
    check::z_test("integral of cos^2 over the sphere", got, se, 4.0 * PI / 3.0)
}

/// This exercise's checks, run on your [`uniform_sphere`] and [`estimate_cos_sq`].
pub fn check() -> CheckResult {
    check_uniform_sphere(uniform_sphere)?;
    check_estimate(|n, rng: &mut dyn RngCore| estimate_cos_sq(n, rng))
}

#[cfg(feature = "solutions")]
mod solution {
    use glam::DVec3;
    use rand::Rng;
    use std::f64::consts::PI;

    pub fn uniform_sphere(u1: f64, u2: f64) -> DVec3 {
        let z = 1.0 - 2.0 * u1;
        let r = (1.0 - z * z).max(0.0).sqrt();
        let phi = 2.0 * PI * u2;
        DVec3::new(r * phi.cos(), r * phi.sin(), z)
    }

    pub fn estimate_cos_sq<R: Rng + ?Sized>(n: usize, rng: &mut R) -> Option<f64> {
        if n == 0 {
            return None;
        }
        let pdf = 1.0 / (4.0 * PI);
        let sum: f64 = (0..n)
            .map(|_| {
                let d = uniform_sphere(rng.random(), rng.random());
                d.z * d.z / pdf
            })
            .sum();
        Some(sum / n as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_sphere_directions_are_unit_and_uniform() {
        check_uniform_sphere(uniform_sphere).unwrap();
    }

    #[test]
    fn estimate_of_cos_sq_is_4_pi_over_3() {
        check_estimate(|n, rng: &mut dyn RngCore| estimate_cos_sq(n, rng)).unwrap();
    }

    #[test]
    fn checks_reject_wrong_samplers_and_estimators() {
        // Wrong: theta uniform in [0, pi] crowds the poles.
        let theta_uniform = |u1: f64, u2: f64| {
            let (theta, phi) = (PI * u1, 2.0 * PI * u2);
            DVec3::new(
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                theta.cos(),
            )
        };
        assert!(check_uniform_sphere(theta_uniform).is_err());
        // Wrong: forgets to divide by the pdf (estimates the mean of cos^2, 1/3).
        let mean_only = |n: usize, rng: &mut dyn RngCore| {
            (n > 0).then(|| {
                (0..n)
                    .map(|_| (1.0 - 2.0 * rng.random::<f64>()).powi(2))
                    .sum::<f64>()
                    / n as f64
            })
        };
        assert!(check_estimate(mean_only).is_err());
    }
}
