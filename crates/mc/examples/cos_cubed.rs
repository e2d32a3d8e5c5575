//! The integral of cos^3(theta) over the hemisphere z > 0 (book 3, chapter 7), exact pi / 2, with
//! uniform hemisphere directions: pdf 1 / 2 pi.
//!
//! `cargo run --release -p rtl-mc --example cos_cubed`

use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_mc::importance;
use std::f64::consts::PI;

/// A uniform direction on the hemisphere z > 0: z = 1 - r2 is uniform on (0, 1] (Archimedes again).
fn uniform_hemisphere<R: Rng>(rng: &mut R) -> [f64; 3] {
    let (r1, r2) = (rng.random::<f64>(), rng.random::<f64>());
    let z = 1.0 - r2;
    let phi = 2.0 * PI * r1;
    let r = (r2 * (2.0 - r2)).sqrt(); // sqrt(1 - z^2) without cancellation
    [r * phi.cos(), r * phi.sin(), z]
}

fn main() -> Result<(), rtl_mc::McError> {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(8);
    let cos_cubed = |d: [f64; 3]| d[2] * d[2] * d[2];
    let pdf = |_| 1.0 / (2.0 * PI);
    let est = importance(cos_cubed, uniform_hemisphere, pdf, 1_000_000, &mut rng)?;
    println!("{}", est.report("uniform, p = 1/2pi", PI / 2.0));
    Ok(())
}
