//! Runs the checks of `exercises/ch12_bug_nan_average.rs`; with `--features solutions`, of the reference solution
//! and of the shipped stub (which they must reject). See `rtl_exercises::harness`.

#[cfg(not(feature = "solutions"))]
#[path = "../exercises/ch12_bug_nan_average.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/ch12_bug_nan_average.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/stubs/ch12_bug_nan_average.rs"]
#[allow(dead_code)]
mod stub;

use rtl_exercises::ch12_bug_nan_average::*;

rtl_exercises::exercise_main!("ch12_bug_nan_average", e => {
    "exact pixels: [1, NaN] is 1, several NaN or infinite samples, empty pixels" => check_exact(e::pixel_value),
    "one pixel with 3 NaN samples in 10^4 (z-test)" => check_pixel(e::pixel_value),
    "400 pixels with NaN samples at a rate of 1/1000: none black" => check_image(e::pixel_value),
});
