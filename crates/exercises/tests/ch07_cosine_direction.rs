//! Runs the checks of `exercises/ch07_cosine_direction.rs`; with `--features solutions`, of the reference solution
//! and of the shipped stub (which they must reject). See `rtl_exercises::harness`.

#[cfg(not(feature = "solutions"))]
#[path = "../exercises/ch07_cosine_direction.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/ch07_cosine_direction.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/stubs/ch07_cosine_direction.rs"]
#[allow(dead_code)]
mod stub;

use rtl_exercises::ch07_cosine_direction::*;

rtl_exercises::exercise_main!("ch07_cosine_direction", e => {
    "cosine_pdf_value: exact values" => check_pdf(e::cosine_pdf_value),
    "random_cosine_direction: unit and above the horizon at u = 0, 1 - 2^-53" => check_corners(e::random_cosine_direction),
    "random_cosine_direction: chi-square of 1e5 directions against cos / pi" => check_distribution(e::random_cosine_direction),
});
