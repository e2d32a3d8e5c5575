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
/// Rounding alone moves even a zero-variance estimate (a perfect importance sampler) a few ulp from
/// `exact`, and its standard error is then 0 or tiny, so an estimate within 4 ulp of `exact` always
/// passes. Otherwise a single unit, a standard error of 0, a non-finite estimate, or an `alpha` outside
/// `(0, 1)` fails.
///
/// ```
/// use rtl_mc::{Interval, check::mean_test, plain};
/// use rand::SeedableRng;
/// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(3);
/// let est = plain(|x| x * x, Interval::new(0.0, 2.0)?, 10_000, &mut rng)?;
/// assert!(mean_test(&est, 8.0 / 3.0, 1e-6).passed);
/// assert!(!mean_test(&est, 3.0, 1e-6).passed);
/// Ok::<(), rtl_mc::McError>(()) // what `?` above returns into
/// ```
pub fn mean_test(estimate: &Estimate, exact: f64, alpha: f64) -> MeanTest {
    let units = estimate.stats.count();
    let value = estimate.value();
    let critical = if !(alpha > 0.0 && alpha < 1.0) {
        f64::NAN // no false-failure rate outside (0, 1): nothing passes but an exact estimate
    } else if units >= 1000 {
        Normal::standard().inverse_cdf(1.0 - alpha / 2.0)
    } else if units >= 2 {
        student_t_quantile(1.0 - alpha / 2.0, units - 1)
    } else {
        0.0
    };
    let within_rounding = (value - exact).abs() <= 4.0 * f64::EPSILON * exact.abs();
    let score = match estimate.std_error() {
        Some(se) if se > 0.0 => (value - exact) / se,
        _ if within_rounding => 0.0,
        _ => f64::NAN,
    };
    MeanTest {
        score,
        critical,
        passed: value.is_finite() && (within_rounding || score.abs() < critical),
    }
}
// ANCHOR_END: mean_test
