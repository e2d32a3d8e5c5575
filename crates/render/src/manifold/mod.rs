//! Manifold next-event estimation through dielectric spheres (Hanika, Droske and Fascione,
//! "Manifold Next Event Estimation", 2015): light that reaches a point only by refracting through
//! a glass ball, found by a connection instead of by chance.
//!
//! A shadow ray meets the glass, a delta interface that next-event estimation cannot pass. Material
//! sampling finds that light only when a path happens to refract through the glass straight
//! towards an emitter: rare, and bright when it happens, so these are the noisiest pixels of a
//! scene with glass. Two kinds of path are connected, each by drawing a point `y` on an emitter and
//! solving for the points of the sphere where the ray refracts towards it:
//! - [`leaving`]: from a vertex inside the ball (book 2's blue subsurface sphere, lit through its
//!   glass shell), one refraction out;
//! - [`crossing`]: from a vertex outside, in and out again (the caustic a glass ball focuses on the
//!   floor under it, the noisiest part of the Cornell box).
//!
//! **The solution lies in a plane.** The sphere and the vertex `p` are symmetric about the axis
//! through the centre and `p`, so the whole path lies in the plane of that axis and `y`, and one
//! unknown remains: the angle `phi` of the first refraction point from the axis. Its zeros may be
//! several (near a caustic), so the arc of candidates is scanned for sign changes and each is
//! refined by safeguarded Newton. The arc is named by `t = tan(theta / 2)` for the angle `theta` from
//! its middle, so that neither needs a trigonometric function.
//!
//! **The density of the connection.** The direction `omega` that leaves `p` varies with `y` by the
//! generalised geometry term, the solid angle at `p` per unit area at `y`: the cross-section of the
//! pencil of refracted rays, in the plane and across it (rotation about the axis moves the first
//! refraction point and `y` by their distances `rho_x` and `rho_y` from it), times `|cos theta_y|` at
//! the emitter. A point drawn with area density `p_A(y)` estimates
//!
//! `f(omega) G (prod (1 - F)) L_e(y) T / p_A(y)`,
//!
//! where `F` is the reflectance the dielectric reflects with at each refraction (Schlick's) and `T`
//! the transmittance of the media the legs cross.
//!
//! **Unbiased whatever the solver misses.** Both the connection and material sampling make these
//! paths. Each is weighted by the power heuristic between the connection's density `p_A(y)` and
//! material sampling's `p_m(omega) G` (both in the area measure at `y`), but only if solving from
//! `(p, y)` finds its first refraction point. A path that material sampling takes through a point
//! the solver does not find keeps weight 1. The two weights of every path sum to 1, so the estimate
//! is unbiased even where a root is missed, near a caustic where two roots merge.

pub mod crossing;
pub mod leaving;

pub use crossing::{Crossing, Crossings};
pub use leaving::{Refraction, Refractions};

use crate::aabb::Aabb;
use crate::hit::Hit;
use crate::ids::MaterialId;
use crate::limits::{MAX_NESTING, WalkBudget};
use crate::material::{Material, schlick};
use crate::scene::{GroupId, Object, Scene, Transform};
use crate::vec::{Point3, Vec3};
use glam::DVec2;

/// Points at which a solver looks across its arc of candidates: two roots closer than the arc's
/// sixteenth are missed (and left to material sampling).
pub(crate) const SCAN: usize = 16;
/// Most Newton or bisection steps refining one root.
pub(crate) const MAX_STEPS: usize = 64;

/// A static dielectric sphere in world space that a connection refracts through: one that holds
/// something a path scatters at (a medium, a diffuse or fuzzy surface; connections leave it from
/// there), or a clear one a connection from outside may cross.
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
    /// Whether the ball holds nothing but media that fill it whole: then a straight leg inside
    /// meets nothing, and its transmittance is `exp(-filled length)`, with no ray traced.
    pub clear: bool,
    /// Whether the ball holds something a path scatters at (where a connection leaves it from).
    pub holds: bool,
}

