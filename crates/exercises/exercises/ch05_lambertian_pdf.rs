//! # Chapter 5, Light Scattering, "The Lambertian surface": the scattering pdf of a Lambertian surface
//!
//! **Read first:** the section "The Lambertian surface" of chapter 5
//! (`book/src/ch05-light-scattering.md`).
//!
//! **Task.** Write [`lambertian_scattering_pdf`]: the density, w.r.t. solid angle, with which a
//! Lambertian surface of unit normal `n` scatters light into the unit direction `d`. It is
//! proportional to the cosine of the angle theta between `n` and `d` on the hemisphere around `n`,
//! integrates to 1 over that hemisphere, and is exactly 0 below it, where the surface does not
//! scatter: never negative, never NaN.
//!
//! The check: exact values along the normal, at 60 degrees from it, grazing and below the surface;
//! never negative nor NaN; and a z-test (1e5 uniform directions, for three normals) that the density
//! integrates to 1 over the sphere.
//!
//! Check your code with `cargo exercises check ch05_lambertian_pdf` (or
//! `rtl exercises check ch05_lambertian_pdf`, the same); `cargo exercises hint ch05_lambertian_pdf`
//! gives a hint.

use glam::DVec3;

// ANCHOR: exercise
/// The Lambertian scattering density per steradian, for a unit `normal` and a unit `direction`;
/// 0 below the surface.
pub fn lambertian_scattering_pdf(normal: DVec3, direction: DVec3) -> f64 {
    let _ = (normal, direction);
    todo!("ch05 lambertian_scattering_pdf: the Lambertian density, 0 below the surface")
}
// ANCHOR_END: exercise
