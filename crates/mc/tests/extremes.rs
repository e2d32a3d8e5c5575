//! rtl-mc at the edges of f64 (issue 15): statistics of values near `f64::MAX` and of subnormal
//! values, intervals and rectangles too wide for an `f64`, estimates whose samples overflow, sample
//! counts that overflow, confidence levels within 2^-53 of 1. The documentation promises no silent
//! NaN: every result is a finite number (or an honest infinity), or an error naming the value.

use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_mc::{
    Interval, McError, Rect, RunningStats, jittered, jittered_2d, plain, plain_2d, sobol, sobol_2d,
    student_t_quantile,
};

fn stats(values: &[f64]) -> RunningStats {
    let mut s = RunningStats::new();
    values.iter().for_each(|&x| s.push(x));
    s
}

fn rng() -> Xoshiro256PlusPlus {
    Xoshiro256PlusPlus::seed_from_u64(3)
}

#[test]
fn welford_of_values_near_f64_max_has_a_finite_mean_and_standard_error() {
    let s = stats(&[f64::MAX, -f64::MAX]);
    assert_eq!(s.mean(), 0.0);
    // M2 = 2 MAX^2: the variance is beyond f64 (+inf, not NaN), its square root over n is not.
    assert_eq!(s.variance(), Some(f64::INFINITY));
    let se = s.std_error().unwrap();
    assert!((se / f64::MAX - 1.0).abs() < 1e-15, "{se}");
    let s = stats(&[1e308, 1e308, 1e308]);
    assert_eq!(
        (s.mean(), s.variance(), s.std_error()),
        (1e308, Some(0.0), Some(0.0))
    );
    let s = stats(&[f64::MAX, f64::MAX, f64::MAX / 2.0, f64::MAX / 2.0]);
    assert!(
        (s.mean() / (0.75 * f64::MAX) - 1.0).abs() < 1e-15,
        "{}",
        s.mean()
    );
    let (lo, hi) = s.confidence_interval(0.95).unwrap();
    assert!(lo.is_finite() && hi == f64::INFINITY, "({lo}, {hi})");
}

#[test]
fn welford_of_subnormal_values_keeps_their_variance() {
    let tiny = f64::from_bits(1);
    let s = stats(&[tiny, 3.0 * tiny]);
    assert_eq!(s.mean(), 2.0 * tiny);
    // M2 = 2 tiny^2 underflowed to 0 before; in units of the scale it is exact.
    assert_eq!(s.variance(), Some(0.0)); // 2 tiny^2 is itself below every f64
    assert_eq!(s.std_error(), Some(tiny)); // sqrt(2 tiny^2 / 2) = tiny
    let s = stats(&[1e-310, 2e-310, 3e-310]);
    assert!((s.std_error().unwrap() / (1e-310 / 3f64.sqrt()) - 1.0).abs() < 1e-6);
}

#[test]
fn welford_with_scaling_equals_the_plain_update_on_ordinary_values() {
    // The scale is a power of two, so scaled and unscaled updates round alike.
    let values: Vec<f64> = (0..1000)
        .map(|k| ((k * 7919) % 1013) as f64 * 0.37 - 100.0)
        .collect();
    let (mut n, mut mean, mut m2) = (0u64, 0.0f64, 0.0f64);
    for &x in &values {
        n += 1;
        let d = x - mean;
        mean += d / n as f64;
        m2 += d * (x - mean);
    }
    let s = stats(&values);
    assert_eq!(s.mean(), mean);
    assert_eq!(s.variance(), Some(m2 / (n - 1) as f64));
}

#[test]
fn merging_statistics_of_very_different_scales_is_finite_and_exact() {
    let (a, b) = (stats(&[1e-300, 3e-300]), stats(&[1e300, -1e300, 1e300]));
    let whole = stats(&[1e-300, 3e-300, 1e300, -1e300, 1e300]);
    for m in [a.merge(&b), b.merge(&a)] {
        assert_eq!(m.count(), 5);
        assert!(
            (m.mean() / whole.mean() - 1.0).abs() < 1e-12,
            "{} {}",
            m.mean(),
            whole.mean()
        );
        let (sm, sw) = (m.std_error().unwrap(), whole.std_error().unwrap());
        assert!((sm / sw - 1.0).abs() < 1e-12, "{sm} vs {sw}");
    }
    let big = stats(&[f64::MAX, -f64::MAX]);
    let m = big.merge(&big);
    assert_eq!(m.mean(), 0.0);
    assert!(m.std_error().unwrap().is_finite());
}

#[test]
fn a_confidence_level_within_2_pow_53_of_one_is_wide_not_nan() {
    let level = 1.0 - f64::EPSILON / 2.0;
    let s = stats(&[1.0, 1.0, 1.0]);
    assert_eq!(s.confidence_interval(level).unwrap(), (1.0, 1.0));
    let s = stats(&[1.0, 2.0, 3.0]);
    let (lo, hi) = s.confidence_interval(level).unwrap();
    assert!(
        lo.is_finite() && hi.is_finite() && lo < 2.0 && hi > 2.0,
        "({lo}, {hi})"
    );
}

