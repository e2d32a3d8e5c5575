//! # Bug museum, chapter 10: a "uniform" pdf whose sampler still samples cosine
//!
//! The checks of the exercise `crates/exercises/exercises/ch10_bug_uniform_samples_cosine.rs`, which
//! holds the bug to find.
//!
//! The check: `value` is 1/(2 pi) above the horizon and 0 below; a chi-square test of 1e5 directions
//! from `generate` against `value`, in 16 x 10 equal-area cells of the hemisphere; and the estimate of
//! the integral of cos theta over the hemisphere (exactly pi) with f / value over `generate`'s
//! directions, z-tested (false failure 1e-6): a sampler that does not draw the density `value` states
//! gives a biased image, not just a noisy one.

use crate::ch10_mixture_pdf::Pdf;
use crate::check::{self, CheckResult, SphereBins};
use glam::DVec3;
use std::f64::consts::PI;

/// Exact values: 1/(2 pi) at and above the horizon, 0 below.
pub fn check_value(pdf: &dyn Pdf) -> CheckResult {
    let mut rng = check::seeded(100);
    for _ in 0..1000 {
        let d = check::uniform_direction(&mut rng);
        let want = if d.z >= 0.0 { 1.0 / (2.0 * PI) } else { 0.0 };
        check::close(&format!("value({d})"), pdf.value(d), want, 1e-12)?;
    }
    Ok(())
}

/// Chi-square of 1e5 generated directions against the density `value` claims.
pub fn check_generate(pdf: &dyn Pdf) -> CheckResult {
    let bins = SphereBins {
        n_phi: 16,
        n_z: 10,
        z_min: 0.0,
        z_max: 1.0,
    };
    let n = 100_000;
    let mut rng = check::seeded(101);
    let dirs: Vec<DVec3> = (0..n).map(|_| pdf.generate(&mut rng)).collect();
    let top = dirs.iter().filter(|d| d.z > 0.9).count();
    let observed = bins.histogram("generate", dirs)?;
    let expected = bins.expected(n, |d| pdf.value(d), |_, _| true, 4);
    check::chi_square("generate against value", &observed, &expected).map_err(|e| {
        format!(
            "{e}\n({top} of {n} directions have cos theta > 0.9, where a uniform hemisphere puts \
             {:.0}: generate does not draw the density value states)",
            0.1 * n as f64
        )
    })
}

/// The integral of cos theta over the hemisphere, pi, estimated with f / value from 1e5 directions.
pub fn check_estimate(pdf: &dyn Pdf) -> CheckResult {
    let mut rng = check::seeded(102);
    let values = (0..100_000).map(|_| {
        let d = pdf.generate(&mut rng);
        let p = pdf.value(d);
        if p > 0.0 { d.z.max(0.0) / p } else { 0.0 }
    });
    check::z_test_mean(
        "the estimate of the integral of cos theta over the hemisphere (pi)",
        values,
        PI,
    )
    .map_err(|e| {
        format!(
            "{e}\n(f / p is unbiased only when the directions are drawn with density p; drawn more \
                 often near the normal, where cos theta is large, they overestimate)"
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
        assert!(err.contains("cos theta > 0.9"), "{err}");
        assert!(check_estimate(&Mislabelled).is_err());
    }
}
