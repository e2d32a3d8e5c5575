//! # Chapter 9, Sampling Lights Directly, "A quad light: from area to solid angle": the solid-angle pdf of a quad light
//!
//! **Read first:** the section "A quad light: from area to solid angle" of chapter 9
//! (`book/src/ch09-sampling-lights-directly.md`), which turns a density per unit area into a
//! density per steradian.
//!
//! **Task.** Write [`quad_pdf_value`]. A point is chosen uniformly (by area) on the parallelogram
//! light {q + a u + b v : a, b in [0, 1]}. Return the density, w.r.t. solid angle at `origin`, of
//! the unit `direction` towards it: intersect the ray origin + t direction (t > 0) with the quad's
//! plane, test the hit against the parallelogram, and convert the area density at the hit to a
//! density per steradian seen from `origin`. Return 0 when the ray misses: it points away, it is
//! parallel to the plane, the hit lies outside the parallelogram, or the origin lies in the plane
//! (t = 0: a density of 0, not infinity). The light is two-sided: a hit from behind counts.
//!
//! The check: exact values head-on and oblique, the hard cases (origin in the plane, 1e-9 above it,
//! parallel, behind, from the back side), and a z-test that the density integrates to 1 over the
//! sphere (1e5 uniform directions, false failure 1e-6).
//!
//! Check your code with `cargo exercises check ch09_quad_pdf_value` (or
//! `rtl exercises check ch09_quad_pdf_value`, the same); `cargo exercises hint ch09_quad_pdf_value`
//! gives a hint.

use glam::DVec3;
use rtl_exercises::ch09_quad_pdf_value::Quad;

// ANCHOR: exercise
/// The density per steradian of the unit `direction` from `origin` towards a point chosen uniformly
/// by area on `quad`; 0 when the ray misses the quad.
pub fn quad_pdf_value(quad: &Quad, origin: DVec3, direction: DVec3) -> f64 {
    let _ = (quad, origin, direction);
    todo!("ch09 quad_pdf_value: hit the quad, turn its area density into a solid-angle density")
}
// ANCHOR_END: exercise
