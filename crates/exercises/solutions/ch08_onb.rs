//! Reference solution of `exercises/ch08_onb.rs`, compiled only with `--features solutions`: try the
//! exercise first (`cargo exercises solution ch08_onb` shows it once your code passes).

use glam::DVec3;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Onb {
    pub u: DVec3,
    pub v: DVec3,
    pub w: DVec3,
}

impl Onb {
    pub fn from_w(w: DVec3) -> Onb {
        let s = 1.0_f64.copysign(w.z);
        let a = -1.0 / (s + w.z);
        let b = w.x * w.y * a;
        let u = DVec3::new(1.0 + s * w.x * w.x * a, s * b, -s * w.x);
        let v = DVec3::new(b, s + w.y * w.y * a, -w.y);
        Onb { u, v, w }
    }

    pub fn transform(&self, a: DVec3) -> DVec3 {
        a.x * self.u + a.y * self.v + a.z * self.w
    }
}
