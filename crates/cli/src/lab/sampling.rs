//! The sampling bench (book chapters 3 and 7).
//!
//! **On a line**: a target density of `rtl study sampling` (the book's `e^(-x/2π) sin² x`, a truncated
//! normal, a spike on a base) or one of the book's densities with an inverse on paper (`x/2` and
//! `3x²/8` on `[0, 2]`), and a method: `analytic` (the inverse on paper), a table of `n` bins
//! searched by binary search, a guide table, an alias table, or numerical inversion at a tolerance.
//! The answer holds the histogram of the samples beside the expected counts (from the exact CDF), the
//! chi-square p-value of the histogram (`rtl_sampling::chi_square`: cells expecting fewer than 5
//! pooled), and the study's numbers: the maximum u-error `|F(x̂) - u|` over 4096 stratified `u`
//! (the study's numerical inversion's set; its figure takes tables at points in every bin instead)
//! and ns per sample (`Reference` and `time_per_sample` of `rtl study sampling`).
//!
//! **On the sphere**: a density of `rtl-pdf` (uniform sphere, uniform hemisphere, cosine, the book's
//! 50/50 cosine + sphere mixture, and the cosine warp with the factor-2 bug of the book's first
//! edition), binned in `(φ, cos θ)` cells of equal solid angle, against the expected counts of
//! `rtl_pdf::chi2` (adaptive quadrature of the density), and its chi-square p-value.

use super::params::{BadRequest, Query, bad, bad_param};
use crate::study::sampling::{Reference, time_per_sample};
use glam::{DVec2, DVec3};
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_pdf::chi2::{ChiSquareTest, SphereDomain};
use rtl_pdf::{CosinePdf, HemispherePdf, MixturePdf, Onb, Pdf, SpherePdf};
use rtl_sampling::analytic::{Linear, Quadratic};
use rtl_sampling::chi_square::{chi_square, histogram};
use rtl_sampling::numeric::NumericInverse;
use rtl_sampling::targets::{BookSinSquared, SpikeOnBase, TargetDensity, TruncatedNormal};
use rtl_sampling::{AliasPiecewise, GuideTable, Sample, TabulatedCdf};
use serde_json::{Value, json};
use std::f64::consts::PI;
use std::time::Instant;

/// Caps of one request.
pub const SAMPLES: (u64, u64) = (1_000, 2_000_000);
/// The most samples of numerical inversion (some targets take tens of microseconds a sample).
pub const NUMERIC_SAMPLES: u64 = 200_000;
pub const TABLE_BINS: (usize, usize) = (2, 1_000_000);
pub const HISTOGRAM_BINS: (usize, usize) = (8, 200);
pub const TOLERANCE: (f64, f64) = (1e-12, 1e-2);
pub const SPHERE_CELLS: (usize, usize) = (4, 40);

/// One of the book's densities with an inverse on paper, as a [`TargetDensity`].
struct OnPaper<S> {
    name: &'static str,
    s: S,
}

macro_rules! on_paper {
    ($t:ty) => {
        impl TargetDensity for OnPaper<$t> {
            fn name(&self) -> &'static str {
                self.name
            }
            fn domain(&self) -> (f64, f64) {
                (0.0, 2.0)
            }
            fn density(&self, x: f64) -> f64 {
                self.s.pdf(x)
            }
            fn cdf(&self, x: f64) -> f64 {
                self.s.invert(x.clamp(0.0, 2.0))
            }
            fn quantile(&self, u: f64) -> f64 {
                self.s.sample(u).x
            }
        }
    };
}
on_paper!(Linear);
on_paper!(Quadratic);

const LINEAR: OnPaper<Linear> = OnPaper {
    name: "linear",
    s: Linear,
};
const QUADRATIC: OnPaper<Quadratic> = OnPaper {
    name: "quadratic",
    s: Quadratic,
};

fn targets() -> [(&'static dyn TargetDensity, &'static str, bool); 5] {
    [
        (
            &BookSinSquared,
            "e^(-x/2pi) sin^2 x on [0, 2pi] (the book's)",
            false,
        ),
        (&TruncatedNormal, "standard normal on [-8, 8]", false),
        (&SpikeOnBase, "a narrow spike on a broad base", false),
        (&LINEAR, "x/2 on [0, 2] (the book's)", true),
        (&QUADRATIC, "3x^2/8 on [0, 2] (the book's)", true),
    ]
}

