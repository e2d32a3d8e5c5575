//! Manifold next-event estimation through a dielectric sphere (Hanika, Droske and Fascione,
//! "Manifold Next Event Estimation", 2015): light that reaches a point inside a glass ball only by
//! refracting through its surface, such as book 2's blue subsurface sphere lit through its glass
//! shell, found by a connection instead of by chance.
//!
//! A shadow ray from inside the ball meets its surface, a delta interface that next-event
//! estimation cannot pass. Material sampling finds that light only when a path happens to leave the
//! ball straight towards an emitter: rare, and bright when it happens, so these are the noisiest
//! pixels of book 2's final scene. The connection draws a point `y` on an emitter instead, and
//! solves for the point `x` of the sphere where a ray from the vertex `p` refracts towards `y`.
//!
//! **The solution lies in a plane.** The sphere and `p` are symmetric about the axis through the
//! centre and `p`, so `x` lies in the plane of that axis and `y`. One unknown remains, the angle
//! `phi` of `x` from the axis. By Fermat's principle the refraction points are the stationary points
//! of the optical length `L(phi) = eta |x - p| + |y - x|` (`eta` the index inside relative to
//! outside) on the arc of the circle that `y` sees, the zeros of
//!
//! `h(phi) = L'(phi) / R = eta (d . t) / |d| - (a . t) / |a|`, with `d = x - p`, `a = y - x`, `t` the
//! unit tangent.
//!
//! There may be more than one: a point near the surface, seen through the far side, has up to three.
//! So the arc is scanned for sign changes of `h`, and each is refined by safeguarded Newton.
//!
//! **The density of the connection.** The direction `omega = d / |d|` that leaves `p` varies with `y`
//! by the generalised geometry term, the solid angle at `p` per unit area at `y`:
//!
//! `G = |d omega / dA(y)| = R rho_x cos_i cos_o |cos theta_y| / (|d|^2 |a| |h'(phi)| rho_y)`.
//!
//! It is the cross-section of the pencil of refracted rays. In the plane, `|a| |h'| / cos_o` per unit
//! of `phi`; across it, rotation about the axis, which moves `x` and `y` by their distances
//! `rho_x` and `rho_y` from it. `cos_i` and `cos_o` are the cosines at `x` inside and outside, and
//! `theta_y` the angle at the emitter. A point drawn with area density `p_A(y)` estimates
//!
//! `f(omega) G (1 - F(cos_i)) L_e(y) T / p_A(y)`,
//!
//! where `F` is the reflectance the dielectric reflects with (Schlick's) and `T` the transmittance of
//! the media the two legs cross.
//!
//! **Unbiased whatever the solver misses.** Both the connection and material sampling make paths
//! `p -> x -> y`. Each such path is weighted by the power heuristic between the connection's density
//! `p_A(y)` and material sampling's `p_m(omega) G` (both in the area measure at `y`), but only if
//! solving from `(p, y)` finds its `x`. A path that material sampling takes through a point the solver
//! does not find keeps weight 1. The two weights of every path sum to 1, so the estimate is unbiased
//! even where a root is missed, near a caustic where two roots merge.

use crate::aabb::Aabb;
use crate::hit::Hit;
use crate::ids::MaterialId;
use crate::material::{Material, schlick};
use crate::scene::{GroupId, Object, Scene, Transform};
use crate::vec::{Point3, Vec3};
use glam::DVec2;

/// A static dielectric sphere in world space that holds something a path can scatter at inside it
/// (a medium, a diffuse or fuzzy surface): the interface a connection refracts through.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Interface {
    pub centre: Point3,
    pub radius: f64,
    /// The index of refraction inside relative to outside.
    pub ior: f64,
    pub material: MaterialId,
    /// The summed density of the constant media that fill the whole ball (each bounded by a sphere
    /// around it): a lower bound on the extinction along any leg inside, for the connection's
    /// roulette ([`Interface::roulette`]).
    pub filled: f64,
}

