//! In and out again: from a vertex `p` outside the sphere, through it, to a point `y` outside: the
//! caustic a glass ball focuses.
//!
//! The first refraction point `x1`, at angle `phi` from the axis on the arc `p` sees, decides the
//! rest. The ray refracts in (Snell's law, `sin i = eta sin r`), crosses the chord of length
//! `2 R cos r` to `x2`, and refracts out at the angle `i` it came in at (a ball gives back what it
//! takes: no total internal reflection for `eta >= 1`). The connection's points are the zeros of
//! the signed distance of `y` from the ray that leaves,
//!
//! `g(phi) = d3 x (y - x2)` (the plane's cross product), with `y` ahead: `(y - x2) . d3 > 0`,
//!
//! and `|g'(phi)|` is the width at `y` of the pencil of leaving rays per unit of `phi`, so that
//!
//! `G = R rho_1 cos_i |cos theta_y| / (|x1 - p|^2 |g'(phi)| rho_y)`.
//!
//! `g'` is carried through the same arithmetic as `g` by forward-mode differentiation (dual
//! numbers), in the arc's parameter `t = tan(phi / 2)`, `dphi / dt = 2 / (1 + t^2)`.

use super::{Interface, MAX_STEPS};

/// Points at which a crossing's solver looks across the arc `p` sees: roots closer than a sixteenth
/// of it are missed (and left to material sampling).
const SCAN: usize = 16;
use crate::vec::{Point3, Vec3};
use std::ops::{Add, Div, Mul, Neg, Sub};

/// A number and its derivative (forward-mode automatic differentiation).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Dual {
    v: f64,
    d: f64,
}

/// What the path's arithmetic needs of its numbers: plain ones for the scan, dual ones where the
/// derivative is wanted.
trait Number:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    fn constant(v: f64) -> Self;
    fn sqrt(self) -> Self;
    fn value(self) -> f64;
    fn scale(self, k: f64) -> Self;
}

impl Number for f64 {
    #[inline(always)]
    fn constant(v: f64) -> f64 {
        v
    }
    #[inline(always)]
    fn sqrt(self) -> f64 {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn value(self) -> f64 {
        self
    }
    #[inline(always)]
    fn scale(self, k: f64) -> f64 {
        k * self
    }
}

impl Number for Dual {
    #[inline(always)]
    fn constant(v: f64) -> Dual {
        Dual { v, d: 0.0 }
    }
    #[inline(always)]
    fn sqrt(self) -> Dual {
        let v = self.v.sqrt();
        Dual {
            v,
            d: self.d / (2.0 * v),
        }
    }
    #[inline(always)]
    fn value(self) -> f64 {
        self.v
    }
    #[inline(always)]
    fn scale(self, k: f64) -> Dual {
        Dual {
            v: k * self.v,
            d: k * self.d,
        }
    }
}

impl Add for Dual {
    type Output = Dual;
    fn add(self, o: Dual) -> Dual {
        Dual {
            v: self.v + o.v,
            d: self.d + o.d,
        }
    }
}

impl Sub for Dual {
    type Output = Dual;
    fn sub(self, o: Dual) -> Dual {
        Dual {
            v: self.v - o.v,
            d: self.d - o.d,
        }
    }
}

impl Mul for Dual {
    type Output = Dual;
    fn mul(self, o: Dual) -> Dual {
        Dual {
            v: self.v * o.v,
            d: self.d * o.v + self.v * o.d,
        }
    }
}

impl Div for Dual {
    type Output = Dual;
    fn div(self, o: Dual) -> Dual {
        Dual {
            v: self.v / o.v,
            d: (self.d * o.v - self.v * o.d) / (o.v * o.v),
        }
    }
}

impl Neg for Dual {
    type Output = Dual;
    fn neg(self) -> Dual {
        Dual {
            v: -self.v,
            d: -self.d,
        }
    }
}

/// Where a ray from `p` crosses an interface towards `y`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Crossing {
    /// Where the ray refracts in.
    pub entry: Point3,
    /// Where it refracts out.
    pub exit: Point3,
    /// The unit direction from `p` to `entry`.
    pub dir_in: Vec3,
    /// The unit direction from `exit` to `y`.
    pub dir_out: Vec3,
    /// The cosine of the angle of incidence outside (at `entry`, and of refraction at `exit`).
    pub cos_outside: f64,
    /// The cosine of the angle inside (of refraction at `entry`, of incidence at `exit`).
    pub cos_inside: f64,
    /// `|entry - p|`.
    pub len_in: f64,
    /// `|exit - entry| = 2 R cos_inside`.
    pub len_inside: f64,
    /// `|y - exit|`.
    pub len_out: f64,
    /// The generalised geometry term without the cosine at the emitter: `G / |cos theta_y|`.
    pub geometry: f64,
    /// The part of `geometry` that comes from rotation about the axis, `rho_1 / rho_y`.
    pub across: f64,
}

