//! # Chapter 12, "Handling Surface Acne": keep NaNs out of a pixel
//!
//! One NaN sample (0/0 from a degenerate pdf) makes a pixel's sum NaN, and the pixel black or garbage
//! for ever; one infinite sample makes it white. The book replaces NaN components by 0 before
//! averaging, which darkens the pixel: it divides by a count that includes the discarded sample.
//!
//! **Task.** Write [`PixelAccumulator::add`] and [`PixelAccumulator::mean`]: `add` drops a sample with
//! any non-finite component (counting it in `dropped`) and otherwise folds it into a running mean of
//! the finite samples (counting it in `used`); `mean` returns that mean, or `None` when no finite
//! sample arrived. Keep a running mean, mean += (x - mean) / used, rather than a sum: a sum of large
//! finite samples can overflow to infinity, a running mean stays finite.
//!
//! The check: constant samples 0.5 for 1, 2, 10, 16 and 1000 samples average to exactly 0.5 (a dyadic
//! value, exact in floating point); one NaN, +inf, -inf or NaN-in-one-channel sample among 100 (first,
//! middle or last) leaves the mean exactly 0.5 and is counted; [1, 2, 3, 4] average to exactly 2.5;
//! two samples of 1e308 average to 1e308; no samples, or only bad ones, give `None`.

use crate::check::CheckResult;
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
        #[cfg(feature = "solutions")]
        return solution::add(self, sample);
        #[cfg(not(feature = "solutions"))]
        {
            let _ = sample;
            todo!(
                "ch12 PixelAccumulator::add: drop (and count) non-finite samples, keep a running mean"
            )
        }
    }

    /// The mean of the finite samples, `None` if there were none.
    pub fn mean(&self) -> Option<DVec3> {
        #[cfg(feature = "solutions")]
        return (self.used > 0).then_some(self.mean);
        #[cfg(not(feature = "solutions"))]
        todo!("ch12 PixelAccumulator::mean: the running mean, None without finite samples")
    }
}
// ANCHOR_END: exercise

/// The accumulator under test: a fold of the samples into `(mean, used, dropped)`.
pub trait Accumulate: Fn(&[DVec3]) -> (Option<DVec3>, u64, u64) {}
impl<F: Fn(&[DVec3]) -> (Option<DVec3>, u64, u64)> Accumulate for F {}

fn expect(
    what: &str,
    acc: &impl Accumulate,
    samples: &[DVec3],
    want: (Option<DVec3>, u64, u64),
) -> CheckResult {
    let got = acc(samples);
    if got == want {
        Ok(())
    } else {
        Err(format!(
            "{what}: (mean, used, dropped) = {got:?}, expected {want:?}"
        ))
    }
}

/// Constant samples, one bad sample among 100, exact means, overflow, and no usable samples.
pub fn check_nan_guard(acc: impl Accumulate) -> CheckResult {
    let half = DVec3::splat(0.5);
    for n in [1usize, 2, 10, 16, 1000] {
        expect(
            &format!("{n} samples of 0.5"),
            &acc,
            &vec![half; n],
            (Some(half), n as u64, 0),
        )?;
    }
    let bad = [
        ("NaN", DVec3::NAN),
        ("+inf", DVec3::INFINITY),
        ("-inf", DVec3::NEG_INFINITY),
        (
            "NaN in the green channel only",
            DVec3::new(0.5, f64::NAN, 0.5),
        ),
        (
            "+inf in the blue channel only",
            DVec3::new(0.5, 0.5, f64::INFINITY),
        ),
    ];
    for (what, b) in bad {
        for at in [0, 50, 99] {
            let mut samples = vec![half; 100];
            samples[at] = b;
            expect(
                &format!("one {what} sample at {at} among 100 samples of 0.5"),
                &acc,
                &samples,
                (Some(half), 99, 1),
            )?;
        }
    }
    let ramp = [
        DVec3::splat(1.0),
        DVec3::splat(2.0),
        DVec3::NAN,
        DVec3::splat(3.0),
        DVec3::splat(4.0),
    ];
    expect(
        "samples 1, 2, NaN, 3, 4",
        &acc,
        &ramp,
        (Some(DVec3::splat(2.5)), 4, 1),
    )?;
    let big = DVec3::splat(1e308);
    expect(
        "two samples of 1e308 (their sum overflows)",
        &acc,
        &[big, big],
        (Some(big), 2, 0),
    )?;
    expect("no samples", &acc, &[], (None, 0, 0))?;
    expect(
        "only bad samples",
        &acc,
        &[DVec3::NAN, DVec3::INFINITY],
        (None, 0, 2),
    )?;
    Ok(())
}

fn learner(samples: &[DVec3]) -> (Option<DVec3>, u64, u64) {
    let mut acc = PixelAccumulator::new();
    for &s in samples {
        acc.add(s);
    }
    (acc.mean(), acc.used, acc.dropped)
}

/// This exercise's checks, run on your [`PixelAccumulator`].
pub fn check() -> CheckResult {
    check_nan_guard(learner)
}

#[cfg(feature = "solutions")]
mod solution {
    use super::PixelAccumulator;
    use glam::DVec3;

    pub fn add(acc: &mut PixelAccumulator, sample: DVec3) {
        if !sample.is_finite() {
            acc.dropped += 1;
            return;
        }
        acc.used += 1;
        acc.mean += (sample - acc.mean) / acc.used as f64;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn non_finite_samples_are_dropped_counted_and_never_reach_the_mean() {
        check_nan_guard(learner).unwrap();
    }

    #[test]
    fn check_rejects_the_books_zeroing_and_a_plain_sum() {
        // Wrong: the book's fix, NaN components replaced by 0, still divided by all samples.
        let zeroing = |s: &[DVec3]| {
            let sum: DVec3 = s
                .iter()
                .map(|x| DVec3::from_array(x.to_array().map(|c| if c.is_nan() { 0.0 } else { c })))
                .sum();
            (
                (!s.is_empty()).then(|| sum / s.len() as f64),
                s.len() as u64,
                0,
            )
        };
        assert!(check_nan_guard(zeroing).is_err());
        // Wrong: drops bad samples correctly but sums, so large finite samples overflow.
        let summing = |s: &[DVec3]| {
            let good: Vec<DVec3> = s.iter().copied().filter(|x| x.is_finite()).collect();
            let sum: DVec3 = good.iter().sum();
            (
                (!good.is_empty()).then(|| sum / good.len() as f64),
                good.len() as u64,
                (s.len() - good.len()) as u64,
            )
        };
        let err = check_nan_guard(summing).unwrap_err();
        assert!(err.contains("1e308"), "{err}");
    }
}
