//! Runs the checks of `exercises/ch03_importance_x_sq.rs`; with `--features solutions`, of the reference solution
//! and of the shipped stub (which they must reject). See `rtl_exercises::harness`.

#[cfg(not(feature = "solutions"))]
#[path = "../exercises/ch03_importance_x_sq.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/ch03_importance_x_sq.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/stubs/ch03_importance_x_sq.rs"]
#[allow(dead_code)]
mod stub;

use rand::RngCore;
use rtl_exercises::ch03_importance_x_sq::*;

rtl_exercises::exercise_main!("ch03_importance_x_sq", e => {
    "uniform and linear densities: z-tests of 1e5 samples" => check_unbiased(|n, rng: &mut dyn RngCore, f: Fx, s: Fx, p: Fx| e::importance_estimate(n, rng, f, s, p)),
    "the density proportional to f: zero variance" => check_zero_variance(|n, rng: &mut dyn RngCore, f: Fx, s: Fx, p: Fx| e::importance_estimate(n, rng, f, s, p)),
    "a sample where p = 0 counts 0; n = 0 gives None" => check_pdf_zero(|n, rng: &mut dyn RngCore, f: Fx, s: Fx, p: Fx| e::importance_estimate(n, rng, f, s, p)),
});