/// How far beyond the ball's cone from a vertex (widened by the sizes of ball and emitter seen from
/// the ball) the emitter's direction may lie for a crossing connection to be made there
/// ([`Manifold::reaches`]); negative: within it. A ray through a glass ball turns by up to
/// `2 (90 - asin(1 / eta))` degrees (96 for glass), but the light a ball focuses, the caustic's
/// variance, is met where the vertex sees the emitter near the middle of the ball: on the Cornell box
/// (200 x 200, 256 spp) the noise constant is 0.1392 whether the allowance is 40 degrees more or 50
/// less than the cone, 0.1402 at 65 less and 0.155 at 80 less, while the connections fall from 0.51
/// to 0.046 a sample; on book 2's final scene, 0.167 at 0 and 0.171 at 20 less, 0.188 at 50 less.
/// -20 degrees loses nothing on the one and 2% on the other for 0.12 connections a sample on the box.
/// What is not connected is left to material sampling.
pub const CROSSING_TURN: f64 = -20.0 * std::f64::consts::PI / 180.0;

impl Interface {
    /// Whether a connection from outside may cross the ball: clear, of index 1 or more, its media
    /// letting a tenth of the light across (`filled 2 R <= ln 10`) or more.
    pub fn crossable(&self) -> bool {
        self.clear && self.ior >= 1.0 && self.filled * 2.0 * self.radius <= 10f64.ln()
    }
}

/// The connection's roulette plays for connections whose inner leg is surely darker than this: it
/// makes one with probability `min(1, T_max / CONNECTION_ROULETTE)` and divides by that, so that a
/// connection made deep in a dense medium, where the light through the surface is nearly gone,
/// counts with at most this weight. On book 2's final scene 1/16 (against connecting from every
/// vertex inside the blue sphere) keeps the noise constant and makes 11% fewer connections: most of
/// a random walk there stays within 14 units (the depth at which the bound reaches 1/16) of the
/// glass.
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
    /// Which of [`Manifold::emitters`].
    pub emitter: u16,
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
}

