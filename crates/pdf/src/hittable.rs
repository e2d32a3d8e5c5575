//! `HittablePdf`: directions towards one or more shapes, seen from a point (book 3, chapters 9 and 12).

use crate::selection::{Selection, SelectionError, choose_by_pmf, choose_uniform};
use crate::{DirectionSample, Pdf, ShapeSampler};
use glam::{DVec2, DVec3};

// ANCHOR: hittable_pdf
/// Directions from `origin` towards a list of shapes: choose shape `i` with probability `p_i` (uniform,
/// from a precomputed [`Selection`], e.g. by power, or from probabilities given for this `origin`
/// alone, e.g. by each shape's importance seen from there) by `u.x`, then sample towards it with the
/// rest of `u.x` and `u.y`. The density of a direction is the total over every shape it could have come
/// from: `pdf(d) = sum_i p_i shape_i.pdf(origin, d)`.
///
/// A shape with no directions from `origin` (a one-sided light seen from behind: `sample` gives
/// `None`, `pdf` 0) makes the sample fail rather than return a direction it did not draw by its
/// density: so `pdf` describes exactly what `sample` draws, a sub-probability density when some shape
/// cannot be sampled from here.
///
/// Borrows the shapes (and the table or the probabilities), so building one per scattering event
/// allocates nothing.
///
/// ```
/// use glam::{DVec2, DVec3};
/// use rtl_pdf::{HittablePdf, Pdf, SphereTarget};
/// let lights = [SphereTarget::new(DVec3::new(0.0, 0.0, -10.0), 1.0)];
/// let pdf = HittablePdf::new(DVec3::ZERO, &lights).expect("at least one light");
/// assert!(pdf.pdf(DVec3::new(0.0, 0.0, -1.0)) > 0.0); // towards the centre
/// assert_eq!(pdf.pdf(DVec3::new(0.0, 0.0, 1.0)), 0.0); // away from it
/// let s = pdf.sample(DVec2::new(0.3, 0.7)).unwrap();
/// assert!((s.pdf - pdf.pdf(s.direction)).abs() <= 1e-12 * s.pdf);
/// let none: [SphereTarget; 0] = [];
/// assert!(HittablePdf::new(DVec3::ZERO, &none).is_none());
/// ```
#[derive(Clone, Copy)]
pub struct HittablePdf<'a, T: ShapeSampler> {
    origin: DVec3,
    targets: &'a [T],
    choice: Choosing<'a>,
    /// Which shapes a direction may meet, for a long list ([`HittablePdf::with_index`]).
    index: Option<&'a dyn ShapeIndex>,
}

/// How a [`HittablePdf`] chooses its shape.
#[derive(Clone, Copy, Debug)]
enum Choosing<'a> {
    /// `1 / n` each.
    Uniform,
    /// A table built once.
    Table(&'a Selection),
    /// Probabilities given per origin, `>= 0` and summing to 1 (chosen by a linear scan).
    Pmf(&'a [f64]),
}

impl<'a, T: ShapeSampler> HittablePdf<'a, T> {
    /// Each shape with probability `1 / n`; `None` for an empty list (there is nothing to sample).
    #[inline]
    pub fn new(origin: DVec3, targets: &'a [T]) -> Option<HittablePdf<'a, T>> {
        (!targets.is_empty()).then_some(HittablePdf {
            origin,
            targets,
            choice: Choosing::Uniform,
            index: None,
        })
    }

    /// Shapes chosen with the probabilities of `selection`, which must have one entry per shape.
    pub fn with_selection(
        origin: DVec3,
        targets: &'a [T],
        selection: &'a Selection,
    ) -> Result<HittablePdf<'a, T>, SelectionError> {
        if targets.is_empty() {
            return Err(SelectionError::Empty);
        }
        if selection.len() != targets.len() {
            return Err(SelectionError::LengthMismatch {
                table: selection.len(),
                parts: targets.len(),
            });
        }
        Ok(HittablePdf {
            origin,
            targets,
            choice: Choosing::Table(selection),
            index: None,
        })
    }

    /// Shape `i` chosen with probability `pmf[i]`, given for this `origin` (one entry per shape, each
    /// `>= 0`, summing to 1: the caller normalises; checked in debug builds). Choosing is a linear
    /// scan of the running sums, for the short lists whose probabilities change from point to point
    /// (a [`Selection`] tabulates once and searches in `O(log n)`). A shape of probability 0 is never
    /// chosen; if every entry is 0, `sample` fails and `pdf` is 0.
    #[inline]
    pub fn with_pmf(
        origin: DVec3,
        targets: &'a [T],
        pmf: &'a [f64],
    ) -> Result<HittablePdf<'a, T>, SelectionError> {
        if targets.is_empty() {
            return Err(SelectionError::Empty);
        }
        if pmf.len() != targets.len() {
            return Err(SelectionError::LengthMismatch {
                table: pmf.len(),
                parts: targets.len(),
            });
        }
        debug_assert!(
            pmf.iter().all(|p| p.is_finite() && *p >= 0.0)
                && (pmf.iter().sum::<f64>() - 1.0).abs() < 1e-9
                || pmf.iter().all(|p| *p == 0.0),
            "pmf {pmf:?} is no probability distribution"
        );
        Ok(HittablePdf {
            origin,
            targets,
            choice: Choosing::Pmf(pmf),
            index: None,
        })
    }

    /// The point the directions start from.
    pub fn origin(&self) -> DVec3 {
        self.origin
    }

    /// The probability of choosing shape `i`.
    #[inline]
    #[doc(alias = "probability")]
    pub fn pmf(&self, i: usize) -> f64 {
        match self.choice {
            Choosing::Uniform => 1.0 / self.targets.len() as f64,
            Choosing::Table(s) => s.pmf(i),
            Choosing::Pmf(p) => p.get(i).copied().unwrap_or(0.0),
        }
    }

    /// `sum_{j != skip} p_j pdf_j(d)`: the density the other shapes give `direction`.
    #[inline]
    fn others_pdf(&self, skip: usize, direction: DVec3) -> f64 {
        let mut sum = 0.0;
        self.for_each_candidate(direction, |j| {
            if j != skip {
                let p = self.pmf(j);
                if p > 0.0 {
                    sum += p * self.targets[j].pdf(self.origin, direction);
                }
            }
        });
        sum
    }
}

