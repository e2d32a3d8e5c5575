//! # Bug museum, chapter 12, after chapter 9, Sampling Lights Directly, "A sphere light: the cone it subtends": find and fix the bug
//!
//! **Read first:** the section "A sphere light: the cone it subtends" of chapter 9
//! (`book/src/ch09-sampling-lights-directly.md`).
//!
//! A sphere light sampled through this function wastes samples: some of the directions drawn
//! towards it miss it, about 12 % when the sphere nearly fills the view (r/d = 0.99), 46 % at
//! r/d = 1/2, and half of them when the light is far away. Weighted by the cone's density, the light
//! still comes out right on average, but noisier; and the sphere's density, which is 0 for a
//! direction that misses it, disagrees with the directions its sampler draws.
//!
//! **Task.** The light is sampled uniformly in the cone of directions from the origin that just
//! encloses the sphere (radius `radius`, centre at `distance`), with density
//! 1 / (2 pi (1 - cos theta_max)). Find the bug in [`cos_theta_max`] and fix it.
//!
//! Check your code with `cargo exercises check ch12_bug_cone_cos_theta_max` (or
//! `rtl exercises check ch12_bug_cone_cos_theta_max`, the same);
//! `cargo exercises hint ch12_bug_cone_cos_theta_max` gives a hint.

// ANCHOR: exercise
/// The cosine of the half-angle of the cone that encloses the sphere of `radius` whose centre is
/// `distance` away (distance > radius).
pub fn cos_theta_max(radius: f64, distance: f64) -> f64 {
    1.0 - radius * radius / (distance * distance)
}
// ANCHOR_END: exercise
