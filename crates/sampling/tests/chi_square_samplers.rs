//! Chi-square goodness of fit of every sampler against its own density (TESTING.md): 10⁵ samples
//! from a fixed seed, equal-width cells, expected counts from the pdf integrated by Gauss-Legendre
//! quadrature, cells expecting < 5 pooled, p-value from statrs, alpha = 0.01 Šidák-corrected over
//! the [`TESTS`] tests below. One more test feeds the checker a deliberately wrong sampler.

use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_sampling::analytic::{Exponential, Linear, Quadratic, Uniform};
use rtl_sampling::chi_square::{
    ChiSquareError, chi_square, expected_counts, histogram, sidak_alpha,
};
use rtl_sampling::numeric::NumericInverse;
use rtl_sampling::targets::{BookSinSquared, TargetDensity};
use rtl_sampling::{
    AliasPiecewise, AliasTable, EytzingerCdf, GuideTable, InverseTransform, PiecewiseConstant2D,
    TabulatedCdf,
};

/// The number of chi-square tests in this file that must pass (the Šidák correction's count).
const TESTS: usize = 13;
const SAMPLES: usize = 100_000;

fn alpha() -> f64 {
    sidak_alpha(0.01, TESTS)
}

fn rng(seed: u64) -> Xoshiro256PlusPlus {
    Xoshiro256PlusPlus::seed_from_u64(seed)
}

fn edges(a: f64, b: f64, cells: usize) -> Vec<f64> {
    (0..=cells)
        .map(|k| a + (b - a) * k as f64 / cells as f64)
        .collect()
}

// ANCHOR: p_value_1d
/// Samples `sample(u)` for uniform `u`, checks that each sample's own pdf equals `pdf(x)`, bins
/// the samples, and returns the chi-square p-value against `pdf` (panics with the reason if the
/// test cannot be run or a sample leaves the support).
fn p_value_1d(
    name: &str,
    seed: u64,
    sample: impl Fn(f64) -> (f64, Option<f64>),
    pdf: impl Fn(f64) -> f64,
    (a, b): (f64, f64),
    cells: usize,
) -> f64 {
    let mut r = rng(seed);
    let xs: Vec<f64> = (0..SAMPLES)
        .map(|_| {
            let (x, p) = sample(r.random::<f64>());
            if let Some(p) = p {
                let q = pdf(x);
                assert!(
                    (p - q).abs() <= 1e-9 * q.max(1.0),
                    "{name}: sample x = {x} claims pdf {p}, pdf(x) = {q}"
                );
            }
            x
        })
        .collect();
    let e = edges(a, b, cells);
    let (observed, outside) = histogram(xs, &e);
    assert_eq!(outside, 0, "{name}: samples outside [{a}, {b}]");
    let expected = expected_counts(&pdf, &e, SAMPLES as f64, 64);
    let result = chi_square(&observed, &expected).unwrap_or_else(|e| panic!("{name}: {e}"));
    eprintln!("{name}: {result:?}");
    result.p_value
}
// ANCHOR_END: p_value_1d

fn assert_fits(name: &str, p: f64) {
    assert!(p >= alpha(), "{name}: p = {p:e} < alpha = {:e}", alpha());
}

fn check_inverse_transform(name: &str, seed: u64, s: &dyn InverseTransform, domain: (f64, f64)) {
    let p = p_value_1d(
        name,
        seed,
        |u| {
            let x = s.sample(u);
            (x.x, Some(x.pdf))
        },
        |x| s.pdf(x),
        domain,
        50,
    );
    assert_fits(name, p);
}

#[test]
fn chi_square_uniform() {
    check_inverse_transform("uniform", 1, &Uniform { a: 0.0, b: 2.0 }, (0.0, 2.0));
}

#[test]
fn chi_square_linear() {
    check_inverse_transform("linear x/2", 2, &Linear, (0.0, 2.0));
}