/// The 1D methods and which take a table size or a tolerance.
pub const METHODS: [&str; 5] = [
    "analytic",
    "binary_search",
    "guide_table",
    "alias",
    "numeric",
];

/// The page's menus.
pub fn list() -> Value {
    json!({
        "densities": targets().iter().map(|(t, about, analytic)| json!({
            "name": t.name(), "about": about, "analytic": analytic, "domain": t.domain(),
        })).collect::<Vec<_>>(),
        "methods": METHODS,
        "directions": DIRECTIONS.iter().map(|(n, about)| json!({"name": n, "about": about})).collect::<Vec<_>>(),
        "caps": {
            "samples": SAMPLES, "numeric_samples": NUMERIC_SAMPLES, "n": TABLE_BINS, "bins": HISTOGRAM_BINS,
            "tolerance": TOLERANCE, "cells": SPHERE_CELLS,
        },
    })
}

/// A numerical inverse behind a plain function of `u` (the study's `u` are all in range).
fn numeric_x<F: Fn(f64) -> f64, P: Fn(f64) -> f64>(inv: &NumericInverse<F, P>, u: f64) -> f64 {
    inv.invert(u).map_or(f64::NAN, |r| r.x)
}

/// `?density=NAME&method=M&n=BINS&tolerance=T&samples=S&bins=H&seed=K`
pub fn run_line(query: &str) -> Result<Value, BadRequest> {
    let q = Query::parse(
        query,
        &[
            "density",
            "method",
            "n",
            "tolerance",
            "samples",
            "bins",
            "seed",
        ],
    )?;
    let names: Vec<&str> = targets().iter().map(|t| t.0.name()).collect();
    let name = q.choice("density", "book_sin2", &names)?;
    let (target, _, has_analytic) = targets()
        .into_iter()
        .find(|t| t.0.name() == name)
        .expect("a listed name");
    let method = q.choice("method", "binary_search", &METHODS)?;
    let n = q.number("n", 1000usize, TABLE_BINS.0, TABLE_BINS.1)?;
    let tolerance = q.number("tolerance", 1e-8, TOLERANCE.0, TOLERANCE.1)?;
    let samples = q.number("samples", 100_000u64, SAMPLES.0, SAMPLES.1)?;
    let bins = q.number("bins", 64usize, HISTOGRAM_BINS.0, HISTOGRAM_BINS.1)?;
    let seed = q.number("seed", 1u64, 0, u64::MAX)?;
    if method == "numeric" && samples > NUMERIC_SAMPLES {
        return Err(bad_param(
            "samples",
            format!(
                "`samples={samples}`: numerical inversion takes at most {NUMERIC_SAMPLES} samples"
            ),
        ));
    }
    if method == "analytic" && !has_analytic {
        return Err(bad_param(
            "method",
            format!(
                "`method=analytic`: {name} has no inverse on paper; the densities that have one: linear, quadratic"
            ),
        ));
    }

    let (a, b) = target.domain();
    let density = |x: f64| target.density(x);
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(2024);
    let reference = Reference::new(target, &mut rng);
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let us: Vec<f64> = (0..samples).map(|_| rng.random::<f64>()).collect();

    let t = Instant::now();
    let table = matches!(method, "binary_search" | "guide_table" | "alias")
        .then(|| TabulatedCdf::from_density(density, a, b, n))
        .transpose()
        .map_err(|e| bad_param("n", format!("table of {n} bins: {e}")))?;
    let sampler: Box<dyn Fn(f64) -> Sample> = match method {
        "analytic" => Box::new(|u| Sample {
            x: target.quantile(u),
            pdf: target.density(target.quantile(u)),
        }),
        "binary_search" => {
            let table = table.clone().expect("built above");
            Box::new(move |u| table.sample(u))
        }
        "guide_table" => {
            let guide = GuideTable::new(table.clone().expect("built above"))
                .map_err(|e| bad(format!("guide table: {e}")))?;
            Box::new(move |u| guide.sample(u))
        }
        "alias" => {
            let alias = AliasPiecewise::from_tabulated(table.as_ref().expect("built above"))
                .map_err(|e| bad(format!("alias table: {e}")))?;
            Box::new(move |u| alias.sample(u))
        }
        _ => {
            let inv = NumericInverse::with_density(move |x| target.cdf(x), density, a, b)
                .and_then(|i| i.with_tolerance(tolerance))
                .map_err(|e| bad_param("tolerance", format!("numerical inversion: {e}")))?;
            Box::new(move |u| {
                let x = numeric_x(&inv, u);
                Sample {
                    x,
                    pdf: target.density(x),
                }
            })
        }
    };
    let build_ms = t.elapsed().as_secs_f64() * 1e3;
    let ns_per_sample = time_per_sample(&us, &sampler);

    // The error of the method's inverse over 4096 stratified `u`, as the study measures numerical
    // inversion's (a request's answer must be quick; the alias table is not an
    // inversion: its u-error is that of the table whose distribution it samples).
    let (u_error, x_error) = match &table {
        Some(t) => {
            let (eu, ex) = reference.errors(target, |u| t.sample(u).x);
            (eu, (method != "alias").then_some(ex))
        }
        None => {
            let (eu, ex) = reference.errors(target, |u| sampler(u).x);
            (eu, Some(ex))
        }
    };

    // The last edge is `b` itself: a sample at `b` is inside.
    let edges: Vec<f64> = (0..=bins)
        .map(|i| a + (b - a) * i as f64 / bins as f64)
        .collect();
    let (observed, outside) = histogram(us.iter().map(|&u| sampler(u).x), &edges);
    let expected: Vec<f64> = edges
        .windows(2)
        .map(|e| samples as f64 * (target.cdf(e[1]) - target.cdf(e[0])).max(0.0))
        .collect();
    let chi2 = chi_square(&observed, &expected).map_err(|e| bad(format!("chi-square: {e}")))?;
    // A sample outside the domain (or NaN) fails the test outright, as in `ChiSquareTest::run`.
    let p_value = if outside > 0 { 0.0 } else { chi2.p_value };
    let curve: Vec<(f64, f64)> = (0..=400)
        .map(|i| {
            let x = a + (b - a) * i as f64 / 400.0;
            (x, target.density(x))
        })
        .collect();
    Ok(json!({
        "density": name, "method": method, "domain": [a, b],
        "n": table.as_ref().map(|_| n), "tolerance": (method == "numeric").then_some(tolerance),
        "samples": samples, "bins": observed, "expected": expected, "outside_domain": outside, "curve": curve,
        "u_error": u_error, "x_error": x_error,
        "ns_per_sample": ns_per_sample, "build_ms": build_ms,
        "chi2": { "statistic": chi2.statistic, "dof": chi2.dof, "p_value": p_value, "pooled": chi2.pooled },
    }))
}

