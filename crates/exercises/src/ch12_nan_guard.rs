//! # Chapter 12, Cleaning Up PDF Management, "The pitfalls as tests": keep NaNs out of a pixel
//!
//! The checks of the exercise `crates/exercises/exercises/ch12_nan_guard.rs`, which states the task,
//! and what that exercise is given.
//!
//! The check: constant samples 0.5 for 1, 2, 10, 16 and 1000 samples average to exactly 0.5 (a dyadic
//! value, exact in floating point); one NaN, +inf, -inf or NaN-in-one-channel sample among 100 (first,
//! middle or last) leaves the mean exactly 0.5 and is counted; [1, 2, 3, 4] average to exactly 2.5;
//! two samples of 1e308 average to 1e308; no samples, or only bad ones, give `None`.

use crate::check::{self, Arg, CheckResult};
use glam::DVec3;

/// `(mean, used, dropped)` of the learner's accumulator fed `samples`, every call recorded so
/// that a panic report names the sample added and the ones added before it.
fn accumulate<A>(
    new: &impl Fn() -> A,
    add: &impl Fn(&mut A, DVec3),
    finish: &impl Fn(&A) -> (Option<DVec3>, u64, u64),
    samples: &[DVec3],
) -> (Option<DVec3>, u64, u64) {
    let mut acc = check::calling("PixelAccumulator::new", &[], new);
    for (i, &s) in samples.iter().enumerate() {
        let before = (
            "on PixelAccumulator::new() after adding",
            Arg::from(&samples[..i]),
        );
        check::calling_method("add", &[("sample", Arg::Vector(s))], before, || {
            add(&mut acc, s)
        });
    }
    let all = (
        "on PixelAccumulator::new() after adding",
        Arg::from(samples),
    );
    check::calling_method("mean", &[], all, || finish(&acc))
}

fn expect(
    what: &str,
    acc: &impl Fn(&[DVec3]) -> (Option<DVec3>, u64, u64),
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

/// Constant samples, one bad sample among 100, exact means, overflow, and no usable samples, on the
/// accumulator that `new` makes, `add` feeds and `finish` reads: `(acc.mean(), acc.used,
/// acc.dropped)`.
pub fn check_nan_guard<A>(
    new: impl Fn() -> A,
    add: impl Fn(&mut A, DVec3),
    finish: impl Fn(&A) -> (Option<DVec3>, u64, u64),
) -> CheckResult {
    let acc = |samples: &[DVec3]| accumulate(&new, &add, &finish, samples);
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

    /// The checks on an accumulator that keeps its samples and computes with `f` at the end.
    fn check_on(f: impl Fn(&[DVec3]) -> (Option<DVec3>, u64, u64)) -> CheckResult {
        check_nan_guard(Vec::new, |v: &mut Vec<DVec3>, s| v.push(s), |v| f(v))
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
        assert!(check_on(zeroing).is_err());
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
        let err = check_on(summing).unwrap_err();
        assert!(err.contains("1e308"), "{err}");
    }

    /// The running mean of the finite samples, as the reference solution computes it.
    fn right(samples: &[DVec3]) -> (Option<DVec3>, u64, u64) {
        let (mut mean, mut used, mut dropped) = (DVec3::ZERO, 0, 0);
        for &s in samples {
            if s.is_finite() {
                used += 1;
                mean += (s - mean) / used as f64;
            } else {
                dropped += 1;
            }
        }
        ((used > 0).then_some(mean), used, dropped)
    }

    #[test]
    fn a_panic_names_the_sample_and_the_ones_added_before() {
        // add panics on a NaN after other samples: first in "one NaN sample at 50 among 100".
        let report = crate::harness::panic_of(|| {
            check_nan_guard(
                Vec::new,
                |v: &mut Vec<DVec3>, s: DVec3| {
                    assert!(!s.is_nan() || v.is_empty(), "a NaN after a sample");
                    v.push(s)
                },
                |v| right(v),
            )
        });
        assert!(
            report.starts_with(
                "your code panicked in add(sample = [NaN, NaN, NaN]) on PixelAccumulator::new() \
                 after adding [[0.5, 0.5, 0.5], [0.5, 0.5, 0.5], [0.5, 0.5, 0.5], ...] (50 values) at "
            ),
            "{report}"
        );
        // mean panics once a sample was dropped: first after "one NaN sample at 0 among 100".
        let report = crate::harness::panic_of(|| {
            check_nan_guard(
                Vec::new,
                |v: &mut Vec<DVec3>, s: DVec3| v.push(s),
                |v| {
                    assert!(v.iter().all(|s| s.is_finite()), "a sample was dropped");
                    (v.first().copied(), v.len() as u64, 0)
                },
            )
        });
        assert!(
            report.starts_with(
                "your code panicked in mean() on PixelAccumulator::new() after adding [[NaN, NaN, \
                 NaN], [0.5, 0.5, 0.5], [0.5, 0.5, 0.5], ...] (100 values; not finite at 0) at "
            ),
            "{report}"
        );
    }
}
