//! # Chapter 12, Cleaning Up PDF Management, "The pitfalls as tests": keep NaNs out of a pixel
//!
//! **Read first:** the section "The pitfalls as tests" of chapter 12
//! (`book/src/ch12-cleaning-up-pdf-management.md`), the row `pitfall_a_nan_sample_in_a_pixel`.
//!
//! One NaN sample (0/0 from a degenerate pdf) makes a pixel's sum NaN, and the pixel black or garbage
//! for ever; one infinite sample makes it white. The book replaces NaN components by 0 before
//! averaging, which darkens the pixel: it divides by a count that includes the discarded sample.
//!
//! **Task.** Write [`PixelAccumulator::add`] and [`PixelAccumulator::mean`]: `add` drops a sample with
//! any non-finite component (counting it in `dropped`) and otherwise folds it into the mean of the
//! finite samples (counting it in `used`); `mean` returns that mean, or `None` when no finite sample
//! arrived. Keep a running mean, updated sample by sample, rather than a sum: a sum of large finite
//! samples can overflow to infinity, a running mean stays finite.
//!
//! The check: constant samples 0.5 for 1, 2, 10, 16 and 1000 samples average to exactly 0.5 (a dyadic
//! value, exact in floating point); one NaN, +inf, -inf or NaN-in-one-channel sample among 100 (first,
//! middle or last) leaves the mean exactly 0.5 and is counted; [1, 2, 3, 4] average to exactly 2.5;
//! two samples of 1e308 average to 1e308; no samples, or only bad ones, give `None`.
//!
//! Check your code with `cargo exercises check ch12_nan_guard` (or
//! `rtl exercises check ch12_nan_guard`, the same); `cargo exercises hint ch12_nan_guard` gives a
//! hint.

use glam::DVec3;

/// The running estimate of one pixel: the mean of its finite samples, and how many were used or dropped.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PixelAccumulator {
    /// The mean of the finite samples so far (zero before the first).
    pub mean: DVec3,
    /// How many finite samples the mean includes.
    pub used: u64,
    /// How many non-finite samples were dropped.
    pub dropped: u64,
}

// ANCHOR: exercise
impl PixelAccumulator {
    /// An empty accumulator.
    pub fn new() -> Self {
        Self::default()
    }

    /// Fold `sample` into the running mean if all its components are finite; otherwise count it as
    /// dropped.
    pub fn add(&mut self, sample: DVec3) {
        let _ = sample;
        todo!(
            "ch12 PixelAccumulator::add: drop (and count) non-finite samples, keep a running mean"
        )
    }

    /// The mean of the finite samples, `None` if there were none.
    pub fn mean(&self) -> Option<DVec3> {
        todo!("ch12 PixelAccumulator::mean: the running mean, None without finite samples")
    }
}
// ANCHOR_END: exercise
