//! Runs the checks of `exercises/ch10_bug_uniform_samples_cosine.rs`; with `--features solutions`, of the reference solution
//! and of the shipped stub (which they must reject). See `rtl_exercises::harness`.

#[cfg(not(feature = "solutions"))]
#[path = "../exercises/ch10_bug_uniform_samples_cosine.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/ch10_bug_uniform_samples_cosine.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/stubs/ch10_bug_uniform_samples_cosine.rs"]
#[allow(dead_code)]
mod stub;

use rtl_exercises::ch10_bug_uniform_samples_cosine::*;

rtl_exercises::exercise_main!("ch10_bug_uniform_samples_cosine", e => {
    "value is 1/(2 pi) above the horizon" => check_value(&e::HemispherePdf),
    "generate draws what value states (chi-square)" => check_generate(&e::HemispherePdf),
    "the estimate of the integral of cos theta is pi (z-test)" => check_estimate(&e::HemispherePdf),
});
