//! Reference solution of `exercises/ch04_sphere_integral.rs`, compiled only with `--features solutions`: try the
//! exercise first (`cargo exercises solution ch04_sphere_integral` shows it once your code passes).

use glam::DVec3;
use rand::Rng;
use std::f64::consts::PI;

pub fn uniform_sphere(u1: f64, u2: f64) -> DVec3 {
    let z = 1.0 - 2.0 * u1;
    // z lies in (-1, 1], so z * z rounds to at most 1 and 1 - z * z is never negative.
    let r = (1.0 - z * z).sqrt();
    let phi = 2.0 * PI * u2;
    DVec3::new(r * phi.cos(), r * phi.sin(), z)
}

pub fn estimate_cos_sq<R: Rng + ?Sized>(n: usize, rng: &mut R) -> Option<f64> {
    if n == 0 {
        return None;
    }
    let pdf = 1.0 / (4.0 * PI);
    let sum: f64 = (0..n)
        .map(|_| {
            let d = uniform_sphere(rng.random(), rng.random());
            d.z * d.z / pdf
        })
        .sum();
    Some(sum / n as f64)
}
