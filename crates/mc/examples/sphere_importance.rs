//! The integral of cos^2(theta) over the whole sphere of directions (book 3, chapter 4), exact 4 pi / 3:
//! uniform directions (pdf 1 / 4 pi), and directions with pdf 3 cos^2(theta) / 4 pi, which is
//! proportional to the integrand and so exact for every sample.
//!
//! rtl-mc knows nothing of directions (that is rtl-pdf's job), so the two samplers are written here.
//!
//! `cargo run --release -p rtl-mc --example sphere_importance`

use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_mc::importance;
use std::f64::consts::PI;

/// A uniform direction on the unit sphere (Archimedes: z uniform on [-1, 1], phi uniform).
fn uniform_sphere<R: Rng>(rng: &mut R) -> [f64; 3] {
    let z = 1.0 - 2.0 * rng.random::<f64>();
    let phi = 2.0 * PI * rng.random::<f64>();
    let r = (1.0 - z * z).max(0.0).sqrt();
    [r * phi.cos(), r * phi.sin(), z]
}

/// A direction with density `3 z^2 / 4 pi`: z has density `3 z^2 / 2` on [-1, 1], so |z| = v^(1/3) with
/// v uniform on (0, 1] and a random sign; phi uniform.
fn z_squared_sphere<R: Rng>(rng: &mut R) -> [f64; 3] {
    let magnitude = (1.0 - rng.random::<f64>()).cbrt();
    let z = if rng.random::<bool>() {
        magnitude
    } else {
        -magnitude
    };
    let phi = 2.0 * PI * rng.random::<f64>();
    let r = (1.0 - z * z).max(0.0).sqrt();
    [r * phi.cos(), r * phi.sin(), z]
}

fn main() -> Result<(), rtl_mc::McError> {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(7);
    let exact = 4.0 * PI / 3.0;
    let n = 1_000_000;
    let cos_sq = |d: [f64; 3]| d[2] * d[2];
    let uniform = importance(cos_sq, uniform_sphere, |_| 1.0 / (4.0 * PI), n, &mut rng)?;
    println!("{}", uniform.report("uniform, p = 1/4pi", exact));
    let pdf = |d: [f64; 3]| 3.0 * (d[2] * d[2]) / (4.0 * PI);
    let matched = importance(cos_sq, z_squared_sphere, pdf, n, &mut rng)?;
    println!("{}", matched.report("p = 3cos^2/4pi", exact));
    Ok(())
}
