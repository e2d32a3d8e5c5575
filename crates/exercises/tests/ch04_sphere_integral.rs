//! Runs the checks of `exercises/ch04_sphere_integral.rs`; with `--features solutions`, of the reference solution
//! and of the shipped stub (which they must reject). See `rtl_exercises::harness`.

#[cfg(not(feature = "solutions"))]
#[path = "../exercises/ch04_sphere_integral.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/ch04_sphere_integral.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/stubs/ch04_sphere_integral.rs"]
#[allow(dead_code)]
mod stub;

use rand::RngCore;
use rtl_exercises::ch04_sphere_integral::*;

rtl_exercises::exercise_main!("ch04_sphere_integral", e => {
    "uniform_sphere: unit at the corners, chi-square of 1e5 directions" => check_uniform_sphere(e::uniform_sphere),
    "estimate_cos_sq: z-test against 4 pi / 3" => check_estimate(|n, rng: &mut dyn RngCore| e::estimate_cos_sq(n, rng)),
});
