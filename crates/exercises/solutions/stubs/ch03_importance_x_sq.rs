//! # Chapter 3, "Importance Sampling": integrate x^2 on [0, 2] with three densities
//!
//! **Task.** Write the importance-sampled estimator [`importance_estimate`] of I = integral of f:
//! draw u uniform in [0, 1), take x = `sample(u)` (distributed with density p = `pdf`), and average
//! f(x) / p(x) over `n` samples. Where p(x) = 0 the sample contributes 0 (f must vanish there for the
//! estimate to be unbiased), never 0/0 = NaN. `None` for `n = 0`.
//!
//! The check integrates f(x) = x^2 on [0, 2] (I = 8/3) with three densities, each z-tested with its
//! exact variance Var(f/p) = integral of f^2/p - I^2:
//!
//! | density p(x) | sample(u)    | Var(f/p)  |
//! |--------------|--------------|-----------|
//! | 1/2          | 2u           | 256/45    |
//! | x/2          | 2 sqrt(u)    | 8/9       |
//! | 3x^2/8       | 2 cbrt(u)    | 0: every sample is exactly 8/3 |
//!
//! and the hard case u = 0 with p = x/2: x = 0, p = 0, f = 0, and the sample contributes 0.
//!
//! Check your code with `rtl exercises check ch03_importance_x_sq`; `rtl exercises hint ch03_importance_x_sq` gives a hint.

use rand::Rng;

// ANCHOR: exercise
/// The importance-sampled estimate (1/n) sum f(x_k) / p(x_k), x_k = `sample(u_k)`, counting a sample
/// with p(x_k) = 0 as 0; `None` when `n = 0`.
pub fn importance_estimate<R: Rng + ?Sized>(
    n: usize,
    rng: &mut R,
    f: impl Fn(f64) -> f64,
    sample: impl Fn(f64) -> f64,
    pdf: impl Fn(f64) -> f64,
) -> Option<f64> {
    let _ = (n, rng, f, sample, pdf);
    todo!("ch03 importance_estimate: average f(x)/p(x) over x = sample(u), 0 where p(x) = 0")
}
// ANCHOR_END: exercise
