//! Pearson's chi-square goodness-of-fit test: do the counts a sampler produced in a set of cells
//! match the counts its density predicts? (The check pbrt-v4 and Mitsuba 3 run on every warp.)
//!
//! The statistics here are independent of what is sampled, so every crate reuses them:
//!
//! 1. Bin the samples into cells and count them: `observed[i]` (see [`histogram`]).
//! 2. Integrate the density over each cell and multiply by the number of samples: `expected[i]`
//!    (see [`expected_counts`]). Decide which cells lie outside the support on paper and give them
//!    exactly 0.
//! 3. [`chi_square`] pools the cells expected to hold fewer than [`MIN_EXPECTED`] samples into one
//!    (smallest first, until the pool expects at least that many), sums
//!    `(observed - expected)² / expected` over the remaining cells, and takes the p-value from the
//!    chi-square distribution with `cells - 1` degrees of freedom (statrs `ChiSquared::sf`).
//!    A sample in a cell of expected count 0 is an error: that sampler is wrong, whatever the
//!    statistic says.
//! 4. Reject when `p < alpha`, with `alpha` Šidák-corrected for the number of tests in the run:
//!    [`sidak_alpha`]`(0.01, tests)`, so the whole run fails falsely with probability 0.01.
//!
//! ```
//! use rtl_sampling::chi_square::{chi_square, sidak_alpha};
//! let observed = [27.0, 22.0, 26.0, 25.0];
//! let expected = [25.0; 4];
//! let result = chi_square(&observed, &expected).unwrap();
//! assert_eq!(result.dof, 3);
//! assert!((result.statistic - 0.56).abs() < 1e-12);
//! assert!(result.passes(sidak_alpha(0.01, 1)));
//! ```

use statrs::distribution::{ChiSquared, ContinuousCDF};

/// Cells expected to hold fewer samples than this are pooled.
pub const MIN_EXPECTED: f64 = 5.0;

/// The outcome of a chi-square test that could be carried out.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChiSquare {
    /// `Σ (observed - expected)² / expected` over the cells after pooling.
    pub statistic: f64,
    /// Degrees of freedom: cells after pooling, minus 1.
    pub dof: usize,
    /// The probability of a statistic at least this large if the sampler is right.
    pub p_value: f64,
    /// How many of the input cells went into the pool.
    pub pooled: usize,
}

impl ChiSquare {
    /// True when the test does not reject at significance `alpha` (`p_value >= alpha`).
    pub fn passes(&self, alpha: f64) -> bool {
        self.p_value >= alpha
    }
}

/// Why no p-value could be computed; [`SampleOutsideSupport`](Self::SampleOutsideSupport) is a
/// rejection of the sampler, the others are misuse.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ChiSquareError {
    #[error("observed has {observed} cells but expected has {expected}")]
    LengthMismatch { observed: usize, expected: usize },
    #[error("cell {cell}: expected count {value} is not finite and >= 0")]
    BadExpected { cell: usize, value: f64 },
    #[error("cell {cell}: observed count {value} is not finite and >= 0")]
    BadObserved { cell: usize, value: f64 },
    #[error("cell {cell} expects no samples but holds {observed}: the sampler leaves its support")]
    SampleOutsideSupport { cell: usize, observed: f64 },
    #[error("only {cells} cell(s) after pooling: no degrees of freedom")]
    TooFewCells { cells: usize },
}

// ANCHOR: chi_square
/// Pearson's test of `observed` against `expected` counts (see the module documentation).
pub fn chi_square(observed: &[f64], expected: &[f64]) -> Result<ChiSquare, ChiSquareError> {
    if observed.len() != expected.len() {
        return Err(ChiSquareError::LengthMismatch {
            observed: observed.len(),
            expected: expected.len(),
        });
    }
    for (cell, (&o, &e)) in observed.iter().zip(expected).enumerate() {
        if !(e.is_finite() && e >= 0.0) {
            return Err(ChiSquareError::BadExpected { cell, value: e });
        }
        if !(o.is_finite() && o >= 0.0) {
            return Err(ChiSquareError::BadObserved { cell, value: o });
        }
        if e == 0.0 && o > 0.0 {
            return Err(ChiSquareError::SampleOutsideSupport { cell, observed: o });
        }
    }
    // Cells in the support, smallest expectation first.
    let mut order: Vec<usize> = (0..expected.len()).filter(|&i| expected[i] > 0.0).collect();
    order.sort_by(|&i, &j| expected[i].total_cmp(&expected[j]));
    let (mut statistic, mut cells, mut pooled) = (0.0, 0usize, 0usize);
    let (mut pool_observed, mut pool_expected) = (0.0, 0.0);
    for i in order {
        let (o, e) = (observed[i], expected[i]);
        if e < MIN_EXPECTED || (pool_expected > 0.0 && pool_expected < MIN_EXPECTED) {
            pool_observed += o;
            pool_expected += e;
            pooled += 1;
        } else {
            statistic += (o - e) * (o - e) / e;
            cells += 1;
        }
    }
    if pooled > 0 {
        statistic += (pool_observed - pool_expected).powi(2) / pool_expected;
        cells += 1;
    }
    if cells < 2 {
        return Err(ChiSquareError::TooFewCells { cells });
    }
    let dof = cells - 1;
    let p_value = ChiSquared::new(dof as f64)
        .expect("dof >= 1 is a valid chi-square parameter")
        .sf(statistic);
    Ok(ChiSquare {
        statistic,
        dof,
        p_value,
        pooled,
    })
}
// ANCHOR_END: chi_square

