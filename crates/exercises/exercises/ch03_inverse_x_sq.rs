//! # Chapter 3, Inverse Transform Sampling, "Choosing our samples": sample x/2 and 3x^2/8 on [0, 2]
//!
//! **Read first:** the sections "Constructing a PDF" and "Choosing our samples" of the page Inverse
//! Transform Sampling (`book/src/ch03-inverse-transform-sampling.md`), which derive both samplers.
//!
//! **Task.** Turn a uniform `u` in [0, 1) into a sample x in [0, 2] of a given density (w.r.t.
//! length) by inverting its cumulative distribution function:
//!
//! - [`sample_linear`]: the density p(x) = x/2 on [0, 2];
//! - [`sample_quadratic`]: the density p(x) = 3x^2/8 on [0, 2].
//!
//! Each must be increasing in `u`, give exactly 0 at u = 0, and stay in [0, 2] (just below 2, never
//! above, never NaN) at the largest uniform u = 1 - 2^-53.
//!
//! The check: exact values x = P^-1(P(x)) at x = 0, 1/2 and 1 (P the CDF), the value at
//! u = 1 - 2^-53, monotonicity, and a chi-square test of 1e5 samples in 40 equal bins of [0, 2]
//! against n (P(b) - P(a)) per bin [a, b].
//!
//! Check your code with `cargo exercises check ch03_inverse_x_sq` (or
//! `rtl exercises check ch03_inverse_x_sq`, the same); `cargo exercises hint ch03_inverse_x_sq`
//! gives a hint.

// ANCHOR: exercise
/// A sample of the density x/2 on [0, 2] from a uniform `u` in [0, 1).
pub fn sample_linear(u: f64) -> f64 {
    let _ = u;
    todo!("ch03 sample_linear: a sample of the density x/2 on [0, 2], by inverse transform")
}

/// A sample of the density 3x^2/8 on [0, 2] from a uniform `u` in [0, 1).
pub fn sample_quadratic(u: f64) -> f64 {
    let _ = u;
    todo!("ch03 sample_quadratic: a sample of the density 3x^2/8 on [0, 2], by inverse transform")
}
// ANCHOR_END: exercise
