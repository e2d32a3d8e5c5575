//! The statistics every exercise's checks share: a z-test against an exact answer, a chi-square
//! goodness-of-fit test that says where the samples went wrong, exact comparisons, the seeded
//! generators, and the record of the call in progress that a panic report names (its arguments,
//! and for a generator, how to rebuild it and what the call drew: [`calling`], [`Generator`]).
//!
//! Numbers in messages are printed as a reader would write them ([`num`], [`sig`], [`count`]): 0.25
//! and 19,000, not 2.5e-1 and 1.9e4; scientific notation only for the very small or very large.

use glam::DVec3;
use statrs::distribution::{ContinuousCDF, Normal};

mod call;
mod chi_square;
mod format;
mod rng;

#[cfg(test)]
pub(crate) use call::PUBLISHING_TEST;
pub use call::{
    Arg, List, call_in_progress, calling, calling_method, forget_call, publish_calls,
    published_call,
};
pub use chi_square::{
    Cells, ChiSquareError, Intervals, Region, SphereBins, chi_square, chi_square_p_value,
};
pub use format::{count, num, sig};
pub use rng::{Generator, RngState, SCRIPT_MAX, ScriptedRng, replay, seeded, uniform_direction};

/// What a check returns: `Ok` or the reason it failed, naming the exercise and the case.
pub type CheckResult = Result<(), String>;

/// The largest `f64` a uniform draw in [0, 1) can return: 1 - 2^-53.
pub const U_MAX: f64 = 1.0 - f64::EPSILON / 2.0;

/// The false-failure rate of every z-test.
pub const Z_FALSE_FAILURE: f64 = 1e-6;

/// The family-wise significance level of the chi-square tests of one run.
pub const CHI_SQUARE_ALPHA: f64 = 0.01;

/// How many chi-square tests expected to pass one test run makes (`cargo test -p rtl-exercises
/// --features solutions`: 7 in the checks of the reference solutions of the exercises to write, 2 in
/// those of the bug museum's fixes, 2 more checking the mixture checker on a consistent mixture, 2 in
/// this module's tests; the chi-square tests that the shipped stubs and bugs must fail are not
/// counted); the Sidak correction divides [`CHI_SQUARE_ALPHA`] among them. Update it with a new test.
pub const CHI_SQUARE_TESTS: u32 = 13;

/// The two-sided critical value of a z-test at [`Z_FALSE_FAILURE`] (about 4.89).
pub fn z_critical() -> f64 {
    let normal = Normal::standard();
    normal.inverse_cdf(1.0 - Z_FALSE_FAILURE / 2.0)
}

/// The per-test level of a chi-square test: 1 - (1 - alpha)^(1/m), Sidak-corrected over
/// [`CHI_SQUARE_TESTS`] tests.
pub fn sidak_alpha() -> f64 {
    1.0 - (1.0 - CHI_SQUARE_ALPHA).powf(1.0 / f64::from(CHI_SQUARE_TESTS))
}

/// Mean and standard error of the mean of `values` (Welford's running mean and variance).
pub fn mean_and_std_error(values: impl IntoIterator<Item = f64>) -> (f64, f64) {
    let (mut n, mut mean, mut m2) = (0.0_f64, 0.0_f64, 0.0_f64);
    for x in values {
        n += 1.0;
        let delta = x - mean;
        mean += delta / n;
        m2 += delta * (x - mean);
    }
    if n < 2.0 {
        return (mean, f64::INFINITY);
    }
    (mean, (m2 / (n - 1.0) / n).sqrt())
}

/// z-test of `estimate` against the exact `truth`, given the estimate's standard error. A standard
/// error of 0 (a zero-variance estimator) demands the truth to a relative `1e-12`.
///
/// ```
/// use rtl_exercises::check::z_test;
/// assert!(z_test("one standard error off", 0.51, 0.01, 0.5).is_ok());
/// assert!(z_test("ten standard errors off", 0.6, 0.01, 0.5).is_err());
/// ```
pub fn z_test(what: &str, estimate: f64, std_error: f64, truth: f64) -> CheckResult {
    if !estimate.is_finite() {
        return Err(format!(
            "{what}: the estimate is {}, expected about {}",
            num(estimate),
            sig(truth, 6)
        ));
    }
    if !(std_error >= 0.0 && std_error.is_finite()) {
        return Err(format!(
            "{what}: no usable standard error ({}): fewer than two values?",
            num(std_error)
        ));
    }
    if std_error == 0.0 {
        return close(what, estimate, truth, 1e-12);
    }
    let z = (estimate - truth) / std_error;
    if z.abs() < z_critical() {
        Ok(())
    } else {
        Err(format!(
            "{what}: estimate {} is {z:.1} standard errors ({}) from the exact {}",
            sig(estimate, 6),
            sig(std_error, 3),
            sig(truth, 6)
        ))
    }
}

/// z-test of the mean of `values` against `truth`, with the standard error measured from the values.
pub fn z_test_mean(what: &str, values: impl IntoIterator<Item = f64>, truth: f64) -> CheckResult {
    let (mean, se) = mean_and_std_error(values);
    z_test(what, mean, se, truth)
}

/// `got` equals `want` to a relative tolerance `rel` (absolute when `want` is 0).
pub fn close(what: &str, got: f64, want: f64, rel: f64) -> CheckResult {
    let scale = if want == 0.0 { 1.0 } else { want.abs() };
    if got.is_finite() && (got - want).abs() <= rel * scale {
        Ok(())
    } else if rel == 0.0 {
        Err(format!(
            "{what}: got {}, expected exactly {}",
            num(got),
            num(want)
        ))
    } else {
        Err(format!(
            "{what}: got {}, expected {} (to a relative {})",
            num(got),
            num(want),
            num(rel)
        ))
    }
}

/// `v` has unit length to 1e-12 and finite components.
pub fn unit(what: &str, v: DVec3) -> CheckResult {
    if v.is_finite() && (v.length() - 1.0).abs() <= 1e-12 {
        Ok(())
    } else {
        Err(format!(
            "{what}: {v} is not a unit vector (length {})",
            v.length()
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn z_critical_is_the_two_sided_1e_minus_6_quantile() {
        assert!((z_critical() - 4.8916).abs() < 1e-3);
    }

    #[test]
    fn z_test_rejects_a_biased_estimate_and_demands_exactness_at_zero_error() {
        z_test("ok", 1.0 + 4.0 * 0.01, 0.01, 1.0).unwrap();
        assert!(z_test("biased", 1.0 + 5.0 * 0.01, 0.01, 1.0).is_err());
        assert!(z_test("exact", 1.0 + 1e-9, 0.0, 1.0).is_err());
        assert!(z_test("nan", f64::NAN, 0.1, 1.0).is_err());
        // No data, or one value, has no standard error: never a pass.
        assert!(z_test_mean("empty", [], 0.0).is_err());
        assert!(z_test_mean("one value", [0.5], 0.5).is_err());
    }
}
