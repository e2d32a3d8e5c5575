//! # Chapter 2, "Stratified Samples (Jittering)": estimate pi with one point per grid cell
//!
//! **Task.** Split the square [-1, 1]^2 into `sqrt_n x sqrt_n` equal cells and draw one uniform point
//! inside each cell (cell (i, j) spans x in [-1 + 2i/k, -1 + 2(i+1)/k), likewise y, with k = `sqrt_n`).
//! Return `4 * inside / sqrt_n^2`, the same estimator as [`estimate_pi`](crate::ch02_estimate_pi::estimate_pi)
//! but with stratified samples; `None` for `sqrt_n = 0`.
//!
//! Stratification keeps the estimator unbiased but only the cells cut by the circle contribute
//! variance, so its variance falls well below the binomial 16 p (1 - p) / N of independent points.
//! The check z-tests the mean of 400 estimates against pi, and tests (a chi-square test on the sample
//! variance, false failure 1e-6) that the variance is below that of independent points.
//!
//! Check your code with `rtl exercises check ch02_jittered_pi`; `rtl exercises hint ch02_jittered_pi` gives a hint.

use rand::Rng;

// ANCHOR: exercise
/// Estimate pi from one uniform point in each of the `sqrt_n x sqrt_n` cells of [-1, 1]^2;
/// `None` when `sqrt_n = 0`.
pub fn jittered_pi<R: Rng + ?Sized>(sqrt_n: usize, rng: &mut R) -> Option<f64> {
    let _ = (sqrt_n, rng);
    todo!("ch02 jittered_pi: one uniform point per cell of a sqrt_n x sqrt_n grid on [-1,1]^2")
}
// ANCHOR_END: exercise