#[test]
fn student_t_quantile_never_panics() {
    assert!(student_t_quantile(0.975, 0) > 12.0); // taken as 1 degree of freedom
    assert!(student_t_quantile(1.5, 3).is_nan());
    assert!(student_t_quantile(f64::NAN, 3).is_nan());
    assert_eq!(student_t_quantile(0.0, 3), f64::NEG_INFINITY);
    assert_eq!(student_t_quantile(1.0, 3), f64::INFINITY);
    // statrs alone panicked below p = 1e-150 or so, and did not return for 10^8 degrees of freedom
    // or more; every p from the smallest subnormal up, and every count up to u64::MAX, now returns
    // a number, monotone in p and antisymmetric about 1/2
    let ps = [5e-324, 1e-300, 1e-150, 1e-30, 1e-20, 1e-10, 0.025, 0.4, 0.5];
    for dof in [
        0,
        1,
        2,
        3,
        10,
        1000,
        10_000,
        10_001,
        30_000,
        10_000_000,
        1 << 40,
        u64::MAX,
    ] {
        let mut last = f64::NEG_INFINITY;
        for p in ps {
            let t = student_t_quantile(p, dof);
            assert!(
                !t.is_nan() && t >= last,
                "t({p:e}, {dof}) = {t} after {last}"
            );
            assert!(t.is_finite() || p == 5e-324, "t({p:e}, {dof}) = {t}");
            // antisymmetric: the quantile of 1 - p is minus that of 1 - (1 - p), which is p
            // to within 2^-53 (p itself where 1 - p is exact)
            let mirror = student_t_quantile(1.0 - p, dof);
            let back = student_t_quantile(1.0 - (1.0 - p), dof);
            assert_eq!(mirror, -back, "t({p:e}, {dof}) = {t}");
            last = t;
        }
    }
}

/// The t quantile where statrs' inverse alone is wrong, against values checked independently: the
/// closed form for 1 degree of freedom, the tail `F(t) ~ K nu^((nu - 1)/2) |t|^-nu` (exact to 1e-19
/// relative at t = 1e10, nu = 3), mpmath's incomplete beta function (50 digits: F(-54.29138855305176)
/// = 1.0e-300 at 1000 degrees of freedom), and for many degrees of freedom the normal quantile `z`
/// moved by the first term `z (z^2 + 1) / (4 nu)` of its expansion, within 0.1% of that term.
#[test]
fn student_t_quantile_is_right_where_statrs_alone_is_not() {
    let close = |got: f64, want: f64, rel: f64, what: &str| {
        assert!(
            (got - want).abs() <= rel * want.abs(),
            "{what}: {got} vs {want}"
        );
    };
    close(
        student_t_quantile(1e-150, 1),
        -1.0 / (std::f64::consts::PI * 1e-150),
        1e-14,
        "Cauchy",
    );
    close(
        student_t_quantile(1e-30, 3),
        -1.033110836044646e10,
        1e-9,
        "3 dof, 1e-30",
    );
    close(
        student_t_quantile(1e-300, 1000),
        -54.29138855305176,
        1e-9,
        "1000 dof, 1e-300",
    );
    let z = -1.959963984540054; // the normal quantile of 0.025
    for dof in [30_000u64, 1_000_000, 10_000_000, 100_000_000, 1 << 40] {
        let nu = dof as f64;
        let first = z * (z * z + 1.0) / (4.0 * nu);
        let t = student_t_quantile(0.025, dof);
        close(t - z, first, 1e-3, &format!("{dof} dof"));
    }
    // the deliberately wrong answer, statrs' inverse alone at 10^7 degrees of freedom, fails it
    use statrs::distribution::{ContinuousCDF, StudentsT};
    let wrong = StudentsT::new(0.0, 1.0, 1e7).unwrap().inverse_cdf(0.025);
    let first = z * (z * z + 1.0) / 4e7;
    assert!(
        (wrong - z - first).abs() > 1e-3 * first.abs(),
        "statrs: {wrong}"
    );
}

/// A confidence interval over 2^33 values (merged, as threads merge theirs) returns at once with
/// the normal quantile: statrs' inverse did not return at all from 10^8 degrees of freedom on.
#[test]
fn confidence_interval_of_billions_of_values_returns() {
    let mut s = stats(&[1.0, 3.0]);
    for _ in 0..32 {
        s = s.merge(&s);
    }
    assert_eq!(s.count(), 1 << 33);
    let (lo, hi) = s.confidence_interval(0.95).unwrap();
    let se = s.std_error().unwrap();
    // t = z + z (z^2 + 1) / (4 nu) is 2.8e-10 above z, and the ends are rounded to ulps of 2
    // (4e-11 standard errors)
    assert!(
        (hi - 2.0 - 1.959963984540054 * se).abs() <= 1e-9 * se,
        "{lo} {hi} {se}"
    );
    assert!((2.0 - lo - (hi - 2.0)).abs() <= 1e-9 * se);
}