impl AreaEmitter {
    /// A ball around the emitter: its centre and radius.
    pub fn bounds(&self) -> (Point3, f64) {
        match self.shape {
            AreaShape::Quad { q, u, v, .. } => (
                q + 0.5 * (u + v),
                0.5 * (u + v).length().max((u - v).length()),
            ),
            AreaShape::Sphere { centre, radius } => (centre, radius),
        }
    }

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
    /// The interfaces a connection from outside may cross ([`Interface::crossable`]).
    pub crossable: Vec<u16>,
    /// Per interface and emitter (`k * emitters + e`), what [`Manifold::reaches`] needs: the unit
    /// direction from the ball to the emitter, and the cosine and sine of `beta`, the allowance
    /// beyond the ball's own cone (the two sizes seen from the ball, and [`CROSSING_TURN`]).
    reach: Vec<(Vec3, f64, f64)>,
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
        world_dielectric_spheres(
            scene,
            GroupId(0),
            0,
            &mut WalkBudget::new(),
            &mut candidates,
        );
        let mut bounds = GroupBounds::new(scene);
        // Every world dielectric sphere that holds something a path scatters at (a connection
        // leaves it from there), or that a connection can cross; not one whose contents were not
        // all seen (past a walk's budget or nesting), which could be taken for clear.
        let interfaces: Vec<Interface> = candidates
            .into_iter()
            .filter_map(|i| {
                let mut inside = Contents::default();
                Walk {
                    scene,
                    iface: &i,
                    budget: WalkBudget::new(),
                    bounds: &mut bounds,
                }
                .contents(GroupId(0), Transform::IDENTITY, 0, &mut inside);
                if inside.unseen {
                    return None;
                }
                let i = Interface {
                    filled: inside.filled,
                    clear: !inside.blocks,
                    holds: inside.scatters,
                    ..i
                };
                (i.holds || i.crossable()).then_some(i)
            })
            .collect();
        let most = MAX_CROSSING_PAIRS / emitters.len().max(1);
        let crossable = (interfaces.iter().enumerate())
            .filter(|(_, i)| i.crossable())
            .map(|(k, _)| k as u16)
            .take(most)
            .collect();
        let reach = interfaces
            .iter()
            .flat_map(|i| {
                emitters.iter().map(|e| {
                    let (centre, size) = e.bounds();
                    let onward = centre - i.centre;
                    let len = onward.length();
                    let beta = ((i.radius + size) / len).min(1.0).asin() + CROSSING_TURN;
                    let (sin_b, cos_b) = beta.sin_cos();
                    (onward / len, cos_b, sin_b)
                })
            })
            .collect();
        Manifold {
            interfaces,
            emitters,
            crossable,
            reach,
        }
    }

    /// Whether a crossing connection is made from `p` through interface `k` towards emitter `e`:
    /// whether the direction from the ball to the emitter lies within the ball's cone from `p`
    /// (half-angle `alpha = asin(R / |c - p|)`) widened by `beta` (the two sizes seen from the ball,
    /// and [`CROSSING_TURN`]). A choice of `p` and the emitter alone, made the same way by the
    /// connection and by the weight of the emission material sampling meets.
    ///
    /// With `a = c - p` (`|a| = d`) and `o` the unit direction to the emitter, `angle <= alpha + beta`
    /// reads `a . o >= d cos(alpha + beta) = cos(beta) sqrt(d^2 - R^2) - R sin(beta)`, and holds for
    /// every direction where `alpha + beta >= pi`, `cos(beta) d <= -sqrt(d^2 - R^2)`: one square root.
    #[inline]
    pub fn reaches(&self, k: u16, e: u16, p: Point3) -> bool {
        let iface = &self.interfaces[k as usize];
        let Some(&(onward, cos_b, sin_b)) = self
            .reach
            .get(k as usize * self.emitters.len() + e as usize)
        else {
            return false;
        };
        let axis = iface.centre - p;
        let (d2, r) = (axis.length_squared(), iface.radius);
        if d2.is_nan() || d2 <= r * r {
            return false;
        }
        let tangent = (d2 - r * r).sqrt();
        // (`tangent > 0` here, so the second test can hold only where `cos(beta) < 0`: its square
        // root is taken only there)
        axis.dot(onward) >= cos_b * tangent - r * sin_b
            || (cos_b < 0.0 && cos_b * d2.sqrt() <= -tangent)
    }

    /// Whether some crossable interface and some emitter pass [`Manifold::reaches`] from `p`: where
    /// none does, no crossing connection is made, and nothing is drawn for one.
    #[inline]
    pub fn reaches_any(&self, p: Point3) -> bool {
        (self.crossable.iter())
            .any(|&k| (0..self.emitters.len() as u16).any(|e| self.reaches(k, e, p)))
    }

    /// Whether connections are made at all: some interface holds something or can be crossed, and
    /// some emitter can be drawn on.
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
            emitter: i as u16,
        })
    }

    /// The point of an emitter of `material` that `hit` found, as [`Manifold::sample_emitter`]
    /// would have drawn it (its normal and density), if any emitter it draws on holds it.
    pub fn emitter_point(&self, hit: &Hit) -> Option<EmitterPoint> {
        let n = self.emitters.len() as f64;
        self.emitters
            .iter()
            .enumerate()
            .filter(|(_, e)| e.material == hit.material)
            .find_map(|(i, e)| {
                e.normal_at(hit.p, hit.err).map(|normal| EmitterPoint {
                    y: hit.p,
                    normal,
                    density: 1.0 / (n * e.area()),
                    emitter: i as u16,
                })
            })
    }

    /// One line for `--explain`.
    pub fn describe(&self) -> String {
        let holding = self.interfaces.iter().filter(|i| i.holds).count();
        let plural = |n: usize| if n == 1 { "" } else { "s" };
        if self.interfaces.is_empty() {
            return "skipped (no glass sphere in world space that holds something or can be \
                    crossed)"
                .into();
        }
        if self.emitters.is_empty() {
            return "skipped (no emitter to connect to)".into();
        }
        let mut through = Vec::new();
        if holding > 0 {
            through.push(format!(
                "out of {holding} glass sphere{} holding media or surfaces",
                plural(holding)
            ));
        }
        if !self.crossable.is_empty() {
            let n = self.crossable.len();
            through.push(format!("across {n} clear glass sphere{}", plural(n)));
        }
        let e = self.emitters.len();
        format!(
            "used    ({}, to {e} emitter{})",
            through.join(" and "),
            plural(e)
        )
    }
}

