//! Values at the edges of f64 (issue 15): weights whose sum overflows, subnormal weights, domains
//! wider than `f64::MAX`, bins too narrow for their density, cell counts that overflow. Every
//! constructor either builds a distribution that samples with a positive finite density, in
//! proportion to its weights, or refuses with an error naming the value and the limit.

use rtl_sampling::{
    AliasPiecewise, AliasTable, EytzingerCdf, GuideTable, ONE_MINUS_EPSILON, PiecewiseConstant2D,
    SamplingError, TabulatedCdf, integrate,
};

/// `u` spread evenly over `[0, 1)`, with both ends.
fn us() -> impl Iterator<Item = f64> {
    (0..1000)
        .map(|k| k as f64 / 1000.0)
        .chain([ONE_MINUS_EPSILON])
}

/// Points of the grid of `u` in [`bin_fractions`].
const GRID: usize = 100_000;
/// How far a grid fraction may be from the bin's probability: an inversion and an alias table send
/// every grid `u` between a bin's two boundaries to it, so it is off by at most one grid step at
/// each boundary.
const GRID_TOL: f64 = 2.0 / GRID as f64;

/// The fraction of an even grid of `u` that a table sends to each bin.
fn bin_fractions(n: usize, bin: impl Fn(f64) -> usize) -> Vec<f64> {
    let m = GRID;
    let mut counts = vec![0usize; n];
    for k in 0..m {
        counts[bin((k as f64 + 0.5) / m as f64)] += 1;
    }
    counts.iter().map(|&c| c as f64 / m as f64).collect()
}

fn assert_close(got: &[f64], want: &[f64], tol: f64) {
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert!((g - w).abs() <= tol, "bin {i}: {g} vs {w} (all: {got:?})");
    }
}

#[test]
fn tabulated_cdf_of_weights_whose_sum_overflows_is_finite_and_in_proportion() {
    let t = TabulatedCdf::from_weights(0.0, 3.0, &[1e308; 3]).unwrap();
    assert_eq!(t.cdf_values()[3], 1.0);
    assert!(t.cdf_values().iter().all(|c| c.is_finite()));
    assert_close(&bin_fractions(3, |u| t.bin(u)), &[1.0 / 3.0; 3], GRID_TOL);
    let t = TabulatedCdf::from_weights(0.0, 2.0, &[f64::MAX, f64::MAX / 2.0]).unwrap();
    assert_close(
        &bin_fractions(2, |u| t.bin(u)),
        &[2.0 / 3.0, 1.0 / 3.0],
        GRID_TOL,
    );
    for u in us() {
        let s = t.sample(u);
        assert!(s.pdf > 0.0 && s.pdf.is_finite() && s.pdf == t.pdf(s.x));
    }
}

#[test]
fn alias_table_of_weights_whose_sum_overflows_samples_in_proportion() {
    let t = AliasTable::new(&[1e308; 3]).unwrap();
    for i in 0..3 {
        assert!((t.pmf(i) - 1.0 / 3.0).abs() < 1e-15, "{}", t.pmf(i));
    }
    assert_close(
        &bin_fractions(3, |u| t.sample(u).0),
        &[1.0 / 3.0; 3],
        GRID_TOL,
    );
    let t = AliasTable::new(&[f64::MAX, 0.0, f64::MAX]).unwrap();
    assert_close(
        &bin_fractions(3, |u| t.sample(u).0),
        &[0.5, 0.0, 0.5],
        GRID_TOL,
    );
}

#[test]
fn subnormal_weights_are_sampled_in_proportion() {
    let tiny = f64::from_bits(1); // 5e-324, the smallest subnormal
    let w = [tiny, 3.0 * tiny, 0.0];
    let t = TabulatedCdf::from_weights(0.0, 1.0, &w).unwrap();
    assert_close(
        &bin_fractions(3, |u| t.bin(u)),
        &[0.25, 0.75, 0.0],
        GRID_TOL,
    );
    let a = AliasTable::new(&w).unwrap();
    assert_close(
        &bin_fractions(3, |u| a.sample(u).0),
        &[0.25, 0.75, 0.0],
        GRID_TOL,
    );
    let m = PiecewiseConstant2D::new(&[tiny, 0.0, 0.0, 3.0 * tiny], 2, 2, (0.0, 1.0), (0.0, 1.0))
        .unwrap();
    assert!(
        (m.pdf(0.25, 0.25) - 1.0).abs() < 1e-15,
        "{}",
        m.pdf(0.25, 0.25)
    );
    assert!((m.pdf(0.75, 0.75) - 3.0).abs() < 1e-15);
}

