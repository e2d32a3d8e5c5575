//! # Bug museum, chapter 10, Mixture Densities, "The Pdf trait": a "uniform" pdf whose sampler still samples cosine
//!
//! The checks of the exercise `crates/exercises/exercises/ch10_bug_uniform_samples_cosine.rs`, which
//! holds the bug to find.
//!
//! The check: `value` is 1/(2 pi) above the horizon and 0 below; `generate` gives unit directions,
//! and a chi-square test of 1e5 of them against `value`, in 16 x 10 equal-area cells of the
//! hemisphere, says where they differ; and the estimate of
//! the integral of cos theta over the hemisphere (exactly pi) with f / value over `generate`'s
//! directions, z-tested (false failure 1e-6): a sampler that does not draw the density `value` states
//! gives a biased image, not just a noisy one.

use crate::ch10_mixture_pdf::Pdf;
use crate::check::{self, CheckResult, Generator, SphereBins};
use glam::DVec3;
use std::f64::consts::PI;

/// `pdf.value(d)`, recorded so that a panic report names `d`.
fn value(pdf: &dyn Pdf, d: DVec3) -> f64 {
    check::calling("HemispherePdf::value", &[("direction", d.into())], || {
        pdf.value(d)
    })
}

/// `pdf.generate(rng)`, recorded so that a panic report says how to replay the generator.
fn generate(pdf: &dyn Pdf, rng: &mut Generator) -> DVec3 {
    let args = [("rng", rng.arg())];
    check::calling("HemispherePdf::generate", &args, || pdf.generate(rng))
}

/// Exact values: 1/(2 pi) at and above the horizon, 0 below.
pub fn check_value(pdf: &dyn Pdf) -> CheckResult {
    let mut rng = check::seeded(100);
    for _ in 0..1000 {
        let d = check::uniform_direction(&mut rng);
        let want = if d.z >= 0.0 { 1.0 / (2.0 * PI) } else { 0.0 };
        let got = value(pdf, d);
        check::close(&format!("value({d})"), got, want, 1e-12)?;
    }
    Ok(())
}

/// Unit directions from `generate`, and a chi-square test of 1e5 of them against the density
/// `value` claims.
pub fn check_generate(pdf: &dyn Pdf) -> CheckResult {
    let bins = SphereBins::hemisphere();
    let n = 100_000;
    let mut rng = Generator::new(101);
    let mut dirs: Vec<DVec3> = Vec::with_capacity(n);
    for _ in 0..n {
        let d = generate(pdf, &mut rng);
        check::unit("generate()", d).map_err(|e| {
            format!("{e}: a direction is a unit vector, and value's density is per unit direction")
        })?;
        dirs.push(d);
    }
    let observed = bins.histogram("generate", dirs)?;
    let expected = bins.expected(n, |d| value(pdf, d), |_, _| true, 4);
    check::chi_square("generate against value", &observed, &expected, &bins)
        .map_err(|e| format!("{e}\n(generate does not draw the density value states)"))
}

/// The integral of cos theta over the hemisphere, pi, estimated with f / value from 1e5 directions.
pub fn check_estimate(pdf: &dyn Pdf) -> CheckResult {
    let mut rng = Generator::new(102);
    let estimates: Vec<f64> = (0..100_000)
        .map(|_| {
            let d = generate(pdf, &mut rng);
            let p = value(pdf, d);
            if p > 0.0 { d.z.max(0.0) / p } else { 0.0 }
        })
        .collect();
    check::z_test_mean(
        "the estimate of the integral of cos theta over the hemisphere (pi)",
        estimates.iter().copied(),
        PI,
    )
    .map_err(|e| {
        // The estimate is too large when generate favours large cos theta more than value says,
        // too small when it favours it less.
        let (mean, _) = check::mean_and_std_error(estimates.iter().copied());
        let which = if mean > PI {
            "more often near the normal (where cos theta is large) than value says, so the estimate is too large"
        } else {
            "less often near the normal (where cos theta is large) than value says, so the estimate is too small"
        };
        format!(
            "{e}\n(f / p is unbiased only when the directions are drawn with density p; these are drawn \
             {which})"
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ch10_mixture_pdf::CosinePdf;
    use rand::RngCore;

    /// The bug: uniform value, cosine sampler.
    struct Mislabelled;
    impl Pdf for Mislabelled {
        fn value(&self, d: DVec3) -> f64 {
            if d.z >= 0.0 { 1.0 / (2.0 * PI) } else { 0.0 }
        }
        fn generate(&self, rng: &mut dyn RngCore) -> DVec3 {
            CosinePdf.generate(rng)
        }
    }

    #[test]
    fn checks_reject_a_uniform_value_with_a_cosine_sampler() {
        assert!(check_value(&Mislabelled).is_ok());
        let err = check_generate(&Mislabelled).unwrap_err();
        assert!(
            err.contains("\ntoo many near the normal: cos theta in [0.9, 1]: ")
                && err.contains("10,000 expected"),
            "{err}"
        );
        let err = check_estimate(&Mislabelled).unwrap_err();
        assert!(err.contains("estimate is too large"), "{err}");
    }

    /// A wrong fix: z uniform in [0, 1] as it should be, but the radius left at sqrt(u2), so the
    /// directions are not of unit length.
    struct NotUnit;
    impl Pdf for NotUnit {
        fn value(&self, d: DVec3) -> f64 {
            Mislabelled.value(d)
        }
        fn generate(&self, rng: &mut dyn RngCore) -> DVec3 {
            use rand::Rng;
            let (u1, u2): (f64, f64) = (rng.random(), rng.random());
            let phi = 2.0 * PI * u1;
            DVec3::new(phi.cos() * u2.sqrt(), phi.sin() * u2.sqrt(), u2)
        }
    }

    #[test]
    fn checks_reject_directions_that_are_not_unit_vectors() {
        let err = check_generate(&NotUnit).unwrap_err();
        assert!(err.contains("not a unit vector"), "{err}");
    }

    /// Panics on its first draw above 0.99, and where its value is asked below the horizon.
    struct Panics;
    impl Pdf for Panics {
        fn value(&self, d: DVec3) -> f64 {
            assert!(d.z >= 0.0, "below the horizon");
            Mislabelled.value(d)
        }
        fn generate(&self, rng: &mut dyn RngCore) -> DVec3 {
            use rand::Rng;
            let u: f64 = rng.random();
            assert!(u <= 0.99, "u = {u}");
            CosinePdf.generate(rng)
        }
    }

    #[test]
    fn a_panic_names_the_direction_or_how_to_replay_the_generator() {
        let report = crate::harness::panic_of(|| check_generate(&Panics));
        // Each generate draws 3 values; the report names where the panicking one starts.
        let mut rng = check::seeded(101);
        let mut skip = 0;
        let u = loop {
            use rand::Rng;
            let u: f64 = rng.random();
            if u > 0.99 {
                break u;
            }
            rng.next_u64();
            rng.next_u64();
            skip += 3;
        };
        assert!(
            report.starts_with(&format!(
                "your code panicked in HemispherePdf::generate(rng = \
                 rtl_exercises::check::replay(101, {skip})), which drew u = {}, at ",
                check::num(u)
            )),
            "{report}"
        );
        let report = crate::harness::panic_of(|| check_value(&Panics));
        assert!(
            report.starts_with("your code panicked in HemispherePdf::value(direction = ["),
            "{report}"
        );
    }
}
