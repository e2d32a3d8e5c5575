//! # Bug museum, chapter 12, after chapter 9, Sampling Lights Directly, "Several lights": find and fix the bug
//!
//! **Read first:** the section "Several lights" of chapter 9
//! (`book/src/ch09-sampling-lights-directly.md`).
//!
//! With two lights in the scene, the book's readers put them in a list and sampled the list: and the
//! image came out black. Sampling either light alone works.
//!
//! **Task.** [`LightList`] picks one of its lights at random and samples it. Find why an integrator
//! that uses it gets no light, and fix it. The trait [`Light`] (given, in `rtl_exercises`) is like
//! the book's `hittable`: it has a default `pdf_value`.
//!
//! Check your code with `cargo exercises check ch12_bug_light_list_pdf` (or
//! `rtl exercises check ch12_bug_light_list_pdf`, the same);
//! `cargo exercises hint ch12_bug_light_list_pdf` gives a hint.

use glam::DVec3;
use rand::{Rng, RngCore};
use rtl_exercises::ch12_bug_light_list_pdf::{ConeLight, Light};

/// Several lights, sampled as one: a light chosen uniformly, then a direction towards it.
pub struct LightList {
    pub lights: Vec<ConeLight>,
}

// ANCHOR: exercise
impl Light for LightList {
    fn random(&self, rng: &mut dyn RngCore) -> DVec3 {
        let i = rng.random_range(0..self.lights.len());
        self.lights[i].random(rng)
    }
}
// ANCHOR_END: exercise
