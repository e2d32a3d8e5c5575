//! The integral of x^2 on [0, 2] (exact 8/3) three ways, as in book 3, chapter 3: uniform samples,
//! importance sampling with pdf x/2, and with pdf 3x^2/8, which is proportional to x^2 and so gets the
//! exact answer from a single sample. Jittered and Sobol estimates are printed for comparison.
//!
//! `cargo run --release -p rtl-mc --example integrate_x_sq`

use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_mc::densities::{linear_pdf, perfect_pdf, sample_linear, sample_perfect};
use rtl_mc::{Interval, importance, jittered, plain, sobol};

fn main() -> Result<(), rtl_mc::McError> {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(3);
    let exact = 8.0 / 3.0;
    let n = 1_000_000;
    let domain = Interval::new(0.0, 2.0)?;
    // ANCHOR: three_pdfs
    let f = |x: f64| x * x;
    let uniform = plain(f, domain, n, &mut rng)?;
    println!("{}", uniform.report("uniform, p = 1/2", exact));

    let linear = |r: &mut Xoshiro256PlusPlus| sample_linear(r.random::<f64>());
    let by_linear = importance(f, linear, linear_pdf, n, &mut rng)?;
    println!("{}", by_linear.report("importance, p = x/2", exact));

    let perfect = |r: &mut Xoshiro256PlusPlus| sample_perfect(r.random::<f64>());
    let one_sample = importance(f, perfect, perfect_pdf, 1, &mut rng)?;
    println!("{}", one_sample.report("importance, p = 3x^2/8", exact));
    // ANCHOR_END: three_pdfs
    let many = importance(f, perfect, perfect_pdf, n, &mut rng)?;
    println!("{}", many.report("importance, p = 3x^2/8", exact));

    let strata = jittered(f, domain, n / 16, 16, &mut rng)?;
    println!("{}", strata.report("jittered (x16)", exact));
    let quasi = sobol(f, domain, 1 << 16, 16, &mut rng)?;
    println!("{}", quasi.report("scrambled Sobol (x16)", exact));
    Ok(())
}
