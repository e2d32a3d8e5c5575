//! # Chapter 3, Inverse Transform Sampling, "Choosing our samples": sample x/2 and 3x^2/8 on [0, 2]
//!
//! The checks of the exercise `crates/exercises/exercises/ch03_inverse_x_sq.rs`, which states the
//! task.
//!
//! The check: exact values x = P^-1(P(x)) at x = 0, 1/2, 1; a value just below 2 at u = 1 - 2^-53;
//! monotone in u; and a chi-square test of 1e5 samples in 40 equal bins of [0, 2] against
//! n (P(b) - P(a)).

use crate::check::{self, Arg, CheckResult, Intervals, U_MAX};
use rand::Rng;

/// Exact values, range and monotonicity of a sampler of the density with CDF `cdf`, and a chi-square
/// test of 1e5 samples in 40 bins of [0, 2].
pub fn check_sampler(
    name: &'static str,
    sample: impl Fn(f64) -> f64,
    cdf: impl Fn(f64) -> f64,
) -> CheckResult {
    let sample = |u: f64| check::calling(name, &[("u", Arg::Real(u))], || sample(u));
    // Exact values: P^-1(P(x)) = x at x = 0, 1/2, 1 (P(x) is dyadic there, so u is exact).
    for x in [0.0, 0.5, 1.0] {
        let u = cdf(x);
        let what = format!("{name}(u = P({x}) = {})", check::num(u));
        check::close(&what, sample(u), x, 1e-15)?;
    }
    let top = sample(U_MAX);
    if !(top.is_finite() && (1.99..=2.0).contains(&top)) {
        return Err(format!(
            "{name}(u = 1 - 2^-53) = {}, expected just below 2",
            check::num(top)
        ));
    }
    let mut last = sample(0.0);
    for i in 1..=1000 {
        let u = i as f64 / 1001.0;
        let x = sample(u);
        if x.is_nan() || x < last {
            return Err(format!(
                "{name} is not increasing in u: {name}(u = {}) = {} after {}",
                check::num(u),
                check::num(x),
                check::num(last)
            ));
        }
        last = x;
    }
    let (n, bins) = (100_000usize, 40usize);
    let mut rng = check::seeded(30);
    let mut observed = vec![0u64; bins];
    for _ in 0..n {
        let x = sample(rng.random());
        if !(0.0..=2.0).contains(&x) {
            return Err(format!("{name} returned {}, outside [0, 2]", check::num(x)));
        }
        observed[((x / 2.0 * bins as f64) as usize).min(bins - 1)] += 1;
    }
    let expected: Vec<f64> = (0..bins)
        .map(|i| {
            let (a, b) = (
                2.0 * i as f64 / bins as f64,
                2.0 * (i + 1) as f64 / bins as f64,
            );
            n as f64 * (cdf(b) - cdf(a))
        })
        .collect();
    check::chi_square(
        name,
        &observed,
        &expected,
        &Intervals::equal("x", 0.0, 2.0, bins),
    )
}

/// [`check_sampler`] for a sampler of x/2.
pub fn check_linear(sample: impl Fn(f64) -> f64) -> CheckResult {
    check_sampler("sample_linear", sample, |x| x * x / 4.0)
}

/// [`check_sampler`] for a sampler of 3x^2/8.
pub fn check_quadratic(sample: impl Fn(f64) -> f64) -> CheckResult {
    check_sampler("sample_quadratic", sample, |x| x * x * x / 8.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checks_reject_wrong_inverses() {
        // Wrong: sqrt(2u) inverts x^2/2, a density on [0, sqrt 2].
        assert!(check_linear(|u| (2.0 * u).sqrt()).is_err());
        // Wrong: 2u is uniform on [0, 2]; passes the end points, fails the exact values and the fit.
        assert!(check_linear(|u| 2.0 * u).is_err());
        // Wrong: 2 sqrt(u) is the linear sampler, not the quadratic one.
        assert!(check_quadratic(|u| 2.0 * u.sqrt()).is_err());
        // Wrong: exact at u = 0, 1/64, 1/8 but not following the density elsewhere.
        let wiggly =
            |u: f64| 2.0 * u.cbrt() + 0.05 * (8.0 * std::f64::consts::PI * u.cbrt()).sin().powi(2);
        let err = check_quadratic(wiggly).unwrap_err();
        assert!(
            err.contains("do not follow the density") && err.contains("\ntoo few at x in ["),
            "the failure says where: {err}"
        );
        // The exact value's message gives u's value, not only its formula.
        let err = check_linear(|u| 2.0 * u).unwrap_err();
        assert!(
            err.starts_with("sample_linear(u = P(0.5) = 0.0625)"),
            "{err}"
        );
    }
}
