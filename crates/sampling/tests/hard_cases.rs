//! The hard cases of TESTING.md for tabulated CDFs, guide tables, the Eytzinger layout, alias tables
//! and 2D maps: bad weights are errors naming the bin, zero-probability bins are never returned,
//! no segment has zero width, every index stays in range.

use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_sampling::{
    AliasPiecewise, AliasTable, EytzingerCdf, GuideTable, ONE_MINUS_EPSILON, PiecewiseConstant2D,
    SamplingError, TabulatedCdf,
};

/// Zero bins at the start, in the middle (two in a row) and at the end.
const WEIGHTS: [f64; 12] = [0.0, 0.0, 1.0, 0.0, 0.0, 2.0, 0.5, 0.0, 3.0, 1e-9, 0.0, 0.0];

fn table() -> TabulatedCdf {
    TabulatedCdf::from_weights(-1.0, 2.0, &WEIGHTS).unwrap()
}

/// The awkward `u`: both ends, every CDF step and the floats either side of it, and out-of-range
/// values that must be clamped.
fn awkward_u(t: &TabulatedCdf) -> Vec<f64> {
    let mut us = vec![
        0.0,
        ONE_MINUS_EPSILON,
        1.0,
        -0.25,
        1.5,
        f64::NAN,
        f64::MIN_POSITIVE,
    ];
    for &c in t.cdf_values() {
        us.extend([c, c.next_down(), c.next_up()]);
    }
    us
}

#[test]
fn bad_weights_are_errors_naming_the_bin() {
    for (bad, value) in [
        (3, -0.5),
        (0, f64::NAN),
        (7, f64::INFINITY),
        (11, f64::NEG_INFINITY),
    ] {
        let mut w = [1.0; 12];
        w[bad] = value;
        for err in [
            TabulatedCdf::from_weights(0.0, 1.0, &w).unwrap_err(),
            AliasTable::new(&w).unwrap_err(),
            AliasPiecewise::from_weights(0.0, 1.0, &w).unwrap_err(),
        ] {
            match err {
                SamplingError::BadWeight { bin, .. } => assert_eq!(bin, bad),
                other => panic!("expected BadWeight for bin {bad}, got {other}"),
            }
            assert!(err.to_string().contains(&format!("bin {bad}")), "{err}");
        }
    }
    let mut w = vec![1.0; 12];
    w[7] = -2.0;
    let err = PiecewiseConstant2D::new(&w, 4, 3, (0.0, 1.0), (0.0, 1.0)).unwrap_err();
    assert_eq!(
        err,
        SamplingError::BadCellWeight {
            row: 1,
            col: 3,
            value: -2.0
        }
    );
}

#[test]
fn all_zero_weights_are_an_error() {
    let zeros = [0.0; 5];
    assert!(matches!(
        TabulatedCdf::from_weights(0.0, 1.0, &zeros),
        Err(SamplingError::AllZero { bins: 5 })
    ));
    assert!(matches!(
        AliasTable::new(&zeros),
        Err(SamplingError::AllZero { .. })
    ));
    assert!(matches!(
        PiecewiseConstant2D::new(&[0.0; 6], 3, 2, (0.0, 1.0), (0.0, 1.0)),
        Err(SamplingError::AllZero { bins: 6 })
    ));
    assert!(matches!(
        TabulatedCdf::from_points(&[(0.0, 0.5), (1.0, 0.5)]),
        Err(SamplingError::ZeroMass { .. })
    ));
    assert!(matches!(
        TabulatedCdf::from_weights(0.0, 1.0, &[]),
        Err(SamplingError::TooFew { .. })
    ));
}

#[test]
fn a_bad_density_value_is_an_error_naming_bin_and_x() {
    let err =
        TabulatedCdf::from_density(|x| if x > 0.5 { -1.0 } else { 1.0 }, 0.0, 1.0, 4).unwrap_err();
    match err {
        SamplingError::BadDensity { bin, x, value } => {
            assert_eq!(bin, 2);
            assert!(x > 0.5 && x < 0.75 && value == -1.0);
        }
        other => panic!("{other}"),
    }
    let err = TabulatedCdf::from_density(|x| 1.0 / (x - 0.3), 0.0, 1.0, 10).unwrap_err();
    assert!(
        matches!(err, SamplingError::BadDensity { bin: 0, .. }),
        "{err}"
    );
}