#[test]
fn a_weight_negligible_beside_the_largest_is_never_sampled_with_density_zero() {
    // 5e-324 / 1e308 underflows to probability 0: that bin is simply never chosen.
    let w = [1e308, f64::from_bits(1), 1e308];
    let t = TabulatedCdf::from_weights(0.0, 3.0, &w).unwrap();
    let a = AliasPiecewise::from_weights(0.0, 3.0, &w).unwrap();
    for u in us() {
        for s in [t.sample(u), a.sample(u)] {
            assert!(s.pdf > 0.0 && s.pdf.is_finite(), "{s:?} at u = {u}");
            assert!(!(1.0..2.0).contains(&s.x), "{s:?} in the negligible bin");
        }
    }
}

#[test]
fn points_whose_cdf_range_overflows_are_normalised() {
    let t = TabulatedCdf::from_points(&[(0.0, -1e308), (1.0, 0.0), (2.0, 1e308)]).unwrap();
    assert_eq!(t.cdf_values(), &[0.0, 0.5, 1.0]);
    let t = TabulatedCdf::from_points(&[(0.0, -f64::MAX), (1.0, f64::MAX)]).unwrap();
    assert_eq!(t.sample(0.25).x, 0.25);
}

#[test]
fn a_domain_wider_than_f64_max_is_refused_naming_the_bin_or_split_into_finite_bins() {
    let err = TabulatedCdf::from_weights(-1e308, 1e308, &[1.0]).unwrap_err();
    assert_eq!(
        err,
        SamplingError::WidthOverflow {
            bin: 0,
            x0: -1e308,
            x1: 1e308
        }
    );
    let msg = err.to_string();
    assert!(
        msg.contains("bin 0") && msg.contains("1.7976931348623157e308"),
        "{msg}"
    );
    for e in [
        AliasPiecewise::from_weights(-1e308, 1e308, &[1.0]).unwrap_err(),
        EytzingerCdf::from_weights(-1e308, 1e308, &[1.0]).unwrap_err(),
        TabulatedCdf::from_density(|_| 1.0, -1e308, 1e308, 1).unwrap_err(),
        PiecewiseConstant2D::new(&[1.0], 1, 1, (-1e308, 1e308), (0.0, 1.0)).unwrap_err(),
    ] {
        assert!(matches!(e, SamplingError::WidthOverflow { .. }), "{e}");
    }
    // Two bins of width 1e308 each are fine, and sample with a tiny positive density.
    let t = TabulatedCdf::from_weights(-1e308, 1e308, &[1.0, 3.0]).unwrap();
    let d =
        TabulatedCdf::from_density(|x| if x < 0.0 { 1.0 } else { 3.0 }, -1e308, 1e308, 2).unwrap();
    let g = GuideTable::new(t.clone()).unwrap();
    for table in [&t, &d, g.table()] {
        assert!((table.bin_probability(1) - 0.75).abs() < 1e-12);
        for u in us() {
            let s = table.sample(u);
            assert!(s.x.is_finite() && s.pdf > 0.0 && s.pdf.is_finite(), "{s:?}");
            assert_eq!(s.pdf, table.pdf(s.x));
        }
    }
}

