//! Every estimator against exact integrals (false-failure rate 1e-6 each), and bad input.

use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_mc::check::mean_test;
use rtl_mc::densities::{linear_pdf, sample_linear};
use rtl_mc::{
    Estimate, Interval, McError, Rect, importance, jittered, jittered_2d, plain, plain_2d, sobol,
    sobol_2d,
};
use std::f64::consts::{E, PI};

const ALPHA: f64 = 1e-6;

fn rng(seed: u64) -> Xoshiro256PlusPlus {
    Xoshiro256PlusPlus::seed_from_u64(seed)
}

fn assert_consistent(name: &str, est: Result<Estimate, McError>, exact: f64) {
    let est = est.unwrap();
    let t = mean_test(&est, exact, ALPHA);
    assert!(
        t.passed,
        "{name}: estimate {} vs exact {exact}, std error {:?}, score {} (critical {})",
        est.value(),
        est.std_error(),
        t.score,
        t.critical
    );
}

fn x_sq(x: f64) -> f64 {
    x * x
}

fn in_circle(p: [f64; 2]) -> f64 {
    if p[0] * p[0] + p[1] * p[1] < 1.0 {
        1.0
    } else {
        0.0
    }
}

fn zero_two() -> Interval {
    Interval::new(0.0, 2.0).unwrap()
}

fn square() -> Rect {
    Rect::new(-1.0, 1.0, -1.0, 1.0).unwrap()
}

#[test]
fn plain_estimates_match_exact_integrals() {
    assert_consistent(
        "x^2 on [0,2]",
        plain(x_sq, zero_two(), 100_000, &mut rng(1)),
        8.0 / 3.0,
    );
    let shifted = Interval::new(-1.0, 3.0).unwrap();
    assert_consistent(
        "x^3 on [-1,3]",
        plain(|x| x * x * x, shifted, 100_000, &mut rng(2)),
        20.0,
    );
    assert_consistent(
        "pi",
        plain_2d(in_circle, square(), 100_000, &mut rng(3)),
        PI,
    );
}

#[test]
fn jittered_estimates_match_exact_integrals() {
    let unit = Interval::new(0.0, 1.0).unwrap();
    assert_consistent(
        "x^2",
        jittered(x_sq, zero_two(), 1000, 32, &mut rng(4)),
        8.0 / 3.0,
    );
    assert_consistent(
        "e^x",
        jittered(f64::exp, unit, 1000, 32, &mut rng(5)),
        E - 1.0,
    );
    assert_consistent(
        "pi",
        jittered_2d(in_circle, square(), (64, 64), 32, &mut rng(6)),
        PI,
    );
    assert_consistent(
        "pi 64x16",
        jittered_2d(in_circle, square(), (64, 16), 32, &mut rng(7)),
        PI,
    );
}

#[test]
fn sobol_estimates_match_exact_integrals() {
    let unit = Interval::new(0.0, 1.0).unwrap();
    assert_consistent(
        "x^2",
        sobol(x_sq, zero_two(), 1024, 32, &mut rng(8)),
        8.0 / 3.0,
    );
    assert_consistent("e^x", sobol(f64::exp, unit, 1000, 32, &mut rng(9)), E - 1.0);
    assert_consistent(
        "pi",
        sobol_2d(in_circle, square(), 4096, 32, &mut rng(10)),
        PI,
    );
    let xy = |p: [f64; 2]| p[0] * p[1] * p[1];
    let r = Rect::new(0.0, 2.0, 1.0, 3.0).unwrap(); // 2 * 26/3
    assert_consistent("x y^2", sobol_2d(xy, r, 512, 32, &mut rng(11)), 52.0 / 3.0);
}

