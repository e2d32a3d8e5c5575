//! # Bug museum, chapter 12: NaN guarded after averaging instead of per sample
//!
//! The checks of the exercise `crates/exercises/exercises/ch12_bug_nan_average.rs`, which holds the
//! bug to find.
//!
//! The setting, in a few lines: a pixel's samples are the radiance of random paths, uniform in [0, 1)
//! (mean 1/2), and once in a while a path hits a degenerate pdf and returns NaN.
//!
//! The check: a pixel of 10^4 samples with 3 NaN among them is z-tested against 1/2 with the standard
//! error of its finite samples (false failure 1e-6); a pixel whose samples are all NaN, or that has
//! none, is 0; and of 400 pixels of 256 samples, each sample NaN with probability 1/1000, the mean
//! pixel value is z-tested against 1/2, and a black pixel (exactly 0) there means the guard came too late.

use crate::check::{self, CheckResult};
use rand::{Rng, RngCore};

/// The pixel estimate under test: its samples -> its value.
pub trait PixelValue: Fn(&[f64]) -> f64 {}
impl<F: Fn(&[f64]) -> f64> PixelValue for F {}

fn samples(rng: &mut dyn RngCore, n: usize, nan_rate: f64) -> Vec<f64> {
    (0..n)
        .map(|_| {
            if rng.random::<f64>() < nan_rate {
                f64::NAN
            } else {
                rng.random::<f64>()
            }
        })
        .collect()
}

/// One pixel of 10^4 samples, 3 of them NaN: z-test against 1/2; and the edge cases.
pub fn check_pixel(value: impl PixelValue) -> CheckResult {
    let mut rng = check::seeded(130);
    let mut s = samples(&mut rng, 10_000, 0.0);
    for at in [17, 5_000, 9_999] {
        s[at] = f64::NAN;
    }
    let got = value(&s);
    let (_, se) = check::mean_and_std_error(s.iter().copied().filter(|x| x.is_finite()));
    check::z_test("a pixel of 10^4 samples in [0, 1), 3 of them NaN", got, se, 0.5).map_err(|e| {
        if got == 0.0 {
            format!(
                "{e}\n(the pixel is black: one NaN sample makes the whole sum NaN, so a guard on the \
                 average throws away the 9997 good samples with it; drop the bad sample, not the pixel)"
            )
        } else {
            e
        }
    })?;
    for (what, s) in [
        ("only NaN samples", vec![f64::NAN; 4]),
        ("no samples", vec![]),
    ] {
        let got = value(&s);
        if got != 0.0 {
            return Err(format!(
                "a pixel with {what} is {got}, expected 0 (no usable sample)"
            ));
        }
    }
    Ok(())
}

/// 400 pixels of 256 samples, NaN at a rate of 1/1000: no black pixel, and the mean is 1/2.
pub fn check_image(value: impl PixelValue) -> CheckResult {
    let mut rng = check::seeded(131);
    let pixels: Vec<f64> = (0..400)
        .map(|_| value(&samples(&mut rng, 256, 1e-3)))
        .collect();
    let black = pixels.iter().filter(|&&p| p == 0.0).count();
    if black > 0 {
        return Err(format!(
            "{black} of 400 pixels are black (exactly 0): with one sample in 1000 NaN, a pixel of 256 \
             samples has a NaN with probability 1 - 0.999^256 = 23%, and each such pixel lost all its \
             samples instead of one"
        ));
    }
    check::z_test_mean("the mean of 400 pixels", pixels, 0.5)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checks_reject_a_guard_after_the_average_and_the_books_zeroing_count() {
        let late = |s: &[f64]| {
            let mean = s.iter().sum::<f64>() / s.len() as f64;
            if mean.is_nan() { 0.0 } else { mean }
        };
        let err = check_pixel(late).unwrap_err();
        assert!(err.contains("black"), "{err}");
        assert!(check_image(late).is_err());
        // Wrong: drops NaN but returns NaN for an empty pixel.
        let empty_nan = |s: &[f64]| {
            let good: Vec<f64> = s.iter().copied().filter(|x| x.is_finite()).collect();
            good.iter().sum::<f64>() / good.len() as f64
        };
        assert!(check_pixel(empty_nan).is_err());
    }
}