/// The per-test significance that keeps the chance of any false rejection among `tests`
/// independent tests at `alpha`: `1 - (1 - alpha)^(1/tests)` (Šidák).
pub fn sidak_alpha(alpha: f64, tests: usize) -> f64 {
    1.0 - (1.0 - alpha).powf(1.0 / tests.max(1) as f64)
}

/// Counts samples in the cells between consecutive `edges` (increasing); a sample outside
/// `[edges[0], edges[last]]`, or NaN, is counted in `outside` and should fail the test.
pub fn histogram(samples: impl IntoIterator<Item = f64>, edges: &[f64]) -> (Vec<f64>, u64) {
    let cells = edges.len().saturating_sub(1);
    let mut counts = vec![0.0; cells];
    let mut outside = 0;
    for x in samples {
        if cells == 0 || !(edges[0]..=edges[cells]).contains(&x) {
            outside += 1;
            continue;
        }
        let i = edges[1..cells].partition_point(|&e| e <= x);
        counts[i] += 1.0;
    }
    (counts, outside)
}

/// `n ∫ pdf` over each cell between consecutive `edges`, by Gauss-Legendre quadrature on `pieces`
/// sub-intervals per cell (use many when the pdf jumps inside cells).
pub fn expected_counts(pdf: impl Fn(f64) -> f64, edges: &[f64], n: f64, pieces: usize) -> Vec<f64> {
    edges
        .windows(2)
        .map(|e| n * crate::integrate(&pdf, e[0], e[1], pieces))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_cells_are_pooled_smallest_first() {
        // Cells expecting 1, 2 and 3 pool into one expecting 6 (which reaches 5 at the third).
        let expected = [1.0, 2.0, 3.0, 50.0, 44.0];
        let observed = [0.0, 3.0, 3.0, 50.0, 44.0];
        let r = chi_square(&observed, &expected).unwrap();
        assert_eq!(r.pooled, 3);
        assert_eq!(r.dof, 2);
        assert_eq!(r.statistic, 0.0);
        assert_eq!(r.p_value, 1.0);
    }

    #[test]
    fn a_sample_where_none_is_expected_is_rejected() {
        let r = chi_square(&[10.0, 1.0, 10.0], &[10.5, 0.0, 10.5]);
        assert!(matches!(
            r,
            Err(ChiSquareError::SampleOutsideSupport { cell: 1, .. })
        ));
        // Empty cells outside the support are simply skipped.
        let r = chi_square(&[10.0, 0.0, 11.0], &[10.5, 0.0, 10.5]).unwrap();
        assert_eq!(r.dof, 1);
    }

    #[test]
    fn misuse_is_reported() {
        assert!(matches!(
            chi_square(&[1.0], &[1.0, 2.0]),
            Err(ChiSquareError::LengthMismatch { .. })
        ));
        assert!(matches!(
            chi_square(&[1.0, 2.0], &[f64::NAN, 2.0]),
            Err(ChiSquareError::BadExpected { cell: 0, .. })
        ));
        assert!(matches!(
            chi_square(&[3.0, 3.0], &[3.0, 3.0]),
            Err(ChiSquareError::TooFewCells { cells: 1 })
        ));
    }

    #[test]
    fn sidak_alpha_for_one_test_is_alpha() {
        assert!((sidak_alpha(0.01, 1) - 0.01).abs() < 1e-15);
        let a = sidak_alpha(0.01, 10);
        assert!((1.0 - (1.0 - a).powi(10) - 0.01).abs() < 1e-12);
    }

    #[test]
    fn a_gross_mismatch_has_a_tiny_p_value() {
        let r = chi_square(&[100.0, 0.0], &[50.0, 50.0]).unwrap();
        assert!(r.statistic == 100.0 && r.p_value < 1e-20);
    }
}
