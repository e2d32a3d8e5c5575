//! Runs the checks of `exercises/ch06_scatter_weight.rs`; with `--features solutions`, of the reference solution
//! and of the shipped stub (which they must reject). See `rtl_exercises::harness`.

#[cfg(not(feature = "solutions"))]
#[path = "../exercises/ch06_scatter_weight.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/ch06_scatter_weight.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/stubs/ch06_scatter_weight.rs"]
#[allow(dead_code)]
mod stub;

use rtl_exercises::ch06_scatter_weight::*;

rtl_exercises::exercise_main!("ch06_scatter_weight", e => {
    "exact values and degenerate densities" => check_cases(e::scatter_contribution),
    "white furnace: the mean is the albedo (z-test)" => check_furnace(e::scatter_contribution),
});
