//! Runs the checks of `exercises/ch12_nan_guard.rs`; with `--features solutions`, of the reference solution
//! and of the shipped stub (which they must reject). See `rtl_exercises::harness`.

#[cfg(not(feature = "solutions"))]
#[path = "../exercises/ch12_nan_guard.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/ch12_nan_guard.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/stubs/ch12_nan_guard.rs"]
#[allow(dead_code)]
mod stub;

use glam::DVec3;
use rtl_exercises::ch12_nan_guard::*;

rtl_exercises::exercise_main!("ch12_nan_guard", e => {
    "bad samples dropped and counted; exact means; no overflow" => check_nan_guard(e::PixelAccumulator::new, |acc: &mut e::PixelAccumulator, s: DVec3| acc.add(s), |acc: &e::PixelAccumulator| (acc.mean(), acc.used, acc.dropped)),
});
