//! # Chapter 9, "Sampling Lights Directly": the solid-angle pdf of a quad light
//!
//! A point chosen uniformly on a light of area A has density 1/A w.r.t. area. Seen from a point p,
//! an area element dA at distance r whose normal makes angle theta with the direction subtends a
//! solid angle d omega = |cos theta| dA / r^2, so the same choice has density w.r.t. solid angle
//!
//! p(omega) = r^2 / (|cos theta| A).
//!
//! **Task.** Write [`quad_pdf_value`]: for the parallelogram {q + a u + b v : a, b in [0, 1]}, the
//! origin p and a unit direction d, intersect the ray p + t d (t > 0) with the quad's plane, test the
//! hit against the parallelogram, and return r^2 / (|cos theta| A) with r = t (d is unit),
//! cos theta = n . d for the unit normal n, and A = |u x v|. Return 0 when the ray misses: it points
//! away, it is parallel to the plane, the hit lies outside the parallelogram, or the origin lies in the
//! plane (t = 0: a pdf of 0, not infinity). The light is two-sided.
//!
//! The check: exact values head-on and oblique, the hard cases (origin in the plane, 1e-9 above it,
//! parallel, behind, from the back side), and a z-test that E[4 pi p(omega)] = 1 over uniform
//! directions: the density integrates to 1 over the sphere.
//!
//! Check your code with `rtl exercises check ch09_quad_pdf_value`; `rtl exercises hint ch09_quad_pdf_value` gives a hint.

use glam::DVec3;
use rtl_exercises::ch09_quad_pdf_value::Quad;

// ANCHOR: exercise
/// The solid-angle density r^2 / (|cos theta| A) of the direction `direction` (unit) from `origin`
/// towards a uniformly chosen point of `quad`; 0 when the ray misses the quad.
pub fn quad_pdf_value(quad: &Quad, origin: DVec3, direction: DVec3) -> f64 {
    let _ = (quad, origin, direction);
    todo!("ch09 quad_pdf_value: hit the quad, return distance^2 / (|cos| area), 0 on a miss")
}
// ANCHOR_END: exercise