/// The most crossings found from one `(p, y)`.
pub const MAX_CROSSINGS: usize = 4;

/// The crossings found from one `(p, y)`, kept on the stack.
#[derive(Clone, Copy, Debug, Default)]
pub struct Crossings {
    found: [Crossing; MAX_CROSSINGS],
    n: usize,
}

impl Crossings {
    pub fn as_slice(&self) -> &[Crossing] {
        &self.found[..self.n]
    }

    fn push(&mut self, c: Crossing) {
        if self.n < MAX_CROSSINGS {
            self.found[self.n] = c;
            self.n += 1;
        }
    }
}

/// The plane of the axis: the centre at the origin, `p = (p, 0)` with `p > R`, `y = (y1, y2)` with
/// `y2 > 0`; the arc `p` sees is `|t| < sqrt((p - R) / (p + R))`.
#[derive(Clone, Copy, Debug)]
struct Plane {
    r: f64,
    eta: f64,
    p: f64,
    y1: f64,
    y2: f64,
}

/// The path through the ball for one `t`, in the plane.
#[derive(Clone, Copy, Debug)]
struct Traced<N> {
    g: N,
    /// `(cos phi, sin phi)` of the entry.
    c: f64,
    s: f64,
    x2: [f64; 2],
    d1: [f64; 2],
    d3: [f64; 2],
    cos_i: f64,
    cos_r: f64,
    len_in: f64,
    /// `(y - x2) . d3`: the distance of `y` ahead along the leaving ray.
    ahead: f64,
}

impl Plane {
    /// The path for the arc's point `t` (plain, or dual for `g`'s derivative).
    #[inline(always)]
    fn trace<N: Number>(&self, t: N) -> Traced<N> {
        let Plane { r, eta, p, y1, y2 } = *self;
        let one = N::constant(1.0);
        let q = one / (one + t * t);
        let c = (one - t * t) * q;
        let s = (t * q).scale(2.0);
        // in: from p to x1 = R (c, s), whose outward normal is (c, s)
        let (dx, dy) = (c.scale(r) - N::constant(p), s.scale(r));
        let len = (dx * dx + dy * dy).sqrt();
        let (d1x, d1y) = (dx / len, dy / len);
        let cos_i = -(d1x * c + d1y * s);
        let inv = 1.0 / eta;
        let cos_r = (one - (one - cos_i * cos_i).scale(inv * inv)).sqrt();
        let k = cos_i.scale(inv) - cos_r;
        let (d2x, d2y) = (d1x.scale(inv) + k * c, d1y.scale(inv) + k * s);
        // across the chord to x2, and out
        let chord = cos_r.scale(2.0 * r);
        let (x2x, x2y) = (c.scale(r) + chord * d2x, s.scale(r) + chord * d2y);
        let (n2x, n2y) = (x2x.scale(1.0 / r), x2y.scale(1.0 / r));
        let k = cos_i - cos_r.scale(eta);
        let (d3x, d3y) = (d2x.scale(eta) + k * n2x, d2y.scale(eta) + k * n2y);
        let (ax, ay) = (N::constant(y1) - x2x, N::constant(y2) - x2y);
        Traced {
            g: d3x * ay - d3y * ax,
            c: c.value(),
            s: s.value(),
            x2: [x2x.value(), x2y.value()],
            d1: [d1x.value(), d1y.value()],
            d3: [d3x.value(), d3y.value()],
            cos_i: cos_i.value(),
            cos_r: cos_r.value(),
            len_in: len.value(),
            ahead: d3x.value() * ax.value() + d3y.value() * ay.value(),
        }
    }

