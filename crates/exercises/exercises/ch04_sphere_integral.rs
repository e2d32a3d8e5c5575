//! # Chapter 4, Monte Carlo Integration on the Sphere of Directions, "A density over directions": integrate cos^2 theta
//!
//! **Read first:** the sections "A density over directions" and "The estimator" of chapter 4
//! (`book/src/ch04-mc-on-the-sphere.md`): how uniform directions follow from the area of the
//! sphere's slices, and the estimator of an integral over directions.
//!
//! **Task.** Two functions:
//!
//! - [`uniform_sphere`]: a direction uniform on the unit sphere (density 1/(4 pi) w.r.t. solid
//!   angle) from two uniforms `u1`, `u2` in [0, 1), without rejection: a map from the unit square to
//!   the sphere. It must be of unit length (to 1e-12) for every input, u = 0 and u = 1 - 2^-53
//!   included, where the direction is at a pole, or within rounding of it.
//! - [`estimate_cos_sq`]: the Monte Carlo estimate of the integral of cos^2 theta = z^2 over the
//!   sphere (exactly 4 pi / 3) from `n` directions of [`uniform_sphere`], each divided by its density.
//!   `None` for `n = 0`.
//!
//! The check: unit length at u = 0, 1/2 and 1 - 2^-53; a chi-square test of 1e5 directions in
//! 16 x 9 equal-area (phi, z) cells; and a z-test of the estimate from 1e5 directions with its exact
//! variance (false failure 1e-6).
//!
//! Check your code with `cargo exercises check ch04_sphere_integral` (or
//! `rtl exercises check ch04_sphere_integral`, the same);
//! `cargo exercises hint ch04_sphere_integral` gives a hint.

use glam::DVec3;
use rand::Rng;

// ANCHOR: exercise
/// A direction uniform on the unit sphere, density 1/(4 pi) per steradian, from `u1`, `u2` in [0, 1).
pub fn uniform_sphere(u1: f64, u2: f64) -> DVec3 {
    let _ = (u1, u2);
    todo!("ch04 uniform_sphere: a uniform direction on the unit sphere from two uniforms")
}

/// The estimate of the integral of cos^2 theta over the sphere (exactly 4 pi / 3) from `n` uniform
/// directions; `None` when `n = 0`.
pub fn estimate_cos_sq<R: Rng + ?Sized>(n: usize, rng: &mut R) -> Option<f64> {
    let _ = (n, rng);
    todo!("ch04 estimate_cos_sq: the integral of cos^2 over the sphere from n uniform directions")
}
// ANCHOR_END: exercise