/// The densities of directions.
pub const DIRECTIONS: [(&str, &str); 5] = [
    ("sphere", "uniform on the sphere, 1/4pi"),
    ("hemisphere", "uniform on the hemisphere, 1/2pi"),
    ("cosine", "cosine-weighted, cos(theta)/pi"),
    ("mixture", "the book's 50/50 mixture of cosine and sphere"),
    (
        "cosine_bug",
        "cosine samples claiming cos(theta)/2pi: the factor-2 bug (a wrong pdf, to see the test fail)",
    ),
];

/// A density of directions that reports one density and samples by another, for the bug case.
struct Claims<P> {
    samples: P,
    factor: f64,
}

impl<P: Pdf> Pdf for Claims<P> {
    fn pdf(&self, d: DVec3) -> f64 {
        self.factor * self.samples.pdf(d)
    }
    fn sample(&self, u: DVec2) -> Option<rtl_pdf::DirectionSample> {
        let s = self.samples.sample(u)?;
        rtl_pdf::DirectionSample::new(s.direction, self.factor * s.pdf)
    }
}

/// `?pdf=NAME&samples=S&cells=C&seed=K`: `C` cells in cos theta by `C` in phi.
pub fn run_sphere(query: &str) -> Result<Value, BadRequest> {
    let q = Query::parse(query, &["pdf", "samples", "cells", "seed"])?;
    let names: Vec<&str> = DIRECTIONS.iter().map(|d| d.0).collect();
    let name = q.choice("pdf", "cosine", &names)?;
    let samples = q.number("samples", 100_000u64, SAMPLES.0, SAMPLES.1)?;
    let cells = q.number("cells", 20usize, SPHERE_CELLS.0, SPHERE_CELLS.1)?;
    let seed = q.number("seed", 1u64, 0, u64::MAX)?;
    let z = DVec3::Z;
    match name {
        "sphere" => sphere_histogram(SpherePdf, false, samples, cells, seed),
        "hemisphere" => sphere_histogram(HemispherePdf::new(z), true, samples, cells, seed),
        "cosine" => sphere_histogram(CosinePdf::new(z), true, samples, cells, seed),
        "mixture" => sphere_histogram(
            MixturePdf::new(CosinePdf::new(z), SpherePdf),
            false,
            samples,
            cells,
            seed,
        ),
        _ => sphere_histogram(
            Claims {
                samples: CosinePdf::new(z),
                factor: 0.5,
            },
            true,
            samples,
            cells,
            seed,
        ),
    }
}

