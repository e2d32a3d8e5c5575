//! Vectors, points and colours: glam's `DVec3` (f64) under the book's names, and the few vector
//! operations the book defines (reflection, refraction). The orthonormal basis is rtl-pdf's `Onb`.

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

#[cfg(test)]
mod tests {
    use super::*;

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

/// A number as a message shows it: as written for ordinary sizes (`0.5`, `-3`, `130`), in exponent
/// form for very small or very large ones (`1e-70`, not seventy digits).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Num(pub f64);

impl Num {
    /// A vector as `[x, y, z]`, each component as [`Num`] shows it.
    pub fn v3(v: Vec3) -> String {
        format!("[{}, {}, {}]", Num(v.x), Num(v.y), Num(v.z))
    }
}

impl std::fmt::Display for Num {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let a = self.0.abs();
        if a == 0.0 || !a.is_finite() || (1e-4..1e15).contains(&a) {
            write!(f, "{}", self.0)
        } else {
            write!(f, "{:e}", self.0)
        }
    }
}
