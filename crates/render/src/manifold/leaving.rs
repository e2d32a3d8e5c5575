//! One refraction out of the sphere: from a vertex `p` inside it to a point `y` outside.
//!
//! By Fermat's principle the refraction points are the stationary points of the optical length
//! `L(phi) = eta |x - p| + |y - x|` (`eta` the index inside relative to outside) on the arc of the
//! circle that `y` sees, the zeros of
//!
//! `h(phi) = L'(phi) / R = eta (d . t) / |d| - (a . t) / |a|`, with `d = x - p`, `a = y - x`, `t` the
//! unit tangent.
//!
//! A point near the surface, seen through the far side, has up to three. The generalised geometry
//! term is
//!
//! `G = |d omega / dA(y)| = R rho_x cos_i cos_o |cos theta_y| / (|d|^2 |a| |h'(phi)| rho_y)`:
//! in the plane the pencil is `|a| |h'| / cos_o` wide per unit of `phi`, and `cos_i`, `cos_o` are
//! the cosines at `x` inside and outside.

use super::{Interface, MAX_STEPS, SCAN};
use crate::vec::{Point3, Vec3};

/// Where a ray from `p` refracts out of an interface towards `y`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Refraction {
    /// The point on the sphere.
    pub x: Point3,
    /// The unit direction from `p` to `x`.
    pub dir_in: Vec3,
    /// The unit direction from `x` to `y`.
    pub dir_out: Vec3,
    /// The cosine between `dir_in` and the outward normal at `x` (the Fresnel reflectance's).
    pub cos_in: f64,
    /// `|x - p|`.
    pub len_in: f64,
    /// `|y - x|`.
    pub len_out: f64,
    /// The generalised geometry term without the cosine at the emitter: `G / |cos theta_y|`.
    pub geometry: f64,
    /// The part of `geometry` that comes from rotation about the axis, `rho_x / rho_y`.
    pub across: f64,
}

/// The most refraction points found from one `(p, y)`.
pub const MAX_REFRACTIONS: usize = 4;

/// The refraction points found from one `(p, y)`, kept on the stack.
#[derive(Clone, Copy, Debug, Default)]
pub struct Refractions {
    found: [Refraction; MAX_REFRACTIONS],
    n: usize,
}

impl Refractions {
    pub fn as_slice(&self) -> &[Refraction] {
        &self.found[..self.n]
    }

    fn push(&mut self, r: Refraction) {
        if self.n < MAX_REFRACTIONS {
            self.found[self.n] = r;
            self.n += 1;
        }
    }
}

/// `h(phi)` and `h'(phi)` in the plane of the axis (coordinates along the axis and across it: the
/// centre at the origin, `p = (p, 0)`, `y = (y1, y2)` with `y2 > 0`), for a sphere of radius `r` and
/// relative index `eta`.
///
/// A point of the arc `y` sees is named by `t = tan(theta / 2)`, `theta` its angle from the
/// direction `(cy, sy)` of `y`: `cos theta = (1 - t^2) / (1 + t^2)`, `sin theta = 2 t / (1 + t^2)`,
/// and the arc is `|t| < tan(beta / 2) = sqrt((|y| - R) / (|y| + R))` (`cos beta = R / |y|`), so that
/// the scan and Newton's steps need no trigonometric function.
#[derive(Clone, Copy, Debug)]
struct Plane {
    r: f64,
    eta: f64,
    p: f64,
    y1: f64,
    y2: f64,
    /// `y`'s direction: `(y1, y2) / |y|`.
    cy: f64,
    sy: f64,
}

impl Plane {
    /// `(h, h')` at `phi`, from `(cos phi, sin phi)`:
    /// `h = eta p s / |d| - (y2 c - y1 s) / |a|`, with `|d|^2 = (R c - p)^2 + (R s)^2` and
    /// `|a|^2 = (y1 - R c)^2 + (y2 - R s)^2` written as sums of squares (no cancellation where `p`
    /// lies near the surface), and
    /// `h' = eta p (c / |d| - R p s^2 / |d|^3) - ((-y2 s - y1 c) / |a| + R (y2 c - y1 s)^2 / |a|^3)`.
    #[inline]
    fn h(&self, c: f64, s: f64) -> (f64, f64) {
        let Plane {
            r, eta, p, y1, y2, ..
        } = *self;
        let (dx, dy) = (r * c - p, r * s);
        let d2 = dx * dx + dy * dy;
        let d = d2.sqrt();
        let (ax, ay) = (y1 - r * c, y2 - r * s);
        let a2 = ax * ax + ay * ay;
        let a = a2.sqrt();
        let n2 = y2 * c - y1 * s;
        let h = eta * p * s / d - n2 / a;
        let dh = eta * p * (c / d - r * p * s * s / (d2 * d))
            - ((-y2 * s - y1 * c) / a + r * n2 * n2 / (a2 * a));
        (h, dh)
    }

