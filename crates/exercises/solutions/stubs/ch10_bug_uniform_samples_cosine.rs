//! # Bug museum, chapter 10, Mixture Densities, "The Pdf trait": find and fix the bug
//!
//! **Read first:** the section "The `Pdf` trait" of chapter 10
//! (`book/src/ch10-mixture-densities.md`), and "Uniform over the hemisphere" of chapter 7
//! (`book/src/ch07-generating-random-directions.md`).
//!
//! Someone wanted a uniform-hemisphere density to compare with the cosine one, copied `CosinePdf` and
//! changed its value to 1/(2 pi). The images it gives are smooth, clean, and too bright.
//!
//! **Task.** Find the bug in [`HemispherePdf`] and fix it: `generate` must draw directions with the
//! density that `value` states, uniform on the hemisphere z >= 0.
//!
//! Check your code with `cargo exercises check ch10_bug_uniform_samples_cosine` (or
//! `rtl exercises check ch10_bug_uniform_samples_cosine`, the same);
//! `cargo exercises hint ch10_bug_uniform_samples_cosine` gives a hint.

use glam::DVec3;
use rand::{Rng, RngCore};
use rtl_exercises::ch10_mixture_pdf::Pdf;
use std::f64::consts::PI;

/// The uniform density 1/(2 pi) on the hemisphere around +z.
#[derive(Clone, Copy, Debug)]
pub struct HemispherePdf;

// ANCHOR: exercise
impl Pdf for HemispherePdf {
    fn value(&self, direction: DVec3) -> f64 {
        if direction.z >= 0.0 {
            1.0 / (2.0 * PI)
        } else {
            0.0
        }
    }

    fn generate(&self, rng: &mut dyn RngCore) -> DVec3 {
        let (u1, u2): (f64, f64) = (rng.random(), rng.random());
        let phi = 2.0 * PI * u1;
        let r = u2.sqrt();
        DVec3::new(phi.cos() * r, phi.sin() * r, (1.0 - u2).sqrt())
    }
}
// ANCHOR_END: exercise
