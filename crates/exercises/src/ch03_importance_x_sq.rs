//! # Chapter 3, "Importance Sampling": integrate x^2 on [0, 2] with three densities
//!
//! **Task.** Write the importance-sampled estimator [`importance_estimate`] of I = integral of f:
//! draw u uniform in [0, 1), take x = `sample(u)` (distributed with density p = `pdf`), and average
//! f(x) / p(x) over `n` samples. Where p(x) = 0 the sample contributes 0 (f must vanish there for the
//! estimate to be unbiased), never 0/0 = NaN. `None` for `n = 0`.
//!
//! The check integrates f(x) = x^2 on [0, 2] (I = 8/3) with three densities, each z-tested with its
//! exact variance Var(f/p) = integral of f^2/p - I^2:
//!
//! | density p(x) | sample(u)    | Var(f/p)  |
//! |--------------|--------------|-----------|
//! | 1/2          | 2u           | 256/45    |
//! | x/2          | 2 sqrt(u)    | 8/9       |
//! | 3x^2/8       | 2 cbrt(u)    | 0: every sample is exactly 8/3 |
//!
//! and the hard case u = 0 with p = x/2: x = 0, p = 0, f = 0, and the sample contributes 0.

use crate::check::{self, CheckResult, ScriptedRng};
use rand::{Rng, RngCore};

// ANCHOR: exercise
/// The importance-sampled estimate (1/n) sum f(x_k) / p(x_k), x_k = `sample(u_k)`, counting a sample
/// with p(x_k) = 0 as 0; `None` when `n = 0`.
pub fn importance_estimate<R: Rng + ?Sized>(
    n: usize,
    rng: &mut R,
    f: impl Fn(f64) -> f64,
    sample: impl Fn(f64) -> f64,
    pdf: impl Fn(f64) -> f64,
) -> Option<f64> {
    #[cfg(feature = "solutions")]
    return solution::importance_estimate(n, rng, f, sample, pdf);
    #[cfg(not(feature = "solutions"))]
    {
        let _ = (n, rng, f, sample, pdf);
        todo!("ch03 importance_estimate: average f(x)/p(x) over x = sample(u), 0 where p(x) = 0")
    }
}
// ANCHOR_END: exercise

type Fx<'a> = &'a dyn Fn(f64) -> f64;

/// The estimator under test: `(n, rng, f, sample, pdf) -> estimate`.
pub trait Estimator: Fn(usize, &mut dyn RngCore, Fx, Fx, Fx) -> Option<f64> {}
impl<F: Fn(usize, &mut dyn RngCore, Fx, Fx, Fx) -> Option<f64>> Estimator for F {}

const I: f64 = 8.0 / 3.0;

fn f(x: f64) -> f64 {
    x * x
}

/// z-tests with the uniform and the linear density, 1e5 samples each.
pub fn check_unbiased(estimate: impl Estimator) -> CheckResult {
    let n = 100_000usize;
    let cases: [(&str, Fx, Fx, f64); 2] = [
        ("uniform pdf 1/2", &|u| 2.0 * u, &|_| 0.5, 256.0 / 45.0),
        (
            "linear pdf x/2",
            &|u| 2.0 * u.sqrt(),
            &|x| x / 2.0,
            8.0 / 9.0,
        ),
    ];
    for (k, (name, sample, pdf, var)) in cases.into_iter().enumerate() {
        let got = estimate(n, &mut check::seeded(32 + k as u64), &f, sample, pdf)
            .ok_or(format!("importance_estimate with the {name} returned None"))?;
        check::z_test(
            &format!("integral of x^2 on [0,2] with the {name}"),
            got,
            (var / n as f64).sqrt(),
            I,
        )?;
    }
    Ok(())
}

/// The density proportional to f gives every sample f/p = 8/3: the estimate equals 8/3 to rounding.
pub fn check_zero_variance(estimate: impl Estimator) -> CheckResult {
    let got = estimate(
        1000,
        &mut check::seeded(34),
        &f,
        &|u| 2.0 * u.cbrt(),
        &|x| 3.0 * x * x / 8.0,
    )
    .ok_or("importance_estimate(1000) returned None")?;
    check::z_test(
        "integral of x^2 with the perfect pdf 3x^2/8 (zero variance)",
        got,
        0.0,
        I,
    )
}