/// The most glass spheres connections go through: the first ones of the scene (in the order of
/// its world group). A scene with more leaves the light through the others to material sampling:
/// each refraction into glass looks its sphere up among them, and each is checked against the
/// whole scene when it is built.
pub const MAX_INTERFACES: usize = 32;

/// The most pairs of a crossable interface and an emitter ([`Manifold::reaches`] tries them all
/// at every vertex): the first crossable interfaces that keep within it, none with more emitters.
pub const MAX_CROSSING_PAIRS: usize = 32;

/// The static dielectric spheres of radius > 0 placed in world space (the world group and the
/// groups nested in it without a transform), at most [`MAX_INTERFACES`], found within `budget` (a
/// group nested twice in each of 40 others is in 2^40 places) and [`MAX_NESTING`].
fn world_dielectric_spheres(
    scene: &Scene,
    g: GroupId,
    depth: u32,
    budget: &mut WalkBudget,
    out: &mut Vec<Interface>,
) {
    let Some(group) = scene.groups.get(g.0 as usize) else {
        return;
    };
    if depth > MAX_NESTING {
        return;
    }
    for o in &group.objects {
        if out.len() >= MAX_INTERFACES || !budget.visit() {
            return;
        }
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
                        clear: false,
                        holds: false,
                    };
                    if !out.contains(&i) {
                        out.push(i);
                    }
                }
            }
            Object::Group(inner) => world_dielectric_spheres(scene, *inner, depth + 1, budget, out),
            _ => {}
        }
    }
}

/// Whether a material makes vertices a path scatters at (not a dielectric's specular bounce, not an
/// emitter, which scatters nothing).
fn scatters(scene: &Scene, material: MaterialId) -> bool {
    !matches!(
        scene.materials.get(material.index()),
        None | Some(Material::Dielectric { .. }) | Some(Material::DiffuseLight { .. })
    )
}

/// What lies inside the open ball of an interface, in world space.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Contents {
    /// Something a path scatters at there: a surface of a scattering material that crosses the
    /// ball, or a medium that overlaps it.
    scatters: bool,
    /// Anything but media that fill the whole ball: a surface crossing it (whatever its material,
    /// but for the interface itself), or a medium that fills only part of it.
    blocks: bool,
    /// The summed density of the constant media that fill the whole ball.
    filled: f64,
    /// Whether part of the scene was not looked at (groups nested deeper than [`MAX_NESTING`], or
    /// objects past the walk's budget): then what the ball holds is not known.
    unseen: bool,
}

/// The walk over the scene that finds what lies inside one interface's ball.
struct Walk<'w, 's> {
    scene: &'s Scene,
    iface: &'w Interface,
    /// The objects the walk may still visit (an instance once for every place it ends up in).
    budget: WalkBudget,
    bounds: &'w mut GroupBounds,
}

impl Walk<'_, '_> {
    /// The bounding box of group `g` in its own frame, reached at `depth`; empty, and the walk marked
    /// as not seeing all, if it nests deeper than [`MAX_NESTING`] allows there.
    fn bounds(&mut self, g: GroupId, depth: u32, out: &mut Contents) -> Aabb {
        self.bounds.get(self.scene, g, depth).unwrap_or_else(|| {
            out.unseen = true;
            Aabb::EMPTY
        })
    }

