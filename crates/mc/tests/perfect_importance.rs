//! The perfect importance sampler of chapter 3: pdf 3x^2/8 for x^2 on [0, 2].

mod common;

use common::{chi_square_p, sidak_alpha};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_mc::check::mean_test;
use rtl_mc::densities::{linear_pdf, perfect_pdf, sample_linear, sample_perfect};
use rtl_mc::importance;

/// Chi-square tests in this file (the Sidak correction is over these).
const CHI_SQUARE_TESTS: u32 = 2;

const EIGHT_THIRDS: f64 = 8.0 / 3.0;
const LARGEST_U: f64 = 1.0 - f64::EPSILON / 2.0; // 1 - 2^-53, the largest f64 below 1

fn ulps_from_eight_thirds(v: f64) -> u64 {
    (v.to_bits() as i64 - EIGHT_THIRDS.to_bits() as i64).unsigned_abs()
}

#[test]
fn one_sample_gives_eight_thirds_within_two_ulp_for_any_x() {
    let ratio = |x: f64| (x * x) / perfect_pdf(x);
    // every x the sampler can produce: its two ends and 1e5 random draws
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(31);
    let us = [0.0, f64::EPSILON, 0.5, LARGEST_U]
        .into_iter()
        .chain((0..100_000).map(|_| rng.random::<f64>()));
    for u in us {
        let x = sample_perfect(u);
        assert!(x > 0.0 && x <= 2.0, "u {u} gave x {x}");
        assert!(ulps_from_eight_thirds(ratio(x)) <= 2, "x {x}: {}", ratio(x));
    }
    // and any x in (0, 2] down to 1e-150 (below that x * x leaves the normal range)
    let mut x = 2.0f64;
    while x > 1e-150 {
        assert!(ulps_from_eight_thirds(ratio(x)) <= 2, "x {x}: {}", ratio(x));
        x *= 0.9;
    }
    // and one sample through the estimator itself, at the worst place: u -> 1, x -> 0
    let mut r = Xoshiro256PlusPlus::seed_from_u64(0);
    let est = importance(
        |x| x * x,
        |_: &mut _| sample_perfect(LARGEST_U),
        perfect_pdf,
        1,
        &mut r,
    )
    .unwrap();
    assert!(ulps_from_eight_thirds(est.value()) <= 2);
}

#[test]
fn the_perfect_estimator_has_no_variance_beyond_rounding() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(32);
    let sample = |r: &mut Xoshiro256PlusPlus| sample_perfect(r.random::<f64>());
    let est = importance(|x| x * x, sample, perfect_pdf, 100_000, &mut rng).unwrap();
    assert!(est.std_error().unwrap() < 1e-15);
    assert!(mean_test(&est, EIGHT_THIRDS, 1e-6).passed);
}

/// Bins `n` samples of `sample` on [0, 2] in 50 equal cells against the expected counts of 3x^2/8:
/// `n (b^3 - a^3) / 8` for the cell [a, b], exact.
fn perfect_chi_square_p(sample: impl Fn(f64) -> f64, seed: u64) -> f64 {
    const CELLS: usize = 50;
    const N: usize = 100_000;
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let mut observed = vec![0u64; CELLS];
    for _ in 0..N {
        let x = sample(rng.random::<f64>());
        assert!((0.0..=2.0).contains(&x), "sample {x} outside [0, 2]");
        observed[((x / 2.0 * CELLS as f64) as usize).min(CELLS - 1)] += 1;
    }
    let expected: Vec<f64> = (0..CELLS)
        .map(|k| {
            let (a, b) = (
                2.0 * k as f64 / CELLS as f64,
                2.0 * (k + 1) as f64 / CELLS as f64,
            );
            N as f64 * (b * b * b - a * a * a) / 8.0
        })
        .collect();
    chi_square_p(&observed, &expected)
}

#[test]
fn the_perfect_sampler_draws_3x2_over_8() {
    let p = perfect_chi_square_p(sample_perfect, 33);
    assert!(p > sidak_alpha(CHI_SQUARE_TESTS), "p-value {p}");
    // the pdf integrates to 1 (midpoint rule, exact to 1e-9 for a quadratic)
    let n = 100_000;
    let integral: f64 = (0..n)
        .map(|k| perfect_pdf(2.0 * (k as f64 + 0.5) / n as f64))
        .sum::<f64>()
        * 2.0
        / n as f64;
    assert!((integral - 1.0).abs() < 1e-9);
    assert_eq!(perfect_pdf(-0.1), 0.0);
    assert_eq!(perfect_pdf(2.1), 0.0);
}

#[test]
fn the_chi_square_test_rejects_a_wrong_sampler() {
    // The linear sampler (pdf x/2) is a fine sampler, but not of 3x^2/8.
    let p = perfect_chi_square_p(sample_linear, 34);
    assert!(p < sidak_alpha(CHI_SQUARE_TESTS), "p-value {p}");
    // and the linear pair agrees with itself: x/2 integrates to 1 and the sampler stays in [0, 2]
    assert_eq!(sample_linear(0.0), 2.0);
    assert!(sample_linear(LARGEST_U) > 0.0);
    assert_eq!(linear_pdf(2.0), 1.0);
}
