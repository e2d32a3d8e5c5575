//! Reference solution of `exercises/ch07_cosine_direction.rs`, compiled only with `--features solutions`: try the
//! exercise first (`cargo exercises solution ch07_cosine_direction` shows it once your code passes).

use glam::DVec3;
use std::f64::consts::{FRAC_1_PI, PI};

pub fn random_cosine_direction(u1: f64, u2: f64) -> DVec3 {
    let phi = 2.0 * PI * u1;
    let r = u2.sqrt();
    DVec3::new(phi.cos() * r, phi.sin() * r, (1.0 - u2).sqrt())
}

pub fn cosine_pdf_value(cos_theta: f64) -> f64 {
    cos_theta.max(0.0) * FRAC_1_PI
}