#[test]
fn stratification_and_sobol_beat_plain_sampling_on_a_smooth_integrand() {
    // Same budget of 2^14 evaluations: the replicate spread of jittered and Sobol estimates must be far
    // below plain Monte Carlo's standard error (for x^2, about N^-1 times smaller, not a few percent).
    let n = 1 << 14;
    let plain_se = plain(x_sq, zero_two(), n, &mut rng(12))
        .unwrap()
        .std_error()
        .unwrap();
    let jit_se = jittered(x_sq, zero_two(), n / 16, 16, &mut rng(13))
        .unwrap()
        .std_error()
        .unwrap();
    let sob_se = sobol(x_sq, zero_two(), n / 16, 16, &mut rng(14))
        .unwrap()
        .std_error()
        .unwrap();
    assert!(
        jit_se < plain_se / 20.0,
        "jittered {jit_se} vs plain {plain_se}"
    );
    assert!(
        sob_se < plain_se / 20.0,
        "sobol {sob_se} vs plain {plain_se}"
    );
}

#[test]
fn importance_sampling_matches_exact_integrals() {
    let linear = |r: &mut Xoshiro256PlusPlus| sample_linear(r.random::<f64>());
    assert_consistent(
        "x^2 with pdf x/2",
        importance(x_sq, linear, linear_pdf, 100_000, &mut rng(15)),
        8.0 / 3.0,
    );
    // cos^2 over the unit sphere, uniform directions (pdf 1 / 4 pi): 4 pi / 3.
    let uniform_sphere = |r: &mut Xoshiro256PlusPlus| {
        let z = 1.0 - 2.0 * r.random::<f64>();
        let phi = 2.0 * PI * r.random::<f64>();
        let s = (1.0 - z * z).max(0.0).sqrt();
        [s * phi.cos(), s * phi.sin(), z]
    };
    assert_consistent(
        "cos^2 over the sphere",
        importance(
            |d: [f64; 3]| d[2] * d[2],
            uniform_sphere,
            |_| 0.25 / PI,
            100_000,
            &mut rng(16),
        ),
        4.0 * PI / 3.0,
    );
}

#[test]
fn the_mean_test_rejects_a_wrong_estimator() {
    // Integrating over [0, 1.9] instead of [0, 2] (exact 2.286...) while claiming 8/3.
    let short = Interval::new(0.0, 1.9).unwrap();
    let est = plain(x_sq, short, 100_000, &mut rng(17)).unwrap();
    assert!(!mean_test(&est, 8.0 / 3.0, ALPHA).passed);
    // Sampling x/2 but dividing by the uniform density 1/2: biased towards large x.
    let linear = |r: &mut Xoshiro256PlusPlus| sample_linear(r.random::<f64>());
    let est = importance(x_sq, linear, |_| 0.5, 100_000, &mut rng(18)).unwrap();
    assert!(!mean_test(&est, 8.0 / 3.0, ALPHA).passed);
    // Sobol points off by half a cell: a small bias that only a tiny standard error can show.
    let est = sobol(|x| x_sq(x + 1e-3), zero_two(), 4096, 16, &mut rng(19)).unwrap();
    assert!(!mean_test(&est, 8.0 / 3.0, ALPHA).passed);
}

#[test]
fn bad_input_gets_a_clear_error() {
    for (a, b) in [
        (1.0, 1.0),
        (2.0, 0.0),
        (f64::NAN, 1.0),
        (0.0, f64::INFINITY),
    ] {
        assert!(matches!(
            Interval::new(a, b),
            Err(McError::EmptyInterval { .. })
        ));
    }
    assert!(Rect::new(0.0, 1.0, 1.0, 1.0).is_err());
    let r = &mut rng(20);
    let d = zero_two();
    let no = |e: Result<Estimate, McError>| matches!(e, Err(McError::NoSamples { .. }));
    assert!(no(plain(x_sq, d, 0, r)));
    assert!(no(plain_2d(in_circle, square(), 0, r)));
    assert!(no(jittered(x_sq, d, 0, 8, r)));
    assert!(no(jittered_2d(in_circle, square(), (0, 8), 8, r)));
    assert!(no(sobol(x_sq, d, 0, 8, r)));
    assert!(no(sobol_2d(in_circle, square(), 0, 8, r)));
    assert!(no(importance(
        x_sq,
        |r: &mut Xoshiro256PlusPlus| r.random(),
        |_| 1.0,
        0,
        r
    )));
    let few = |e: Result<Estimate, McError>| matches!(e, Err(McError::TooFewReplicates { .. }));
    assert!(few(jittered(x_sq, d, 8, 1, r)));
    assert!(few(sobol_2d(in_circle, square(), 8, 0, r)));
    assert!(matches!(
        sobol(x_sq, d, (1 << 32) + 1, 2, r),
        Err(McError::TooManyPoints { .. })
    ));
}

