//! # Chapter 5, "Light Scattering": the scattering pdf of a Lambertian surface
//!
//! **Task.** Write [`lambertian_scattering_pdf`]: the density, w.r.t. solid angle, with which a
//! Lambertian surface of unit normal `n` scatters light into the unit direction `d`:
//! s(d) = max(0, cos theta) / pi, cos theta = n . d. It integrates to 1 over the hemisphere around
//! `n` and is exactly 0 below it (the surface does not transmit), never negative.
//!
//! The check: exact values (1/pi along the normal, 1/(2 pi) at 60 degrees, 0 when grazing and below),
//! never negative nor NaN, and a z-test (1e5 uniform directions, for a few normals) that
//! E[4 pi s(d)] = 1, i.e. the density integrates to 1 over the sphere.
//!
//! Check your code with `rtl exercises check ch05_lambertian_pdf`; `rtl exercises hint ch05_lambertian_pdf` gives a hint.

use glam::DVec3;

// ANCHOR: exercise
/// The Lambertian scattering density max(0, n . d) / pi per steradian, for unit `normal` and `direction`.
pub fn lambertian_scattering_pdf(normal: DVec3, direction: DVec3) -> f64 {
    let _ = (normal, direction);
    todo!("ch05 lambertian_scattering_pdf: max(0, cos theta) / pi")
}
// ANCHOR_END: exercise
