//! # Bug museum, chapter 7, Generating Random Directions, "Cosine-weighted": find and fix the bug
//!
//! **Read first:** the sections "Cosine-weighted" and "How we know a sampler is right: the
//! chi-square test" of chapter 7 (`book/src/ch07-generating-random-directions.md`).
//!
//! The book's first editions sampled cosine-weighted directions with this code. Renders with it looked
//! plausible, only a little darker and flatter than they should. The chi-square test of chapter 7
//! rejects it at once.
//!
//! **Task.** Find the bug in [`random_cosine_direction`] and fix it: the directions must have density
//! cos theta / pi on the hemisphere z >= 0, for `u1`, `u2` in [0, 1).
//!
//! Check your code with `cargo exercises check ch07_bug_cosine_factor_two` (or
//! `rtl exercises check ch07_bug_cosine_factor_two`, the same);
//! `cargo exercises hint ch07_bug_cosine_factor_two` gives a hint.

use glam::DVec3;
use std::f64::consts::PI;

// ANCHOR: exercise
/// A direction with density cos theta / pi around +z, from `u1`, `u2` in [0, 1).
pub fn random_cosine_direction(u1: f64, u2: f64) -> DVec3 {
    let phi = 2.0 * PI * u1;
    let x = phi.cos() * 2.0 * u2.sqrt();
    let y = phi.sin() * 2.0 * u2.sqrt();
    let z = (1.0 - u2).sqrt();
    DVec3::new(x, y, z).normalize()
}
// ANCHOR_END: exercise
