//! Property tests (proptest, a short budget in the normal `cargo test` run): the tabulated
//! distributions, alias tables and 2D tables built from arbitrary finite weights, extremes included
//! (0, subnormals, 1e308, f64::MAX), on arbitrary domains. What a constructor accepts samples inside
//! its support, never from a bin of weight 0, with a positive finite density equal to its `pdf`, in
//! proportion to the weights; what it refuses, it refuses for a reason that holds.

use proptest::prelude::*;
use rtl_sampling::{
    AliasPiecewise, AliasTable, EytzingerCdf, GuideTable, ONE_MINUS_EPSILON, PiecewiseConstant2D,
    SamplingError, TabulatedCdf,
};

const TINY: f64 = 5e-324;

/// One weight: often 0 or an extreme, otherwise any finite non-negative value.
fn weight() -> impl Strategy<Value = f64> {
    prop_oneof![
        2 => Just(0.0),
        1 => Just(TINY),
        1 => Just(1e308),
        1 => Just(f64::MAX),
        1 => Just(f64::MIN_POSITIVE),
        2 => 0.0..10.0f64,
        2 => (prop::num::f64::POSITIVE | prop::num::f64::SUBNORMAL).prop_filter("finite", |w| w.is_finite()),
    ]
}

fn weights() -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec(weight(), 1..40)
}

/// A query: the ends of `[0, 1)` or anywhere inside.
fn u() -> impl Strategy<Value = f64> {
    prop_oneof![Just(0.0), Just(ONE_MINUS_EPSILON), Just(TINY), 0.0..1.0f64]
}

/// A domain `[a, b]`: ordinary, huge (whose width may overflow), tiny or subnormal.
fn domain() -> impl Strategy<Value = (f64, f64)> {
    prop_oneof![
        (-10.0..10.0f64, 1e-3..10.0f64).prop_map(|(a, w)| (a, a + w)),
        Just((-1e308, 1e308)),
        Just((-f64::MAX, f64::MAX)),
        Just((0.0, 1e-308)),
        Just((1.0, 1.0 + f64::EPSILON * 64.0)),
        (prop::num::f64::NORMAL, prop::num::f64::NORMAL),
    ]
}

