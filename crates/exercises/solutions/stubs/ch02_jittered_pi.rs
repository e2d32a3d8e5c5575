//! # Chapter 2, A Simple Monte Carlo Program, "Stratified samples (jittering)": estimate pi with one point per grid cell
//!
//! **Read first:** the section "Stratified samples (jittering)" of chapter 2
//! (`book/src/ch02-a-simple-monte-carlo-program.md`).
//!
//! **Task.** Write [`jittered_pi`]: split the square [-1, 1]^2 into `sqrt_n x sqrt_n` equal square
//! cells and draw one point uniformly inside each cell (not at its centre), then return the same
//! estimate of pi as [`estimate_pi`](crate::ch02_estimate_pi::estimate_pi) from those
//! `sqrt_n^2` points; `None` for `sqrt_n = 0`. Mind the last row and column of cells: together the
//! cells cover the whole square, once.
//!
//! Stratification keeps the estimator unbiased, but only the cells cut by the circle contribute
//! variance, so its variance falls well below that of as many independent points. The check z-tests
//! the mean of 400 estimates of 16 x 16 points against pi, and tests (a chi-square test on the sample
//! variance, false failure 1e-6) that their variance is below that of 256 independent points.
//!
//! Check your code with `cargo exercises check ch02_jittered_pi` (or
//! `rtl exercises check ch02_jittered_pi`, the same); `cargo exercises hint ch02_jittered_pi` gives
//! a hint.

use rand::Rng;

// ANCHOR: exercise
/// Estimate pi from one uniform point in each of the `sqrt_n x sqrt_n` cells of [-1, 1]^2;
/// `None` when `sqrt_n = 0`.
pub fn jittered_pi<R: Rng + ?Sized>(sqrt_n: usize, rng: &mut R) -> Option<f64> {
    let _ = (sqrt_n, rng);
    todo!("ch02 jittered_pi: one uniform point per cell of a sqrt_n x sqrt_n grid on [-1,1]^2")
}
// ANCHOR_END: exercise
