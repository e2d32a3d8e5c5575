//! Runs the checks of `exercises/ch03_tabulated_inverse_cdf.rs`; with `--features solutions`, of the reference solution
//! and of the shipped stub (which they must reject). See `rtl_exercises::harness`.

#[cfg(not(feature = "solutions"))]
#[path = "../exercises/ch03_tabulated_inverse_cdf.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/ch03_tabulated_inverse_cdf.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/stubs/ch03_tabulated_inverse_cdf.rs"]
#[allow(dead_code)]
mod stub;

use rtl_exercises::ch03_tabulated_inverse_cdf::*;

rtl_exercises::exercise_main!("ch03_tabulated_inverse_cdf", e => {
    "u outside [0, 1) is an error" => check_out_of_range(e::invert),
    "exact values, zero-weight bins first, middle and last" => check_exact(e::invert),
    "never a zero-weight bin, at every c_i and its neighbours" => check_zero_bins(e::invert),
    "chi-square test of 1e5 samples" => check_distribution(e::invert),
});
