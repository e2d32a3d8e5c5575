//! Runs the checks of `exercises/ch08_bug_left_handed_onb.rs`; with `--features solutions`, of the reference solution
//! and of the shipped stub (which they must reject). See `rtl_exercises::harness`.

#[cfg(not(feature = "solutions"))]
#[path = "../exercises/ch08_bug_left_handed_onb.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/ch08_bug_left_handed_onb.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/stubs/ch08_bug_left_handed_onb.rs"]
#[allow(dead_code)]
mod stub;

use rtl_exercises::ch08_bug_left_handed_onb::*;
use rtl_exercises::ch08_onb::Onb;

rtl_exercises::exercise_main!("ch08_bug_left_handed_onb", e => {
    "orthonormal and right-handed: u x v = w" => check_right_handed(|w| { let b = e::Onb::from_w(w); Onb { u: b.u, v: b.v, w: b.w } }),
    "a sampled azimuth keeps its sense" => check_azimuth(|w| { let b = e::Onb::from_w(w); Onb { u: b.u, v: b.v, w: b.w } }),
});
