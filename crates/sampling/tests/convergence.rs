//! Tabulated inversion against the exact quantile of the book's `e^(-x/2π) sin² x` on `[0, 2π]`:
//! the error must shrink at the rate the method promises, measured as a log-log slope over
//! N = 2⁶ … 2¹⁴ bins, not as one value.
//!
//! The norm: the maximum over u in [0, 1] of the error of `T⁻¹(u)` (T the tabulated CDF), taken
//! at u = T(x) for 16 equally spaced x in every bin (so no bin escapes the maximum).
//! * u-error `|F(T⁻¹(u)) - u| = |F(x) - T(x)|`: the linear interpolant of a smooth CDF errs by
//!   `h² max|F''| / 8`, so the slope is -2.
//! * x-error `|T⁻¹(u) - F⁻¹(u)|`: near a zero of the density `F` is flat, a u-error is magnified
//!   by `1/p`. At x = π, `p ≈ c (x - π)²` and `F` is locally cubic; inside a bin of width h the
//!   inverse of a cubic departs from a straight line by about 0.38 h, so the slope is only -1.

use rtl_sampling::TabulatedCdf;
use rtl_sampling::targets::{BookSinSquared, TargetDensity};
use std::f64::consts::TAU;

/// Least-squares slope of log y against log x.
fn slope(points: &[(f64, f64)]) -> f64 {
    let logs: Vec<(f64, f64)> = points.iter().map(|(x, y)| (x.ln(), y.ln())).collect();
    let n = logs.len() as f64;
    let mx = logs.iter().map(|p| p.0).sum::<f64>() / n;
    let my = logs.iter().map(|p| p.1).sum::<f64>() / n;
    let sxy: f64 = logs.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = logs.iter().map(|p| (p.0 - mx).powi(2)).sum();
    sxy / sxx
}

/// (max u-error, max x-error) of a table of `n` bins.
fn errors(n: usize) -> (f64, f64) {
    let target = BookSinSquared;
    let table = TabulatedCdf::from_density(BookSinSquared::unnormalised, 0.0, TAU, n).unwrap();
    let (mut u_err, mut x_err) = (0.0f64, 0.0f64);
    let edges = table.nodes();
    for bin in 0..n {
        for k in 0..16 {
            let x = edges[bin] + (edges[bin + 1] - edges[bin]) * k as f64 / 16.0;
            let u = table.invert(x);
            u_err = u_err.max((target.cdf(x) - u).abs());
            x_err = x_err.max((x - target.quantile(u)).abs());
        }
    }
    (u_err, x_err)
}

#[test]
fn tabulated_inversion_converges_at_the_promised_rates() {
    let ns: Vec<usize> = (6..=14).map(|k| 1 << k).collect();
    let errs: Vec<(f64, f64, f64)> = ns
        .iter()
        .map(|&n| {
            let (u, x) = errors(n);
            (n as f64, u, x)
        })
        .collect();
    for e in &errs {
        eprintln!(
            "N = {:6}: max u-error {:.3e}, max x-error {:.3e}",
            e.0, e.1, e.2
        );
    }
    let su = slope(&errs.iter().map(|e| (e.0, e.1)).collect::<Vec<_>>());
    let sx = slope(&errs.iter().map(|e| (e.0, e.2)).collect::<Vec<_>>());
    eprintln!("slopes: u-error {su:.3}, x-error {sx:.3}");
    assert!((su + 2.0).abs() < 0.1, "u-error slope {su}, expected -2");
    assert!((sx + 1.0).abs() < 0.1, "x-error slope {sx}, expected -1");
    // At the largest N the x-error is dominated by the bins at the density's zeros: a constant
    // fraction of a bin width there (≈ 0.385 h for a cubic CDF).
    let h = TAU / *ns.last().unwrap() as f64;
    let last = errs.last().unwrap();
    assert!(
        last.2 > 0.2 * h && last.2 < 0.5 * h,
        "x-error {} vs bin width {h}",
        last.2
    );
}
