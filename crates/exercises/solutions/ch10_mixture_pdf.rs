//! Reference solution of `exercises/ch10_mixture_pdf.rs`, compiled only with `--features solutions`: try the
//! exercise first (`cargo exercises solution ch10_mixture_pdf` shows it once your code passes).

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
        // A part of weight 0 is not evaluated: its value may be NaN, and 0 * NaN is NaN.
        let mut value = 0.0;
        if self.weight_a > 0.0 {
            value += self.weight_a * self.a.value(direction);
        }
        if self.weight_a < 1.0 {
            value += (1.0 - self.weight_a) * self.b.value(direction);
        }
        value
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
