//! Runs the checks of `exercises/ch02_estimate_pi.rs`; with `--features solutions`, of the reference solution
//! and of the shipped stub (which they must reject). See `rtl_exercises::harness`.

#[cfg(not(feature = "solutions"))]
#[path = "../exercises/ch02_estimate_pi.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/ch02_estimate_pi.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/stubs/ch02_estimate_pi.rs"]
#[allow(dead_code)]
mod stub;

use rand::RngCore;
use rtl_exercises::ch02_estimate_pi::*;

rtl_exercises::exercise_main!("ch02_estimate_pi", e => {
    "n = 0 gives None; an estimate is a count of points scaled by a constant" => check_lattice(|n, rng: &mut dyn RngCore| e::estimate_pi(n, rng)),
    "1e5 points: z-test against pi" => check_value(|n, rng: &mut dyn RngCore| e::estimate_pi(n, rng)),
});