    /// The root of `g` for `t` in `[lo, hi]`, where `g` changes sign (positive at `lo` if
    /// `positive_lo`): Newton's steps in `t` from `start`, a bisection wherever a step would leave
    /// the bracket.
    fn refine(
        &self,
        mut lo: f64,
        mut hi: f64,
        positive_lo: bool,
        start: f64,
    ) -> (f64, Traced<Dual>) {
        let rising = !positive_lo;
        let mut x = start;
        let mut at = self.trace(Dual { v: x, d: 1.0 });
        for _ in 0..MAX_STEPS {
            let g = at.g;
            if g.v == 0.0 {
                break;
            }
            if (g.v < 0.0) == rising {
                lo = x;
            } else {
                hi = x;
            }
            let newton = x - g.v / g.d;
            let next = if newton > lo && newton < hi {
                newton
            } else {
                0.5 * (lo + hi)
            };
            let step = (next - x).abs();
            x = next;
            at = self.trace(Dual { v: x, d: 1.0 });
            if step <= 4.0 * f64::EPSILON || hi - lo <= 4.0 * f64::EPSILON {
                break;
            }
        }
        (x, at)
    }
}

impl Interface {
    /// Whether a crossing can start from `p`: strictly outside the sphere, and an index of 1 or more
    /// inside (so that the ray always gets through).
    #[inline]
    pub fn crossed_from(&self, p: Point3) -> bool {
        self.ior >= 1.0 && (p - self.centre).length() > self.radius * (1.0 + 1e-9)
    }

    /// The share of light a crossing lets through: `(1 - F)` in and `(1 - F)` out, as the
    /// dielectric's own coin decides each (Schlick's `F` at the incident side's cosine).
    #[inline]
    pub fn transmission_through(&self, cos_outside: f64, cos_inside: f64) -> f64 {
        (1.0 - crate::material::schlick(cos_outside, 1.0 / self.ior))
            * (1.0 - crate::material::schlick(cos_inside, self.ior))
    }

    /// Every crossing found from `p` (outside, [`Interface::crossed_from`]) towards `y` (outside):
    /// the roots of `g` on the arc `p` sees, found by a scan of sixteen steps and refined. None
    /// if `y` lies on the axis (a set of measure 0: paths through it keep material sampling's
    /// weight of 1).
    pub fn crossings(&self, p: Point3, y: Point3) -> Crossings {
        let mut out = Crossings::default();
        let r = self.radius;
        let along = p - self.centre;
        let p_dist = along.length();
        let e1 = along / p_dist;
        let to_y = y - self.centre;
        let y1 = to_y.dot(e1);
        let across = to_y - y1 * e1;
        let y2 = across.length();
        if !(p_dist > r && y2 > 1e-12 * to_y.length() && self.ior >= 1.0) {
            return out;
        }
        let e2 = across / y2;
        let plane = Plane {
            r,
            eta: self.ior,
            p: p_dist,
            y1,
            y2,
        };
        let half = ((p_dist - r) / (p_dist + r)).sqrt();
        let at = |j: usize| half * (2.0 * j as f64 / SCAN as f64 - 1.0);
        // (every point first, independently of the others, so that their arithmetic overlaps)
        let g: [f64; SCAN + 1] = std::array::from_fn(|j| plane.trace(at(j)).g);
        for j in 1..=SCAN {
            let (a, b) = (g[j - 1], g[j]);
            if (a > 0.0) != (b > 0.0) {
                let (lo, hi) = (at(j - 1), at(j));
                // Newton starts where the chord crosses 0
                let secant = lo + (hi - lo) * a / (a - b);
                let start = if secant > lo && secant < hi {
                    secant
                } else {
                    0.5 * (lo + hi)
                };
                let (t, traced) = plane.refine(lo, hi, a > 0.0, start);
                if let Some(found) = self.crossing_at(&plane, t, &traced, e1, e2) {
                    out.push(found);
                }
            }
        }
        out
    }