    /// Adds to `out` what group `g`, placed by `to_world`, has inside the open ball of the interface:
    /// surfaces that cross it (exactly for spheres and quads, by its box for a moving sphere or an
    /// instance's group), and media whose volume overlaps it (a medium bounded by a sphere fills the
    /// ball if that sphere holds it). A surface must reach a relative 1e-9 into the ball to count.
    fn contents(&mut self, g: GroupId, to_world: Transform, depth: u32, out: &mut Contents) {
        let scene = self.scene;
        let Some(group) = scene.groups.get(g.0 as usize) else {
            return;
        };
        if depth > MAX_NESTING {
            out.unseen = true;
            return;
        }
        // A surface that only touches the ball (a ball resting on a floor) leaves it clear: what
        // crosses it must come closer to the centre than the radius less a relative 1e-9.
        let iface = self.iface;
        let (c, r) = (iface.centre, iface.radius * (1.0 - 1e-9));
        for o in &group.objects {
            if !self.budget.visit() {
                out.unseen = true;
                return;
            }
            let (crosses, material) = match o {
                Object::Sphere(s) => {
                    let centre = to_world.point(s.center);
                    let itself = !s.is_moving()
                        && centre == c
                        && s.radius == iface.radius
                        && s.material == iface.material;
                    let crosses = if itself {
                        false
                    } else if s.is_moving() {
                        box_meets_ball(&to_world.bounds(&s.bounds()), c, r)
                    } else {
                        // the surface crosses the open ball: not wholly outside it, not wholly
                        // around it
                        let (d, rs) = ((centre - c).length(), s.radius.abs());
                        d < r + rs && d + r > rs
                    };
                    (crosses, s.material)
                }
                Object::Quad(q) => (
                    parallelogram_distance2(
                        c,
                        to_world.point(q.q),
                        to_world.vector(q.u),
                        to_world.vector(q.v),
                    ) < r * r,
                    q.material,
                ),
                Object::Instance { transform, group } => {
                    let placed = transform.then(to_world);
                    let inner = self.bounds(*group, depth + 1, out);
                    if box_meets_ball(&placed.bounds(&inner), c, r) {
                        self.contents(*group, placed, depth + 1, out);
                    }
                    continue;
                }
                Object::Group(inner) => {
                    self.contents(*inner, to_world, depth + 1, out);
                    continue;
                }
                Object::Medium(m) => {
                    let boundary = scene
                        .groups
                        .get(m.boundary.0 as usize)
                        .map(|b| &b.objects[..]);
                    let (overlaps, fills) = match boundary {
                        Some([Object::Sphere(s)]) if !s.is_moving() => {
                            let d = (to_world.point(s.center) - c).length();
                            let rs = s.radius.abs();
                            (d < r + rs, d + r <= rs * (1.0 + 1e-12))
                        }
                        _ => {
                            let inner = self.bounds(m.boundary, depth + 1, out);
                            (box_meets_ball(&to_world.bounds(&inner), c, r), false)
                        }
                    };
                    let density = -1.0 / m.neg_inv_density;
                    if fills && density.is_finite() && density > 0.0 {
                        out.filled += density;
                        out.scatters = true;
                    } else if overlaps {
                        out.scatters = true;
                        out.blocks = true;
                    }
                    continue;
                }
            };
            if crosses {
                out.blocks = true;
                out.scatters |= scatters(scene, material);
            }
        }
    }
}

/// The bounding boxes of a scene's groups in their own frames, each found once (by instance after
/// instance, a group placed in 2^40 places would be bounded 2^40 times).
struct GroupBounds {
    /// Per group, once found: its box, and how deep groups nest inside it.
    found: Vec<Option<(Aabb, u32)>>,
}

impl GroupBounds {
    fn new(scene: &Scene) -> Self {
        GroupBounds {
            found: vec![None; scene.groups.len()],
        }
    }

