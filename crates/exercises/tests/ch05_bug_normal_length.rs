//! Runs the checks of `exercises/ch05_bug_normal_length.rs`; with `--features solutions`, of the reference solution
//! and of the shipped stub (which they must reject). See `rtl_exercises::harness`.

#[cfg(not(feature = "solutions"))]
#[path = "../exercises/ch05_bug_normal_length.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/ch05_bug_normal_length.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/stubs/ch05_bug_normal_length.rs"]
#[allow(dead_code)]
mod stub;

use glam::DVec3;
use rtl_exercises::ch05_bug_normal_length::*;

rtl_exercises::exercise_main!("ch05_bug_normal_length", e => {
    "unit normals, inwards for a negative radius" => check_unit(|c: DVec3, r: f64, p: DVec3| e::outward_normal(c, r, p)),
    "the Lambertian density on the normal integrates to 1 (z-test)" => check_normalised(|c: DVec3, r: f64, p: DVec3| e::outward_normal(c, r, p)),
});