#[test]
fn chi_square_quadratic() {
    check_inverse_transform("quadratic 3x^2/8", 3, &Quadratic, (0.0, 2.0));
}

#[test]
fn chi_square_exponential() {
    // 40 / rate leaves e^-40 of the mass outside: no sample lands there in 10^5.
    check_inverse_transform("exponential", 4, &Exponential { rate: 2.0 }, (0.0, 20.0));
}

/// The book's density tabulated in 64 bins: its own pdf is piecewise constant, so the 50 cells
/// straddle jumps and each cell is integrated in 64 pieces.
fn book_table() -> TabulatedCdf {
    TabulatedCdf::from_density(BookSinSquared::unnormalised, 0.0, std::f64::consts::TAU, 64)
        .unwrap()
}

#[test]
fn chi_square_tabulated_from_points() {
    // The classic program's table: F(x) = x³ at x = 0, 0.1, ..., 1.
    let points: Vec<(f64, f64)> = (0..=10)
        .map(|i| {
            let x = i as f64 / 10.0;
            (x, x * x * x)
        })
        .collect();
    let t = TabulatedCdf::from_points(&points).unwrap();
    check_inverse_transform("tabulated from points", 5, &t, (0.0, 1.0));
}

#[test]
fn chi_square_tabulated_binary_search() {
    check_inverse_transform(
        "binary search",
        6,
        &book_table(),
        (0.0, std::f64::consts::TAU),
    );
}

#[test]
fn chi_square_guide_table() {
    let g = GuideTable::new(book_table()).unwrap();
    check_inverse_transform("guide table", 7, &g, (0.0, std::f64::consts::TAU));
}

#[test]
fn chi_square_eytzinger() {
    let e = EytzingerCdf::new(&book_table());
    check_inverse_transform("eytzinger", 8, &e, (0.0, std::f64::consts::TAU));
}

#[test]
fn chi_square_alias_piecewise() {
    let a = AliasPiecewise::from_tabulated(&book_table()).unwrap();
    let p = p_value_1d(
        "alias piecewise",
        9,
        |u| {
            let s = a.sample(u);
            (s.x, Some(s.pdf))
        },
        |x| a.pdf(x),
        (0.0, std::f64::consts::TAU),
        50,
    );
    assert_fits("alias piecewise", p);
}

#[test]
fn chi_square_alias_discrete() {
    // Zero weights at both ends and inside: those cells expect 0, and a sample there fails.
    let weights = [0.0, 3.0, 0.5, 0.0, 0.0, 7.0, 1e-3, 2.0, 0.0, 4.0, 0.25, 0.0];
    let total: f64 = weights.iter().sum();
    let table = AliasTable::new(&weights).unwrap();
    let mut r = rng(10);
    let mut observed = vec![0.0; weights.len()];
    for _ in 0..SAMPLES {
        observed[r.sample(&table)] += 1.0;
    }
    let expected: Vec<f64> = weights.iter().map(|w| SAMPLES as f64 * w / total).collect();
    let result = chi_square(&observed, &expected).unwrap();
    assert_fits("alias discrete", result.p_value);
}

