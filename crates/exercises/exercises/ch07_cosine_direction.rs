//! # Chapter 7, "Cosine Sampling a Hemisphere": a cosine-weighted direction and its pdf
//!
//! **Task.** Two functions, in the frame where the surface normal is +z:
//!
//! - [`random_cosine_direction`]: a direction on the hemisphere z >= 0 with density cos theta / pi
//!   w.r.t. solid angle, from two uniforms: phi = 2 pi u1, z = sqrt(1 - u2), x = cos(phi) sqrt(u2),
//!   y = sin(phi) sqrt(u2). (Under this density z^2 is uniform in [0, 1]:
//!   P(z <= t) = t^2, so z = sqrt(1 - u2) inverts it.)
//! - [`cosine_pdf_value`]: that density, max(0, cos theta) / pi, given cos theta; exactly 0 below the
//!   horizon, never negative.
//!
//! The check: unit length to 1e-12 and z >= 0 at u = 0 and u = 1 - 2^-53 (where z = sqrt(2^-53) is
//! tiny but must not underflow the length); exact pdf values; and a chi-square test of 1e5 directions
//! in 16 x 10 cells of (phi, z) on the hemisphere, against n (delta phi / 2 pi) (z_hi^2 - z_lo^2), the
//! exact integral of the density over each cell.
//!
//! Check your code with `rtl exercises check ch07_cosine_direction`; `rtl exercises hint ch07_cosine_direction` gives a hint.

use glam::DVec3;

// ANCHOR: exercise
/// A direction on the hemisphere z >= 0 with density cos theta / pi, from `u1`, `u2` in [0, 1).
pub fn random_cosine_direction(u1: f64, u2: f64) -> DVec3 {
    let _ = (u1, u2);
    todo!("ch07 random_cosine_direction: phi = 2 pi u1, z = sqrt(1 - u2), radius sqrt(u2)")
}

/// The cosine density max(0, cos theta) / pi per steradian.
pub fn cosine_pdf_value(cos_theta: f64) -> f64 {
    let _ = cos_theta;
    todo!("ch07 cosine_pdf_value: max(0, cos theta) / pi")
}
// ANCHOR_END: exercise