#[test]
fn an_interval_wider_than_f64_max_is_refused_naming_it() {
    let e = Interval::new(-1e308, 1e308).unwrap_err();
    assert_eq!(
        e,
        McError::IntervalTooWide {
            a: -1e308,
            b: 1e308
        }
    );
    let msg = e.to_string();
    assert!(
        msg.contains("-1e308") && msg.contains("1.7976931348623157e308"),
        "{msg}"
    );
    assert!(Interval::new(-1e308, 7e307).is_ok());
    // a subnormal width is fine
    let i = Interval::new(0.0, f64::from_bits(1)).unwrap();
    assert_eq!(i.length(), f64::from_bits(1));
}

#[test]
fn a_rectangle_whose_area_overflows_is_refused_by_new_and_by_the_estimators() {
    let e = Rect::new(0.0, 1e200, 0.0, 1e200).unwrap_err();
    assert!(matches!(e, McError::AreaTooLarge { .. }), "{e}");
    let by_hand = Rect {
        x: Interval::new(0.0, 1e200).unwrap(),
        y: Interval::new(0.0, 1e200).unwrap(),
    };
    for e in [
        plain_2d(|_| 1.0, by_hand, 10, &mut rng()).unwrap_err(),
        jittered_2d(|_| 1.0, by_hand, (2, 2), 2, &mut rng()).unwrap_err(),
        sobol_2d(|_| 1.0, by_hand, 4, 2, &mut rng()).unwrap_err(),
    ] {
        assert!(matches!(e, McError::AreaTooLarge { .. }), "{e}");
    }
}

#[test]
fn samples_that_overflow_are_an_error_naming_the_product_not_a_silent_infinity() {
    let domain = Interval::new(0.0, 4.0).unwrap();
    let e = plain(|_| 1e308, domain, 10, &mut rng()).unwrap_err();
    assert!(
        matches!(
            e,
            McError::Overflow {
                estimator: "plain",
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("(b - a) f(x)"), "{e}");
    for e in [
        jittered(|_| 1e308, domain, 8, 2, &mut rng()).unwrap_err(),
        sobol(|_| 1e308, domain, 8, 2, &mut rng()).unwrap_err(),
    ] {
        assert!(matches!(e, McError::Overflow { .. }), "{e}");
    }
}

#[test]
fn integrands_near_f64_max_whose_integral_fits_are_estimated() {
    // The strata's sum of 1e308 would overflow; their mean does not, nor (b - a) times it.
    let domain = Interval::new(0.0, 1.0).unwrap();
    for est in [
        plain(|_| 1e308, domain, 64, &mut rng()).unwrap(),
        jittered(|_| 1e308, domain, 64, 2, &mut rng()).unwrap(),
        sobol(|_| 1e308, domain, 64, 2, &mut rng()).unwrap(),
    ] {
        assert!((est.value() / 1e308 - 1.0).abs() < 1e-12, "{}", est.value());
        assert!(est.std_error().unwrap().is_finite());
    }
    let r = Rect::new(0.0, 1.0, 0.0, 1.0).unwrap();
    let est = jittered_2d(|_| f64::MAX, r, (8, 8), 2, &mut rng()).unwrap();
    assert!((est.value() / f64::MAX - 1.0).abs() < 1e-12);
}

#[test]
fn sample_counts_that_overflow_a_u64_are_an_error_before_any_work() {
    let r = Rect::new(0.0, 1.0, 0.0, 1.0).unwrap();
    let e = jittered_2d(|_| 1.0, r, (u64::MAX, 2), 2, &mut rng()).unwrap_err();
    assert!(matches!(e, McError::TooManySamples { .. }), "{e}");
    assert!(e.to_string().contains(&u64::MAX.to_string()), "{e}");
    let domain = Interval::new(0.0, 1.0).unwrap();
    let e = jittered(|_| 1.0, domain, u64::MAX, 2, &mut rng()).unwrap_err();
    assert!(matches!(e, McError::TooManySamples { .. }), "{e}");
}

#[test]
fn importance_weights_that_overflow_are_an_error_naming_the_point() {
    use rand::Rng;
    let e = rtl_mc::importance(
        |_: f64| 1.0,
        |r: &mut Xoshiro256PlusPlus| r.random::<f64>(),
        |_| 5e-324, // a subnormal pdf: f / p = 2e323 overflows
        10,
        &mut rng(),
    )
    .unwrap_err();
    assert!(
        matches!(e, McError::NonFiniteIntegrand { value, .. } if value == f64::INFINITY),
        "{e}"
    );
    assert!(e.to_string().contains("f/p"), "{e}");
}

#[test]
fn mean_test_with_an_alpha_outside_zero_one_fails_instead_of_panicking() {
    let est = plain(|x| x, Interval::new(0.0, 1.0).unwrap(), 2000, &mut rng()).unwrap();
    for alpha in [0.0, 1.0, 3.0, -1.0, f64::NAN] {
        let t = rtl_mc::check::mean_test(&est, 0.5, alpha);
        assert!(!t.passed, "alpha {alpha}: {t:?}");
    }
    assert!(rtl_mc::check::mean_test(&est, 0.5, 1e-6).passed);
}