#[test]
fn zero_width_segments_are_errors_not_divisions_by_zero() {
    assert!(matches!(
        TabulatedCdf::from_points(&[(0.0, 0.0), (0.5, 0.3), (0.5, 0.6), (1.0, 1.0)]),
        Err(SamplingError::NotIncreasing { index: 2, .. })
    ));
    // 100 bins on an interval 4 ulp wide: the edges repeat.
    assert!(matches!(
        TabulatedCdf::from_weights(1.0, 1.0 + 4.0 * f64::EPSILON, &[1.0; 100]),
        Err(SamplingError::NotIncreasing { .. })
    ));
    assert!(matches!(
        TabulatedCdf::from_edges_and_weights(&[0.0, 1.0, 1.0, 2.0], &[1.0, 1.0, 1.0]),
        Err(SamplingError::NotIncreasing { index: 2, .. })
    ));
    assert!(matches!(
        TabulatedCdf::from_points(&[(0.0, 0.0), (0.5, 0.7), (1.0, 0.6)]),
        Err(SamplingError::Decreasing { index: 2, .. })
    ));
    assert!(matches!(
        TabulatedCdf::from_points(&[(0.0, 0.0), (f64::NAN, 0.7), (1.0, 1.0)]),
        Err(SamplingError::NonFinitePoint { index: 1, .. })
    ));
    assert!(matches!(
        TabulatedCdf::from_weights(0.0, f64::INFINITY, &[1.0]),
        Err(SamplingError::BadInterval { .. })
    ));
}

#[test]
fn zero_bins_are_never_returned_by_any_search() {
    let t = table();
    let guides = [1, 3, 12, 100].map(|m| GuideTable::with_cells(t.clone(), m).unwrap());
    let eytzinger = EytzingerCdf::new(&t);
    let alias = AliasPiecewise::from_tabulated(&t).unwrap();
    for u in awkward_u(&t) {
        let clamped = if u.is_nan() {
            0.0
        } else {
            u.clamp(0.0, ONE_MINUS_EPSILON)
        };
        let bin = t.bin(clamped);
        assert!(bin < t.len(), "u = {u}: bin {bin} out of range");
        assert!(t.bin_probability(bin) > 0.0, "u = {u}: zero bin {bin}");
        assert_eq!(t.bin_by_linear_scan(clamped), bin, "linear scan at u = {u}");
        for g in &guides {
            assert_eq!(g.bin(clamped), bin, "guide table at u = {u}");
        }
        let s = t.sample(u);
        assert!(
            s.pdf > 0.0 && s.pdf == t.pdf(s.x),
            "u = {u}: {s:?}, pdf(x) = {}",
            t.pdf(s.x)
        );
        assert_eq!(eytzinger.sample(u), s, "eytzinger at u = {u}");
        let a = alias.sample(u);
        assert!(
            a.pdf > 0.0 && alias.pdf(a.x) == a.pdf,
            "alias at u = {u}: {a:?}"
        );
    }
    let discrete = AliasTable::new(&WEIGHTS).unwrap();
    for u in awkward_u(&t) {
        let (i, v) = discrete.sample(u);
        assert!(
            WEIGHTS[i] > 0.0 && (0.0..1.0).contains(&v),
            "alias at u = {u}: ({i}, {v})"
        );
    }
}

#[test]
fn all_searches_agree_on_random_tables() {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(7);
    for n in [1, 2, 3, 5, 17, 64, 1000] {
        let weights: Vec<f64> = (0..n)
            .map(|_| {
                if rng.random::<f64>() < 0.3 {
                    0.0
                } else {
                    rng.random::<f64>().powi(4)
                }
            })
            .chain(std::iter::once(1.0)) // at least one positive weight
            .collect();
        let t = TabulatedCdf::from_weights(0.0, 1.0, &weights).unwrap();
        let g = GuideTable::new(t.clone()).unwrap();
        let e = EytzingerCdf::new(&t);
        let us = awkward_u(&t)
            .into_iter()
            .chain((0..2000).map(|_| rng.random::<f64>()));
        for u in us {
            let s = t.sample(u);
            assert_eq!(g.sample(u), s, "n = {n}, u = {u}");
            assert_eq!(e.sample(u), s, "n = {n}, u = {u}");
            assert!(s.pdf > 0.0 && s.pdf.is_finite() && s.x.is_finite());
        }
    }
}

#[test]
fn u_times_total_rounding_to_total_is_harmless() {
    // With subnormal weights, ONE_MINUS_EPSILON * total rounds to total: a sampler that searched
    // for u * total in running sums would land past the last positive bin. The table divides the
    // running sums by the total instead, so the last step is exactly 1 and u < 1 stays inside.
    let tiny = f64::from_bits(1); // 5e-324
    let weights = [tiny, 0.0, tiny, 0.0];
    let total = 2.0 * tiny;
    assert_eq!(ONE_MINUS_EPSILON * total, total, "the premise of this test");
    let t = TabulatedCdf::from_weights(0.0, 4.0, &weights).unwrap();
    assert_eq!(t.cdf_values(), &[0.0, 0.5, 0.5, 1.0, 1.0]);
    assert_eq!(t.bin(ONE_MINUS_EPSILON), 2);
    let s = t.sample(ONE_MINUS_EPSILON);
    assert!((2.0..3.0).contains(&s.x) && s.pdf == 0.5, "{s:?}");
    let a = AliasTable::new(&weights).unwrap();
    assert_eq!(a.sample(ONE_MINUS_EPSILON).0, 2);
}

