//! Choosing one of several parts (lights, or the components of a mixture) with fixed probabilities.

use rtl_sampling::{ONE_MINUS_EPSILON, SamplingError, TabulatedCdf};

/// Why a table of selection weights was refused.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SelectionError {
    /// No parts to choose from.
    #[error("selection: there is nothing to choose from (empty list)")]
    Empty,
    /// Weight `index` is negative, infinite or NaN.
    #[error("selection: weight {index} is {weight}; weights must be finite and >= 0")]
    BadWeight { index: usize, weight: f64 },
    /// Every weight is 0.
    #[error("selection: every weight is 0")]
    AllZero,
    /// The table has `table` entries but there are `parts` parts.
    #[error("selection: the table has {table} weights but there are {parts} parts")]
    LengthMismatch { table: usize, parts: usize },
    /// The weights cannot be tabulated (a weight so small beside the largest that its probability
    /// underflows, say).
    #[error("selection: {0}")]
    Table(SamplingError),
}

/// One discrete choice: the part, its probability, and the rest of the uniform number that chose it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Choice {
    /// The part chosen.
    pub index: usize,
    /// Its probability (`> 0`).
    pub pmf: f64,
    /// `(u - F_i) / p_i`: uniform on `[0, 1)` again given the choice, to be handed on (so the choice
    /// and what follows come from one stratified number).
    pub u_remapped: f64,
}

/// `x` in `[0, 1)`: clamped to `[0, 1 - 2^-53]`, and a NaN to 0 (which `f64::clamp` would keep).
#[inline]
#[allow(clippy::manual_clamp)]
pub(crate) fn below_one(x: f64) -> f64 {
    x.max(0.0).min(ONE_MINUS_EPSILON)
}

/// `(u - lo) / p`, the leftover of `u` in `[lo, lo + p)`, kept below 1.
#[inline]
pub(crate) fn remap(u: f64, lo: f64, p: f64) -> f64 {
    below_one((u - lo) / p)
}

/// The uniform choice among `n >= 1` parts by `u` in `[0, 1)`: `i = floor(n u)` (kept below `n`),
/// and the rest `n u - i` in `[0, 1)` for a sample of the part (a NaN chooses part 0 with rest 0).
#[inline]
pub fn choose_uniform(n: usize, u: f64) -> (usize, f64) {
    let scaled = u * n as f64;
    let i = (scaled as usize).min(n - 1);
    (i, below_one(scaled - i as f64))
}

/// The part chosen by `u` from probabilities `pmf` (`>= 0`, summing to 1) by a linear scan: the first
/// `i` of `p_i > 0` with `u < F_{i+1}` (`F` the running sums), and the rest of `u` remapped to
/// `[0, 1)`. Should rounding leave the sum below `u`, the last part of positive probability; `None`
/// only if every `p_i` is 0.
#[inline]
pub(crate) fn choose_by_pmf(pmf: &[f64], u: f64) -> Option<(usize, f64)> {
    let u = below_one(u);
    let mut lo = 0.0;
    let mut last = None;
    for (i, &p) in pmf.iter().enumerate() {
        if p > 0.0 {
            if u < lo + p {
                return Some((i, remap(u, lo, p)));
            }
            last = Some((i, lo, p));
            lo += p;
        }
    }
    last.map(|(i, lo, p)| (i, remap(u, lo, p)))
}

// ANCHOR: selection
/// Fixed probabilities `p_i = w_i / sum w` of choosing part `i`, built once (e.g. per scene, from the
/// lights' powers) and borrowed by the per-sample code, which then allocates nothing.
///
/// Built on rtl-sampling's [`TabulatedCdf`] over `[0, n)` with one bin per part: choosing is its
/// binary search of the cumulative sums, `O(log n)`, which never returns a part of weight 0. The
/// inversion keeps each part's share of `[0, 1)` in one piece, so the remapped rest of `u` of a
/// stratified `u` is stratified again for every part (an alias table would cut shares into pieces).
#[derive(Clone, Debug, PartialEq)]
pub struct Selection {
    cdf: TabulatedCdf,
}

impl Selection {
    /// Each of `n` parts with probability `1 / n`.
    pub fn uniform(n: usize) -> Result<Selection, SelectionError> {
        Selection::from_weights(&vec![1.0; n])
    }

    /// Probabilities proportional to `weights`, which must be finite, `>= 0`, and not all 0.
    pub fn from_weights(weights: &[f64]) -> Result<Selection, SelectionError> {
        if weights.is_empty() {
            return Err(SelectionError::Empty);
        }
        if let Some((index, &weight)) = weights
            .iter()
            .enumerate()
            .find(|(_, w)| !(w.is_finite() && **w >= 0.0))
        {
            return Err(SelectionError::BadWeight { index, weight });
        }
        // The table scales the weights by the largest before summing, so weights whose sum overflows
        // (`[1e308; 3]`) are chosen in proportion all the same.
        let cdf =
            TabulatedCdf::from_weights(0.0, weights.len() as f64, weights).map_err(
                |e| match e {
                    SamplingError::BadWeight { bin, value } => SelectionError::BadWeight {
                        index: bin,
                        weight: value,
                    },
                    SamplingError::AllZero { .. } => SelectionError::AllZero,
                    other => SelectionError::Table(other),
                },
            )?;
        Ok(Selection { cdf })
    }

    /// The number of parts.
    pub fn len(&self) -> usize {
        self.cdf.len()
    }