#[test]
fn a_density_that_overflows_or_underflows_is_refused_naming_the_bin() {
    // Probability 1 over the smallest subnormal width: density 2e323 overflows.
    let narrow = f64::from_bits(1);
    let e = TabulatedCdf::from_edges_and_weights(&[0.0, narrow], &[1.0]).unwrap_err();
    assert!(
        matches!(e, SamplingError::DensityOutOfRange { bin: 0, .. }),
        "{e}"
    );
    assert!(e.to_string().contains("1.7976931348623157e308"), "{e}");
    // A width of 1e-308 is fine: density 1e308.
    let t = TabulatedCdf::from_edges_and_weights(&[0.0, 1e-308], &[1.0]).unwrap();
    assert_eq!(t.sample(0.5).pdf, 1e308);
    // Probability 1e-30 spread over width 1e300 underflows: refused, not sampled with density 0.
    let (edges, w) = ([0.0, 1e300, 2e300], [1e-30, 1.0]);
    let e = TabulatedCdf::from_edges_and_weights(&edges, &w).unwrap_err();
    assert!(
        matches!(e, SamplingError::DensityOutOfRange { bin: 0, .. }),
        "{e}"
    );
    let e = AliasPiecewise::new(&edges, &w).unwrap_err();
    assert!(
        matches!(e, SamplingError::DensityOutOfRange { bin: 0, .. }),
        "{e}"
    );
    // A 2D cell: each side's density is finite, their product is not.
    let e = PiecewiseConstant2D::new(&[1.0], 1, 1, (0.0, 1e-200), (0.0, 1e-200)).unwrap_err();
    assert!(
        matches!(
            e,
            SamplingError::CellDensityOutOfRange { row: 0, col: 0, .. }
        ),
        "{e}"
    );
}

#[test]
fn a_2d_table_whose_cell_count_overflows_is_an_error_not_a_panic() {
    let e = PiecewiseConstant2D::new(&[1.0], usize::MAX, 2, (0.0, 1.0), (0.0, 1.0)).unwrap_err();
    assert_eq!(
        e,
        SamplingError::CellCountOverflow {
            nx: usize::MAX,
            ny: 2
        }
    );
    assert!(e.to_string().contains(&usize::MAX.to_string()), "{e}");
    let e = PiecewiseConstant2D::new(&[], usize::MAX, 0, (0.0, 1.0), (0.0, 1.0)).unwrap_err();
    assert!(matches!(e, SamplingError::TooFew { .. }), "{e}");
}

#[test]
fn a_2d_table_of_weights_whose_sum_overflows_samples_in_proportion() {
    let w = [1e308, 1e308, 1e308, 1e308, 1e308, 1e308];
    let m = PiecewiseConstant2D::new(&w, 3, 2, (0.0, 3.0), (0.0, 2.0)).unwrap();
    for u1 in us().step_by(37) {
        for u2 in us().step_by(41) {
            let s = m.sample(u1, u2);
            assert!((s.pdf - 1.0 / 6.0).abs() < 1e-12, "{s:?}");
            assert_eq!(s.pdf, m.pdf(s.x, s.y));
        }
    }
}

#[test]
fn integrate_over_a_domain_wider_than_f64_max_is_finite() {
    let i = integrate(|_| 1e-300, -1e308, 1e308, 4);
    assert!((i - 2e8).abs() < 1e-6, "{i}");
}

#[test]
fn numerical_inversion_on_a_domain_wider_than_f64_max_converges_inside_it() {
    use rtl_sampling::NumericInverse;
    // F(x) = x / 2e308 + 1/2 written so that it never overflows
    let cdf = |x: f64| 0.5 + x / 4e307 / 5.0;
    let brent = NumericInverse::new(cdf, -1e308, 1e308).unwrap();
    let newton = NumericInverse::with_density(cdf, |_| 1.0 / 4e307 / 5.0, -1e308, 1e308).unwrap();
    for u in [0.0, 1e-300, 0.25, 0.5, 0.75, 1.0 - f64::EPSILON] {
        for inv in [brent.invert(u).unwrap(), newton.invert(u).unwrap()] {
            let want = (u - 0.5) * 1e308 * 2.0;
            assert!(
                inv.x.is_finite() && (-1e308..=1e308).contains(&inv.x),
                "u = {u}: {inv:?}"
            );
            assert!(
                (inv.x - want).abs() <= 1e-9 * 1e308,
                "u = {u}: {} vs {want}",
                inv.x
            );
        }
    }
}