/// 256 cases from a fixed seed, so every run draws the same cases (set `PROPTEST_RNG_SEED` or
/// `PROPTEST_CASES` to explore further).
fn config() -> ProptestConfig {
    let from_env = ProptestConfig::default();
    let set = |var: &str| std::env::var_os(var).is_some();
    ProptestConfig {
        cases: if set("PROPTEST_CASES") {
            from_env.cases
        } else {
            256
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

/// The bin a table samples at `u` holds weight, and the sample carries its density.
fn check_table(t: &TabulatedCdf, w: &[f64], us: &[f64]) -> Result<(), TestCaseError> {
    let (a, b) = t.domain();
    let g = GuideTable::new(t.clone()).unwrap();
    let e = EytzingerCdf::new(t);
    for &u in us {
        let bin = t.bin(u);
        prop_assert!(bin < w.len() && w[bin] > 0.0, "bin {} at u = {}", bin, u);
        let s = t.sample(u);
        prop_assert!(s.x >= a && s.x < b, "x = {} outside [{}, {})", s.x, a, b);
        prop_assert!(s.pdf > 0.0 && s.pdf.is_finite(), "pdf {}", s.pdf);
        prop_assert_eq!(s.pdf, t.pdf(s.x));
        prop_assert_eq!(g.sample(u), s);
        let es = e.sample(u);
        prop_assert!(es.pdf > 0.0 && es.pdf.is_finite() && es.pdf == e.pdf(es.x));
    }
    Ok(())
}

/// Whether the weights on this domain are a table a user may expect to be built: a positive weight,
/// bins narrower than f64::MAX and wide enough to be distinct, densities of every bin that fits.
fn reasonable(a: f64, b: f64, w: &[f64]) -> bool {
    let n = w.len() as f64;
    let width = (b - a) / n;
    let largest = w.iter().copied().fold(0.0, f64::max);
    a.is_finite()
        && b.is_finite()
        && a < b
        && (b - a).is_finite()
        && width > 1e-300
        && width * 4.0 >= (a.abs().max(b.abs())) * f64::EPSILON * n
        && largest > 0.0
        // every positive bin's probability over its width is a normal density
        && w.iter().all(|&x| x == 0.0 || x / largest > 1e-290 * width.max(1.0))
        && 1.0 / width < 1e300
}

/// The cell of `x` among `n` equal cells of `[a, b]`, with the tables' own edges (`(1 - t) a + t b`)
/// and rule (an edge belongs to the cell on its right).
fn cell_of(x: f64, a: f64, b: f64, n: usize) -> usize {
    (1..n)
        .filter(|&i| {
            let t = i as f64 / n as f64;
            (1.0 - t) * a + t * b <= x
        })
        .count()
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn tabulated_tables_of_arbitrary_weights_sample_only_weighted_bins(
        w in weights(), (a, b) in domain(), us in prop::collection::vec(u(), 8),
    ) {
        match TabulatedCdf::from_weights(a, b, &w) {
            Ok(t) => {
                check_table(&t, &w, &us)?;
                prop_assert_eq!(t.cdf_values()[w.len()], 1.0);
            }
            Err(e) => {
                prop_assert!(!reasonable(a, b, &w), "refused {:?} on [{}, {}]: {}", w, a, b, e);
                if let SamplingError::AllZero { .. } = e {
                    prop_assert!(w.iter().all(|&x| x == 0.0));
                }
            }
        }
    }

    #[test]
    fn tabulated_probabilities_are_the_weights_in_proportion(w in weights()) {
        let largest = w.iter().copied().fold(0.0, f64::max);
        prop_assume!(largest > 0.0);
        let t = TabulatedCdf::from_weights(0.0, 1.0, &w);
        prop_assume!(t.is_ok()); // a density beyond f64 (TINY weights among 1e308) is refused
        let t = t.unwrap();
        let total: f64 = w.iter().map(|x| x / largest).sum();
        for (i, &x) in w.iter().enumerate() {
            let want = (x / largest) / total;
            prop_assert!((t.bin_probability(i) - want).abs() <= 1e-12, "bin {}: {} vs {}", i, t.bin_probability(i), want);
        }
    }

    #[test]
    fn alias_tables_of_arbitrary_weights_are_in_proportion_and_skip_zero_bins(
        w in weights(), us in prop::collection::vec(u(), 8),
    ) {
        let largest = w.iter().copied().fold(0.0, f64::max);
        match AliasTable::new(&w) {
            Ok(t) => {
                let total: f64 = w.iter().map(|x| x / largest).sum();
                for (i, &x) in w.iter().enumerate() {
                    let want = (x / largest) / total;
                    prop_assert!((t.pmf(i) - want).abs() <= 1e-15 * want.max(1e-300) + 1e-300);
                }
                for &u in &us {
                    let (i, rest) = t.sample(u);
                    prop_assert!(i < w.len() && t.pmf(i) > 0.0 && w[i] > 0.0, "bin {} at {}", i, u);
                    prop_assert!((0.0..1.0).contains(&rest));
                }
            }
            Err(e) => {
                prop_assert!(largest == 0.0, "refused {:?}: {}", w, e);
            }
        }
        if let Ok(t) = AliasPiecewise::from_weights(-1.0, 3.0, &w) {
            for &u in &us {
                let s = t.sample(u);
                prop_assert!((-1.0..3.0).contains(&s.x) && s.pdf > 0.0 && s.pdf.is_finite());
                prop_assert_eq!(s.pdf, t.pdf(s.x));
            }
        }
    }

    #[test]
    fn points_of_any_finite_running_total_normalise_to_zero_and_one(
        steps in prop::collection::vec(weight(), 1..20), f0 in prop_oneof![Just(-1e308), Just(0.0), -1e3..1e3f64],
    ) {
        // F is a running total that may pass through ±1e308; clamp it so it stays finite.
        let mut f = f0;
        let mut points = vec![(0.0, f)];
        for (k, s) in steps.iter().enumerate() {
            f = (f + s).min(f64::MAX);
            points.push(((k + 1) as f64, f));
        }
        if let Ok(t) = TabulatedCdf::from_points(&points) {
            let c = t.cdf_values();
            prop_assert!(c[0] == 0.0 && c[c.len() - 1] == 1.0 && c.windows(2).all(|p| p[0] <= p[1]));
            prop_assert!(c.iter().all(|x| x.is_finite()));
        } else {
            prop_assert!(f <= f0 || steps.iter().all(|&s| s < 1e-300), "refused {:?}", points);
        }
    }

    #[test]
    fn two_d_tables_of_arbitrary_weights_sample_weighted_cells(
        w in prop::collection::vec(weight(), 1..48), nx in 1usize..8,
        u1 in prop::collection::vec(u(), 6), u2 in prop::collection::vec(u(), 6),
    ) {
        let ny = w.len() / nx;
        prop_assume!(ny > 0);
        let w = &w[..nx * ny];
        if let Ok(m) = PiecewiseConstant2D::new(w, nx, ny, (0.0, 2.0), (-1.0, 1.0)) {
            for (&a, &b) in u1.iter().zip(&u2) {
                let s = m.sample(a, b);
                prop_assert!((0.0..2.0).contains(&s.x) && (-1.0..1.0).contains(&s.y), "{:?}", s);
                prop_assert!(s.pdf > 0.0 && s.pdf.is_finite(), "{:?}", s);
                prop_assert_eq!(s.pdf, m.pdf(s.x, s.y));
                let (col, row) = (cell_of(s.x, 0.0, 2.0, nx), cell_of(s.y, -1.0, 1.0, ny));
                prop_assert!(w[row * nx + col] > 0.0, "cell ({}, {}) of weight 0: {:?}", row, col, s);
            }
        } else {
            let largest = w.iter().copied().fold(0.0, f64::max);
            // only all-zero maps, or ones with a cell too light for its density, are refused
            prop_assert!(largest == 0.0 || w.iter().any(|&x| x > 0.0 && x / largest < 1e-290));
        }
    }
}
