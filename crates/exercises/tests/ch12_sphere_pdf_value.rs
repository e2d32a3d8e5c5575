//! Runs the checks of `exercises/ch12_sphere_pdf_value.rs`; with `--features solutions`, of the reference solution
//! and of the shipped stub (which they must reject). See `rtl_exercises::harness`.

#[cfg(not(feature = "solutions"))]
#[path = "../exercises/ch12_sphere_pdf_value.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/ch12_sphere_pdf_value.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/stubs/ch12_sphere_pdf_value.rs"]
#[allow(dead_code)]
mod stub;

use rtl_exercises::ch12_sphere_pdf_value::*;

rtl_exercises::exercise_main!("ch12_sphere_pdf_value", e => {
    "sphere_solid_angle: far, near, inside and on" => check_solid_angle(e::sphere_solid_angle),
    "sphere_pdf_value: hits, misses, inside, on and just above" => check_values(e::sphere_pdf_value),
    "sphere_pdf_value: integrates to 1 (z-test)" => check_normalised(e::sphere_pdf_value),
});
