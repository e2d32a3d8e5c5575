//! # Chapter 3, One Dimensional Monte Carlo Integration, "Importance sampling": integrate x^2 on [0, 2] with three densities
//!
//! The checks of the exercise `crates/exercises/exercises/ch03_importance_x_sq.rs`, which states the
//! task.
//!
//! The check integrates f(x) = x^2 on [0, 2] (I = 8/3) with three densities, each z-tested with its
//! exact variance Var(f/p) = integral of f^2/p - I^2:

use crate::check::{self, Arg, CheckResult, Generator};
use rand::RngCore;

pub type Fx<'a> = &'a dyn Fn(f64) -> f64;

/// The estimator under test: `(n, rng, f, sample, pdf) -> estimate`.
pub trait Estimator: Fn(usize, &mut dyn RngCore, Fx, Fx, Fx) -> Option<f64> {}
impl<F: Fn(usize, &mut dyn RngCore, Fx, Fx, Fx) -> Option<f64>> Estimator for F {}

const I: f64 = 8.0 / 3.0;

/// `estimate` with its calls recorded, so that a panic names the `n`, the generator (where it was,
/// and what it drew) and the functions (as Rust) that caused it.
fn recorded(
    estimate: impl Estimator,
) -> impl Fn(usize, &mut Generator, Fx, &Density) -> Option<f64> {
    move |n, rng: &mut Generator, f: Fx, density: &Density| {
        let args = [
            ("n", Arg::Count(n)),
            ("rng", rng.arg()),
            ("f", Arg::Text("|x| x * x")),
            ("sample", Arg::Text(density.sample_text)),
            ("pdf", Arg::Text(density.pdf_text)),
        ];
        check::calling("importance_estimate", &args, || {
            estimate(n, rng, f, density.sample, density.pdf)
        })
    }
}

/// A density on [0, 2] and its sampler, with their code for a panic report.
struct Density {
    sample: Fx<'static>,
    sample_text: &'static str,
    pdf: Fx<'static>,
    pdf_text: &'static str,
}

const UNIFORM: Density = Density {
    sample: &|u| 2.0 * u,
    sample_text: "|u| 2.0 * u",
    pdf: &|_| 0.5,
    pdf_text: "|_| 0.5",
};

const LINEAR: Density = Density {
    sample: &|u| 2.0 * u.sqrt(),
    sample_text: "|u| 2.0 * u.sqrt()",
    pdf: &|x| x / 2.0,
    pdf_text: "|x| x / 2.0",
};

const PERFECT: Density = Density {
    sample: &|u| 2.0 * u.cbrt(),
    sample_text: "|u| 2.0 * u.cbrt()",
    pdf: &|x| 3.0 * x * x / 8.0,
    pdf_text: "|x| 3.0 * x * x / 8.0",
};

fn f(x: f64) -> f64 {
    x * x
}

/// z-tests with the uniform and the linear density, 1e5 samples each.
pub fn check_unbiased(estimate: impl Estimator) -> CheckResult {
    let estimate = recorded(estimate);
    let n = 100_000usize;
    let cases = [
        ("uniform pdf 1/2", UNIFORM, 256.0 / 45.0),
        ("linear pdf x/2", LINEAR, 8.0 / 9.0),
    ];
    for (k, (name, density, var)) in cases.into_iter().enumerate() {
        let got = estimate(n, &mut Generator::new(32 + k as u64), &f, &density)
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
    let got = estimate(1000, &mut Generator::new(34), &f, &PERFECT)
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
    let got = estimate(1, &mut Generator::scripted(&[0.0], 35), &f, &LINEAR);
    if got != Some(0.0) {
        return Err(format!(
            "one sample at u = 0 (x = 0, p(x) = 0) gave {got:?}, expected Some(0.0)"
        ));
    }
    // Four samples: u = 0 (contributes 0) and u = 1/4, 1/16, 1/64 (x = 1, 1/2, 1/4: f/p = 2x).
    let got = estimate(
        4,
        &mut Generator::scripted(&[0.0, 0.25, 0.0625, 0.015625], 35),
        &f,
        &LINEAR,
    );
    if got != Some((2.0 + 1.0 + 0.5) / 4.0) {
        return Err(format!(
            "samples at u = 0, 1/4, 1/16, 1/64 gave {got:?}, expected Some(0.875)"
        ));
    }
    match estimate(0, &mut Generator::new(36), &f, &LINEAR) {
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

    #[test]
    fn a_panic_names_the_density_and_the_scripted_generator() {
        // Panics on its second sample, u = 1/4 of the script.
        let second = |n: usize, rng: &mut dyn RngCore, f: Fx, sample: Fx, pdf: Fx| {
            let mut sum = 0.0;
            for i in 0..n {
                let x = sample(rng.random());
                assert!(i < 1, "sample {i}");
                let p = pdf(x);
                sum += if p > 0.0 { f(x) / p } else { 0.0 };
            }
            (n > 0).then(|| sum / n as f64)
        };
        let report = crate::harness::panic_of(move || check_pdf_zero(second));
        assert!(
            report.starts_with(
                "your code panicked in importance_estimate(n = 4, rng = \
                 rtl_exercises::check::ScriptedRng::new(&[0, 0.25, 0.0625, 0.015625], 35), \
                 f = |x| x * x, sample = |u| 2.0 * u.sqrt(), pdf = |x| x / 2.0), which drew \
                 u = 0, 0.25, at "
            ),
            "{report}"
        );
    }
}
