//! Runs the checks of `exercises/ch12_bug_cone_cos_theta_max.rs`; with `--features solutions`, of the reference solution
//! and of the shipped stub (which they must reject). See `rtl_exercises::harness`.

#[cfg(not(feature = "solutions"))]
#[path = "../exercises/ch12_bug_cone_cos_theta_max.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/ch12_bug_cone_cos_theta_max.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/stubs/ch12_bug_cone_cos_theta_max.rs"]
#[allow(dead_code)]
mod stub;

use rtl_exercises::ch12_bug_cone_cos_theta_max::*;

rtl_exercises::exercise_main!("ch12_bug_cone_cos_theta_max", e => {
    "exact values" => check_values(e::cos_theta_max),
    "every direction of the cone hits the sphere" => check_cone_hits(e::cos_theta_max),
    "the cone's solid angle against the fraction of uniform directions that hit (z-test)" => check_solid_angle(e::cos_theta_max),
});
