//! Reference solution of `exercises/ch08_bug_left_handed_onb.rs`, compiled only with `--features solutions`: try the
//! exercise first (`cargo exercises solution ch08_bug_left_handed_onb` shows it once your code passes).

use glam::DVec3;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Onb {
    pub u: DVec3,
    pub v: DVec3,
    pub w: DVec3,
}

impl Onb {
    /// The bug: u = w x v makes u x v = -w. With v = w x a, u = v x w gives u x v = w.
    pub fn from_w(w: DVec3) -> Onb {
        let a = if w.x.abs() > 0.9 { DVec3::Y } else { DVec3::X };
        let v = w.cross(a).normalize();
        let u = v.cross(w);
        Onb { u, v, w }
    }
}
