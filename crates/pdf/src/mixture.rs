//! Mixture densities (book 3, chapter 10): pick a part at random, sample it; the density is the
//! weighted sum of the parts' densities.

use crate::Pdf;
use crate::selection::{Selection, SelectionError};
use glam::DVec3;
use rand::Rng;

/// Why a mixture was refused.
#[derive(Clone, Debug, PartialEq)]
pub enum MixtureError {
    /// The weight of the first part must be in `[0, 1]`.
    BadWeight(f64),
    /// The parts' selection table was refused.
    Selection(SelectionError),
}

impl std::fmt::Display for MixtureError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            MixtureError::BadWeight(w) => {
                write!(
                    f,
                    "MixturePdf: the weight of the first part is {w}, not in [0, 1]"
                )
            }
            MixtureError::Selection(e) => write!(f, "mixture of pdfs: {e}"),
        }
    }
}

impl std::error::Error for MixtureError {}

// ANCHOR: mixture_pdf
/// The mixture `w a + (1 - w) b` of two densities: `generate` samples `a` with probability `w`, else
/// `b`; `value` is exactly `w a.value + (1 - w) b.value`. The book's 50/50 mixture is
/// [`MixturePdf::new`].
///
/// Generic over its parts, so a mixture is a plain value (no `Box`, no virtual calls) and mixtures nest:
/// `MixturePdf<CosinePdf, HittablePdf<'_, QuadTarget>>`.
///
/// ```
/// use glam::DVec3;
/// use rtl_pdf::{CosinePdf, MixturePdf, Pdf, SpherePdf};
/// let m = MixturePdf::new(CosinePdf::new(DVec3::Z), SpherePdf);
/// let d = DVec3::Z;
/// let expected = 0.5 * (1.0 / std::f64::consts::PI) + 0.5 / (4.0 * std::f64::consts::PI);
/// assert!((m.value(d) - expected).abs() < 1e-15);
/// ```
#[derive(Clone, Copy, Debug)]
pub struct MixturePdf<A: Pdf, B: Pdf> {
    a: A,
    b: B,
    /// probability of sampling `a`
    weight_a: f64,
}

impl<A: Pdf, B: Pdf> MixturePdf<A, B> {
    /// The book's even mixture: each part with probability 1/2.
    #[inline]
    pub fn new(a: A, b: B) -> MixturePdf<A, B> {
        MixturePdf {
            a,
            b,
            weight_a: 0.5,
        }
    }

    /// `a` with probability `weight_a` in `[0, 1]`, `b` with `1 - weight_a`.
    #[inline]
    pub fn with_weight(a: A, b: B, weight_a: f64) -> Result<MixturePdf<A, B>, MixtureError> {
        if !(0.0..=1.0).contains(&weight_a) {
            return Err(MixtureError::BadWeight(weight_a));
        }
        Ok(MixturePdf { a, b, weight_a })
    }

    /// The probability of sampling the first part.
    pub fn weight(&self) -> f64 {
        self.weight_a
    }

    /// The parts.
    pub fn parts(&self) -> (&A, &B) {
        (&self.a, &self.b)
    }
}

impl<A: Pdf, B: Pdf> Pdf for MixturePdf<A, B> {
    #[inline]
    fn value(&self, direction: DVec3) -> f64 {
        // A part of weight 0 is never sampled and never evaluated (its value may be anything).
        let wa = self.weight_a;
        let va = if wa > 0.0 {
            wa * self.a.value(direction)
        } else {
            0.0
        };
        let vb = if wa < 1.0 {
            (1.0 - wa) * self.b.value(direction)
        } else {
            0.0
        };
        va + vb
    }

    #[inline]
    fn generate<R: Rng + ?Sized>(&self, rng: &mut R) -> DVec3 {
        if rng.random::<f64>() < self.weight_a {
            self.a.generate(rng)
        } else {
            self.b.generate(rng)
        }
    }
}
// ANCHOR_END: mixture_pdf

/// A mixture of any number of densities of one type `P` (an enum of the kinds in use, say), chosen with
/// the probabilities of a [`Selection`]: `value = sum_i p_i parts_i.value`. Borrows both, so it
/// allocates nothing per sample.
#[derive(Clone, Copy, Debug)]
pub struct MixtureOfPdfs<'a, P: Pdf> {
    parts: &'a [P],
    selection: &'a Selection,
}

impl<'a, P: Pdf> MixtureOfPdfs<'a, P> {
    /// `parts[i]` with probability `selection.probability(i)`; the lengths must agree.
    pub fn new(
        parts: &'a [P],
        selection: &'a Selection,
    ) -> Result<MixtureOfPdfs<'a, P>, MixtureError> {
        if parts.len() != selection.len() {
            return Err(MixtureError::Selection(SelectionError::LengthMismatch {
                table: selection.len(),
                parts: parts.len(),
            }));
        }
        Ok(MixtureOfPdfs { parts, selection })
    }
}

impl<P: Pdf> Pdf for MixtureOfPdfs<'_, P> {
    #[inline]
    fn value(&self, direction: DVec3) -> f64 {
        self.parts
            .iter()
            .enumerate()
            .map(|(i, part)| {
                let p = self.selection.probability(i);
                if p > 0.0 {
                    p * part.value(direction)
                } else {
                    0.0
                }
            })
            .sum()
    }

    #[inline]
    fn generate<R: Rng + ?Sized>(&self, rng: &mut R) -> DVec3 {
        let i = self.selection.choose(rng.random::<f64>());
        self.parts[i].generate(rng)
    }
}