#[test]
fn chi_square_piecewise_2d() {
    // A 16 x 12 map with a zero row, a zero column and a bright spot; tested on 10 x 7 cells
    // that do not line up with the map's.
    let (nx, ny) = (16, 12);
    let weights: Vec<f64> = (0..nx * ny)
        .map(|k| {
            let (i, j) = (k % nx, k / nx);
            if j == 3 || i == 0 {
                0.0
            } else if (i, j) == (9, 7) {
                40.0
            } else {
                1.0 + (i as f64 * 0.7).sin().abs() * j as f64
            }
        })
        .collect();
    let map = PiecewiseConstant2D::new(&weights, nx, ny, (0.0, 2.0), (-1.0, 1.0)).unwrap();
    let (cx, cy) = (10, 7);
    let mut observed = vec![0.0; cx * cy];
    let mut r = rng(11);
    for _ in 0..SAMPLES {
        let s = map.sample(r.random(), r.random());
        assert!((s.pdf - map.pdf(s.x, s.y)).abs() <= 1e-9 * s.pdf, "{s:?}");
        let i = ((s.x / 2.0 * cx as f64) as usize).min(cx - 1);
        let j = (((s.y + 1.0) / 2.0 * cy as f64) as usize).min(cy - 1);
        observed[j * cx + i] += 1.0;
    }
    let mut expected = vec![0.0; cx * cy];
    for j in 0..cy {
        for i in 0..cx {
            let (x0, x1) = (2.0 * i as f64 / cx as f64, 2.0 * (i + 1) as f64 / cx as f64);
            let (y0, y1) = (
                -1.0 + 2.0 * j as f64 / cy as f64,
                -1.0 + 2.0 * (j + 1) as f64 / cy as f64,
            );
            let mass = rtl_sampling::integrate(
                |y| rtl_sampling::integrate(|x| map.pdf(x, y), x0, x1, 16),
                y0,
                y1,
                16,
            );
            expected[j * cx + i] = SAMPLES as f64 * mass;
        }
    }
    let result = chi_square(&observed, &expected).unwrap();
    assert_fits("piecewise 2D", result.p_value);
}

#[test]
fn chi_square_numeric_brent() {
    let t = BookSinSquared;
    let inv = NumericInverse::new(|x| t.cdf(x), 0.0, std::f64::consts::TAU)
        .unwrap()
        .with_tolerance(1e-10)
        .unwrap();
    let p = p_value_1d(
        "numeric inversion (Brent)",
        12,
        |u| (inv.invert(u).unwrap().x, None),
        |x| t.density(x),
        t.domain(),
        50,
    );
    assert_fits("numeric inversion (Brent)", p);
}

#[test]
fn chi_square_numeric_newton() {
    let t = BookSinSquared;
    let inv =
        NumericInverse::with_density(|x| t.cdf(x), |x| t.density(x), 0.0, std::f64::consts::TAU)
            .unwrap()
            .with_tolerance(1e-10)
            .unwrap();
    let p = p_value_1d(
        "numeric inversion (Newton)",
        13,
        |u| (inv.invert(u).unwrap().x, None),
        |x| t.density(x),
        t.domain(),
        50,
    );
    assert_fits("numeric inversion (Newton)", p);
}

// ANCHOR: wrong_sampler
#[test]
fn chi_square_rejects_a_wrong_sampler() {
    // Claims p(x) = x/2 on [0, 2] but returns 2u, which is uniform.
    let p = p_value_1d(
        "wrong sampler",
        14,
        |u| (2.0 * u, None),
        |x| Linear.pdf(x),
        (0.0, 2.0),
        50,
    );
    assert!(
        p < alpha(),
        "the checker accepted a uniform sampler for x/2: p = {p}"
    );
    // And a sampler that is right except for leaving the support is rejected outright.
    let leaky = |u: f64| if u < 1e-3 { 2.5 } else { Linear.sample(u).x };
    let mut r = rng(15);
    let xs: Vec<f64> = (0..SAMPLES).map(|_| leaky(r.random())).collect();
    let mut e = edges(0.0, 2.0, 50);
    e.push(3.0); // a cell outside the support, expected count 0 by the support, not by quadrature
    let (observed, _) = histogram(xs, &e);
    let mut expected = expected_counts(|x| Linear.pdf(x), &e[..51], SAMPLES as f64, 64);
    expected.push(0.0);
    // The first cell past 2 (cell 50) holds the leaked samples, and that is the reason given.
    assert!(matches!(
        chi_square(&observed, &expected),
        Err(ChiSquareError::SampleOutsideSupport { cell: 50, .. })
    ));
}
// ANCHOR_END: wrong_sampler
