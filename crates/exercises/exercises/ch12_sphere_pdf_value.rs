//! # Chapter 12, after chapter 9, Sampling Lights Directly, "A sphere light: the cone it subtends": the pdf of directions towards a sphere light
//!
//! **Read first:** the section "A sphere light: the cone it subtends" of chapter 9
//! (`book/src/ch09-sampling-lights-directly.md`), which derives the cone's solid angle and a form
//! of it that stays accurate for a small or distant sphere.
//!
//! From a point at distance d from the centre of a sphere of radius r < d, the sphere fills a cone of
//! half-angle theta_max, with sin theta_max = r / d. Directions drawn uniformly in that cone have the
//! density 1 / Omega w.r.t. solid angle, Omega the solid angle of the cone. Computed naively, Omega
//! cancels catastrophically for a small or distant sphere: at d = 1e9 r, cos theta_max rounds to
//! exactly 1, and Omega to 0.
//!
//! **Task.** Write [`sphere_solid_angle`]: Omega for d > r, accurate to a relative 1e-6 up to
//! d = 1e9 r (no subtraction of nearly equal numbers), and the whole sphere, 4 pi, when the point is
//! inside or on the sphere (d <= r). And [`sphere_pdf_value`]: the density 1 / Omega of a unit
//! direction whose ray from `origin` hits the sphere (t > 0), 0 for one that misses or points away;
//! from inside or on the sphere every direction counts and the density is that of uniform directions
//! on the whole sphere.
//!
//! The check: the solid angle at distances 1e2 .. 1e9 within 1e-6 relative of a series expansion,
//! finite positive pdfs far away, inside, on and 1e-4 above the sphere, 0 on a miss, a positive pdf
//! for at least 99.9% of the directions drawn in the cone from just above, and a z-test that the
//! density integrates to 1 over the sphere (1e5 uniform directions).
//!
//! Check your code with `cargo exercises check ch12_sphere_pdf_value` (or
//! `rtl exercises check ch12_sphere_pdf_value`, the same);
//! `cargo exercises hint ch12_sphere_pdf_value` gives a hint.

use glam::DVec3;

// ANCHOR: exercise
/// The solid angle of a sphere of `radius` seen from `distance` from its centre: the cone it fills
/// when `distance > radius`, accurate for a far sphere; 4 pi when `distance <= radius`.
pub fn sphere_solid_angle(radius: f64, distance: f64) -> f64 {
    let _ = (radius, distance);
    todo!("ch12 sphere_solid_angle: the cone's solid angle without cancellation, 4 pi inside")
}

/// The density w.r.t. solid angle of the unit `direction` from `origin` towards the sphere
/// (`center`, `radius`): 1 / [`sphere_solid_angle`] if the ray hits it, else 0.
pub fn sphere_pdf_value(center: DVec3, radius: f64, origin: DVec3, direction: DVec3) -> f64 {
    let _ = (center, radius, origin, direction);
    todo!("ch12 sphere_pdf_value: 1 / solid angle on a hit, 0 on a miss")
}
// ANCHOR_END: exercise
