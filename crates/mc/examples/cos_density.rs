//! The integral of cos^3(theta) over the hemisphere (book 3, chapter 7), exact pi / 2: uniform directions
//! against cosine-distributed directions (pdf cos(theta) / pi), which leave f/p = pi cos^2(theta) with
//! far less variance.
//!
//! `cargo run --release -p rtl-mc --example cos_density`

use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_mc::importance;
use std::f64::consts::PI;

/// A uniform direction on the hemisphere z > 0.
fn uniform_hemisphere<R: Rng>(rng: &mut R) -> [f64; 3] {
    let (r1, r2) = (rng.random::<f64>(), rng.random::<f64>());
    let z = 1.0 - r2;
    let phi = 2.0 * PI * r1;
    let r = (r2 * (2.0 - r2)).sqrt();
    [r * phi.cos(), r * phi.sin(), z]
}

/// A direction with density cos(theta) / pi on the hemisphere: z = sqrt(1 - r2) in (0, 1], so the
/// density is never 0 where a sample lands.
fn cosine_hemisphere<R: Rng>(rng: &mut R) -> [f64; 3] {
    let (r1, r2) = (rng.random::<f64>(), rng.random::<f64>());
    let phi = 2.0 * PI * r1;
    let r = r2.sqrt();
    [r * phi.cos(), r * phi.sin(), (1.0 - r2).sqrt()]
}

fn main() -> Result<(), rtl_mc::McError> {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(9);
    let n = 1_000_000;
    let cos_cubed = |d: [f64; 3]| d[2] * d[2] * d[2];
    let uniform = importance(
        cos_cubed,
        uniform_hemisphere,
        |_| 1.0 / (2.0 * PI),
        n,
        &mut rng,
    )?;
    println!("{}", uniform.report("uniform, p = 1/2pi", PI / 2.0));
    let cosine = importance(cos_cubed, cosine_hemisphere, |d| d[2] / PI, n, &mut rng)?;
    println!("{}", cosine.report("cosine, p = cos/pi", PI / 2.0));
    Ok(())
}
