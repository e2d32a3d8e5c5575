//! The equiangular density along a ray about a point (Kulla and Fajardo 2012, "Importance Sampling
//! Techniques for Path Tracing in Participating Media"): `q(t)` proportional to the inverse square
//! of the distance to the point, with respect to the ray parameter `t`.

use crate::ray::Ray;
use crate::vec::Point3;

// ANCHOR: equiangular
/// The equiangular density about a point (Kulla and Fajardo 2012) along a ray: with `delta` the ray
/// parameter of the point's foot on the line and `h > 0` its distance from the line (in units of the
/// ray parameter), `t = delta + h tan(theta)` with `theta` uniform, i.e. `q(t) = h / ((t - delta)^2 + h^2)`
/// per unit of `theta`'s range. It cancels the inverse square of the distance to the point.
#[derive(Clone, Copy, Default)]
pub(super) struct Equiangular {
    pub(super) delta: f64,
    pub(super) h: f64,
    /// `theta`'s range summed over the stretches (the density's normalisation).
    pub(super) mass: f64,
}

impl Equiangular {
    pub(super) fn about(ray: &Ray, c: Point3) -> Equiangular {
        let dd = ray.direction.length_squared();
        let oc = c - ray.origin;
        let delta = oc.dot(ray.direction) / dd;
        let h2 = (oc.length_squared() / dd - delta * delta).max(0.0);
        // a ray through the point: keep the density finite
        let h = h2.sqrt().max(1e-9 * (delta.abs() + 1.0));
        Equiangular {
            delta,
            h,
            mass: 0.0,
        }
    }
    /// `x = (t - delta) / h = tan(theta)`.
    #[inline]
    pub(super) fn x(&self, t: f64) -> f64 {
        (t - self.delta) / self.h
    }
    /// `theta`'s range over `t0..t1` (`t0 <= t1`). On one side of the foot as
    /// `atan((x1 - x0) / (1 + x0 x1))` with `x1 - x0 = (t1 - t0) / h`: the difference of the two
    /// angles cancels to rounding when they are alike (an emitter far from a short stretch: at 1e20
    /// units away the stretch's angle is below the angles' rounding, and read as 0).
    #[inline]
    pub(super) fn angle(&self, t0: f64, t1: f64) -> f64 {
        let (x0, x1) = (self.x(t0), self.x(t1));
        if x0 * x1 >= 0.0 {
            ((t1 - t0) / self.h / (1.0 + x0 * x1)).atan()
        } else {
            x1.atan() - x0.atan()
        }
    }
    /// The `t` in `t0..t1` whose angle from `t0` is `phi` (in `0..=angle(t0, t1)`). On one side of
    /// the foot by the tangent's addition formula, as an offset from `t0`:
    /// `t - t0 = h tan(phi) (1 + x0^2) / (1 - x0 tan(phi))` (for the same reason as [`Self::angle`]).
    #[inline]
    pub(super) fn at_angle(&self, t0: f64, t1: f64, phi: f64) -> f64 {
        let (x0, x1) = (self.x(t0), self.x(t1));
        let t = if x0 * x1 >= 0.0 {
            let tau = phi.tan();
            let den = 1.0 - x0 * tau;
            // (positive for phi within the range; rounding at the pole ends at t1)
            if den > 0.0 {
                t0 + self.h * tau * (1.0 + x0 * x0) / den
            } else {
                t1
            }
        } else {
            self.delta + self.h * (x0.atan() + phi).tan()
        };
        t.clamp(t0, t1)
    }
    #[inline]
    pub(super) fn q(&self, t: f64) -> f64 {
        let x = t - self.delta;
        self.h / (x * x + self.h * self.h) / self.mass
    }
}
// ANCHOR_END: equiangular

#[cfg(test)]
mod tests {
    use super::Equiangular;

    /// `angle` is the difference of the angles, and `at_angle` its inverse, for a point near the
    /// stretch and for one 1e20 away (where the plain difference `atan(x1) - atan(x0)` of two angles
    /// near pi/4 is all rounding). (Not for `h` near the floor of 1e-9: there the ulp of `t` itself
    /// is a sizeable angle.)
    #[test]
    fn equiangular_angles_and_their_inverse_hold_near_and_far() {
        for (delta, h) in [
            (0.5, 2.0),
            (-3.0, 0.1),
            (1e20, 1e20),
            (-1e20, 1e18),
            (4.0, 1e-4),
        ] {
            let e = Equiangular {
                delta,
                h,
                mass: 1.0,
            };
            for (t0, t1) in [(0.0, 1.0), (2.0, 9.0), (3.9, 4.1)] {
                let range = e.angle(t0, t1);
                let plain = e.x(t1).atan() - e.x(t0).atan();
                assert!(range >= 0.0);
                if h < 1e10 {
                    assert!((range - plain).abs() <= 1e-12 * plain.abs().max(1e-300) + 1e-15);
                }
                for f in [0.1, 0.5, 0.9] {
                    let t = e.at_angle(t0, t1, f * range);
                    assert!((t0..=t1).contains(&t));
                    let back = e.angle(t0, t);
                    assert!(
                        (back - f * range).abs() <= 1e-9 * range,
                        "{delta} {h} {t0}..{t1}: {back} vs {}",
                        f * range
                    );
                }
            }
        }
        // The plain difference loses the far stretch: it is what the density was built from before.
        let far = Equiangular {
            delta: 1e20,
            h: 1e20,
            mass: 1.0,
        };
        let plain = far.x(1.0).atan() - far.x(0.0).atan();
        assert!((plain - far.angle(0.0, 1.0)).abs() > 0.5 * far.angle(0.0, 1.0));
    }
}