    /// The bounding box of group `g`'s objects in its own frame, reached at `depth`: `None` if groups
    /// nest inside it deeper than [`MAX_NESTING`] allows there.
    fn get(&mut self, scene: &Scene, g: GroupId, depth: u32) -> Option<Aabb> {
        let (b, nesting) = self.find(scene, g, 0)?;
        (depth.saturating_add(nesting) <= MAX_NESTING).then_some(b)
    }

    /// Group `g`'s box and the depth of groups inside it, found `depth` deep from where the search
    /// began (`None` past [`MAX_NESTING`]: a cycle, which the scene builder refuses, or too deep).
    fn find(&mut self, scene: &Scene, g: GroupId, depth: u32) -> Option<(Aabb, u32)> {
        if let Some(found) = self.found.get(g.0 as usize).copied().flatten() {
            return Some(found);
        }
        if depth > MAX_NESTING {
            return None;
        }
        let group = scene.groups.get(g.0 as usize)?;
        let (mut b, mut nesting) = (Aabb::EMPTY, 0);
        for o in &group.objects {
            let (ob, n) = match o {
                Object::Sphere(s) => (s.bounds(), 0),
                Object::Quad(q) => (q.bounds(), 0),
                Object::Instance { transform, group } => {
                    let (inner, n) = self.find(scene, *group, depth + 1)?;
                    (transform.bounds(&inner), n + 1)
                }
                Object::Group(inner) => {
                    let (inner, n) = self.find(scene, *inner, depth + 1)?;
                    (inner, n + 1)
                }
                Object::Medium(m) => {
                    let (inner, n) = self.find(scene, m.boundary, depth + 1)?;
                    (inner, n + 1)
                }
            };
            b = b.union(&ob);
            nesting = nesting.max(n);
        }
        self.found[g.0 as usize] = Some((b, nesting));
        Some((b, nesting))
    }
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

/// What the solvers' tests share: a ball, random directions and Snell's law written plainly.
#[cfg(test)]
pub(crate) mod testing {
    use super::Interface;
    use crate::ids::MaterialId;
    use crate::vec::{Point3, Vec3};
    use rand::Rng;

    pub fn ball(ior: f64) -> Interface {
        Interface {
            centre: Point3::new(0.3, -0.2, 0.5),
            radius: 1.3,
            ior,
            material: MaterialId(0),
            filled: 0.0,
            clear: true,
            holds: true,
        }
    }

    pub use crate::shapes::quad_cases::unit;

    /// The solid angle that the unit directions `omega(q)` sweep as `q` crosses a small square at
    /// `y` facing `n_y` (side `2 e`, central differences), over the square's area: what a
    /// connection's `G |cos theta_y|` must equal. `None` where `omega` is not defined around `y`.
    pub fn swept_per_area(
        omega: impl Fn(Point3) -> Option<Vec3>,
        y: Point3,
        n_y: Vec3,
        e: f64,
    ) -> Option<f64> {
        let t1 = n_y.any_orthonormal_vector();
        let t2 = n_y.cross(t1);
        let (a1, b1) = (omega(y + e * t1)?, omega(y - e * t1)?);
        let (a2, b2) = (omega(y + e * t2)?, omega(y - e * t2)?);
        Some(
            ((a1 - b1) / (2.0 * e))
                .cross((a2 - b2) / (2.0 * e))
                .length(),
        )
    }

    /// A random vertex inside and point outside the ball.
    pub fn configuration<R: Rng>(rng: &mut R, b: &Interface) -> (Point3, Point3) {
        let p = b.centre + b.radius * rng.random_range(0.05..0.97f64) * unit(rng);
        let y = b.centre + b.radius * rng.random_range(1.05..8.0f64) * unit(rng);
        (p, y)
    }

    /// The refracted direction of `d` (unit, towards the surface) at the unit normal `n` on its side
    /// (`d . n > 0`), for the ratio `eta` of the index behind to the index ahead, by Snell's law.
    pub fn snell(d: Vec3, n: Vec3, eta: f64) -> Option<Vec3> {
        let cos_i = d.dot(n);
        let k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
        (k >= 0.0).then(|| eta * d + (k.sqrt() - eta * cos_i) * n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
