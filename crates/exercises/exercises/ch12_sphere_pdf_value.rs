//! # Chapter 12, "Sampling a Sphere Object": the pdf of directions towards a sphere light
//!
//! From a point at distance d from the centre of a sphere of radius r < d, the sphere fills a cone of
//! half-angle theta_max with sin^2 theta_max = r^2 / d^2. Sampling directions uniformly in that cone
//! gives the density 1 / Omega w.r.t. solid angle, with the cone's solid angle
//!
//! Omega = 2 pi (1 - cos theta_max).
//!
//! Computed as written this cancels catastrophically for a small or distant sphere: at d = 1e9 r,
//! cos theta_max = sqrt(1 - 1e-18) rounds to exactly 1, Omega to 0 and the pdf to infinity. Multiply
//! by (1 + cos)/(1 + cos) instead: Omega = 2 pi sin^2 theta_max / (1 + cos theta_max), with no
//! subtraction of nearly equal numbers.
//!
//! **Task.** Write [`sphere_solid_angle`] (that formula for d > r; the whole sphere, 4 pi, when the
//! point is inside or on the sphere, d <= r) and [`sphere_pdf_value`]: the density 1 / Omega for a
//! unit direction whose ray from the origin hits the sphere (t > 0), 0 for one that misses; from
//! inside or on the sphere every direction counts and the density is 1 / (4 pi) (uniform directions).
//!
//! The check: the solid angle at distances 1e2 .. 1e9 within 1e-6 relative of a series expansion,
//! finite positive pdfs far away, inside, on and 1e-4 above the sphere, 0 on a miss, a positive pdf
//! for at least 99.9% of the directions drawn in the cone from just above, and a z-test that the
//! density integrates to 1 over the sphere (E[4 pi p] = 1 over uniform directions).
//!
//! Check your code with `rtl exercises check ch12_sphere_pdf_value`; `rtl exercises hint ch12_sphere_pdf_value` gives a hint.

use glam::DVec3;

// ANCHOR: exercise
/// The solid angle of a sphere of `radius` seen from `distance` from its centre: 4 pi when
/// `distance <= radius`, else 2 pi sin^2 theta_max / (1 + cos theta_max), sin^2 = r^2 / d^2.
pub fn sphere_solid_angle(radius: f64, distance: f64) -> f64 {
    let _ = (radius, distance);
    todo!("ch12 sphere_solid_angle: 2 pi sin^2 / (1 + cos) outside, 4 pi inside")
}

/// The density w.r.t. solid angle of the unit `direction` from `origin` towards the sphere
/// (`center`, `radius`): 1 / [`sphere_solid_angle`] if the ray hits it, else 0.
pub fn sphere_pdf_value(center: DVec3, radius: f64, origin: DVec3, direction: DVec3) -> f64 {
    let _ = (center, radius, origin, direction);
    todo!("ch12 sphere_pdf_value: 1 / solid angle on a hit, 0 on a miss")
}
// ANCHOR_END: exercise
