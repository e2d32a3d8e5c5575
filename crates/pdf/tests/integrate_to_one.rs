//! Every pdf integrates to 1 over the sphere, `generate` returns unit vectors, and `value` is never
//! negative or NaN.
//!
//! The integral is `E[4 pi value(d)]` over uniform directions `d`, checked by a z-test at a false
//! failure rate of 1e-6 (`|z| < 4.89`; a standard error of 0 demands equality to a few ulp), and, where
//! the uniform estimator would be useless (a far, tiny light), by quadrature in the light's own domain.

use glam::{DVec2, DVec3};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_mc::RunningStats;
use rtl_pdf::chi2::{ChiSquareTest, ConeDomain, ParallelogramDomain};
use rtl_pdf::warp;
use rtl_pdf::{
    CosinePdf, HemispherePdf, HittablePdf, MixtureOfPdfs, MixturePdf, Onb, Pdf, QuadTarget,
    Selection, SpherePdf, SphereTarget, SphereView,
};
use std::f64::consts::PI;

const Z_CRIT: f64 = 4.89; // two-sided 1e-6

fn rng(seed: u64) -> Xoshiro256PlusPlus {
    Xoshiro256PlusPlus::seed_from_u64(seed)
}

/// Checks unit length, finiteness and sign of `value` on generated and on uniform directions, and
/// the z-test of `E[4 pi value]` = 1 over `n` uniform directions.
fn check<P: Pdf>(name: &str, pdf: &P, seed: u64, n: usize) {
    let mut r = rng(seed);
    for _ in 0..10_000 {
        let d = pdf.generate(&mut r);
        assert!(
            d.is_finite() && (d.length() - 1.0).abs() < 1e-12,
            "{name}: generated {d}"
        );
        let v = pdf.value(d);
        assert!(
            v.is_finite() && v > 0.0,
            "{name}: value {v} of a generated direction"
        );
    }
    let mut stats = RunningStats::new();
    for _ in 0..n {
        let d = warp::sample_uniform_sphere(DVec2::new(r.random(), r.random()));
        let v = pdf.value(d);
        assert!(v.is_finite() && v >= 0.0, "{name}: value {v} at {d}");
        stats.push(4.0 * PI * v);
    }
    let (mean, se) = (stats.mean(), stats.std_error().expect("n >= 2"));
    if se == 0.0 {
        assert!(
            (mean - 1.0).abs() < 1e-12,
            "{name}: constant estimate {mean} is not 1"
        );
    } else {
        let z = (mean - 1.0) / se;
        assert!(
            z.abs() < Z_CRIT,
            "{name}: E[4 pi value] = {mean} +- {se} (z = {z:.2})"
        );
    }
}

fn tilted() -> DVec3 {
    DVec3::new(-0.2, 0.4, 0.7).normalize()
}

/// A density 1% too large everywhere: what the check exists to catch.
struct OnePercentHeavy(CosinePdf);

impl Pdf for OnePercentHeavy {
    fn pdf(&self, direction: DVec3) -> f64 {
        1.01 * self.0.pdf(direction)
    }
    fn sample(&self, u: glam::DVec2) -> Option<rtl_pdf::DirectionSample> {
        self.0.sample(u)
    }
}

#[test]
#[should_panic(expected = "E[4 pi value]")]
fn a_density_that_integrates_to_1_01_is_caught() {
    // z is about 7.7 at 1e6 samples: far beyond 4.89.
    check(
        "cosine x 1.01",
        &OnePercentHeavy(CosinePdf::new(tilted())),
        3,
        1_000_000,
    );
}

#[test]
fn sphere_pdf_integrates_to_one() {
    check("SpherePdf", &SpherePdf, 1, 100_000);
}

#[test]
fn hemisphere_pdf_integrates_to_one() {
    check("HemispherePdf", &HemispherePdf::new(tilted()), 2, 1_000_000);
}

#[test]
fn cosine_pdf_integrates_to_one() {
    check("CosinePdf", &CosinePdf::new(tilted()), 3, 1_000_000);
}

#[test]
fn mixture_pdf_integrates_to_one() {
    check(
        "MixturePdf",
        &MixturePdf::new(CosinePdf::new(tilted()), SpherePdf),
        4,
        1_000_000,
    );
    let table = Selection::from_weights(&[2.0, 1.0, 1.0]).unwrap();
    let parts = [
        CosinePdf::new(DVec3::Z),
        CosinePdf::new(-DVec3::Z),
        CosinePdf::new(tilted()),
    ];
    check(
        "MixtureOfPdfs",
        &MixtureOfPdfs::new(&parts, &table).unwrap(),
        5,
        1_000_000,
    );
}

#[test]
fn sphere_light_pdf_integrates_to_one_near_inside_and_far() {
    let lights = [SphereTarget::new(DVec3::new(0.0, 1.0, 2.0), 1.0)];
    for (i, o) in [
        DVec3::new(0.0, 1.0, 0.5),
        DVec3::new(0.2, 0.9, 2.3),
        DVec3::new(-2.0, 0.0, 0.0),
    ]
    .into_iter()
    .enumerate()
    {
        check(
            "HittablePdf(sphere)",
            &HittablePdf::new(o, &lights).unwrap(),
            10 + i as u64,
            1_000_000,
        );
    }
    // far: the cone is 3e-8 sr; integrate in the cone by quadrature
    let o = DVec3::new(0.0, 1.0, 2.0 - 1e4);
    let pdf = HittablePdf::new(o, &lights).unwrap();
    let SphereView::Cone {
        axis,
        one_minus_cos_max,
    } = lights[0].view(o)
    else {
        panic!("outside")
    };
    let domain = ConeDomain {
        frame: Onb::new(axis),
        one_minus_cos_max,
    };
    let total: f64 = ChiSquareTest::new(4, 4)
        .expected(&domain, |d| pdf.value(d), |_, _| true, 1000)
        .unwrap()
        .iter()
        .sum();
    assert!((total - 1.0).abs() < 1e-9, "far sphere: {total}");
}

#[test]
fn quad_light_pdf_integrates_to_one_by_area_and_by_spherical_rectangles() {
    let (q, u, v) = (
        DVec3::new(-1.0, -0.5, 1.0),
        DVec3::new(2.0, 0.0, 0.0),
        DVec3::new(0.0, 1.5, 0.0),
    );
    for spherical in [false, true] {
        let lights = [QuadTarget::new(q, u, v).with_spherical_rectangles(spherical)];
        for (i, o) in [DVec3::new(0.1, 0.2, 0.0), DVec3::new(2.0, 1.0, 0.9)]
            .into_iter()
            .enumerate()
        {
            let pdf = HittablePdf::new(o, &lights).unwrap();
            check(
                "HittablePdf(quad)",
                &pdf,
                20 + i as u64 + 2 * spherical as u64,
                1_000_000,
            );
            let domain = ParallelogramDomain {
                origin: o,
                q,
                e1: u,
                e2: v,
            };
            let total: f64 = ChiSquareTest::new(8, 8)
                .expected(&domain, |d| pdf.value(d), |_, _| true, 1_000_000)
                .unwrap()
                .iter()
                .sum();
            assert!(
                (total - 1.0).abs() < 1e-9,
                "quad from {o} (spherical: {spherical}): {total}"
            );
        }
    }
}
