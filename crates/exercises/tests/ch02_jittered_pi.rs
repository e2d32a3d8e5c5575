//! Runs the checks of `exercises/ch02_jittered_pi.rs`; with `--features solutions`, of the reference solution
//! and of the shipped stub (which they must reject). See `rtl_exercises::harness`.

#[cfg(not(feature = "solutions"))]
#[path = "../exercises/ch02_jittered_pi.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/ch02_jittered_pi.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/stubs/ch02_jittered_pi.rs"]
#[allow(dead_code)]
mod stub;

use rand::RngCore;
use rtl_exercises::ch02_jittered_pi::*;

rtl_exercises::exercise_main!("ch02_jittered_pi", e => {
    "unbiased, and less variance than independent points" => check_jittered_pi(|k, rng: &mut dyn RngCore| e::jittered_pi(k, rng)),
});
