//! Estimating pi (book 3, chapter 2): the fraction of random points in the square [-1, 1]^2 that fall
//! inside the unit circle, times the square's area 4. Plain sampling against jittered (stratified)
//! sampling, and an Owen-scrambled Sobol set, with the same number of points.
//!
//! `cargo run --release -p rtl-mc --example pi`

use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_mc::{Rect, jittered_2d, plain_2d, sobol_2d};
use std::f64::consts::PI;

// ANCHOR: pi
/// 1 inside the unit circle, 0 outside: its integral over [-1, 1]^2 is the circle's area, pi.
fn inside_circle(p: [f64; 2]) -> f64 {
    if p[0] * p[0] + p[1] * p[1] < 1.0 {
        1.0
    } else {
        0.0
    }
}

fn main() -> Result<(), rtl_mc::McError> {
    let square = Rect::new(-1.0, 1.0, -1.0, 1.0)?;
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(1);
    let n = 1 << 20;
    println!("estimating pi with {n} points in [-1, 1]^2");
    let plain = plain_2d(inside_circle, square, n, &mut rng)?;
    println!("{}", plain.report("plain", PI));
    // 16 independent replicates of a 256 x 256 grid of cells, one point in each cell
    let jittered = jittered_2d(inside_circle, square, (256, 256), 16, &mut rng)?;
    println!("{}", jittered.report("jittered 256x256 (x16)", PI));
    let sobol = sobol_2d(inside_circle, square, 1 << 16, 16, &mut rng)?;
    println!("{}", sobol.report("scrambled Sobol (x16)", PI));
    Ok(())
}
// ANCHOR_END: pi
