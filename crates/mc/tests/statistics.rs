//! Running statistics: Welford against the naive formula, exact merging, confidence-interval coverage.

mod common;

use common::coverage_ok;
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_mc::{Interval, McError, RunningStats, plain};

fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// 1e9 plus dyadic noise (exactly representable): the exact variance is that of the noise alone.
fn offset_data() -> (Vec<f64>, f64) {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(11);
    let noise: Vec<f64> = (0..100_000)
        .map(|_| rng.random_range(0..4096) as f64 / 1024.0)
        .collect();
    let m = noise.iter().sum::<f64>() / noise.len() as f64;
    let var = noise.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (noise.len() - 1) as f64;
    (noise.iter().map(|x| 1e9 + x).collect(), var)
}

#[test]
fn welford_survives_a_huge_offset_where_the_naive_formula_fails() {
    let (data, exact) = offset_data();
    assert!(data.iter().all(|x| x - 1e9 < 4.0)); // the offset did not round the noise
    let mut s = RunningStats::new();
    data.iter().for_each(|&x| s.push(x));
    let welford = s.variance().unwrap();
    assert!(
        relative(welford, exact) < 1e-6,
        "welford {welford} vs {exact}"
    );

    let n = data.len() as f64;
    let (sum, sum_sq) = data.iter().fold((0.0, 0.0), |(a, b), x| (a + x, b + x * x));
    let naive = (sum_sq - sum * sum / n) / (n - 1.0);
    assert!(
        relative(naive, exact) > 0.1,
        "naive {naive} unexpectedly close to {exact}"
    );
}

#[test]
fn merging_partial_statistics_equals_one_pass() {
    let (data, _) = offset_data();
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(5);
    let data: Vec<f64> = data[..1000]
        .iter()
        .map(|x| x - 1e9 + rng.random::<f64>())
        .collect();
    let mut whole = RunningStats::new();
    data.iter().for_each(|&x| whole.push(x));
    for split in [0, 1, 2, 500, 999, 1000] {
        let (mut a, mut b) = (RunningStats::new(), RunningStats::new());
        data[..split].iter().for_each(|&x| a.push(x));
        data[split..].iter().for_each(|&x| b.push(x));
        let m = a.merge(&b);
        assert_eq!(m.count(), whole.count());
        assert!(relative(m.mean(), whole.mean()) < 1e-14, "split {split}");
        assert!(relative(m.variance().unwrap(), whole.variance().unwrap()) < 1e-12);
    }
    // many chunks, as threads would produce them
    let merged = data
        .chunks(37)
        .map(|c| {
            let mut s = RunningStats::new();
            c.iter().for_each(|&x| s.push(x));
            s
        })
        .fold(RunningStats::new(), |acc, s| acc.merge(&s));
    assert!(relative(merged.variance().unwrap(), whole.variance().unwrap()) < 1e-12);
}

#[test]
fn variance_and_intervals_need_two_values_and_a_valid_level() {
    let mut s = RunningStats::new();
    s.push(1.0);
    assert_eq!(s.variance(), None);
    assert_eq!(
        s.confidence_interval(0.95),
        Err(McError::TooFewValues { count: 1 })
    );
    s.push(3.0);
    assert_eq!(s.variance(), Some(2.0));
    for level in [0.0, 1.0, -0.5, f64::NAN] {
        assert!(matches!(
            s.confidence_interval(level),
            Err(McError::BadLevel { .. })
        ));
    }
}

/// Counts how often the interval of `level` from 100 uniform samples of x^2 on [0, 2] covers 8/3,
/// over 2000 runs.
fn coverage(level: f64) -> u64 {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(2024);
    let domain = Interval::new(0.0, 2.0).unwrap();
    (0..2000)
        .filter(|_| {
            let est = plain(|x| x * x, domain, 100, &mut rng).unwrap();
            let (lo, hi) = est.confidence_interval(level).unwrap();
            lo <= 8.0 / 3.0 && 8.0 / 3.0 <= hi
        })
        .count() as u64
}

#[test]
fn a_95_percent_interval_covers_the_truth_95_percent_of_the_time() {
    // 2000 runs: the binomial margin at false-failure rate 1e-6 is 4.89 * sqrt(0.95 * 0.05 / 2000) = 2.4%.
    let covered = coverage(0.95);
    assert!(
        coverage_ok(covered, 2000, 0.95, 1e-6),
        "covered {covered} of 2000"
    );
}

#[test]
fn the_coverage_check_rejects_an_interval_that_is_too_narrow() {
    // An 80% interval passed off as a 95% one.
    let covered = coverage(0.80);
    assert!(
        !coverage_ok(covered, 2000, 0.95, 1e-6),
        "covered {covered} of 2000"
    );
}
