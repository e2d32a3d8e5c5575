//! Runs the checks of `exercises/ch12_bug_light_list_pdf.rs`; with `--features solutions`, of the reference solution
//! and of the shipped stub (which they must reject). See `rtl_exercises::harness`.

#[cfg(not(feature = "solutions"))]
#[path = "../exercises/ch12_bug_light_list_pdf.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/ch12_bug_light_list_pdf.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/stubs/ch12_bug_light_list_pdf.rs"]
#[allow(dead_code)]
mod stub;

use rtl_exercises::ch12_bug_light_list_pdf::*;

rtl_exercises::exercise_main!("ch12_bug_light_list_pdf", e => {
    "pdf_value is positive where random lands, and integrates to 1" => check_pdf_value(&e::LightList { lights: lights().to_vec() }),
    "the lights' solid angle from 1 / pdf_value (z-test)" => check_estimate(&e::LightList { lights: lights().to_vec() }),
    "two lights whose cones overlap: exact densities, and they integrate to 1" => check_overlapping(&e::LightList { lights: overlapping_lights().to_vec() }),
});