/// The connection's roulette plays for connections whose inner leg is surely darker than this: it
/// makes one with probability `min(1, T_max / CONNECTION_ROULETTE)` and divides by that, so that a
/// connection made deep in a dense medium, where the light through the surface is nearly gone,
/// counts with at most this weight. On book 2's final scene 1/16 (against connecting from every
/// vertex) keeps the noise constant and saves most of the connections' cost.
pub const CONNECTION_ROULETTE: f64 = 1.0 / 16.0;

/// An emitter the connection draws its point `y` on, uniformly by area.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AreaEmitter {
    shape: AreaShape,
    pub material: MaterialId,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum AreaShape {
    /// The parallelogram `q + a u + b v`, `a, b` in `[0, 1]`, with its unit normal and its area.
    Quad {
        q: Point3,
        u: Vec3,
        v: Vec3,
        normal: Vec3,
        area: f64,
    },
    /// A static sphere.
    Sphere { centre: Point3, radius: f64 },
}

/// A point drawn on an emitter: where, the emitter's unit normal there, and the density of drawing
/// it, with respect to area (the choice of emitter included).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EmitterPoint {
    pub y: Point3,
    pub normal: Vec3,
    pub density: f64,
}

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

/// Points at which `h` is looked at across the arc `y` sees: two roots closer than the arc's
/// sixteenth are missed (and left to material sampling).
const SCAN: usize = 16;
/// Most Newton or bisection steps refining one root.
const MAX_STEPS: usize = 64;

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
    /// Whether a connection can be made from `p`: strictly inside the sphere, and off its centre
    /// (where the axis would be undefined). A choice made from `p` alone, before anything is drawn.
    #[inline]
    pub fn connects_from(&self, p: Point3) -> bool {
        let d = (p - self.centre).length();
        d < self.radius * (1.0 - 1e-9) && d > self.radius * 1e-9
    }

    /// The probability with which a connection from `p` is made: `min(1, T_max / CONNECTION_ROULETTE)`,
    /// `T_max = exp(-filled (R - |p - c|))` a bound on the transmittance of any leg from `p` to the
    /// surface (at least `R - |p - c|` long, through the media that fill the ball).
    #[inline]
    pub fn roulette(&self, p: Point3) -> f64 {
        let depth = self.radius - (p - self.centre).length();
        ((-self.filled * depth.max(0.0)).exp() / CONNECTION_ROULETTE).min(1.0)
    }

    /// Whether `p` (a hit point with error bound `err`) lies on the sphere.
    #[inline]
    pub fn on_surface(&self, p: Point3, err: f64) -> bool {
        ((p - self.centre).length() - self.radius).abs() <= 1e-7 * self.radius + 8.0 * err
    }

    /// The share of light the dielectric lets through at `x` for the cosine `cos_in` inside: the
    /// probability with which it refracts rather than reflects, `1 - F` (Schlick's `F`, as the
    /// dielectric's own coin).
    #[inline]
    pub fn transmission(&self, cos_in: f64) -> f64 {
        1.0 - schlick(cos_in, self.ior)
    }

    /// Every point found where a ray from `p` (strictly inside, [`Interface::connects_from`])
    /// refracts out towards `y` (outside): the roots of `h` on the arc `y` sees, found by a scan of
    /// sixteen steps and refined. None if `y` is not outside or lies on the axis (a set of measure
    /// 0: paths through it keep material sampling's weight of 1).
    pub fn refractions(&self, p: Point3, y: Point3) -> Refractions {
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
        let mut previous = positive_at(at(0));
        for j in 1..=SCAN {
            let positive = positive_at(at(j));
            if positive != previous {
                let (c, s) = plane.refine(at(j - 1), at(j), previous);
                if let Some(found) = self.refraction_at(&plane, c, s, e1, e2, y2) {
                    out.push(found);
                }
            }
            previous = positive;
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

impl AreaEmitter {
    fn area(&self) -> f64 {
        match self.shape {
            AreaShape::Quad { area, .. } => area,
            AreaShape::Sphere { radius, .. } => 2.0 * std::f64::consts::TAU * radius * radius,
        }
    }

    /// The point for `u`, uniform by area, and the unit normal there.
    fn point(&self, u: DVec2) -> (Point3, Vec3) {
        match self.shape {
            AreaShape::Quad {
                q,
                u: eu,
                v,
                normal,
                ..
            } => (q + u.x * eu + u.y * v, normal),
            AreaShape::Sphere { centre, radius } => {
                let n = rtl_pdf::warp::sample_uniform_sphere(u);
                (centre + radius * n, n)
            }
        }
    }

    /// The unit normal at `y` if `y` (a hit point with error bound `err`) lies on this emitter.
    fn normal_at(&self, y: Point3, err: f64) -> Option<Vec3> {
        let tol = 8.0 * err;
        match self.shape {
            AreaShape::Quad {
                q, u, v, normal, ..
            } => {
                let w = y - q;
                let scale = 1e-9 * (u.length() + v.length()) + tol;
                if w.dot(normal).abs() > scale {
                    return None;
                }
                let n = u.cross(v);
                let nn = n.length_squared();
                let a = w.dot(v.cross(n)) / nn;
                let b = w.dot(n.cross(u)) / nn;
                let slack = 1e-9;
                ((-slack..=1.0 + slack).contains(&a) && (-slack..=1.0 + slack).contains(&b))
                    .then_some(normal)
            }
            AreaShape::Sphere { centre, radius } => {
                let d = (y - centre).length();
                ((d - radius).abs() <= 1e-7 * radius + tol).then(|| (y - centre) / d)
            }
        }
    }
}

/// What manifold next-event estimation needs of a scene, made once per render: the interfaces, and
/// the emitters it draws points on. It is on only where both lists are non-empty
/// ([`Manifold::is_active`]).
#[derive(Clone, Debug, Default)]
pub struct Manifold {
    pub interfaces: Vec<Interface>,
    pub emitters: Vec<AreaEmitter>,
}

/// An emitter found in the scene, in world space, as [`crate::lights`] collects them.
#[derive(Clone, Copy, Debug)]
pub(crate) enum FoundShape {
    Quad {
        q: Point3,
        u: Vec3,
        v: Vec3,
    },
    Sphere {
        centre: Point3,
        radius: f64,
        moving: bool,
    },
}

impl Manifold {
    /// The interfaces of `scene` and its emitters `found` (static ones only: a connection to a moving
    /// sphere would aim at one place of it).
    pub(crate) fn new(scene: &Scene, found: &[(FoundShape, MaterialId)]) -> Manifold {
        let emitters: Vec<AreaEmitter> = found
            .iter()
            .filter_map(|&(shape, material)| {
                let shape = match shape {
                    FoundShape::Quad { q, u, v } => {
                        let n = u.cross(v);
                        let area = n.length();
                        (area > 0.0 && area.is_finite()).then_some(AreaShape::Quad {
                            q,
                            u,
                            v,
                            normal: n / area,
                            area,
                        })?
                    }
                    FoundShape::Sphere {
                        centre,
                        radius,
                        moving,
                    } => (!moving && radius.abs() > 0.0).then_some(AreaShape::Sphere {
                        centre,
                        radius: radius.abs(),
                    })?,
                };
                Some(AreaEmitter { shape, material })
            })
            .collect();
        let mut candidates = Vec::new();
        world_dielectric_spheres(scene, GroupId(0), 0, &mut candidates);
        let interfaces = candidates
            .into_iter()
            .filter(|i| scatters_inside(scene, GroupId(0), Transform::IDENTITY, i, 0))
            .map(|i| Interface {
                filled: filling_density(scene, GroupId(0), &i, 0),
                ..i
            })
            .collect();
        Manifold {
            interfaces,
            emitters,
        }
    }

    /// Whether connections are made at all: some interface holds something, and some emitter can
    /// be drawn on.
    pub fn is_active(&self) -> bool {
        !self.interfaces.is_empty() && !self.emitters.is_empty()
    }

    /// The interface whose surface `hit` (on a dielectric) lies on, if any.
    pub fn interface_at(&self, hit: &Hit) -> Option<u16> {
        self.interfaces
            .iter()
            .position(|i| i.material == hit.material && i.on_surface(hit.p, hit.err))
            .map(|k| k as u16)
    }

    /// A point on an emitter for `u`: the emitter chosen uniformly (from `u.x`, whose rest is
    /// handed on), the point uniformly by its area.
    pub fn sample_emitter(&self, u: DVec2) -> Option<EmitterPoint> {
        let n = self.emitters.len();
        if n == 0 {
            return None;
        }
        let scaled = u.x * n as f64;
        let i = (scaled as usize).min(n - 1);
        let rest = (scaled - i as f64).clamp(0.0, 1.0 - f64::EPSILON / 2.0);
        let e = &self.emitters[i];
        let (y, normal) = e.point(DVec2::new(rest, u.y));
        Some(EmitterPoint {
            y,
            normal,
            density: 1.0 / (n as f64 * e.area()),
        })
    }

    /// The point of an emitter of `material` that `hit` found, as [`Manifold::sample_emitter`]
    /// would have drawn it (its normal and density), if any emitter it draws on holds it.
    pub fn emitter_point(&self, hit: &Hit) -> Option<EmitterPoint> {
        let n = self.emitters.len() as f64;
        self.emitters
            .iter()
            .filter(|e| e.material == hit.material)
            .find_map(|e| {
                e.normal_at(hit.p, hit.err).map(|normal| EmitterPoint {
                    y: hit.p,
                    normal,
                    density: 1.0 / (n * e.area()),
                })
            })
    }

    /// One line for `--explain`.
    pub fn describe(&self) -> String {
        match (self.interfaces.len(), self.emitters.len()) {
            (0, _) => "skipped (no dielectric sphere holds anything that scatters)".into(),
            (_, 0) => "skipped (no emitter to connect to)".into(),
            (i, e) => format!(
                "used    (through {i} dielectric sphere{} holding media or surfaces, to {e} \
                 emitter{})",
                if i == 1 { "" } else { "s" },
                if e == 1 { "" } else { "s" },
            ),
        }
    }
}

/// Groups nest at most this deep (as in [`crate::lights`]).
const MAX_NESTING: u32 = 64;

/// The static dielectric spheres of radius > 0 placed in world space (the world group and the
/// groups nested in it without a transform).
fn world_dielectric_spheres(scene: &Scene, g: GroupId, depth: u32, out: &mut Vec<Interface>) {
    let Some(group) = scene.groups.get(g.0 as usize) else {
        return;
    };
    if depth > MAX_NESTING {
        return;
    }
    for o in &group.objects {
        match o {
            Object::Sphere(s) if !s.is_moving() && s.radius > 0.0 && s.radius.is_finite() => {
                if let Some(Material::Dielectric { ior }) = scene.materials.get(s.material.index())
                    && ior.is_finite()
                    && *ior > 0.0
                {
                    let i = Interface {
                        centre: s.center,
                        radius: s.radius,
                        ior: *ior,
                        material: s.material,
                        filled: 0.0,
                    };
                    if !out.contains(&i) {
                        out.push(i);
                    }
                }
            }
            Object::Group(inner) => world_dielectric_spheres(scene, *inner, depth + 1, out),
            _ => {}
        }
    }
}

/// The summed density of the constant media in world space (the world group and the groups nested
/// in it without a transform) bounded by a static sphere that holds the whole ball of `iface`.
fn filling_density(scene: &Scene, g: GroupId, iface: &Interface, depth: u32) -> f64 {
    let Some(group) = scene.groups.get(g.0 as usize) else {
        return 0.0;
    };
    if depth > MAX_NESTING {
        return 0.0;
    }
    group
        .objects
        .iter()
        .map(|o| match o {
            Object::Medium(m) => match scene
                .groups
                .get(m.boundary.0 as usize)
                .map(|b| &b.objects[..])
            {
                Some([Object::Sphere(s)])
                    if !s.is_moving()
                        && (s.center - iface.centre).length() + iface.radius
                            <= s.radius.abs() * (1.0 + 1e-12) =>
                {
                    let density = -1.0 / m.neg_inv_density;
                    if density.is_finite() && density > 0.0 {
                        density
                    } else {
                        0.0
                    }
                }
                _ => 0.0,
            },
            Object::Group(inner) => filling_density(scene, *inner, iface, depth + 1),
            _ => 0.0,
        })
        .sum()
}

/// Whether a material makes vertices a path scatters at (not a dielectric's specular bounce, not an
/// emitter, which scatters nothing).
fn scatters(scene: &Scene, material: MaterialId) -> bool {
    !matches!(
        scene.materials.get(material.index()),
        None | Some(Material::Dielectric { .. }) | Some(Material::DiffuseLight { .. })
    )
}

/// Whether anything of group `g`, placed by `to_world`, lies partly inside the open ball of
/// `iface` and makes vertices there: a surface that crosses it (exactly for spheres and quads,
/// by its box for an instance), or a medium whose volume overlaps it.
fn scatters_inside(
    scene: &Scene,
    g: GroupId,
    to_world: Transform,
    iface: &Interface,
    depth: u32,
) -> bool {
    let Some(group) = scene.groups.get(g.0 as usize) else {
        return false;
    };
    if depth > MAX_NESTING {
        return false;
    }
    let (c, r) = (iface.centre, iface.radius);
    group.objects.iter().any(|o| match o {
        Object::Sphere(s) => {
            if !scatters(scene, s.material) {
                return false;
            }
            if s.is_moving() {
                return box_meets_ball(&to_world.bounds(&s.bounds()), c, r);
            }
            let d = (to_world.point(s.center) - c).length();
            let rs = s.radius.abs();
            // the surface crosses the open ball: not wholly outside it, not wholly around it
            d < r + rs && d + r > rs
        }
        Object::Quad(q) => {
            scatters(scene, q.material)
                && parallelogram_distance2(
                    c,
                    to_world.point(q.q),
                    to_world.vector(q.u),
                    to_world.vector(q.v),
                ) < r * r
        }
        Object::Instance { transform, group } => {
            let b = group_bounds(scene, *group, depth + 1);
            box_meets_ball(&transform.then(to_world).bounds(&b), c, r)
                && scatters_inside(scene, *group, transform.then(to_world), iface, depth + 1)
        }
        Object::Group(inner) => scatters_inside(scene, *inner, to_world, iface, depth + 1),
        Object::Medium(m) => match scene
            .groups
            .get(m.boundary.0 as usize)
            .map(|b| &b.objects[..])
        {
            // a ball of medium: the two balls overlap
            Some([Object::Sphere(s)]) if !s.is_moving() => {
                (to_world.point(s.center) - c).length() < r + s.radius.abs()
            }
            _ => box_meets_ball(
                &to_world.bounds(&group_bounds(scene, m.boundary, depth + 1)),
                c,
                r,
            ),
        },
    })
}

/// The bounding box of group `g`'s objects in its own frame.
fn group_bounds(scene: &Scene, g: GroupId, depth: u32) -> Aabb {
    let Some(group) = scene.groups.get(g.0 as usize) else {
        return Aabb::EMPTY;
    };
    if depth > MAX_NESTING {
        return Aabb::EMPTY;
    }
    group.objects.iter().fold(Aabb::EMPTY, |acc, o| {
        let b = match o {
            Object::Sphere(s) => s.bounds(),
            Object::Quad(q) => q.bounds(),
            Object::Instance { transform, group } => {
                transform.bounds(&group_bounds(scene, *group, depth + 1))
            }
            Object::Group(inner) => group_bounds(scene, *inner, depth + 1),
            Object::Medium(m) => group_bounds(scene, m.boundary, depth + 1),
        };
        acc.union(&b)
    })
}

/// Whether the box comes closer than `r` to `c`.
fn box_meets_ball(b: &Aabb, c: Point3, r: f64) -> bool {
    let nearest = c.clamp(b.min, b.max);
    b.min.x <= b.max.x && (nearest - c).length_squared() < r * r
}

/// The squared distance from `c` to the parallelogram `q + a u + b v`, `a, b` in `[0, 1]`.
fn parallelogram_distance2(c: Point3, q: Point3, u: Vec3, v: Vec3) -> f64 {
    let n = u.cross(v);
    let nn = n.length_squared();
    let w = c - q;
    if nn > 0.0 {
        let a = w.dot(v.cross(n)) / nn;
        let b = w.dot(n.cross(u)) / nn;
        if (0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b) {
            let h = w.dot(n);
            return h * h / nn;
        }
    }
    let segment = |a: Point3, e: Vec3| {
        let ee = e.length_squared();
        let t = if ee > 0.0 {
            ((c - a).dot(e) / ee).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (c - a - t * e).length_squared()
    };
    segment(q, u)
        .min(segment(q, v))
        .min(segment(q + u, v))
        .min(segment(q + v, u))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_xoshiro::Xoshiro256PlusPlus;

    fn ball(ior: f64) -> Interface {
        Interface {
            centre: Point3::new(0.3, -0.2, 0.5),
            radius: 1.3,
            ior,
            material: MaterialId(0),
            filled: 0.0,
        }
    }

    fn unit<R: Rng>(rng: &mut R) -> Vec3 {
        loop {
            let v = Vec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            );
            let l = v.length_squared();
            if l > 1e-4 && l <= 1.0 {
                return v / l.sqrt();
            }
        }
    }

    /// A random vertex inside and point outside the ball.
    fn configuration<R: Rng>(rng: &mut R, b: &Interface) -> (Point3, Point3) {
        let p = b.centre + b.radius * rng.random_range(0.05..0.97f64) * unit(rng);
        let y = b.centre + b.radius * rng.random_range(1.05..8.0f64) * unit(rng);
        (p, y)
    }

    /// The refracted direction of `d` (unit, inside) at the outward unit normal `n`, by Snell's law.
    fn snell(d: Vec3, n: Vec3, eta: f64) -> Option<Vec3> {
        let cos_i = d.dot(n);
        let k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
        (k >= 0.0).then(|| eta * d + (k.sqrt() - eta * cos_i) * n)
    }

    #[test]
    fn every_refraction_found_obeys_snell_and_reaches_y() {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(7);
        let mut found = 0;
        for ior in [1.33, 1.5, 2.4] {
            let b = ball(ior);
            for _ in 0..2000 {
                let (p, y) = configuration(&mut rng, &b);
                for r in b.refractions(p, y).as_slice() {
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
            let scanned = b.refractions(p, y).as_slice().len();
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
            let found = b.refractions(p, y);
            let [r] = found.as_slice() else { continue };
            let n_y = unit(&mut rng);
            let t1 = n_y.any_orthonormal_vector();
            let t2 = n_y.cross(t1);
            let e = 1e-6 * b.radius;
            let omega = |q: Point3| {
                let f = b.refractions(p, q);
                let [r] = f.as_slice() else { return None };
                Some(r.dir_in)
            };
            let (Some(a1), Some(b1), Some(a2), Some(b2)) = (
                omega(y + e * t1),
                omega(y - e * t1),
                omega(y + e * t2),
                omega(y - e * t2),
            ) else {
                continue;
            };
            let swept = ((a1 - b1) / (2.0 * e))
                .cross((a2 - b2) / (2.0 * e))
                .length();
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
            let found = b.refractions(p, y);
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
        let found = b.refractions(p, y);
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
            b.refractions(p, b.centre + Vec3::new(5.0, 0.0, 0.0))
                .as_slice()
                .is_empty()
        );
        assert!(
            b.refractions(p, b.centre + Vec3::new(0.0, 0.5, 0.0))
                .as_slice()
                .is_empty()
        );
        assert!(!b.connects_from(b.centre));
        assert!(!b.connects_from(b.centre + Vec3::new(b.radius, 0.0, 0.0)));
        assert!(b.connects_from(p));
    }

    #[test]
    fn a_parallelogram_is_as_far_as_its_nearest_point() {
        let (q, u, v) = (
            Point3::ZERO,
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 1.0),
        );
        let d = |c: Point3| parallelogram_distance2(c, q, u, v).sqrt();
        assert!((d(Point3::new(1.5, 3.0, 0.5)) - 3.0).abs() < 1e-12);
        assert!((d(Point3::new(-1.0, 0.0, 0.0)) - 1.0).abs() < 1e-12);
        assert!((d(Point3::new(3.0, 0.0, 2.0)) - 1.0).abs() < 1e-12);
        // the Cornell box's glass ball just touches its floor: not inside
        let floor = parallelogram_distance2(
            Point3::new(190.0, 90.0, 190.0),
            Point3::ZERO,
            Vec3::new(555.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, 555.0),
        );
        assert!(floor >= 90.0 * 90.0);
    }
}
