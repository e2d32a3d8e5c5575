//! Reference solution of `exercises/ch10_mixture_pdf.rs`, compiled only with `--features solutions`: try the
//! exercise first (`rtl exercises solution ch10_mixture_pdf` shows it once your code passes).

use glam::DVec3;
use rand::{Rng, RngCore};
use rtl_exercises::ch10_mixture_pdf::Pdf;

#[derive(Clone, Copy, Debug)]
pub struct MixturePdf<A, B> {
    pub a: A,
    pub b: B,
    pub weight_a: f64,
}

impl<A: Pdf, B: Pdf> Pdf for MixturePdf<A, B> {
    fn value(&self, direction: DVec3) -> f64 {
        self.weight_a * self.a.value(direction) + (1.0 - self.weight_a) * self.b.value(direction)
    }

    fn generate(&self, rng: &mut dyn RngCore) -> DVec3 {
        // u < w is never true for w = 0 and always for w = 1, as u lies in [0, 1).
        if rng.random::<f64>() < self.weight_a {
            self.a.generate(rng)
        } else {
            self.b.generate(rng)
        }
    }
}
