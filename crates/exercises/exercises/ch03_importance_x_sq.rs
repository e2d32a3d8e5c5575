//! # Chapter 3, One Dimensional Monte Carlo Integration, "Importance sampling": integrate x^2 on [0, 2] with three densities
//!
//! **Read first:** the section "Importance sampling" of chapter 3
//! (`book/src/ch03-one-dimensional-mc-integration.md`), which derives the estimator.
//!
//! **Task.** Write [`importance_estimate`], the importance-sampled Monte Carlo estimate of the
//! integral I of `f`, from `n` samples: each draws u uniform in [0, 1) with `rng.random()` and takes
//! x = `sample(u)`, which has the density `pdf` (w.r.t. length). A sample where `pdf(x) = 0`
//! contributes 0 (f must vanish there for the estimate to be unbiased), never 0/0 = NaN. `None` for
//! `n = 0`.
//!
//! The check integrates f(x) = x^2 on [0, 2] (I = 8/3) with three densities, each z-tested at its
//! exact variance (false failure 1e-6):
//!
//! | density p(x) on [0, 2] | variance of one sample |
//! |------------------------|------------------------|
//! | 1/2                    | 256/45                 |
//! | x/2                    | 8/9                    |
//! | 3x^2/8                 | 0: every sample is exactly 8/3 |
//!
//! and the hard case u = 0 with p = x/2, where x = 0, p(x) = 0 and f(x) = 0: that sample contributes 0.
//!
//! Check your code with `cargo exercises check ch03_importance_x_sq` (or
//! `rtl exercises check ch03_importance_x_sq`, the same);
//! `cargo exercises hint ch03_importance_x_sq` gives a hint.

use rand::Rng;

// ANCHOR: exercise
/// The importance-sampled estimate of the integral of `f` from `n` samples x = `sample(u)`, u uniform
/// in [0, 1), whose density is `pdf`; a sample with `pdf(x) = 0` contributes 0. `None` when `n = 0`.
pub fn importance_estimate<R: Rng + ?Sized>(
    n: usize,
    rng: &mut R,
    f: impl Fn(f64) -> f64,
    sample: impl Fn(f64) -> f64,
    pdf: impl Fn(f64) -> f64,
) -> Option<f64> {
    let _ = (n, rng, f, sample, pdf);
    todo!("ch03 importance_estimate: the integral of f from n samples of the density pdf")
}
// ANCHOR_END: exercise
