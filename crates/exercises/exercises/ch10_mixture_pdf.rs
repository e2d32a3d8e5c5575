//! # Chapter 10, Mixture Densities, "MixturePdf": a mixture pdf whose value is what it generates
//!
//! **Read first:** the sections "The `Pdf` trait" and "`MixturePdf`" of chapter 10
//! (`book/src/ch10-mixture-densities.md`).
//!
//! A [`Pdf`] over directions has two halves that must agree: `generate` draws a direction, `value`
//! says with what density (w.r.t. solid angle) such directions come.
//!
//! **Task.** Implement [`Pdf`] for [`MixturePdf`]: `generate` chooses part a with probability
//! `weight_a` (else part b) and returns that part's direction; `value` returns the density of the
//! directions `generate` draws, whichever part drew them. Weights of exactly 0 and 1 must work: the
//! part of weight 0 is then neither sampled nor evaluated, as the book says, since it may be
//! anything (its value NaN, say).
//!
//! The check: `value` at 1000 random directions (to rounding), for weights 0, 0.3 and 1; a part of
//! weight 0 whose value and samples are NaN, which must change neither `value` nor `generate`
//! (the first draw with u = 0, or 1 - 2^-53 for weight 1); and, for the mixture of a cosine lobe around +z and a narrow cone towards +z (like the book's
//! cosine-plus-light mixture), a chi-square test of 1e5 generated directions in 16 x 25
//! (phi, cos theta) cells against `n` times the integral of the mixture's own `value` over each
//! cell: whatever `generate` samples, `value` must be its density.
//!
//! Check your code with `cargo exercises check ch10_mixture_pdf` (or
//! `rtl exercises check ch10_mixture_pdf`, the same); `cargo exercises hint ch10_mixture_pdf` gives
//! a hint.

use glam::DVec3;
use rand::RngCore;
use rtl_exercises::ch10_mixture_pdf::Pdf;

/// The mixture of two densities that samples a with probability `weight_a` (in [0, 1]), else b.
#[derive(Clone, Copy, Debug)]
pub struct MixturePdf<A, B> {
    pub a: A,
    pub b: B,
    pub weight_a: f64,
}

// ANCHOR: exercise
impl<A: Pdf, B: Pdf> Pdf for MixturePdf<A, B> {
    fn value(&self, direction: DVec3) -> f64 {
        let _ = direction;
        todo!("ch10 MixturePdf::value: the density of the directions generate draws")
    }

    fn generate(&self, rng: &mut dyn RngCore) -> DVec3 {
        let _ = rng;
        todo!("ch10 MixturePdf::generate: a's direction with probability weight_a, else b's")
    }
}
// ANCHOR_END: exercise