    /// Never true: a selection has at least one part.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The probability of choosing part `i` (0 outside the table).
    #[inline]
    #[doc(alias = "probability")]
    pub fn pmf(&self, i: usize) -> f64 {
        if i < self.len() {
            self.cdf.bin_probability(i)
        } else {
            0.0
        }
    }

    /// The part chosen by `u` in `[0, 1)`, the first `i` with `u < F_{i+1}` (which has `p_i > 0`),
    /// with its probability and the remapped rest of `u`.
    #[inline]
    #[doc(alias = "choose")]
    pub fn sample(&self, u: f64) -> Choice {
        let u = below_one(u);
        let index = self.cdf.bin(u);
        let lo = self.cdf.cdf_values()[index];
        let pmf = self.cdf.bin_probability(index);
        Choice {
            index,
            pmf,
            u_remapped: remap(u, lo, pmf),
        }
    }

    /// The `u` that chooses part `i` (`i < len()`) and leaves `u_remapped`: `F_i + u_remapped p_i`,
    /// the inverse of [`Selection::sample`].
    pub fn invert(&self, i: usize, u_remapped: f64) -> f64 {
        let lo = self.cdf.cdf_values()[i];
        (lo + u_remapped * self.pmf(i)).min(ONE_MINUS_EPSILON)
    }
}
// ANCHOR_END: selection

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_weights_are_refused_by_name() {
        assert_eq!(Selection::from_weights(&[]), Err(SelectionError::Empty));
        assert_eq!(
            Selection::from_weights(&[0.0, 0.0]),
            Err(SelectionError::AllZero)
        );
        assert_eq!(
            Selection::from_weights(&[1.0, -1.0]),
            Err(SelectionError::BadWeight {
                index: 1,
                weight: -1.0
            })
        );
        assert!(matches!(
            Selection::from_weights(&[f64::NAN]),
            Err(SelectionError::BadWeight { index: 0, .. })
        ));
        assert!(Selection::from_weights(&[1.0, f64::INFINITY]).is_err());
        assert!(format!("{}", SelectionError::Empty).contains("empty"));
    }

    #[test]
    fn a_pmf_given_per_call_is_chosen_by_its_running_sums() {
        let pmf = [0.0, 0.25, 0.0, 0.75];
        assert_eq!(choose_by_pmf(&pmf, 0.0), Some((1, 0.0)));
        assert_eq!(choose_by_pmf(&pmf, 0.125), Some((1, 0.5)));
        assert_eq!(choose_by_pmf(&pmf, 0.25), Some((3, 0.0)));
        assert_eq!(choose_by_pmf(&pmf, 0.625), Some((3, 0.5)));
        // never a part of probability 0, the rest of u below 1, also at and past the end
        for u in [1.0 - f64::EPSILON / 2.0, 1.0, 2.0] {
            let (i, rest) = choose_by_pmf(&pmf, u).unwrap();
            assert!(i == 3 && rest < 1.0, "u = {u}: {i} {rest}");
        }
        // a sum that rounding leaves short of 1 still chooses a part of positive probability
        let (i, rest) = choose_by_pmf(&[0.5, 0.5 - 1e-12, 0.0], 1.0 - 1e-15).unwrap();
        assert!(i == 1 && rest < 1.0);
        assert_eq!(choose_by_pmf(&[0.0, 0.0], 0.5), None);
        // the same choice as the tabulated selection of the same probabilities
        let table = Selection::from_weights(&pmf).unwrap();
        for k in 0..1000 {
            let u = (k as f64 + 0.5) / 1000.0;
            let c = table.sample(u);
            let (i, rest) = choose_by_pmf(&pmf, u).unwrap();
            assert_eq!(i, c.index, "u = {u}");
            assert!((rest - c.u_remapped).abs() < 1e-12, "u = {u}");
        }
    }

    #[test]
    fn weights_whose_sum_overflows_are_chosen_in_proportion() {
        // 3e308 is past f64::MAX: summing first would call these "all zero".
        let s = Selection::from_weights(&[1e308, 1e308, 1e308]).unwrap();
        for i in 0..3 {
            assert!(
                (s.pmf(i) - 1.0 / 3.0).abs() < 1e-15,
                "pmf({i}) = {}",
                s.pmf(i)
            );
        }
        let s = Selection::from_weights(&[f64::MAX, f64::MAX / 2.0]).unwrap();
        assert!((s.pmf(0) - 2.0 / 3.0).abs() < 1e-15);
    }

    #[test]
    fn zero_weights_are_never_chosen_and_indices_stay_in_range() {
        let s = Selection::from_weights(&[0.0, 1.0, 0.0, 3.0, 0.0]).unwrap();
        for u in [
            0.0,
            1e-300,
            0.25 - 1e-17,
            0.25,
            0.5,
            1.0 - f64::EPSILON / 2.0,
            1.0,
        ] {
            let i = s.sample(u).index;
            assert!(i == 1 || i == 3, "u = {u} chose {i}");
        }
        assert_eq!(s.sample(0.1).index, 1);
        assert_eq!(s.sample(0.3).index, 3);
        let p: Vec<f64> = (0..5).map(|i| s.pmf(i)).collect();
        assert_eq!(p, [0.0, 0.25, 0.0, 0.75, 0.0]);
        // the rest of u is handed on, and inverting gives u back
        let c = s.sample(0.25 + 0.75 * 0.5);
        assert_eq!((c.index, c.pmf, c.u_remapped), (3, 0.75, 0.5));
        assert_eq!(s.invert(3, 0.5), 0.625);
    }
}
