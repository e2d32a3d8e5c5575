//! Helpers shared by the statistical tests of rtl-mc: a chi-square goodness-of-fit test and a binomial
//! coverage check. (rtl-sampling has the full chi-square machinery; these are the few lines we need.)
#![allow(dead_code)]

use statrs::distribution::{ChiSquared, ContinuousCDF, Normal};

/// The p-value of Pearson's chi-square test of `observed` counts against `expected` counts (TESTING.md):
/// cells are pooled in order until each pool expects at least 5; a count in a cell that expects 0 (outside
/// the support, decided by the caller analytically) gives p = 0 at once.
pub fn chi_square_p(observed: &[u64], expected: &[f64]) -> f64 {
    assert_eq!(observed.len(), expected.len());
    let mut pools: Vec<(f64, f64)> = Vec::new();
    let (mut obs, mut exp) = (0.0, 0.0);
    for (&o, &e) in observed.iter().zip(expected) {
        if e == 0.0 {
            if o > 0 {
                return 0.0;
            }
            continue;
        }
        obs += o as f64;
        exp += e;
        if exp >= 5.0 {
            pools.push((obs, exp));
            (obs, exp) = (0.0, 0.0);
        }
    }
    if exp > 0.0 {
        match pools.last_mut() {
            Some(last) => {
                last.0 += obs;
                last.1 += exp;
            }
            None => pools.push((obs, exp)),
        }
    }
    assert!(pools.len() >= 2, "too few cells left after pooling");
    let stat: f64 = pools.iter().map(|(o, e)| (o - e) * (o - e) / e).sum();
    ChiSquared::new((pools.len() - 1) as f64).unwrap().sf(stat)
}

/// The per-test significance level when `tests` chi-square tests run together at family-wise level 0.01
/// (Sidak correction, as pbrt-v4 and Mitsuba 3).
pub fn sidak_alpha(tests: u32) -> f64 {
    1.0 - (1.0 - 0.01f64).powf(1.0 / tests as f64)
}

/// Is `covered` out of `runs` consistent with coverage `level`? Accepts within the two-sided binomial
/// (normal approximation) margin at false-failure rate `alpha`.
pub fn coverage_ok(covered: u64, runs: u64, level: f64, alpha: f64) -> bool {
    let z = Normal::standard().inverse_cdf(1.0 - alpha / 2.0);
    let margin = z * (level * (1.0 - level) / runs as f64).sqrt();
    (covered as f64 / runs as f64 - level).abs() < margin
}
