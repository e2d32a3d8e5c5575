//! Reference solution of `exercises/ch10_bug_uniform_samples_cosine.rs`, compiled only with `--features solutions`: try the
//! exercise first (`cargo exercises solution ch10_bug_uniform_samples_cosine` shows it once your code passes).

use glam::DVec3;
use rand::{Rng, RngCore};
use rtl_exercises::ch10_mixture_pdf::Pdf;
use std::f64::consts::PI;

#[derive(Clone, Copy, Debug)]
pub struct HemispherePdf;

impl Pdf for HemispherePdf {
    fn value(&self, direction: DVec3) -> f64 {
        if direction.z >= 0.0 {
            1.0 / (2.0 * PI)
        } else {
            0.0
        }
    }

    /// The bug: the cosine sampler was kept. Uniform on the hemisphere: z uniform in [0, 1].
    fn generate(&self, rng: &mut dyn RngCore) -> DVec3 {
        let (u1, u2): (f64, f64) = (rng.random(), rng.random());
        let phi = 2.0 * PI * u1;
        let z = 1.0 - u2;
        let r = (1.0 - z * z).max(0.0).sqrt();
        DVec3::new(phi.cos() * r, phi.sin() * r, z)
    }
}
