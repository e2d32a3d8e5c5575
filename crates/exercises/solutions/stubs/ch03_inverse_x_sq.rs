//! # Chapter 3, "Inverse Transform Sampling": sample x/2 and 3x^2/8 on [0, 2]
//!
//! **Task.** Turn a uniform `u` in [0, 1) into a sample of a density on [0, 2] by inverting its CDF:
//!
//! - [`sample_linear`]: density p(x) = x/2, CDF P(x) = x^2/4, so x = P^-1(u) = 2 sqrt(u);
//! - [`sample_quadratic`]: density p(x) = 3x^2/8, CDF P(x) = x^3/8, so x = 2 cbrt(u).
//!
//! Both must be monotone in `u`, give 0 at u = 0 and stay in [0, 2] up to u = 1 - 2^-53. The check
//! compares exact values, then bins 1e5 samples into 40 equal bins of [0, 2] and chi-square tests
//! the counts against n (P(b) - P(a)).
//!
//! Check your code with `rtl exercises check ch03_inverse_x_sq`; `rtl exercises hint ch03_inverse_x_sq` gives a hint.

// ANCHOR: exercise
/// A sample of the density x/2 on [0, 2] from a uniform `u` in [0, 1).
pub fn sample_linear(u: f64) -> f64 {
    let _ = u;
    todo!("ch03 sample_linear: invert the CDF x^2/4 of the density x/2 on [0,2]")
}

/// A sample of the density 3x^2/8 on [0, 2] from a uniform `u` in [0, 1).
pub fn sample_quadratic(u: f64) -> f64 {
    let _ = u;
    todo!("ch03 sample_quadratic: invert the CDF x^3/8 of the density 3x^2/8 on [0,2]")
}
// ANCHOR_END: exercise
