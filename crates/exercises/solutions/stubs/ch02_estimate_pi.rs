//! # Chapter 2, A Simple Monte Carlo Program, "Estimating π": estimate pi by throwing darts
//!
//! **Read first:** the section "Estimating π" of chapter 2
//! (`book/src/ch02-a-simple-monte-carlo-program.md`), which turns the fraction of random points
//! inside a circle into an estimate of pi.
//!
//! **Task.** Write [`estimate_pi`]: draw `n` points uniformly in the square [-1, 1]^2 (two
//! `rng.random_range(-1.0..1.0)` each), count the ones strictly inside the unit circle, and return
//! the estimate of pi that this count gives: a whole number of points times a constant, divided by
//! `n`. Return `None` for `n = 0`: no samples, no estimate.
//!
//! The check: `None` for n = 0; for n = 1, 2, 3, 10, 1000 an estimate that is a count scaled as
//! above; and the estimate from 1e5 points z-tested against pi at its binomial standard error (false
//! failure 1e-6).
//!
//! Check your code with `cargo exercises check ch02_estimate_pi` (or
//! `rtl exercises check ch02_estimate_pi`, the same); `cargo exercises hint ch02_estimate_pi` gives
//! a hint.

use rand::Rng;

// ANCHOR: exercise
/// Estimate pi from `n` points drawn uniformly in [-1, 1]^2 by the fraction inside the unit circle;
/// `None` when `n = 0`.
pub fn estimate_pi<R: Rng + ?Sized>(n: usize, rng: &mut R) -> Option<f64> {
    let _ = (n, rng);
    todo!("ch02 estimate_pi: pi from the points of [-1,1]^2 inside the unit circle")
}
// ANCHOR_END: exercise
