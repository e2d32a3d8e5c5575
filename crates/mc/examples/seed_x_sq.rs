//! The book's first integral (book 3, chapter 3): the integral of x^2 on [0, 2] from one million
//! uniform samples, printed with 12 decimals as the book does. The seed is fixed, so every run prints
//! the same digits.
//!
//! `cargo run --release -p rtl-mc --example seed_x_sq`

use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_mc::{Interval, plain};

// ANCHOR: seed_x_sq
fn main() -> Result<(), rtl_mc::McError> {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(2024);
    let estimate = plain(|x| x * x, Interval::new(0.0, 2.0)?, 1_000_000, &mut rng)?;
    println!("I = {:.12}", estimate.value());
    println!("{}", estimate.report("uniform", 8.0 / 3.0));
    Ok(())
}
// ANCHOR_END: seed_x_sq
