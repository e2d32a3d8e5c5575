//! Mixture densities (book 3, chapter 10): pick a part at random, sample it; the density is the
//! weighted sum of the parts' densities.

use crate::selection::{Selection, SelectionError, below_one, remap};
use crate::{DirectionSample, Pdf};
use glam::{DVec2, DVec3};

/// Why a mixture was refused.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MixtureError {
    /// The weight of the first part must be in `[0, 1]`.
    #[error("MixturePdf: the weight of the first part is {0}, not in [0, 1]")]
    BadWeight(f64),
    /// The parts' selection table was refused.
    #[error("mixture of pdfs: {0}")]
    Selection(SelectionError),
}

// ANCHOR: mixture_pdf
/// The mixture `w a + (1 - w) b` of two densities: `sample(u)` samples `a` if `u.x < w`, else `b`,
/// handing the rest of `u.x` on (`u.x / w` or `(u.x - w) / (1 - w)`); `pdf` is exactly
/// `w a.pdf + (1 - w) b.pdf`, and a sample carries the same sum, with the chosen part's density
/// taken from its sample. The book's 50/50 mixture is
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
/// assert!((m.pdf(d) - expected).abs() < 1e-15);
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

    /// [`Pdf::pdf`] of `direction` where the second part's density of it is known already
    /// (`b_pdf`, e.g. a material's density that weighed a light sample): only `a` is evaluated, and
    /// the sum is made as `pdf` makes it, so the number is the same.
    #[inline]
    pub fn pdf_given_b(&self, direction: DVec3, b_pdf: f64) -> f64 {
        let wa = self.weight_a;
        let va = if wa > 0.0 {
            wa * self.a.pdf(direction)
        } else {
            0.0
        };
        let vb = if wa < 1.0 { (1.0 - wa) * b_pdf } else { 0.0 };
        va + vb
    }
}

impl<A: Pdf, B: Pdf> Pdf for MixturePdf<A, B> {
    #[inline]
    fn pdf(&self, direction: DVec3) -> f64 {
        // A part of weight 0 is never sampled and never evaluated (its value may be anything).
        let wa = self.weight_a;
        let va = if wa > 0.0 {
            wa * self.a.pdf(direction)
        } else {
            0.0
        };
        let vb = if wa < 1.0 {
            (1.0 - wa) * self.b.pdf(direction)
        } else {
            0.0
        };
        va + vb
    }

    #[inline(always)]
    fn sample(&self, u: DVec2) -> Option<DirectionSample> {
        let wa = self.weight_a;
        // u.x in [0, 1 - 2^-53], a NaN as 0 (as `Selection` takes it): a part of weight 0 is
        // then never chosen, not even by u.x = NaN or 1 (which `u.x < 1` would send to `b` with
        // a weight of 0, and a density of 0 where `a` does not reach)
        let ux = below_one(u.x);
        let pdf = if ux < wa {
            let s = self.a.sample(DVec2::new(remap(ux, 0.0, wa), u.y))?;
            let vb = if wa < 1.0 {
                (1.0 - wa) * self.b.pdf(s.direction)
            } else {
                0.0
            };
            (s.direction, wa * s.pdf + vb)
        } else {
            let s = self.b.sample(DVec2::new(remap(ux, wa, 1.0 - wa), u.y))?;
            let va = if wa > 0.0 {
                wa * self.a.pdf(s.direction)
            } else {
                0.0
            };
            (s.direction, va + (1.0 - wa) * s.pdf)
        };
        // positive (the chosen part's density is) and finite (every density is): no check needed
        Some(DirectionSample {
            direction: pdf.0,
            pdf: pdf.1,
        })
    }

    /// The book's `generate()`: the direction [`Self::sample`] draws from the same two numbers,
    /// without the other part's density, which only the mixture's pdf needs (for a light, a
    /// ray-shape intersection).
    #[inline]
    fn generate<R: rand::Rng + ?Sized>(&self, rng: &mut R) -> DVec3 {
        let u = crate::pdf::random_unit_square(rng);
        let wa = self.weight_a;
        let s = if u.x < wa {
            self.a.sample(DVec2::new(remap(u.x, 0.0, wa), u.y))
        } else {
            self.b.sample(DVec2::new(remap(u.x, wa, 1.0 - wa), u.y))
        };
        s.map_or(DVec3::ZERO, |s| s.direction)
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
    /// `parts[i]` with probability `selection.pmf(i)`; the lengths must agree.
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
    fn pdf(&self, direction: DVec3) -> f64 {
        self.parts
            .iter()
            .enumerate()
            .map(|(i, part)| {
                let p = self.selection.pmf(i);
                if p > 0.0 {
                    p * part.pdf(direction)
                } else {
                    0.0
                }
            })
            .sum()
    }

    #[inline]
    fn sample(&self, u: DVec2) -> Option<DirectionSample> {
        let c = self.selection.sample(u.x);
        let s = self.parts[c.index].sample(DVec2::new(c.u_remapped, u.y))?;
        let others: f64 = self
            .parts
            .iter()
            .enumerate()
            .filter(|&(j, _)| j != c.index)
            .map(|(j, part)| {
                let p = self.selection.pmf(j);
                if p > 0.0 {
                    p * part.pdf(s.direction)
                } else {
                    0.0
                }
            })
            .sum();
        DirectionSample::new(s.direction, c.pmf * s.pdf + others)
    }
}
