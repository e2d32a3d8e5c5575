//! Is an estimate consistent with the exact value? The test every estimator's tests use.

use crate::{Estimate, student_t_quantile};
use statrs::distribution::{ContinuousCDF, Normal};

/// The verdict of [`mean_test`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeanTest {
    /// `(estimate - exact) / std_error`, or 0 when the estimate is exact.
    pub score: f64,
    /// The largest `|score|` accepted.
    pub critical: f64,
    /// Whether the estimate passed.
    pub passed: bool,
}

// ANCHOR: mean_test
/// Tests `estimate` against the `exact` integral at a false-failure rate `alpha` (we use 1e-6): passes
/// when `|estimate - exact| / std_error` is below the two-sided critical value. With many units that
/// score is normal (a z-test, critical value 4.89 at 1e-6); with few units (the replicates of a
/// stratified or quasi-Monte Carlo estimate) it follows Student's t with `units - 1` degrees of freedom,
/// and we use that quantile instead.
///
/// A standard error of exactly 0 (every unit gave the same value, as with a perfect importance sampler)
/// leaves nothing to scale by: then the estimate must equal `exact` to within 4 ulp. A single unit, or a
/// non-finite estimate, fails.
///
/// ```
/// use rtl_mc::{Interval, check::mean_test, plain};
/// use rand::SeedableRng;
/// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(3);
/// let est = plain(|x| x * x, Interval::new(0.0, 2.0)?, 10_000, &mut rng)?;
/// assert!(mean_test(&est, 8.0 / 3.0, 1e-6).passed);
/// assert!(!mean_test(&est, 3.0, 1e-6).passed);
/// # Ok::<(), rtl_mc::McError>(())
/// ```
pub fn mean_test(estimate: &Estimate, exact: f64, alpha: f64) -> MeanTest {
    let units = estimate.stats.count();
    let value = estimate.value();
    let critical = if units >= 1000 {
        Normal::standard().inverse_cdf(1.0 - alpha / 2.0)
    } else if units >= 2 {
        student_t_quantile(1.0 - alpha / 2.0, units - 1)
    } else {
        0.0
    };
    match estimate.std_error() {
        Some(se) if se > 0.0 && value.is_finite() => {
            let score = (value - exact) / se;
            MeanTest {
                score,
                critical,
                passed: score.abs() < critical,
            }
        }
        Some(_) if value.is_finite() => MeanTest {
            score: 0.0,
            critical,
            passed: (value - exact).abs() <= 4.0 * f64::EPSILON * exact.abs(),
        },
        _ => MeanTest {
            score: f64::NAN,
            critical,
            passed: false,
        },
    }
}
// ANCHOR_END: mean_test
