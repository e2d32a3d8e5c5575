//! Every `invert` tested as the inverse of its `sample` at the values of `u` where an inverse is
//! most likely to slip: `u = 0`, `1/2` and `1 - 2⁻⁵³` (the largest `u` a generator gives), for the
//! analytic densities, tabulated CDFs with bins of probability 0 at the start, the middle and the
//! end (binary search, guide table, Eytzinger layout) and the 2D map. Each sample must also carry
//! the density that `pdf` gives its point, positive and finite.

use rtl_sampling::analytic::{Exponential, Linear, Quadratic, Uniform};
use rtl_sampling::{
    EytzingerCdf, GuideTable, InverseTransform, ONE_MINUS_EPSILON, PiecewiseConstant2D,
    TabulatedCdf,
};

const US: [f64; 3] = [0.0, 0.5, ONE_MINUS_EPSILON];

/// `invert(sample(u).x)` is `u` to `tol`, and the sample's density is `pdf` of its point.
fn assert_inverse(name: &str, s: &dyn InverseTransform, tol: f64) {
    for u in US {
        let sample = s.sample(u);
        let back = s.invert(sample.x);
        assert!(
            (back - u).abs() <= tol,
            "{name}: u = {u} -> x = {} -> {back}",
            sample.x
        );
        assert!(
            sample.pdf > 0.0 && sample.pdf.is_finite() && sample.pdf == s.pdf(sample.x),
            "{name}: u = {u}: {sample:?} but pdf(x) = {}",
            s.pdf(sample.x)
        );
    }
}

#[test]
fn analytic_inverses_return_u_at_zero_half_and_one_minus_epsilon() {
    // `Linear` and `Quadratic` draw u = 0 as the smallest normal u (so that x > 0, where the
    // density is positive): their inverse gives back that u, within 3e-308 of 0.
    assert_inverse("uniform", &Uniform::new(-1.0, 3.0).unwrap(), f64::EPSILON);
    assert_inverse("linear", &Linear, f64::EPSILON);
    assert_inverse("quadratic", &Quadratic, f64::EPSILON);
    assert_inverse("exponential", &Exponential::new(1.5).unwrap(), f64::EPSILON);
    assert_inverse(
        "exponential, fast",
        &Exponential::new(1e300).unwrap(),
        f64::EPSILON,
    );
}

#[test]
fn tabulated_inverses_return_u_at_zero_half_and_one_minus_epsilon() {
    let edges = [0.0, 0.5, 1.0, 1.5, 2.5, 3.0, 4.0];
    for weights in [
        [1.0, 2.0, 3.0, 1.0, 0.5, 2.0],
        [0.0, 2.0, 3.0, 1.0, 0.5, 2.0], // a first bin that u = 0 must skip
        [1.0, 2.0, 0.0, 0.0, 0.5, 2.0], // empty bins in the middle
        [1.0, 2.0, 3.0, 1.0, 0.0, 0.0], // empty bins that u = 1 - 2⁻⁵³ must not reach
        [0.0, 0.0, 1.0, 1.0, 0.0, 0.0], // F = 1/2 falls on a node
    ] {
        let table = TabulatedCdf::from_edges_and_weights(&edges, &weights).unwrap();
        let name = format!("{weights:?}");
        assert_inverse(&format!("binary search {name}"), &table, f64::EPSILON);
        let guide = GuideTable::new(table.clone()).unwrap();
        assert_inverse(&format!("guide table {name}"), &guide, f64::EPSILON);
        let tree = EytzingerCdf::new(&table);
        assert_inverse(&format!("Eytzinger {name}"), &tree, f64::EPSILON);
    }
}

#[test]
fn the_2d_inverse_returns_both_u_at_zero_half_and_one_minus_epsilon() {
    // 3 rows of 4 cells; an empty row first and an empty column last.
    let weights = [
        0.0, 0.0, 0.0, 0.0, //
        1.0, 2.0, 3.0, 0.0, //
        4.0, 1.0, 1.0, 0.0,
    ];
    let map = PiecewiseConstant2D::new(&weights, 4, 3, (-1.0, 1.0), (0.0, 3.0)).unwrap();
    for u1 in US {
        for u2 in US {
            let s = map.sample(u1, u2);
            let (b1, b2) = map.invert(s.x, s.y);
            assert!(
                (b1 - u1).abs() <= f64::EPSILON && (b2 - u2).abs() <= f64::EPSILON,
                "({u1}, {u2}) -> {s:?} -> ({b1}, {b2})"
            );
            assert!(
                s.pdf > 0.0 && s.pdf == map.pdf(s.x, s.y),
                "({u1}, {u2}): {s:?} but pdf = {}",
                map.pdf(s.x, s.y)
            );
        }
    }
}
