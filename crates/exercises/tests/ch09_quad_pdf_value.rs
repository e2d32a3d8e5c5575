//! Runs the checks of `exercises/ch09_quad_pdf_value.rs`; with `--features solutions`, of the reference solution
//! and of the shipped stub (which they must reject). See `rtl_exercises::harness`.

#[cfg(not(feature = "solutions"))]
#[path = "../exercises/ch09_quad_pdf_value.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/ch09_quad_pdf_value.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/stubs/ch09_quad_pdf_value.rs"]
#[allow(dead_code)]
mod stub;

use rtl_exercises::ch09_quad_pdf_value::*;

rtl_exercises::exercise_main!("ch09_quad_pdf_value", e => {
    "exact values: head-on, oblique, misses" => check_values(e::quad_pdf_value),
    "integrates to 1 over the sphere (z-test)" => check_normalised(e::quad_pdf_value),
});
