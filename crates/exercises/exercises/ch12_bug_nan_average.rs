//! # Bug museum, chapter 12, Cleaning Up PDF Management, "The pitfalls as tests": find and fix the bug
//!
//! **Read first:** the section "The pitfalls as tests" of chapter 12
//! (`book/src/ch12-cleaning-up-pdf-management.md`), the row `pitfall_a_nan_sample_in_a_pixel`.
//!
//! Someone fixed the "NaN pixels" of chapter 12 like this, and the NaN pixels became black pixels:
//! about one pixel in four of a 256-spp render where one path in a thousand returns NaN.
//!
//! **Task.** Find the bug in [`pixel_value`] and fix it: the value of a pixel is the mean of its
//! finite samples, and 0 when it has none.
//!
//! Check your code with `cargo exercises check ch12_bug_nan_average` (or
//! `rtl exercises check ch12_bug_nan_average`, the same);
//! `cargo exercises hint ch12_bug_nan_average` gives a hint.

// ANCHOR: exercise
/// The pixel's value: the mean of its finite samples; 0 if there are none.
pub fn pixel_value(samples: &[f64]) -> f64 {
    let mut sum = 0.0;
    for &s in samples {
        sum += s;
    }
    let mean = sum / samples.len() as f64;
    if mean.is_nan() { 0.0 } else { mean }
}
// ANCHOR_END: exercise