    /// The sign of `h` at `(c, s)`, without a division or a square root: `h` is
    /// `(eta p s |a| - n2 |d|) / (|d| |a|)`, `n2 = y2 c - y1 s`, and the two products compare as their
    /// squares do when their signs agree. (Near a root it may read rounding; the refinement decides.)
    #[inline]
    fn h_positive(&self, c: f64, s: f64) -> bool {
        let Plane {
            r, eta, p, y1, y2, ..
        } = *self;
        let (dx, dy) = (r * c - p, r * s);
        let (ax, ay) = (y1 - r * c, y2 - r * s);
        let (u, w) = (eta * p * s, y2 * c - y1 * s);
        match (u > 0.0, w > 0.0) {
            (true, false) => true,
            (false, true) => false,
            (positive, _) => {
                let (uu, ww) = (u * u * (ax * ax + ay * ay), w * w * (dx * dx + dy * dy));
                if positive { uu > ww } else { uu < ww }
            }
        }
    }

    /// `(cos phi, sin phi)` of the arc's point `t`.
    #[inline]
    fn point(&self, t: f64) -> (f64, f64) {
        let q = 1.0 / (1.0 + t * t);
        let (ct, st) = ((1.0 - t * t) * q, 2.0 * t * q);
        (self.cy * ct - self.sy * st, self.sy * ct + self.cy * st)
    }

    /// The root of `h` for `t` in `[lo, hi]`, where `h` changes sign (positive at `lo` if
    /// `positive_lo`): Newton's steps in `t` (`dh/dt = h'(phi) 2 / (1 + t^2)`), a bisection wherever
    /// a step would leave the bracket. Returns the root's `(cos phi, sin phi)`.
    fn refine(&self, mut lo: f64, mut hi: f64, positive_lo: bool) -> (f64, f64) {
        let rising = !positive_lo;
        let mut x = 0.5 * (lo + hi);
        let mut at = self.point(x);
        for _ in 0..MAX_STEPS {
            let (h, dh) = self.h(at.0, at.1);
            if h == 0.0 {
                break;
            }
            if (h < 0.0) == rising {
                lo = x;
            } else {
                hi = x;
            }
            let newton = x - h * (1.0 + x * x) / (2.0 * dh);
            let next = if newton > lo && newton < hi {
                newton
            } else {
                0.5 * (lo + hi)
            };
            let step = (next - x).abs();
            x = next;
            at = self.point(x);
            if step <= 4.0 * f64::EPSILON || hi - lo <= 4.0 * f64::EPSILON {
                break;
            }
        }
        at
    }
}

impl Interface {
    /// Every point found where a ray from `p` (strictly inside, [`Interface::connects_from`])
    /// refracts out towards `y` (outside): the roots of `h` on the arc `y` sees, found by a scan of
    /// sixteen steps and refined. None if `y` is not outside or lies on the axis (a set of measure
    /// 0: paths through it keep material sampling's weight of 1).
    pub fn leaving(&self, p: Point3, y: Point3) -> Refractions {
        let mut out = Refractions::default();
        let r = self.radius;
        let along = p - self.centre;
        let p_dist = along.length();
        let e1 = along / p_dist;
        let to_y = y - self.centre;
        let y1 = to_y.dot(e1);
        let across = to_y - y1 * e1;
        let y2 = across.length();
        let y_dist = to_y.length();
        if !(y_dist > r && y2 > 1e-12 * y_dist && p_dist > 0.0) {
            return out;
        }
        let e2 = across / y2;
        let plane = Plane {
            r,
            eta: self.ior,
            p: p_dist,
            y1,
            y2,
            cy: y1 / y_dist,
            sy: y2 / y_dist,
        };
        // The arc `y` sees, `cos(phi - phi_y) > R / |y|`: `|t| < tan(beta / 2)`.
        let half = ((y_dist - r) / (y_dist + r)).sqrt();
        let at = |j: usize| half * (2.0 * j as f64 / SCAN as f64 - 1.0);
        let positive_at = |t: f64| {
            let (c, s) = plane.point(t);
            plane.h_positive(c, s)
        };
        // (every point first, independently of the others, so that their arithmetic overlaps)
        let positive: [bool; SCAN + 1] = std::array::from_fn(|j| positive_at(at(j)));
        for j in 1..=SCAN {
            if positive[j] != positive[j - 1] {
                let (c, s) = plane.refine(at(j - 1), at(j), positive[j - 1]);
                if let Some(found) = self.refraction_at(&plane, c, s, e1, e2, y2) {
                    out.push(found);
                }
            }
        }
        out
    }