#[test]
fn a_cdf_not_ending_at_exactly_one_is_normalised() {
    // Ten weights of 0.1 sum to 0.9999999999999999 in floating point.
    let weights = [0.1; 10];
    assert_ne!(weights.iter().sum::<f64>(), 1.0, "the premise of this test");
    let t = TabulatedCdf::from_weights(0.0, 1.0, &weights).unwrap();
    assert_eq!(*t.cdf_values().last().unwrap(), 1.0);
    assert_eq!(t.bin(ONE_MINUS_EPSILON), 9);
    assert!(t.sample(ONE_MINUS_EPSILON).x < 1.0);
    // Points whose F starts above 0 and ends below 1 (a running total, not a CDF).
    let t = TabulatedCdf::from_points(&[(0.0, 0.25), (1.0, 0.5), (3.0, 0.7499)]).unwrap();
    assert_eq!(t.cdf_values()[0], 0.0);
    assert_eq!(t.cdf_values()[2], 1.0);
    assert!((t.pdf(0.5) - 0.25 / 0.4999).abs() < 1e-12);
}

// ANCHOR: classic
#[test]
fn the_classic_inverse_cdf_program_made_right() {
    // The seed report's table, F(x) = x³ at x = 0, 0.1, ..., 1, and its query u = 0.5.
    let points: Vec<(f64, f64)> = (0..=10)
        .map(|i| {
            let x = i as f64 / 10.0;
            (x, x * x * x)
        })
        .collect();
    let t = TabulatedCdf::from_points(&points).unwrap();
    let x = t.quantile(0.5).unwrap();
    // Between (0.7, 0.343) and (0.8, 0.512).
    let expected = 0.7 + 0.1 * (0.5 - 0.343) / (0.512 - 0.343);
    assert!((x - expected).abs() < 1e-12, "{x} vs {expected}");
    assert_eq!(t.quantile(0.0).unwrap(), 0.0);
    assert_eq!(t.quantile(1.0).unwrap(), 1.0);
    for bad in [-0.1, 1.1, f64::NAN] {
        let err = t.quantile(bad).unwrap_err();
        assert!(matches!(err, SamplingError::OutsideRange { .. }), "{err}");
    }
    // A flat stretch of F (where the classic loop divided 0 by 0) is skipped, never returned.
    let flat =
        TabulatedCdf::from_points(&[(0.0, 0.0), (1.0, 0.5), (2.0, 0.5), (3.0, 1.0)]).unwrap();
    assert_eq!(flat.quantile(0.5).unwrap(), 2.0);
    assert_eq!(flat.quantile(1.0).unwrap(), 3.0);
    let trailing = TabulatedCdf::from_points(&[(0.0, 0.0), (1.0, 1.0), (2.0, 1.0)]).unwrap();
    assert_eq!(trailing.quantile(1.0).unwrap(), 1.0);
}
// ANCHOR_END: classic

#[test]
fn round_trips_return_u() {
    let t = TabulatedCdf::from_density(|x| 1.0 + x.sin(), 0.0, 10.0, 1000).unwrap();
    let g = GuideTable::new(t.clone()).unwrap();
    let e = EytzingerCdf::new(&t);
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(3);
    for _ in 0..10_000 {
        let u: f64 = rng.random();
        for (name, back) in [
            ("binary", t.invert(t.sample(u).x)),
            ("guide", g.invert(g.sample(u).x)),
            ("eytzinger", e.invert(e.sample(u).x)),
        ] {
            assert!((back - u).abs() < 1e-14, "{name}: {u} -> {back}");
        }
    }
    let weights: Vec<f64> = (0..48)
        .map(|k| if k % 7 == 3 { 0.0 } else { 1.0 + k as f64 })
        .collect();
    let map = PiecewiseConstant2D::new(&weights, 8, 6, (0.0, 1.0), (0.0, 2.0)).unwrap();
    for _ in 0..10_000 {
        let (u1, u2): (f64, f64) = (rng.random(), rng.random());
        let s = map.sample(u1, u2);
        let (b1, b2) = map.invert(s.x, s.y);
        assert!(
            (b1 - u1).abs() < 1e-13 && (b2 - u2).abs() < 1e-13,
            "({u1}, {u2}) -> ({b1}, {b2})"
        );
    }
}

#[test]
fn a_zero_row_of_a_2d_map_is_never_sampled() {
    let weights = [0.0, 0.0, 0.0, 1.0, 2.0, 0.0, 0.0, 0.0, 0.0];
    let map = PiecewiseConstant2D::new(&weights, 3, 3, (0.0, 3.0), (0.0, 3.0)).unwrap();
    for u2 in [0.0, 1.0 / 3.0, 0.5, ONE_MINUS_EPSILON] {
        for u1 in [0.0, 1.0 / 3.0, 2.0 / 3.0, ONE_MINUS_EPSILON] {
            let s = map.sample(u1, u2);
            assert!((1.0..2.0).contains(&s.y) && s.x < 2.0, "{s:?}");
            assert!(s.pdf > 0.0 && s.pdf == map.pdf(s.x, s.y), "{s:?}");
        }
    }
}
