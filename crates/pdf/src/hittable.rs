//! `HittablePdf`: directions towards one or more targets, seen from a point (book 3, chapters 9 and 12).

use crate::selection::{Selection, SelectionError};
use crate::{Pdf, Target};
use glam::DVec3;
use rand::Rng;

// ANCHOR: hittable_pdf
/// Directions from `origin` towards a list of targets: choose target `i` with probability `p_i` (uniform,
/// or from a precomputed [`Selection`], e.g. by power), then sample towards it. The density of a
/// direction is the total over every target it could have come from:
/// `value(d) = sum_i p_i target_i.pdf_value(origin, d)`.
///
/// Borrows the targets (and the table), so building one per scattering event allocates nothing.
///
/// ```
/// use glam::DVec3;
/// use rtl_pdf::{HittablePdf, Pdf, SphereTarget};
/// let lights = [SphereTarget::new(DVec3::new(0.0, 0.0, -10.0), 1.0)];
/// let pdf = HittablePdf::new(DVec3::ZERO, &lights).expect("at least one light");
/// assert!(pdf.value(DVec3::new(0.0, 0.0, -1.0)) > 0.0); // towards the centre
/// assert_eq!(pdf.value(DVec3::new(0.0, 0.0, 1.0)), 0.0); // away from it
/// let none: [SphereTarget; 0] = [];
/// assert!(HittablePdf::new(DVec3::ZERO, &none).is_none());
/// ```
#[derive(Clone, Copy, Debug)]
pub struct HittablePdf<'a, T: Target> {
    origin: DVec3,
    targets: &'a [T],
    /// `None`: uniform, `1 / n` each.
    selection: Option<&'a Selection>,
}

impl<'a, T: Target> HittablePdf<'a, T> {
    /// Each target with probability `1 / n`; `None` for an empty list (there is nothing to sample).
    #[inline]
    pub fn new(origin: DVec3, targets: &'a [T]) -> Option<HittablePdf<'a, T>> {
        (!targets.is_empty()).then_some(HittablePdf {
            origin,
            targets,
            selection: None,
        })
    }

    /// Targets chosen with the probabilities of `selection`, which must have one entry per target.
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
            selection: Some(selection),
        })
    }

    /// The point the directions start from.
    pub fn origin(&self) -> DVec3 {
        self.origin
    }

    /// The probability of choosing target `i`.
    #[inline]
    pub fn probability(&self, i: usize) -> f64 {
        match self.selection {
            Some(s) => s.probability(i),
            None => 1.0 / self.targets.len() as f64,
        }
    }
}

impl<T: Target> Pdf for HittablePdf<'_, T> {
    #[inline]
    fn value(&self, direction: DVec3) -> f64 {
        if let [only] = self.targets {
            return only.pdf_value(self.origin, direction);
        }
        if self.selection.is_none() {
            // Uniform: `(1 / n) sum_i pdf_i`, one division rather than one a target.
            let sum: f64 = self
                .targets
                .iter()
                .map(|t| t.pdf_value(self.origin, direction))
                .sum();
            return sum / self.targets.len() as f64;
        }
        self.targets
            .iter()
            .enumerate()
            .map(|(i, t)| {
                let p = self.probability(i);
                if p > 0.0 {
                    p * t.pdf_value(self.origin, direction)
                } else {
                    0.0
                }
            })
            .sum()
    }

    #[inline]
    fn generate<R: Rng + ?Sized>(&self, rng: &mut R) -> DVec3 {
        let i = match self.selection {
            Some(s) => s.choose(rng.random::<f64>()),
            None if self.targets.len() == 1 => 0,
            // `floor(n u)` for `u` uniform in [0, 1) (the `min` guards rounding up to `n`): uniform on
            // 0..n to within 2^-53 relative, without `random_range`'s rejection loop.
            None => {
                let n = self.targets.len();
                ((rng.random::<f64>() * n as f64) as usize).min(n - 1)
            }
        };
        self.targets[i].random(self.origin, rng)
    }
}
// ANCHOR_END: hittable_pdf
