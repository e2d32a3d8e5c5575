//! # Chapter 6, "Playing with Importance Sampling": one bounce of `ray_color`
//!
//! In the book's `ray_color`, a surface hit returns its emission plus the scattered light weighted by
//! the Monte Carlo ratio of the scattering density to the density the direction was drawn with:
//!
//! L = L_e + A * s(d) * L_i(d) / p(d)
//!
//! with albedo (attenuation) A, scattering pdf s, incoming radiance L_i along the sampled direction d,
//! and sampling pdf p.
//!
//! **Task.** Write [`scatter_contribution`]. It must stay finite whatever the densities: when p(d) is
//! 0, negative or not finite, or s(d) is negative or not finite, or the weighted product is not finite,
//! the sample carries no scattered light and the result is the emission only. (A direction with p = 0
//! cannot have been sampled honestly; dividing by it is how NaNs and fireflies get into images.)
//!
//! The check: exact values with dyadic inputs, every degenerate density, and a white-furnace test: a
//! Lambertian surface (s = cos/pi) of albedo 0.75 under uniform incoming radiance 1, with directions
//! drawn uniformly on the hemisphere (p = 1/(2 pi)), must return 0.75 on average (z-test, 1e5 samples).
//!
//! Check your code with `rtl exercises check ch06_scatter_weight`; `rtl exercises hint ch06_scatter_weight` gives a hint.

use glam::DVec3;

// ANCHOR: exercise
/// L_e + A s L_i / p, or `emitted` alone when the densities make the ratio meaningless or infinite.
pub fn scatter_contribution(
    emitted: DVec3,
    attenuation: DVec3,
    scattering_pdf: f64,
    pdf_value: f64,
    incoming: DVec3,
) -> DVec3 {
    let _ = (emitted, attenuation, scattering_pdf, pdf_value, incoming);
    todo!(
        "ch06 scatter_contribution: emitted + attenuation * s * incoming / p, emitted only if p is 0 or bad"
    )
}
// ANCHOR_END: exercise
