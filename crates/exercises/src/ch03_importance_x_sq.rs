//! # Chapter 3, One Dimensional Monte Carlo Integration, "Importance sampling": integrate x^2 on [0, 2] with three densities
//!
//! The checks of the exercise `crates/exercises/exercises/ch03_importance_x_sq.rs`, which states the
//! task.
//!
//! The check integrates f(x) = x^2 on [0, 2] (I = 8/3) with three densities, each z-tested with its
//! exact variance Var(f/p) = integral of f^2/p - I^2:

use crate::check::{self, Arg, CheckResult, ScriptedRng};
use rand::RngCore;

pub type Fx<'a> = &'a dyn Fn(f64) -> f64;

/// The estimator under test: `(n, rng, f, sample, pdf) -> estimate`.
pub trait Estimator: Fn(usize, &mut dyn RngCore, Fx, Fx, Fx) -> Option<f64> {}
impl<F: Fn(usize, &mut dyn RngCore, Fx, Fx, Fx) -> Option<f64>> Estimator for F {}

const I: f64 = 8.0 / 3.0;

/// `estimate` with its calls recorded, so that a panic names the `n` that caused it.
fn recorded(estimate: impl Estimator) -> impl Estimator {
    move |n: usize, rng: &mut dyn RngCore, f: Fx, sample: Fx, pdf: Fx| {
        check::calling("importance_estimate", &[("n", Arg::Count(n))], || {
            estimate(n, rng, f, sample, pdf)
        })
    }
}

fn f(x: f64) -> f64 {
    x * x
}

/// z-tests with the uniform and the linear density, 1e5 samples each.
pub fn check_unbiased(estimate: impl Estimator) -> CheckResult {
    let estimate = recorded(estimate);
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
    let estimate = recorded(estimate);
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
    let estimate = recorded(estimate);
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
            "importance_estimate(0) returned Some({}); no samples give None",
            check::num(x)
        )),
    }
}

/// All of this exercise's checks.
pub fn check_importance(estimate: impl Estimator) -> CheckResult {
    check_pdf_zero(&estimate)?;
    check_zero_variance(&estimate)?;
    check_unbiased(&estimate)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::Rng;

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