    /// The refraction at `(cos phi, sin phi)` in the plane spanned by `e1` (the axis) and `e2`, with
    /// what the connection's density needs; `None` where it grazes the sphere on either side or `h'`
    /// vanishes (a caustic, where the density has no finite value).
    fn refraction_at(
        &self,
        plane: &Plane,
        c: f64,
        s: f64,
        e1: Vec3,
        e2: Vec3,
        rho_y: f64,
    ) -> Option<Refraction> {
        let Plane { r, p, y1, y2, .. } = *plane;
        let (_, dh) = plane.h(c, s);
        let (dx, dy) = (r * c - p, r * s);
        let len_in = (dx * dx + dy * dy).sqrt();
        let (ax, ay) = (y1 - r * c, y2 - r * s);
        let len_out = (ax * ax + ay * ay).sqrt();
        let cos_in = (r - p * c) / len_in;
        let cos_out = (y1 * c + y2 * s - r) / len_out;
        let rho_x = r * s.abs();
        let across = rho_x / rho_y;
        let geometry = r * across * cos_in * cos_out / (len_in * len_in * len_out * dh.abs());
        if !(cos_in > 0.0 && cos_out > 0.0 && geometry.is_finite() && geometry > 0.0) {
            return None;
        }
        Some(Refraction {
            x: self.centre + r * (c * e1 + s * e2),
            dir_in: (dx * e1 + dy * e2) / len_in,
            dir_out: (ax * e1 + ay * e2) / len_out,
            cos_in,
            len_in,
            len_out,
            geometry,
            across,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::manifold::testing::{ball, configuration, snell, swept_per_area, unit};
    use rand::SeedableRng;
    use rand_xoshiro::Xoshiro256PlusPlus;

    #[test]
    fn every_refraction_found_obeys_snell_and_reaches_y() {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(7);
        let mut found = 0;
        for ior in [1.33, 1.5, 2.4] {
            let b = ball(ior);
            for _ in 0..2000 {
                let (p, y) = configuration(&mut rng, &b);
                for r in b.leaving(p, y).as_slice() {
                    found += 1;
                    assert!((((r.x - b.centre).length() - b.radius) / b.radius).abs() < 1e-14);
                    let n = (r.x - b.centre) / b.radius;
                    let out = snell(r.dir_in, n, ior).expect("no total internal reflection");
                    assert!((out - r.dir_out).length() < 1e-9, "{out} vs {}", r.dir_out);
                    assert!(((y - r.x).normalize() - r.dir_out).length() < 1e-12);
                    assert!(((r.x - p).normalize() - r.dir_in).length() < 1e-12);
                }
            }
        }
        assert!(found > 4000, "{found}");
    }

    /// A brute-force count of the refractions: the sign changes of `(out - dir_out) x`, sampled
    /// densely over directions of the plane.
    fn brute_force_count(b: &Interface, p: Point3, y: Point3) -> usize {
        let e1 = (p - b.centre).normalize();
        let across = (y - b.centre) - (y - b.centre).dot(e1) * e1;
        let e2 = across.normalize();
        let steps = 200_000;
        let mut count = 0;
        let mut previous: Option<f64> = None;
        for j in 0..=steps {
            let phi = -std::f64::consts::PI + std::f64::consts::TAU * j as f64 / steps as f64;
            let x = b.centre + b.radius * (phi.cos() * e1 + phi.sin() * e2);
            let n = (x - b.centre) / b.radius;
            let sees = (y - x).dot(n) > 0.0;
            let g = snell((x - p).normalize(), n, b.ior)
                .filter(|_| sees)
                .map(|o| {
                    let to_y = (y - x).normalize();
                    o.cross(to_y).dot(e1.cross(e2))
                });
            if let (Some(a), Some(c)) = (previous, g)
                && (a < 0.0) != (c < 0.0)
            {
                count += 1;
            }
            previous = g;
        }
        count
    }

    #[test]
    fn the_scan_finds_the_roots_a_dense_search_finds_almost_always() {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(11);
        let b = ball(1.5);
        let (mut total, mut missed, mut several) = (0, 0, 0);
        for _ in 0..300 {
            let (p, y) = configuration(&mut rng, &b);
            let dense = brute_force_count(&b, p, y);
            let scanned = b.leaving(p, y).as_slice().len();
            assert!(scanned <= dense, "{scanned} found, {dense} exist");
            total += dense;
            missed += dense - scanned;
            several += (dense > 1) as usize;
        }
        assert!(total > 200 && several > 0, "{total} {several}");
        // Misses are allowed (material sampling keeps those paths) but must be rare.
        assert!(missed * 50 <= total, "{missed} of {total} missed");
    }

    /// `G` against finite differences of `omega(y)`: the solid angle swept at `p` by a small square
    /// at `y`, over its area.
    #[test]
    fn the_geometry_term_is_the_solid_angle_per_area() {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(3);
        let b = ball(1.5);
        let mut checked = 0;
        while checked < 50 {
            let (p, y) = configuration(&mut rng, &b);
            let found = b.leaving(p, y);
            let [r] = found.as_slice() else { continue };
            let n_y = unit(&mut rng);
            let omega = |q: Point3| {
                let f = b.leaving(p, q);
                let [r] = f.as_slice() else { return None };
                Some(r.dir_in)
            };
            let Some(swept) = swept_per_area(omega, y, n_y, 1e-6 * b.radius) else {
                continue;
            };
            let g = r.geometry * n_y.dot(r.dir_out).abs();
            assert!(
                ((g - swept) / swept).abs() < 1e-4,
                "G {g} against {swept} by differences"
            );
            checked += 1;
        }
    }

    /// Without refraction (index 1) the connection is a straight line: `G = |cos theta_y| / |y - p|^2`.
    #[test]
    fn index_one_gives_the_ordinary_geometry_term() {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(5);
        let b = ball(1.0);
        for _ in 0..500 {
            let (p, y) = configuration(&mut rng, &b);
            let found = b.leaving(p, y);
            let [r] = found.as_slice() else {
                panic!(
                    "a straight line meets the sphere once: {}",
                    found.as_slice().len()
                )
            };
            let expected = 1.0 / (y - p).length_squared();
            assert!(((r.geometry - expected) / expected).abs() < 1e-9);
            assert!((r.x - p).normalize().dot((y - p).normalize()) > 1.0 - 1e-12);
        }
    }

    /// A wrong term (without the rotation about the axis) is caught by the same comparison.
    #[test]
    fn a_geometry_term_without_its_rotation_is_caught() {
        let b = ball(1.0);
        let (p, y) = (
            b.centre + Vec3::new(0.5, 0.2, 0.1),
            b.centre + Vec3::new(-2.0, 3.0, 1.0),
        );
        let found = b.leaving(p, y);
        let r = found.as_slice()[0];
        let expected = 1.0 / (y - p).length_squared();
        let wrong = r.geometry / r.across;
        assert!(((wrong - expected) / expected).abs() > 0.1);
    }

    #[test]
    fn no_refraction_from_the_axis_or_to_a_point_inside() {
        let b = ball(1.5);
        let p = b.centre + Vec3::new(0.2, 0.0, 0.0);
        assert!(
            b.leaving(p, b.centre + Vec3::new(5.0, 0.0, 0.0))
                .as_slice()
                .is_empty()
        );
        assert!(
            b.leaving(p, b.centre + Vec3::new(0.0, 0.5, 0.0))
                .as_slice()
                .is_empty()
        );
        assert!(!b.connects_from(b.centre));
        assert!(!b.connects_from(b.centre + Vec3::new(b.radius, 0.0, 0.0)));
        assert!(b.connects_from(p));
    }
}
