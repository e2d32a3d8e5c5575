//! Runs the checks of `exercises/ch03_inverse_x_sq.rs`; with `--features solutions`, of the reference solution
//! and of the shipped stub (which they must reject). See `rtl_exercises::harness`.

#[cfg(not(feature = "solutions"))]
#[path = "../exercises/ch03_inverse_x_sq.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/ch03_inverse_x_sq.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/stubs/ch03_inverse_x_sq.rs"]
#[allow(dead_code)]
mod stub;

use rtl_exercises::ch03_inverse_x_sq::*;

rtl_exercises::exercise_main!("ch03_inverse_x_sq", e => {
    "sample_linear: exact values and a chi-square test against x/2" => check_linear(e::sample_linear),
    "sample_quadratic: exact values and a chi-square test against 3x^2/8" => check_quadratic(e::sample_quadratic),
});
