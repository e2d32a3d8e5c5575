//! Reference solution of `exercises/ch07_bug_cosine_factor_two.rs`, compiled only with `--features solutions`: try the
//! exercise first (`cargo exercises solution ch07_bug_cosine_factor_two` shows it once your code passes).

use glam::DVec3;
use std::f64::consts::PI;

/// The bug: the factor 2 pushed the disc point outwards (to radius 2 sqrt(u2)); normalising the
/// result hid the length error but not the wrong density. Malley's method: a uniform disc point,
/// radius sqrt(u2), lifted to the hemisphere.
pub fn random_cosine_direction(u1: f64, u2: f64) -> DVec3 {
    let phi = 2.0 * PI * u1;
    let x = phi.cos() * u2.sqrt();
    let y = phi.sin() * u2.sqrt();
    let z = (1.0 - u2).sqrt();
    DVec3::new(x, y, z)
}
