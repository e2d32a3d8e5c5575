//! Runs the checks of `exercises/ch05_lambertian_pdf.rs`; with `--features solutions`, of the reference solution
//! and of the shipped stub (which they must reject). See `rtl_exercises::harness`.

#[cfg(not(feature = "solutions"))]
#[path = "../exercises/ch05_lambertian_pdf.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/ch05_lambertian_pdf.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/stubs/ch05_lambertian_pdf.rs"]
#[allow(dead_code)]
mod stub;

use rtl_exercises::ch05_lambertian_pdf::*;

rtl_exercises::exercise_main!("ch05_lambertian_pdf", e => {
    "exact values, grazing and below the surface" => check_values(e::lambertian_scattering_pdf),
    "never negative, integrates to 1 (z-test)" => check_normalised(e::lambertian_scattering_pdf),
});
