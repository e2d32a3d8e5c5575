//! # Chapter 7, Generating Random Directions, "Cosine-weighted": a cosine-weighted direction and its pdf
//!
//! **Read first:** the section "Cosine-weighted" of chapter 7
//! (`book/src/ch07-generating-random-directions.md`), which samples this density by Malley's method
//! and mentions in passing the original book's way, inverting the CDF of theta; either will do.
//!
//! **Task.** Two functions, in the frame where the surface normal is +z:
//!
//! - [`random_cosine_direction`]: a unit direction on the hemisphere z >= 0 with density
//!   cos theta / pi w.r.t. solid angle (theta measured from +z), from two uniforms `u1`, `u2` in
//!   [0, 1), without rejection. It must be of unit length (to 1e-12) with z >= 0 for every input,
//!   u = 0 and u = 1 - 2^-53 included, where z is tiny but must not turn negative or NaN.
//! - [`cosine_pdf_value`]: that density, given cos theta; exactly 0 at and below the horizon
//!   (cos theta <= 0), never negative.
//!
//! The check: unit length and z >= 0 at u = 0, 1/4, 1/2 and 1 - 2^-53; exact pdf values; and a
//! chi-square test of 1e5 directions in 16 x 10 cells of (phi, cos theta) on the hemisphere,
//! against n times the exact integral of the density over each cell.
//!
//! Check your code with `cargo exercises check ch07_cosine_direction` (or
//! `rtl exercises check ch07_cosine_direction`, the same);
//! `cargo exercises hint ch07_cosine_direction` gives a hint.

use glam::DVec3;

// ANCHOR: exercise
/// A direction on the hemisphere z >= 0 with density cos theta / pi, from `u1`, `u2` in [0, 1).
pub fn random_cosine_direction(u1: f64, u2: f64) -> DVec3 {
    let _ = (u1, u2);
    todo!("ch07 random_cosine_direction: a direction of density cos theta / pi from two uniforms")
}

/// The cosine density per steradian, given cos theta: 0 at and below the horizon.
pub fn cosine_pdf_value(cos_theta: f64) -> f64 {
    let _ = cos_theta;
    todo!("ch07 cosine_pdf_value: the density cos theta / pi, 0 below the horizon")
}
// ANCHOR_END: exercise
