//! # Bug museum, chapter 12, Cleaning Up PDF Management, "The pitfalls as tests": NaN guarded after averaging instead of per sample
//!
//! The checks of the exercise `crates/exercises/exercises/ch12_bug_nan_average.rs`, which holds the
//! bug to find.
//!
//! The setting, in a few lines: a pixel's samples are the radiance of random paths, uniform in [0, 1)
//! (mean 1/2), and once in a while a path hits a degenerate pdf and returns NaN.
//!
//! The check: exact pixels first, where the z-tests cannot see a small bias: [1, NaN] is 1, the mean
//! of its one finite sample (dividing by both samples gives 1/2, the dropped sample counted as a
//! black one); [NaN, 0.5, NaN, 0.25, NaN] is 0.375; [0.5, +inf, 0.25, -inf] is 0.375 (an infinite
//! sample is not finite either); a pixel whose samples are all NaN, or that has none, is 0. Then a
//! pixel of 10^4 samples with 3 NaN among them is z-tested against 1/2 with the standard error of its
//! finite samples (false failure 1e-6); and of 400 pixels of 256 samples, each sample NaN with
//! probability 1/1000, the mean pixel value is z-tested against 1/2, and a black pixel (exactly 0)
//! there fails.

use crate::check::{self, Arg, CheckResult};
use rand::{Rng, RngCore};

/// The pixel estimate under test: its samples -> its value.
pub trait PixelValue: Fn(&[f64]) -> f64 {}
impl<F: Fn(&[f64]) -> f64> PixelValue for F {}

/// `value(samples)`, recorded so that a panic report names the samples.
fn pixel(value: &impl PixelValue, samples: &[f64]) -> f64 {
    check::calling("pixel_value", &[("samples", Arg::from(samples))], || {
        value(samples)
    })
}

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

/// Samples as the learner would write them: [1, NaN, inf].
fn show(samples: &[f64]) -> String {
    let items: Vec<String> = samples.iter().map(|&x| check::num(x)).collect();
    format!("[{}]", items.join(", "))
}

/// Exact pixels: the mean of the finite samples, whatever the number of NaN or infinite ones, and 0
/// for a pixel with no finite sample. Every value is dyadic, so the mean is exact.
pub fn check_exact(value: impl PixelValue) -> CheckResult {
    let nan = f64::NAN;
    let inf = f64::INFINITY;
    let cases: [(&[f64], f64, &str); 6] = [
        (&[1.0, nan], 1.0, ""),
        (&[nan, 0.5, nan, 0.25, nan], 0.375, ""),
        (
            &[0.5, inf, 0.25, -inf],
            0.375,
            " (an infinite sample is not finite either: drop it too)",
        ),
        (&[0.75], 0.75, ""),
        (
            &[nan, nan, nan, nan],
            0.0,
            " (no finite sample: the pixel is 0)",
        ),
        (&[], 0.0, " (no sample at all: the pixel is 0)"),
    ];
    for (samples, want, why) in cases {
        let got = pixel(&value, samples);
        if got == want {
            continue;
        }
        let finite = samples.iter().filter(|x| x.is_finite()).count();
        let sum: f64 = samples.iter().filter(|x| x.is_finite()).sum();
        let divided_by_all = !samples.is_empty() && got == sum / samples.len() as f64;
        let diagnosis = if divided_by_all && finite < samples.len() {
            let dropped = match samples.len() - finite {
                1 => "the dropped sample were".to_string(),
                n => format!("each of the {n} dropped samples were"),
            };
            format!(
                "\n(as if {dropped} still there, as a black one: the pixel comes out darker by the \
                 share of its samples that were dropped)"
            )
        } else {
            String::new()
        };
        return Err(format!(
            "pixel_value({}) = {}, expected {}: the mean of its finite samples{why}{diagnosis}",
            show(samples),
            check::num(got),
            check::num(want)
        ));
    }
    Ok(())
}

/// One pixel of 10^4 samples, 3 of them NaN: z-test against 1/2.
pub fn check_pixel(value: impl PixelValue) -> CheckResult {
    let mut rng = check::seeded(130);
    let mut s = samples(&mut rng, 10_000, 0.0);
    let clean = pixel(&value, &s);
    for at in [17, 5_000, 9_999] {
        s[at] = f64::NAN;
    }
    let got = pixel(&value, &s);
    let (mean, se) = check::mean_and_std_error(s.iter().copied().filter(|x| x.is_finite()));
    check::z_test("a pixel of 10^4 samples in [0, 1), 3 of them NaN", got, se, 0.5).map_err(|e| {
        // The guard after the average: right without NaN, exactly 0 with one.
        let guard_too_late = got == 0.0 && (clean - mean).abs() < 1e-3;
        if guard_too_late {
            format!(
                "{e}\n(the pixel is black, though the same pixel without its 3 NaN samples is {}: one \
                 NaN sample makes the whole sum NaN, so a guard on the average throws away the 9,997 \
                 good samples with it; drop the bad sample, not the pixel)",
                check::sig(clean, 4)
            )
        } else {
            e
        }
    })
}

