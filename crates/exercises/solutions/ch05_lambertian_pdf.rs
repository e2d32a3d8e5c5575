//! Reference solution of `exercises/ch05_lambertian_pdf.rs`, compiled only with `--features solutions`: try the
//! exercise first (`cargo exercises solution ch05_lambertian_pdf` shows it once your code passes).

use glam::DVec3;
use std::f64::consts::FRAC_1_PI;

pub fn lambertian_scattering_pdf(normal: DVec3, direction: DVec3) -> f64 {
    normal.dot(direction).max(0.0) * FRAC_1_PI
}
