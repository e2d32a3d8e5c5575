//! Property tests of rtl-mc's running statistics (proptest, a short budget in the normal `cargo test`
//! run): arbitrary finite values, extremes included (±f64::MAX, subnormals, mixed scales), pushed in
//! one pass or split at any point and merged. Never a NaN; the mean stays within the values; a merge
//! equals the single pass up to rounding.

use proptest::prelude::*;
use rtl_mc::RunningStats;

fn value() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        Just(f64::MAX),
        Just(-f64::MAX),
        Just(5e-324),
        Just(-1e-310),
        -1e3..1e3f64,
        prop::num::f64::NORMAL | prop::num::f64::SUBNORMAL | prop::num::f64::ZERO,
    ]
}

/// 512 cases from a fixed seed unless `PROPTEST_CASES` / `PROPTEST_RNG_SEED` say otherwise.
fn config() -> ProptestConfig {
    let from_env = ProptestConfig::default();
    let set = |var: &str| std::env::var_os(var).is_some();
    ProptestConfig {
        cases: if set("PROPTEST_CASES") {
            from_env.cases
        } else {
            512
        },
        rng_seed: if set("PROPTEST_RNG_SEED") {
            from_env.rng_seed
        } else {
            proptest::test_runner::RngSeed::Fixed(15)
        },
        failure_persistence: None,
        ..from_env
    }
}

fn stats(values: &[f64]) -> RunningStats {
    let mut s = RunningStats::new();
    values.iter().for_each(|&x| s.push(x));
    s
}

/// `a` and `b` agree to `rel` of `scale`.
fn agree(a: f64, b: f64, scale: f64, rel: f64) -> bool {
    a == b || (a - b).abs() <= rel * scale
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn statistics_of_any_finite_values_are_never_nan(values in prop::collection::vec(value(), 0..50)) {
        let s = stats(&values);
        let largest = values.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        prop_assert!(s.mean().is_finite() && s.mean().abs() <= largest, "mean {}", s.mean());
        if let Some(v) = s.variance() {
            prop_assert!(v >= 0.0 && !v.is_nan(), "variance {}", v);
            let se = s.std_error().unwrap();
            prop_assert!(se >= 0.0 && !se.is_nan(), "std error {}", se);
            if largest <= 1e307 {
                prop_assert!(se.is_finite());
            }
            let (lo, hi) = s.confidence_interval(0.95).unwrap();
            prop_assert!(lo <= s.mean() && s.mean() <= hi && !lo.is_nan() && !hi.is_nan());
        }
    }

    #[test]
    fn merging_at_any_split_equals_one_pass(values in prop::collection::vec(value(), 0..50), at in any::<prop::sample::Index>()) {
        let split = at.index(values.len() + 1);
        let whole = stats(&values);
        let (a, b) = (stats(&values[..split]), stats(&values[split..]));
        let largest = values.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for m in [a.merge(&b), b.merge(&a)] {
            prop_assert_eq!(m.count(), whole.count());
            prop_assert!(agree(m.mean(), whole.mean(), largest, 1e-13), "mean {} vs {}", m.mean(), whole.mean());
            if let (Some(x), Some(y)) = (m.std_error(), whole.std_error()) {
                prop_assert!(!x.is_nan());
                // both are sqrt(M2 / (n (n - 1))), M2 up to rounding of order eps * n * largest^2
                prop_assert!(agree(x, y, largest, 1e-6), "std error {} vs {}", x, y);
            }
        }
    }
}
