//! # Chapter 2, "Estimating Pi": estimate pi by throwing darts
//!
//! **Task.** Draw `n` points uniformly in the square [-1, 1]^2 and count the ones inside the unit
//! circle (x^2 + y^2 < 1). The fraction inside estimates the ratio of areas pi/4, so the estimate is
//! `4 * inside / n`. Return `None` for `n = 0`: no samples, no estimate.
//!
//! The count is binomial with p = pi/4, so the estimate has standard error 4 sqrt(p (1 - p) / n): the
//! check z-tests it against pi at that error, and checks that every estimate is a multiple of 4/n.
//!
//! Check your code with `rtl exercises check ch02_estimate_pi`; `rtl exercises hint ch02_estimate_pi` gives a hint.

use rand::Rng;

// ANCHOR: exercise
/// Estimate pi from `n` uniform points in [-1, 1]^2: `4 * (points inside the unit circle) / n`,
/// `None` when `n = 0`.
pub fn estimate_pi<R: Rng + ?Sized>(n: usize, rng: &mut R) -> Option<f64> {
    let _ = (n, rng);
    todo!("ch02 estimate_pi: count uniform points of [-1,1]^2 inside the unit circle")
}
// ANCHOR_END: exercise
