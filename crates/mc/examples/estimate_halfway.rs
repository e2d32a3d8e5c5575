//! Where is half the area? (book 3, chapter 3): sample f(x) = e^(-x / 2 pi) sin^2 x at uniform points of
//! [0, 2 pi], sort them by x, and walk the running sum of f until it reaches half the total. That
//! approximates the x that splits the area under f in two halves: the median of the density
//! proportional to f, the first step towards inverting a CDF.
//!
//! The area has a closed form and the exact halfway point is found by bisection on the exact
//! antiderivative. The halfway estimate's standard error is the standard deviation of 30 independent
//! runs.
//!
//! `cargo run --release -p rtl-mc --example estimate_halfway`

use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_mc::{Interval, RunningStats, plain};
use std::f64::consts::TAU;
use std::time::Instant;

fn f(x: f64) -> f64 {
    let s = x.sin();
    (-x / TAU).exp() * s * s
}

/// The exact area under `f` on `[0, x]`: with `a = 1 / 2 pi` and `sin^2 = (1 - cos 2x) / 2`,
/// `(1 - e^(-a x)) / 2a - [a - e^(-a x)(a cos 2x - 2 sin 2x)] / (2 (a^2 + 4))`.
fn area_to(x: f64) -> f64 {
    let a = 1.0 / TAU;
    let e = (-a * x).exp();
    (1.0 - e) / (2.0 * a)
        - (a - e * (a * (2.0 * x).cos() - 2.0 * (2.0 * x).sin())) / (2.0 * (a * a + 4.0))
}

/// The x in [0, 2 pi] where `area_to(x)` is half the total, by bisection (area_to increases).
fn exact_halfway() -> f64 {
    let half = area_to(TAU) / 2.0;
    let (mut lo, mut hi) = (0.0, TAU);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if area_to(mid) < half {
            lo = mid
        } else {
            hi = mid
        }
    }
    0.5 * (lo + hi)
}

// ANCHOR: halfway
/// The book's estimate: sort `n` uniform samples by x and return the first x where the running sum of
/// f reaches half of the total.
fn estimate_halfway<R: Rng>(n: usize, rng: &mut R) -> f64 {
    let mut samples: Vec<(f64, f64)> = (0..n)
        .map(|_| {
            let x = rng.random_range(0.0..TAU);
            (x, f(x))
        })
        .collect();
    samples.sort_by(|a, b| a.0.total_cmp(&b.0));
    let half = samples.iter().map(|s| s.1).sum::<f64>() / 2.0;
    let mut running = 0.0;
    for &(x, fx) in &samples {
        running += fx;
        if running >= half {
            return x;
        }
    }
    TAU
}
// ANCHOR_END: halfway

fn main() -> Result<(), rtl_mc::McError> {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(5);
    let n = 10_000;
    let area = plain(f, Interval::new(0.0, TAU)?, n as u64, &mut rng)?;
    println!("{}", area.report("area under f", area_to(TAU)));

    // The book's single run, and 29 more runs to measure how far one run's answer spreads.
    let start = Instant::now();
    let first = estimate_halfway(n, &mut rng);
    let ms = start.elapsed().as_secs_f64() * 1e3;
    let mut runs = RunningStats::new();
    runs.push(first);
    for _ in 1..30 {
        runs.push(estimate_halfway(n, &mut rng));
    }
    let spread = runs.variance().expect("30 runs").sqrt();
    println!(
        "{:<26} N = {n:>9}  estimate = {first:.9}  exact = {:.9}  std error = {spread:>9.3e}  time = {ms:.3} ms",
        "halfway point",
        exact_halfway(),
    );
    Ok(())
}
