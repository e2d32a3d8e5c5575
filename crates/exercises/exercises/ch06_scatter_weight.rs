//! # Chapter 6, Playing with Importance Sampling, "The strategies": one bounce of `ray_color`
//!
//! **Read first:** the introduction of chapter 5 (`book/src/ch05-light-scattering.md`), which
//! writes the light leaving a surface as an integral and its Monte Carlo estimate from one
//! direction, and the section "The strategies" of chapter 6
//! (`book/src/ch06-playing-with-importance-sampling.md`), which says when a sample carries no
//! scattered light.
//!
//! In the book's `ray_color`, a surface hit returns its emission `emitted` plus the one-sample Monte
//! Carlo estimate of the light it scatters towards the viewer: the incoming radiance `incoming`
//! along one direction d, drawn with the density `pdf_value` = p(d) (w.r.t. solid angle), weighted by
//! the albedo `attenuation` and the scattering density `scattering_pdf` = s(d).
//!
//! **Task.** Write [`scatter_contribution`]: that sum. It must stay finite whatever the densities:
//! when p(d) is 0, negative or not finite, or s(d) is negative or not finite, or the estimate of the
//! scattered light is not finite, the sample carries no scattered light and the result is the
//! emission only. (A direction with p = 0 cannot have been sampled honestly; dividing by it is how
//! NaNs and fireflies get into images.) s(d) = 0 is a valid sample: it scatters nothing.
//!
//! The check: exact values with dyadic inputs, every degenerate density, and a white-furnace test: a
//! Lambertian surface of albedo 0.75 under uniform incoming radiance 1, with directions drawn
//! uniformly on the hemisphere, must return 0.75 on average (z-test, 1e5 samples).
//!
//! Check your code with `cargo exercises check ch06_scatter_weight` (or
//! `rtl exercises check ch06_scatter_weight`, the same); `cargo exercises hint ch06_scatter_weight`
//! gives a hint.

use glam::DVec3;

// ANCHOR: exercise
/// The emission plus the one-sample estimate of the scattered light, or `emitted` alone when the
/// densities make that estimate meaningless or infinite.
pub fn scatter_contribution(
    emitted: DVec3,
    attenuation: DVec3,
    scattering_pdf: f64,
    pdf_value: f64,
    incoming: DVec3,
) -> DVec3 {
    let _ = (emitted, attenuation, scattering_pdf, pdf_value, incoming);
    todo!(
        "ch06 scatter_contribution: emission plus the scattered light's estimate, or emission alone"
    )
}
// ANCHOR_END: exercise
