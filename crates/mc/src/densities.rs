//! The book's densities for the integral of `x^2` on `[0, 2]` (chapter 3): each sampler, a warp of a
//! uniform `u` in `[0, 1)` by the inverse of its CDF, sits beside its pdf.
//!
//! Both samplers use `1 - u` rather than `u`: for `u` in `[0, 1)` that lies in `(0, 1]`, so `x` is never
//! 0 and `f(x) / p(x) = 0 / 0` cannot happen. (The f64 values `rand` draws are multiples of `2^-53`, so
//! `1 - u` is exact.)

// ANCHOR: linear
/// The density `p(x) = x / 2` on `[0, 2]` (0 outside).
pub fn linear_pdf(x: f64) -> f64 {
    if (0.0..=2.0).contains(&x) {
        x / 2.0
    } else {
        0.0
    }
}

/// Samples `p(x) = x / 2`: its CDF is `P(x) = x^2 / 4`, so `x = P^-1(1 - u) = 2 sqrt(1 - u)`.
pub fn sample_linear(u: f64) -> f64 {
    2.0 * (1.0 - u).sqrt()
}
// ANCHOR_END: linear

// ANCHOR: perfect
/// The density `p(x) = 3 x^2 / 8` on `[0, 2]` (0 outside): exactly proportional to `f(x) = x^2`, so
/// `f / p = 8 / 3` for every sample and the estimator has zero variance.
///
/// Written as `0.375 * (x * x)` so that `f / p = (x * x) / (0.375 * (x * x))` rounds to within 2 ulp
/// of 8/3 for every `x` the sampler can produce.
pub fn perfect_pdf(x: f64) -> f64 {
    if (0.0..=2.0).contains(&x) {
        0.375 * (x * x)
    } else {
        0.0
    }
}

/// Samples `p(x) = 3 x^2 / 8`: its CDF is `x^3 / 8`, so `x = 2 (1 - u)^(1/3)`, which lies in
/// `[2 * 2^(-53/3), 2]`, about `[4.8e-6, 2]`.
///
/// ```
/// use rtl_mc::densities::{perfect_pdf, sample_perfect};
/// let x = sample_perfect(0.0);
/// assert_eq!(x, 2.0);
/// assert_eq!(x * x / perfect_pdf(x), 8.0 / 3.0);
/// ```
pub fn sample_perfect(u: f64) -> f64 {
    2.0 * (1.0 - u).cbrt()
}
// ANCHOR_END: perfect
