//! Reference solution of `exercises/ch12_bug_nan_average.rs`, compiled only with `--features solutions`: try the
//! exercise first (`cargo exercises solution ch12_bug_nan_average` shows it once your code passes).

/// The bug: the guard came after the sum, which one NaN had already made NaN. Drop each bad sample
/// as it comes, and divide by the number of samples kept.
pub fn pixel_value(samples: &[f64]) -> f64 {
    let (mut sum, mut used) = (0.0, 0usize);
    for &s in samples {
        if s.is_finite() {
            sum += s;
            used += 1;
        }
    }
    if used == 0 { 0.0 } else { sum / used as f64 }
}