    /// The crossing traced for `t`, with what the connection's density needs; `None` where `y` lies
    /// behind the leaving ray, the entry grazes the sphere, or `g'` vanishes (a caustic).
    fn crossing_at(
        &self,
        plane: &Plane,
        t: f64,
        traced: &Traced<Dual>,
        e1: Vec3,
        e2: Vec3,
    ) -> Option<Crossing> {
        let r = plane.r;
        let Traced {
            g,
            c,
            s,
            x2,
            d1,
            d3,
            cos_i,
            cos_r,
            len_in,
            ahead,
        } = *traced;
        let dg_dphi = g.d * (1.0 + t * t) / 2.0;
        let across = r * s.abs() / plane.y2;
        let geometry = r * across * cos_i / (len_in * len_in * dg_dphi.abs());
        if !(ahead > 0.0 && cos_i > 0.0 && geometry.is_finite() && geometry > 0.0) {
            return None;
        }
        let to = |v: [f64; 2]| v[0] * e1 + v[1] * e2;
        Some(Crossing {
            entry: self.centre + r * (c * e1 + s * e2),
            exit: self.centre + to(x2),
            dir_in: to(d1),
            dir_out: to(d3),
            cos_outside: cos_i,
            cos_inside: cos_r,
            len_in,
            len_inside: 2.0 * r * cos_r,
            len_out: ahead,
            geometry,
            across,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::manifold::testing::{ball, snell, swept_per_area, unit};
    use rand::{Rng, SeedableRng};
    use rand_xoshiro::Xoshiro256PlusPlus;

    /// A random vertex and point, both outside the ball.
    fn outside<R: Rng>(rng: &mut R, b: &Interface) -> (Point3, Point3) {
        let p = b.centre + b.radius * rng.random_range(1.02..6.0f64) * unit(rng);
        let y = b.centre + b.radius * rng.random_range(1.02..8.0f64) * unit(rng);
        (p, y)
    }

    #[test]
    fn every_crossing_found_obeys_snell_twice_and_reaches_y() {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(17);
        let mut found = 0;
        for ior in [1.33, 1.5, 2.4] {
            let b = ball(ior);
            for _ in 0..2000 {
                let (p, y) = outside(&mut rng, &b);
                for k in b.crossings(p, y).as_slice() {
                    found += 1;
                    for x in [k.entry, k.exit] {
                        assert!((((x - b.centre).length() - b.radius) / b.radius).abs() < 1e-13);
                    }
                    assert!(((k.entry - p).normalize() - k.dir_in).length() < 1e-12);
                    let n1 = (k.entry - b.centre) / b.radius;
                    let inside = snell(k.dir_in, -n1, 1.0 / ior).expect("always enters");
                    assert!(((k.exit - k.entry).normalize() - inside).length() < 1e-9);
                    let n2 = (k.exit - b.centre) / b.radius;
                    let out = snell(inside, n2, ior).expect("no total internal reflection");
                    assert!((out - k.dir_out).length() < 1e-9, "{out} vs {}", k.dir_out);
                    assert!(((y - k.exit).normalize() - k.dir_out).length() < 1e-9);
                }
            }
        }
        assert!(found > 1000, "{found}");
    }

    /// Without refraction (index 1) a crossing is the straight line: `G = |cos theta_y| / |y - p|^2`,
    /// and there is one if and only if the segment meets the ball.
    #[test]
    fn index_one_gives_the_straight_line() {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(19);
        let b = ball(1.0);
        let mut seen = 0;
        for _ in 0..2000 {
            let (p, y) = outside(&mut rng, &b);
            let d = (y - p).normalize();
            let foot = p + d * (b.centre - p).dot(d);
            let meets = (foot - b.centre).length() < b.radius
                && (b.centre - p).dot(d) > 0.0
                && (b.centre - y).dot(d) < 0.0;
            let found = b.crossings(p, y);
            if (foot - b.centre).length() > b.radius * (1.0 - 1e-6)
                && (foot - b.centre).length() < b.radius * (1.0 + 1e-6)
            {
                continue;
            }
            assert_eq!(found.as_slice().len(), meets as usize, "{p} {y}");
            if let [k] = found.as_slice() {
                seen += 1;
                let expected = 1.0 / (y - p).length_squared();
                assert!(((k.geometry - expected) / expected).abs() < 1e-8);
            }
        }
        assert!(seen > 100, "{seen}");
    }

    /// `G` against finite differences of `omega(y)`.
    #[test]
    fn the_geometry_term_is_the_solid_angle_per_area() {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(23);
        let b = ball(1.5);
        let mut checked = 0;
        while checked < 50 {
            let (p, y) = outside(&mut rng, &b);
            let found = b.crossings(p, y);
            let [k] = found.as_slice() else { continue };
            let n_y = unit(&mut rng);
            let omega = |q: Point3| {
                let f = b.crossings(p, q);
                let [k] = f.as_slice() else { return None };
                Some(k.dir_in)
            };
            let Some(swept) = swept_per_area(omega, y, n_y, 1e-6 * b.radius) else {
                continue;
            };
            let g = k.geometry * n_y.dot(k.dir_out).abs();
            assert!(
                ((g - swept) / swept).abs() < 1e-4,
                "G {g} against {swept} by differences"
            );
            checked += 1;
        }
    }

    /// A wrong term (without the rotation about the axis) is caught by the straight line's.
    #[test]
    fn a_geometry_term_without_its_rotation_is_caught() {
        let b = ball(1.0);
        let (p, y) = (
            b.centre + Vec3::new(2.0, 0.3, 0.1),
            b.centre + Vec3::new(-3.0, -0.2, 0.9),
        );
        let found = b.crossings(p, y);
        let [k] = found.as_slice() else {
            panic!("{} crossings", found.as_slice().len())
        };
        let expected = 1.0 / (y - p).length_squared();
        assert!(((k.geometry - expected) / expected).abs() < 1e-9);
        let wrong = k.geometry / k.across;
        assert!(((wrong - expected) / expected).abs() > 0.1);
    }

    #[test]
    fn a_ball_focuses_light_from_far_above_below_it_not_above_it() {
        // A point light far above: the points under the ball near its focus receive light through
        // several crossings or one, points beside the ball's shadow none.
        // (A ball of index 1.5 focuses at 1.5 radii from its centre; a ray through it turns by at
        // most about 96 degrees, so nothing above it is reached from above.)
        let b = ball(1.5);
        let y = b.centre + Vec3::new(0.0, 1000.0, 0.0);
        let focus = b.centre + b.radius * Vec3::new(0.01, -1.5, 0.0);
        assert!(!b.crossings(focus, y).as_slice().is_empty());
        let above = b.centre + b.radius * Vec3::new(0.3, 2.0, 0.1);
        assert!(b.crossings(above, y).as_slice().is_empty());
        assert!(!b.crossed_from(b.centre));
    }
}
