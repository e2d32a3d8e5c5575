//! Vectors, points and colours: glam's `DVec3` (f64) under the book's names, and the few vector
//! operations the book defines (reflection, refraction, an orthonormal basis).

use glam::DVec3;

/// A direction or displacement in world space.
pub type Vec3 = DVec3;
/// A position in world space.
pub type Point3 = DVec3;
/// Linear RGB radiance or reflectance.
pub type Color = DVec3;

/// `floor(x)` as an integer without a call to libm's `floor` (which x86-64 without SSE4.1 cannot
/// inline); exact for |x| < 2^63.
#[inline(always)]
pub fn floor_i64(x: f64) -> i64 {
    let t = x as i64;
    t - ((x < t as f64) as i64)
}

/// Mirror reflection of `v` about the unit normal `n`: `v - 2 (v . n) n`.
#[inline]
pub fn reflect(v: Vec3, n: Vec3) -> Vec3 {
    v - 2.0 * v.dot(n) * n
}

/// Snell refraction of the unit direction `uv` through a surface with unit normal `n` (facing `uv`'s
/// origin side), with `eta_ratio` = eta_incident / eta_transmitted. The caller checks total internal
/// reflection first (`eta_ratio * sin(theta) > 1`).
#[inline]
pub fn refract(uv: Vec3, n: Vec3, eta_ratio: f64) -> Vec3 {
    let cos_theta = (-uv).dot(n).min(1.0);
    let r_out_perp = eta_ratio * (uv + cos_theta * n);
    let r_out_parallel = -(1.0 - r_out_perp.length_squared()).abs().sqrt() * n;
    r_out_perp + r_out_parallel
}

/// A right-handed orthonormal basis `(u, v, w)` around the unit vector `w`, built branch-free as in
/// Duff et al., "Building an Orthonormal Basis, Revisited" (JCGT 2017). (`u x v = w`.)
#[derive(Clone, Copy, Debug)]
pub struct Frame {
    pub u: Vec3,
    pub v: Vec3,
    pub w: Vec3,
}

impl Frame {
    /// The basis whose third axis is the unit vector `w`.
    #[inline]
    pub fn from_w(w: Vec3) -> Self {
        let sign = 1.0f64.copysign(w.z);
        let a = -1.0 / (sign + w.z);
        let b = w.x * w.y * a;
        let u = Vec3::new(1.0 + sign * w.x * w.x * a, sign * b, -sign * w.x);
        let v = Vec3::new(b, sign + w.y * w.y * a, -w.y);
        Frame { u, v, w }
    }

    /// Local coordinates `(a, b, c)` to world: `a u + b v + c w`.
    #[inline]
    pub fn to_world(&self, a: Vec3) -> Vec3 {
        a.x * self.u + a.y * self.v + a.z * self.w
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_is_orthonormal_and_right_handed() {
        let ws = [
            Vec3::X,
            -Vec3::X,
            Vec3::Y,
            -Vec3::Y,
            Vec3::Z,
            -Vec3::Z,
            Vec3::new(0.000_385_273_16, 0.000_384_600_16, -0.999_999_880_79).normalize(),
            Vec3::new(1.0, 2.0, -3.0).normalize(),
        ];
        for w in ws {
            let f = Frame::from_w(w);
            assert!((f.u.length() - 1.0).abs() < 1e-12 && (f.v.length() - 1.0).abs() < 1e-12);
            assert!(
                f.u.dot(f.v).abs() < 1e-12 && f.u.dot(w).abs() < 1e-12 && f.v.dot(w).abs() < 1e-12
            );
            assert!((f.u.cross(f.v) - w).length() < 1e-12, "left-handed for {w}");
        }
    }

    #[test]
    fn refraction_obeys_snell() {
        let n = Vec3::Y;
        let d = Vec3::new(1.0, -1.0, 0.0).normalize();
        let t = refract(d, n, 1.0 / 1.5);
        let sin_i = d.cross(n).length();
        let sin_t = t.cross(n).length();
        assert!((sin_i - 1.5 * sin_t).abs() < 1e-12);
        assert!((t.length() - 1.0).abs() < 1e-12 && t.y < 0.0);
    }
}
