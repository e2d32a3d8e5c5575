//! # Bug museum, chapter 12: find and fix the bug
//!
//! Someone fixed the "NaN pixels" of chapter 12 like this, and the NaN pixels became black pixels:
//! about one pixel in four of a 256-spp render where one path in a thousand returns NaN.
//!
//! **Task.** Find the bug in [`pixel_value`] and fix it: the value of a pixel is the mean of its
//! finite samples, and 0 when it has none.
//!
//! Check your code with `rtl exercises check ch12_bug_nan_average`; `rtl exercises hint
//! ch12_bug_nan_average` gives a hint.

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