/// 400 pixels of 256 samples, NaN at a rate of 1/1000: no black pixel, and the mean is 1/2.
pub fn check_image(value: impl PixelValue) -> CheckResult {
    let mut rng = check::seeded(131);
    let pixels: Vec<(f64, bool)> = (0..400)
        .map(|_| {
            let s = samples(&mut rng, 256, 1e-3);
            (pixel(&value, &s), s.iter().any(|x| x.is_nan()))
        })
        .collect();
    let black = pixels.iter().filter(|p| p.0 == 0.0).count();
    if black > 0 {
        let with_nan = pixels.iter().filter(|p| p.1).count();
        let black_with_nan = pixels.iter().filter(|p| p.0 == 0.0 && p.1).count();
        // The guard after the average blackens exactly the pixels that have a NaN sample.
        let why = if black == with_nan && black_with_nan == black {
            format!(
                ": exactly the {with_nan} pixels that have a NaN sample. With one sample in 1000 NaN, a \
                 pixel of 256 samples has one with probability 1 - 0.999^256 = 23%, and each such \
                 pixel lost all its samples instead of one"
            )
        } else {
            format!(
                " ({black_with_nan} of them with a NaN sample, of the {with_nan} pixels that have \
                 one); the samples are in [0, 1), so a pixel of finite samples is never 0"
            )
        };
        return Err(format!("{black} of 400 pixels are black (exactly 0){why}"));
    }
    check::z_test_mean("the mean of 400 pixels", pixels.iter().map(|p| p.0), 0.5)
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
        let err = check_image(late).unwrap_err();
        assert!(err.contains("exactly the"), "{err}");
        assert!(check_exact(late).is_err());
        // Wrong: drops NaN but returns NaN for an empty pixel.
        let empty_nan = |s: &[f64]| {
            let good: Vec<f64> = s.iter().copied().filter(|x| x.is_finite()).collect();
            good.iter().sum::<f64>() / good.len() as f64
        };
        assert!(check_exact(empty_nan).is_err());
    }

    #[test]
    fn checks_reject_the_fix_that_divides_by_every_sample() {
        // The learner's wrong fix: NaN skipped in the sum, but the mean still divided by all the
        // samples. Its bias (3 in 10^4 here) is below the z-tests' resolution: only exact pixels
        // catch it.
        let divides_by_all = |samples: &[f64]| {
            let mut sum = 0.0;
            for &s in samples {
                if s.is_finite() {
                    sum += s;
                }
            }
            let mean = sum / samples.len() as f64;
            if mean.is_nan() { 0.0 } else { mean }
        };
        assert!(
            check_pixel(divides_by_all).is_ok(),
            "the z-test cannot see it"
        );
        let err = check_exact(divides_by_all).unwrap_err();
        assert!(
            err.starts_with(
                "pixel_value([1, NaN]) = 0.5, expected 1: the mean of its finite samples"
            ),
            "{err}"
        );
        assert!(
            err.contains("as if the dropped sample were still there, as a black one"),
            "{err}"
        );
        // the symptom, not the fix (the hints give that)
        assert!(!err.contains("divide"), "{err}");
        // A guard that drops NaN but keeps infinities.
        let keeps_infinity = |samples: &[f64]| {
            let kept: Vec<f64> = samples.iter().copied().filter(|x| !x.is_nan()).collect();
            if kept.is_empty() {
                0.0
            } else {
                kept.iter().sum::<f64>() / kept.len() as f64
            }
        };
        let err = check_exact(keeps_infinity).unwrap_err();
        assert!(
            err.contains("an infinite sample is not finite either"),
            "{err}"
        );
    }

    #[test]
    fn the_late_guard_diagnosis_is_given_only_for_its_signature() {
        // Wrong in another way: every pixel is 0. Black, but not because of the NaN samples.
        let always_zero = |_: &[f64]| 0.0;
        let err = check_pixel(always_zero).unwrap_err();
        assert!(!err.contains("guard on the average"), "{err}");
        let err = check_image(always_zero).unwrap_err();
        assert!(
            err.contains("a pixel of finite samples is never 0"),
            "{err}"
        );
        assert!(!err.contains("exactly the"), "{err}");
    }

    #[test]
    fn a_panic_names_the_samples() {
        // Panics on a NaN sample among more than 4: first in the exact pixel [NaN, 0.5, NaN, 0.25,
        // NaN], shown whole; then, given short pixels, in the pixel of 10^4 samples.
        let more_than_4 = |s: &[f64]| {
            assert!(s.len() <= 4 || s.iter().all(|x| !x.is_nan()), "NaN");
            let good: Vec<f64> = s.iter().copied().filter(|x| x.is_finite()).collect();
            if good.is_empty() {
                0.0
            } else {
                good.iter().sum::<f64>() / good.len() as f64
            }
        };
        let report = crate::harness::panic_of(move || check_exact(more_than_4));
        assert!(
            report.starts_with(
                "your code panicked in pixel_value(samples = [NaN, 0.5, NaN, 0.25, NaN]) at "
            ),
            "{report}"
        );
        let report = crate::harness::panic_of(move || check_pixel(more_than_4));
        let mut rng = check::seeded(130);
        let first: Vec<String> = samples(&mut rng, 6, 0.0)
            .iter()
            .map(|&x| check::num(x))
            .collect();
        assert!(
            report.starts_with(&format!(
                "your code panicked in pixel_value(samples = [{}, ...] (10,000 values; not finite \
                 at 17, 5,000, 9,999)) at ",
                first.join(", ")
            )),
            "{report}"
        );
    }
}