impl<T: ShapeSampler> Pdf for HittablePdf<'_, T> {
    #[inline(always)]
    fn pdf(&self, direction: DVec3) -> f64 {
        if let [only] = self.targets {
            return only.pdf(self.origin, direction);
        }
        if let Choosing::Uniform = self.choice {
            // Uniform: `(1 / n) sum_i pdf_i`, one division rather than one a shape.
            let mut sum = 0.0;
            self.for_each_candidate(direction, |j| {
                sum += self.targets[j].pdf(self.origin, direction);
            });
            return sum / self.targets.len() as f64;
        }
        self.others_pdf(usize::MAX, direction)
    }

    #[inline(always)]
    fn sample(&self, u: DVec2) -> Option<DirectionSample> {
        if let [only] = self.targets {
            return only.sample(self.origin, u);
        }
        let (i, u0) = match self.choice {
            Choosing::Uniform => choose_uniform(self.targets.len(), u.x),
            Choosing::Table(s) => {
                let c = s.sample(u.x);
                (c.index, c.u_remapped)
            }
            Choosing::Pmf(p) => choose_by_pmf(p, u.x)?,
        };
        let s = self.targets[i].sample(self.origin, DVec2::new(u0, u.y))?;
        // The chosen shape's density comes with its sample; only the others are evaluated.
        let pdf = match self.choice {
            Choosing::Table(_) | Choosing::Pmf(_) => {
                self.pmf(i) * s.pdf + self.others_pdf(i, s.direction)
            }
            Choosing::Uniform => {
                let mut sum = s.pdf;
                self.for_each_candidate(s.direction, |j| {
                    if j != i {
                        sum += self.targets[j].pdf(self.origin, s.direction);
                    }
                });
                sum / self.targets.len() as f64
            }
        };
        // positive (the chosen part's density is) and finite (every density is): no check needed
        Some(DirectionSample {
            direction: s.direction,
            pdf,
        })
    }
}
// ANCHOR_END: hittable_pdf

impl<T: ShapeSampler + std::fmt::Debug> std::fmt::Debug for HittablePdf<'_, T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("HittablePdf")
            .field("origin", &self.origin)
            .field("targets", &self.targets)
            .field("choice", &self.choice)
            .field("indexed", &self.index.is_some())
            .finish()
    }
}

/// The most shapes a [`ShapeIndex`] names for one direction; past it the list is walked whole.
pub const MAX_CANDIDATES: usize = 32;

/// Which shapes of a list a direction from a point may meet: a superset of those whose density is
/// positive there, so that a long list's density `sum_i p_i pdf_i(d)` adds only their terms (the
/// others are 0). The terms are added in the list's order, so the sum is the same, to the bit, as
/// over the whole list. A bounding-volume hierarchy of the shapes is one (pbrt-v4's
/// `BVHLightSampler` keeps one over its lights, there to choose among them as well).
pub trait ShapeIndex {
    /// Writes into `out`, in increasing order, the indices of every shape that the ray from
    /// `origin` along `direction` may meet, and returns how many; `None` if they are more than
    /// [`MAX_CANDIDATES`] (then every shape is evaluated).
    fn candidates(
        &self,
        origin: DVec3,
        direction: DVec3,
        out: &mut [u32; MAX_CANDIDATES],
    ) -> Option<usize>;
}

impl<'a, T: ShapeSampler> HittablePdf<'a, T> {
    /// The same density, whose sums over the shapes add only those `index` says a direction may
    /// meet (`index` must be built over these `targets`): `O(log n)` rather than `O(n)` a direction
    /// for a long list, with the same result to the bit.
    #[inline]
    pub fn with_index(self, index: &'a dyn ShapeIndex) -> HittablePdf<'a, T> {
        HittablePdf {
            index: Some(index),
            ..self
        }
    }

    /// `f(j)` for every shape `j` whose density in `direction` may be positive, in increasing order:
    /// the index's candidates, or every shape.
    #[inline]
    fn for_each_candidate(&self, direction: DVec3, mut f: impl FnMut(usize)) {
        if let Some(index) = self.index {
            let mut out = [0u32; MAX_CANDIDATES];
            if let Some(k) = index.candidates(self.origin, direction, &mut out) {
                out[..k].iter().for_each(|&j| f(j as usize));
                return;
            }
        }
        (0..self.targets.len()).for_each(f);
    }
}
