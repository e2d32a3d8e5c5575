//! Runs the checks of `exercises/ch07_bug_cosine_factor_two.rs`; with `--features solutions`, of the reference solution
//! and of the shipped stub (which they must reject). See `rtl_exercises::harness`.

#[cfg(not(feature = "solutions"))]
#[path = "../exercises/ch07_bug_cosine_factor_two.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/ch07_bug_cosine_factor_two.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/stubs/ch07_bug_cosine_factor_two.rs"]
#[allow(dead_code)]
mod stub;

use rtl_exercises::ch07_bug_cosine_factor_two::*;

rtl_exercises::exercise_main!("ch07_bug_cosine_factor_two", e => {
    "unit and above the horizon at the corners" => check_corners(e::random_cosine_direction),
    "the mean of cos theta is 2/3 (z-test)" => check_mean_cosine(e::random_cosine_direction),
    "chi-square of 1e5 directions against cos theta / pi" => check_distribution(e::random_cosine_direction),
});
