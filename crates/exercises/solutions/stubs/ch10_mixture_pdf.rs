//! # Chapter 10, "Mixture Densities": a mixture pdf whose value is what it generates
//!
//! A [`Pdf`] over directions has two halves that must agree: `generate` draws a direction, `value`
//! says with what density (w.r.t. solid angle). The mixture of densities a and b with weight w,
//!
//! p(d) = w a(d) + (1 - w) b(d),
//!
//! is sampled by choosing a with probability w (else b) and returning that part's direction.
//!
//! **Task.** Implement [`Pdf`] for [`MixturePdf`]: `value` returns the weighted sum, `generate` picks
//! a part with probability `weight_a` and delegates to it. Weights of exactly 0 or 1 must work (the
//! unchosen part is then never sampled).
//!
//! The check: `value` equals w a + (1 - w) b at 1000 random directions (to rounding), for weights 0,
//! 0.3, 1; and, for the mixture of a cosine lobe around +z and a narrow cone towards +z (like the book's
//! cosine-plus-light mixture), a chi-square test of 1e5 generated directions in 16 x 25 (phi, z) cells
//! against `n` times the integral of the mixture's own `value` over each cell: whatever `generate`
//! samples, `value` must be its density.
//!
//! Check your code with `rtl exercises check ch10_mixture_pdf`; `rtl exercises hint ch10_mixture_pdf` gives a hint.

use glam::DVec3;
use rand::RngCore;
use rtl_exercises::ch10_mixture_pdf::Pdf;

/// The mixture `weight_a` a + (1 - `weight_a`) b of two densities, `weight_a` in [0, 1].
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
        todo!("ch10 MixturePdf::value: w a(d) + (1 - w) b(d)")
    }

    fn generate(&self, rng: &mut dyn RngCore) -> DVec3 {
        let _ = rng;
        todo!("ch10 MixturePdf::generate: a's direction with probability w, else b's")
    }
}
// ANCHOR_END: exercise