#[test]
fn uniform_density_on_a_domain_wider_than_f64_max_is_positive_and_a_too_narrow_one_is_refused() {
    use rtl_sampling::analytic::Uniform;
    let wide = Uniform::new(-1e308, 1e308).unwrap();
    for u in us() {
        let s = wide.sample(u);
        assert!(s.x.is_finite() && s.pdf > 0.0 && s.pdf.is_finite(), "{s:?}");
        assert_eq!(s.pdf, wide.pdf(s.x));
        assert!((wide.invert(s.x) - u).abs() < 1e-15, "u = {u}");
    }
    assert!((wide.pdf(0.0) * 2e307 - 0.1).abs() < 1e-16);
    let e = Uniform::new(0.0, 1e-310).unwrap_err();
    assert!(matches!(e, SamplingError::DensityOutOfRange { .. }), "{e}");
    assert!(matches!(
        Uniform::new(1.0, 1.0),
        Err(SamplingError::BadInterval { .. })
    ));
}

#[test]
fn exponential_rates_whose_samples_overflow_are_refused_naming_the_limit() {
    use rtl_sampling::analytic::Exponential;
    for rate in [Exponential::MIN_RATE, 1.0, f64::MAX] {
        let d = Exponential::new(rate).unwrap();
        for u in us() {
            let s = d.sample(u);
            assert!(
                s.x.is_finite() && s.pdf > 0.0 && s.pdf.is_finite(),
                "rate {rate}, u = {u}: {s:?}"
            );
        }
    }
    for rate in [0.0, -1.0, 1e-310, f64::INFINITY, f64::NAN] {
        let e = Exponential::new(rate).unwrap_err();
        assert!(e.to_string().contains("1e-306"), "{e}");
    }
}

/// Found by the `tables` fuzz target (docs/fuzzing.md): a weight of 2.1e-322 after one of 2 does not
/// move the CDF (the tabulated bin has probability 0), but the alias table gave it probability 1e-322
/// over a width of 1.4e39, a density that underflowed to 0, and refused a table the CDF accepts.
#[test]
fn alias_piecewise_accepts_what_the_tabulated_cdf_accepts_and_samples_the_same_bins() {
    let edges = [0.0, 1.2500000000002274, 3.0, 1.361129467683754e39];
    let weights = [1.39067116159862e-309, 2.000000001862645, 2.1e-322];
    let t = TabulatedCdf::from_edges_and_weights(&edges, &weights).unwrap();
    let a = AliasPiecewise::new(&edges, &weights).unwrap();
    assert_eq!(t.bin_probability(2), 0.0);
    for u in us() {
        let s = a.sample(u);
        assert!(
            s.x < 3.0 && s.pdf > 0.0 && s.pdf.is_finite(),
            "{s:?} at u = {u}"
        );
        assert_eq!(s.pdf, a.pdf(s.x));
        assert_eq!(s.pdf, t.pdf(s.x));
    }
}

#[test]
fn counts_of_usize_max_are_refused_before_any_allocation() {
    let e = TabulatedCdf::from_density(|_| 1.0, 0.0, 1.0, usize::MAX).unwrap_err();
    assert!(
        matches!(e, SamplingError::TooMany { what: "bins", .. }),
        "{e}"
    );
    assert!(e.to_string().contains(&usize::MAX.to_string()), "{e}");
    let t = TabulatedCdf::from_weights(0.0, 1.0, &[1.0, 2.0]).unwrap();
    let e = GuideTable::with_cells(t.clone(), usize::MAX).unwrap_err();
    assert_eq!(
        e,
        SamplingError::TooMany {
            what: "guide cells",
            got: usize::MAX,
            max: 128
        }
    );
    assert!(GuideTable::with_cells(t, 128).is_ok());
}

#[test]
fn one_bin_and_one_weight_sample_the_whole_domain() {
    let t = TabulatedCdf::from_weights(-1.0, 1.0, &[1e-300]).unwrap();
    let a = AliasTable::new(&[f64::MAX]).unwrap();
    let m = PiecewiseConstant2D::new(&[5e-324], 1, 1, (0.0, 1.0), (0.0, 1.0)).unwrap();
    for u in us() {
        assert_eq!(t.sample(u).pdf, 0.5);
        assert_eq!(a.sample(u).0, 0);
        assert_eq!(m.sample(u, u).pdf, 1.0);
    }
}
