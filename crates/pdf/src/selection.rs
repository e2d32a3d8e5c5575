//! Choosing one of several parts (lights, or the components of a mixture) with fixed probabilities.

use std::fmt;

/// Why a table of selection weights was refused.
#[derive(Clone, Debug, PartialEq)]
pub enum SelectionError {
    /// No parts to choose from.
    Empty,
    /// Weight `index` is negative, infinite or NaN.
    BadWeight { index: usize, weight: f64 },
    /// Every weight is 0.
    AllZero,
    /// The table has `table` entries but there are `parts` parts.
    LengthMismatch { table: usize, parts: usize },
}

impl fmt::Display for SelectionError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SelectionError::Empty => {
                write!(f, "selection: there is nothing to choose from (empty list)")
            }
            SelectionError::BadWeight { index, weight } => write!(
                f,
                "selection: weight {index} is {weight}; weights must be finite and >= 0"
            ),
            SelectionError::AllZero => write!(f, "selection: every weight is 0"),
            SelectionError::LengthMismatch { table, parts } => write!(
                f,
                "selection: the table has {table} weights but there are {parts} parts"
            ),
        }
    }
}

impl std::error::Error for SelectionError {}

// ANCHOR: selection
/// Fixed probabilities `p_i = w_i / sum w` of choosing part `i`, built once (e.g. per scene, from the
/// lights' powers) and borrowed by the per-sample code, which then allocates nothing.
/// Choosing is a binary search of the cumulative sums, `O(log n)`; parts of weight 0 are never chosen.
#[derive(Clone, Debug, PartialEq)]
pub struct Selection {
    probabilities: Vec<f64>,
    /// `cdf[i] = p_0 + ... + p_i`, the last forced to exactly 1.
    cdf: Vec<f64>,
    /// the last part with a positive probability
    last: usize,
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
        let total: f64 = weights.iter().sum();
        if !(total > 0.0 && total.is_finite()) {
            return Err(SelectionError::AllZero);
        }
        let probabilities: Vec<f64> = weights.iter().map(|w| w / total).collect();
        let mut cdf = Vec::with_capacity(weights.len());
        let mut acc = 0.0;
        for p in &probabilities {
            acc += p;
            cdf.push(acc);
        }
        // The last part with a positive weight ends the table at exactly 1.
        let last = probabilities.iter().rposition(|&p| p > 0.0).unwrap_or(0);
        for c in &mut cdf[last..] {
            *c = 1.0;
        }
        Ok(Selection {
            probabilities,
            cdf,
            last,
        })
    }

    /// The number of parts.
    pub fn len(&self) -> usize {
        self.probabilities.len()
    }

    /// Never true: a selection has at least one part.
    pub fn is_empty(&self) -> bool {
        self.probabilities.is_empty()
    }

    /// The probability of choosing part `i`.
    #[inline]
    pub fn probability(&self, i: usize) -> f64 {
        self.probabilities[i]
    }

    /// All the probabilities, summing to 1.
    pub fn probabilities(&self) -> &[f64] {
        &self.probabilities
    }

    /// The part chosen by `u` in `[0, 1)`: the first `i` with `u < cdf[i]`, which has `p_i > 0`.
    #[inline]
    pub fn choose(&self, u: f64) -> usize {
        let i = self.cdf.partition_point(|&c| c <= u);
        i.min(self.last) // only reached for u >= 1, outside the contract
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
            let i = s.choose(u);
            assert!(i == 1 || i == 3, "u = {u} chose {i}");
        }
        assert_eq!(s.choose(0.1), 1);
        assert_eq!(s.choose(0.3), 3);
        assert_eq!(s.probabilities(), &[0.0, 0.25, 0.0, 0.75, 0.0]);
    }
}
