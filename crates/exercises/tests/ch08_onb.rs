//! Runs the checks of `exercises/ch08_onb.rs`; with `--features solutions`, of the reference solution
//! and of the shipped stub (which they must reject). See `rtl_exercises::harness`.

#[cfg(not(feature = "solutions"))]
#[path = "../exercises/ch08_onb.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/ch08_onb.rs"]
#[allow(dead_code)]
mod exercise;
#[cfg(feature = "solutions")]
#[path = "../solutions/stubs/ch08_onb.rs"]
#[allow(dead_code)]
mod stub;

use glam::DVec3;
use rtl_exercises::ch08_onb::*;

rtl_exercises::exercise_main!("ch08_onb", e => {
    "from_w: orthonormal and right-handed (axes, near -z, 1000 random w)" => check_basis(|w| { let b = e::Onb::from_w(w); Onb { u: b.u, v: b.v, w: b.w } }),
    "transform: the axes and one more vector" => check_transform(|b: &Onb, a: DVec3| e::Onb { u: b.u, v: b.v, w: b.w }.transform(a)),
});
