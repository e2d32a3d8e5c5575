//! # Chapter 12, Cleaning Up PDF Management, "The pitfalls as tests": keep NaNs out of a pixel
//!
//! The checks of the exercise `crates/exercises/exercises/ch12_nan_guard.rs`, which states the task,
//! and what that exercise is given.
//!
//! The check: constant samples 0.5 for 1, 2, 10, 16 and 1000 samples average to exactly 0.5 (a dyadic
//! value, exact in floating point); one NaN, +inf, -inf or NaN-in-one-channel sample among 100 (first,
//! middle or last) leaves the mean exactly 0.5 and is counted; [1, 2, 3, 4] average to exactly 2.5;
//! two samples of 1e308 average to 1e308; no samples, or only bad ones, give `None`.

use crate::check::CheckResult;
use glam::DVec3;

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

#[cfg(test)]
mod tests {
    use super::*;

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