#[test]
fn a_nan_or_infinite_integrand_is_an_error_naming_the_point() {
    let r = &mut rng(21);
    let d = zero_two();
    let bad = |x: f64| if x > 1.0 { f64::NAN } else { x };
    let err = plain(bad, d, 1000, r).unwrap_err();
    match &err {
        McError::NonFiniteIntegrand {
            estimator,
            at,
            value,
        } => {
            assert_eq!(*estimator, "plain");
            assert!(at.parse::<f64>().unwrap() > 1.0);
            assert!(value.is_nan());
        }
        e => panic!("wrong error {e}"),
    }
    assert!(err.to_string().contains("plain"));
    let inf = |x: f64| 1.0 / (x - x); // infinite everywhere
    assert!(matches!(
        jittered(inf, d, 10, 2, r),
        Err(McError::NonFiniteIntegrand { .. })
    ));
    assert!(matches!(
        sobol(bad, d, 16, 2, r),
        Err(McError::NonFiniteIntegrand { .. })
    ));
    let bad2 = |p: [f64; 2]| if p[0] > 0.0 { f64::NAN } else { 1.0 };
    assert!(matches!(
        plain_2d(bad2, square(), 100, r),
        Err(McError::NonFiniteIntegrand { .. })
    ));
    assert!(matches!(
        jittered_2d(bad2, square(), (4, 4), 2, r),
        Err(McError::NonFiniteIntegrand { .. })
    ));
    assert!(matches!(
        sobol_2d(bad2, square(), 16, 2, r),
        Err(McError::NonFiniteIntegrand { .. })
    ));
}

#[test]
fn a_pdf_of_zero_where_f_is_not_zero_is_an_error_never_an_infinite_estimate() {
    let r = &mut rng(22);
    let uniform = |r: &mut Xoshiro256PlusPlus| 2.0 * r.random::<f64>();
    // The pdf claims nothing is ever sampled above 1.
    let pdf = |x: f64| if x < 1.0 { 1.0 } else { 0.0 };
    let err = importance(x_sq, uniform, pdf, 1000, r).unwrap_err();
    assert!(matches!(err, McError::ZeroPdf { .. }), "{err}");
    assert!(err.to_string().contains("pdf is 0"));
    // Where f is 0 too, the sample carries no weight: fine, and the estimate stays finite.
    let f = |x: f64| if x < 1.0 { x * x } else { 0.0 };
    let est = importance(f, uniform, |x| if x < 1.0 { 0.5 } else { 0.0 }, 100_000, r).unwrap();
    assert!(mean_test(&est, 1.0 / 3.0, ALPHA).passed);
    // A negative or NaN density is an error.
    for p in [-0.5, f64::NAN, f64::INFINITY] {
        let e = importance(x_sq, uniform, |_| p, 10, r).unwrap_err();
        assert!(matches!(e, McError::InvalidPdf { .. }), "{e}");
    }
}

#[test]
fn every_estimator_reports_samples_and_time() {
    let r = &mut rng(23);
    let e = jittered_2d(in_circle, square(), (8, 4), 3, r).unwrap();
    assert_eq!(e.samples, 96);
    assert_eq!(e.stats.count(), 3);
    let e = sobol(x_sq, zero_two(), 64, 4, r).unwrap();
    assert_eq!(e.samples, 256);
    assert!(e.ns_per_sample() > 0.0);
    let (lo, hi) = e.confidence_interval(0.95).unwrap();
    assert!(lo < e.value() && e.value() < hi);
}