fn sphere_histogram<P: Pdf>(
    pdf: P,
    upper_only: bool,
    samples: u64,
    cells: usize,
    seed: u64,
) -> Result<Value, BadRequest> {
    let domain = SphereDomain(Onb::new(DVec3::Z));
    let test = ChiSquareTest::new(cells, cells);
    // Hemisphere densities: the cells below the horizon (y < 1/2) expect nothing.
    let support = |_lo: DVec2, hi: DVec2| !upper_only || hi.y > 0.5;
    let n = samples as usize;
    let probs = test
        .expected(&domain, |d| pdf.value(d), support, n)
        .map_err(|e| bad(format!("{e}")))?;
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed);
    let t = Instant::now();
    let dirs: Vec<DVec3> = (0..n).map(|_| pdf.generate(&mut rng)).collect();
    let ns_per_sample = t.elapsed().as_secs_f64() * 1e9 / n as f64;
    let mut observed = vec![0u64; cells * cells];
    use rtl_pdf::chi2::Domain as _;
    for d in &dirs {
        if let Some(x) = domain.to_square(*d) {
            let ix = ((x.x * cells as f64) as usize).min(cells - 1);
            let iy = ((x.y * cells as f64) as usize).min(cells - 1);
            observed[iy * cells + ix] += 1;
        }
    }
    let expected: Vec<f64> = probs.iter().map(|p| p * n as f64).collect();
    // Samples in cells that expect none fail outright, as in `ChiSquareTest::run`.
    let outside: u64 = observed
        .iter()
        .zip(&probs)
        .filter(|(_, p)| **p == 0.0)
        .map(|(o, _)| *o)
        .sum();
    let report = test
        .statistic(&observed, &expected, n)
        .map_err(|e| bad(format!("{e}")))?;
    let p_value = if outside > 0 { 0.0 } else { report.p_value };
    Ok(json!({
        "cells": cells, "samples": samples, "observed": observed, "expected": expected,
        "statistic": report.statistic, "dof": report.dof, "p_value": p_value,
        "outside_support": outside, "expected_fraction": report.expected_fraction,
        "ns_per_sample": ns_per_sample, "pi": PI,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_right_sampler_passes_and_a_wrong_one_fails() {
        let good = run_sphere("pdf=cosine&samples=20000&cells=10").unwrap();
        assert!(good["p_value"].as_f64().unwrap() > 1e-4);
        let bad = run_sphere("pdf=cosine_bug&samples=20000&cells=10").unwrap();
        assert!(bad["p_value"].as_f64().unwrap() < 1e-10);
        let line = run_line("density=quadratic&method=analytic&samples=20000&bins=20").unwrap();
        assert!(line["u_error"].as_f64().unwrap() < 1e-12);
        assert!(line["chi2"]["p_value"].as_f64().unwrap() > 1e-4);
        // 4 bins of the book's density are visibly not the density.
        let coarse = run_line("density=book_sin2&method=alias&n=4&samples=200000&bins=40").unwrap();
        assert!(coarse["chi2"]["p_value"].as_f64().unwrap() < 1e-10);
    }

    #[test]
    fn refuses_bad_requests() {
        for q in [
            "density=book_sin2&method=analytic",
            "density=nope",
            "method=quicksort",
            "n=1",
            "n=99999999",
            "samples=10",
            "bins=100000",
            "tolerance=0",
            "tolerance=abc",
            "density=normal&method=numeric&samples=200001",
        ] {
            assert!(run_line(q).is_err(), "{q}");
        }
        for q in ["pdf=nope", "cells=1000", "samples=0", "what=1"] {
            assert!(run_sphere(q).is_err(), "{q}");
        }
    }
}