/// u = 0 gives x = 0 where p = x/2 vanishes: the sample counts 0, not NaN. `n = 0` gives `None`.
pub fn check_pdf_zero(estimate: impl Estimator) -> CheckResult {
    let (sample, pdf): (Fx, Fx) = (&|u| 2.0 * u.sqrt(), &|x| x / 2.0);
    let got = estimate(1, &mut ScriptedRng::new(&[0.0], 35), &f, sample, pdf);
    if got != Some(0.0) {
        return Err(format!(
            "one sample at u = 0 (x = 0, p(x) = 0) gave {got:?}, expected Some(0.0)"
        ));
    }
    // Four samples: u = 0 (contributes 0) and u = 1/4, 1/16, 1/64 (x = 1, 1/2, 1/4: f/p = 2x).
    let got = estimate(
        4,
        &mut ScriptedRng::new(&[0.0, 0.25, 0.0625, 0.015625], 35),
        &f,
        sample,
        pdf,
    );
    if got != Some((2.0 + 1.0 + 0.5) / 4.0) {
        return Err(format!(
            "samples at u = 0, 1/4, 1/16, 1/64 gave {got:?}, expected Some(0.875)"
        ));
    }
    match estimate(0, &mut check::seeded(36), &f, sample, pdf) {
        None => Ok(()),
        Some(x) => Err(format!(
            "importance_estimate(0) returned Some({x}); no samples give None"
        )),
    }
}

/// All of this exercise's checks.
pub fn check_importance(estimate: impl Estimator) -> CheckResult {
    check_pdf_zero(&estimate)?;
    check_zero_variance(&estimate)?;
    check_unbiased(&estimate)
}

fn learner(n: usize, rng: &mut dyn RngCore, f: Fx, sample: Fx, pdf: Fx) -> Option<f64> {
    importance_estimate(n, rng, f, sample, pdf)
}

/// This exercise's checks, run on your [`importance_estimate`].
pub fn check() -> CheckResult {
    check_importance(learner)
}

#[cfg(feature = "solutions")]
mod solution {
    use rand::Rng;

    pub fn importance_estimate<R: Rng + ?Sized>(
        n: usize,
        rng: &mut R,
        f: impl Fn(f64) -> f64,
        sample: impl Fn(f64) -> f64,
        pdf: impl Fn(f64) -> f64,
    ) -> Option<f64> {
        if n == 0 {
            return None;
        }
        let mut sum = 0.0;
        for _ in 0..n {
            let x = sample(rng.random());
            let p = pdf(x);
            if p > 0.0 {
                sum += f(x) / p;
            }
        }
        Some(sum / n as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn estimates_are_unbiased_with_uniform_and_linear_pdfs() {
        check_unbiased(learner).unwrap();
    }

    #[test]
    fn the_pdf_proportional_to_f_has_zero_variance() {
        check_zero_variance(learner).unwrap();
    }

    #[test]
    fn a_sample_where_the_pdf_is_zero_contributes_zero() {
        check_pdf_zero(learner).unwrap();
    }

    #[test]
    fn checks_reject_wrong_estimators() {
        // Wrong: averages f(x) without dividing by p(x).
        let no_division = |n: usize, rng: &mut dyn RngCore, f: Fx, sample: Fx, _: Fx| {
            (n > 0).then(|| (0..n).map(|_| f(sample(rng.random()))).sum::<f64>() / n as f64)
        };
        assert!(check_unbiased(no_division).is_err());
        assert!(check_zero_variance(no_division).is_err());
        // Wrong: divides by p(x) = 0 at x = 0 and returns NaN.
        let unguarded = |n: usize, rng: &mut dyn RngCore, f: Fx, sample: Fx, pdf: Fx| {
            (n > 0).then(|| {
                (0..n)
                    .map(|_| {
                        let x = sample(rng.random());
                        f(x) / pdf(x)
                    })
                    .sum::<f64>()
                    / n as f64
            })
        };
        assert!(check_pdf_zero(unguarded).is_err());
    }
}
