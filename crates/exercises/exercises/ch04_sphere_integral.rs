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
//!
//! Check your code with `rtl exercises check ch04_sphere_integral`; `rtl exercises hint ch04_sphere_integral` gives a hint.

use glam::DVec3;
use rand::Rng;

// ANCHOR: exercise
/// A direction uniform on the unit sphere, density 1/(4 pi) per steradian, from `u1`, `u2` in [0, 1).
pub fn uniform_sphere(u1: f64, u2: f64) -> DVec3 {
    let _ = (u1, u2);
    todo!("ch04 uniform_sphere: z = 1 - 2 u1, phi = 2 pi u2")
}

/// The estimate of the integral of cos^2 theta over the sphere (exactly 4 pi / 3) from `n` uniform
/// directions; `None` when `n = 0`.
pub fn estimate_cos_sq<R: Rng + ?Sized>(n: usize, rng: &mut R) -> Option<f64> {
    let _ = (n, rng);
    todo!("ch04 estimate_cos_sq: average cos^2 / (1 / (4 pi)) over uniform directions")
}
// ANCHOR_END: exercise
