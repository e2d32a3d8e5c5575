//! The scene's importance targets ("lights" in book 3, chapter 12) as rtl-pdf [`ShapeSampler`]s, built
//! once per render.
//!
//! Two sources: every emitting sphere and quad of the scene, found by walking its groups and instances
//! (pbrt-v4 and Mitsuba sample every emitter for next-event estimation without being told), and the
//! book's explicit list of targets, [`Scene::targets`](crate::scene::Scene::targets), the way to add
//! shapes that do not emit (the glass sphere) and what the book's `mixture` aims at.
//!
//! A sphere is sampled by the cone of directions it subtends (uniformly over the whole sphere of
//! directions from a point inside it; never from a sphere too small to see), a quad by its area
//! converted to solid angle, or, where it pays, uniformly in its spherical rectangle. A one-sided
//! emitter has no directions from behind, where it emits nothing: there its `sample` fails and its
//! `pdf` is 0, so what a list of targets draws is what its density describes.

use crate::material::Material;
use crate::scene::{GroupId, ImportanceTarget as SceneShape, MaterialId, Object, Scene, Transform};
use crate::vec::{Point3, Vec3};
use glam::DVec2;
use rtl_pdf::{DirectionSample, QuadTarget, ShapeSampler, SphereTarget};

// ANCHOR: light_target
/// A shape to sample directions towards: static dispatch over the two kinds the book needs.
///
/// The quad is the larger variant (its spherical-rectangle frame is kept with it); the targets are a
/// short list walked per vertex, where boxing the quad would add a pointer chase.
#[derive(Clone, Copy, Debug, PartialEq)]
#[allow(clippy::large_enum_variant)]
pub enum LightTarget {
    /// A parallelogram; if `one_sided`, no direction from behind its front face (density 0 there).
    Quad { quad: QuadTarget, one_sided: bool },
    /// A sphere, by the cone it subtends.
    Sphere(SphereTarget),
}

impl LightTarget {
    /// Whether `origin` lies behind a one-sided quad (on the side its normal points away from).
    #[inline]
    fn behind(quad: &QuadTarget, one_sided: bool, origin: Point3) -> bool {
        one_sided && quad.normal().dot(origin - quad.q()) <= 0.0
    }
}

impl ShapeSampler for LightTarget {
    #[inline]
    fn pdf(&self, origin: Point3, direction: Vec3) -> f64 {
        match self {
            LightTarget::Quad { quad, one_sided } => {
                if Self::behind(quad, *one_sided, origin) {
                    0.0
                } else {
                    quad.pdf(origin, direction)
                }
            }
            LightTarget::Sphere(s) => s.pdf(origin, direction),
        }
    }

    /// From behind a one-sided quad there is nothing to sample: `None`, matching its `pdf` of 0 (a
    /// direction drawn there anyway could meet another emitter's front and be weighted by a density
    /// that does not describe how it was drawn).
    #[inline]
    fn sample(&self, origin: Point3, u: DVec2) -> Option<DirectionSample> {
        match self {
            LightTarget::Quad { quad, one_sided } => {
                if Self::behind(quad, *one_sided, origin) {
                    None
                } else {
                    quad.sample(origin, u)
                }
            }
            LightTarget::Sphere(s) => s.sample(origin, u),
        }
    }
}
// ANCHOR_END: light_target

/// The targets of a scene, in the three lists the strategies use.
#[derive(Clone, Debug, Default)]
pub struct Lights {
    /// The book's list in the scene's order, sampled as the book does (quads by area, two-sided): the
    /// `light` and `mixture` strategies.
    pub all: Vec<LightTarget>,
    /// Every emitter of the scene, listed or not, one-sided where the emitter is: next-event
    /// estimation in `mis`.
    pub emitters: Vec<LightTarget>,
    /// The listed targets that do not emit (the glass sphere): `mis` mixes them into its material
    /// sampling.
    pub others: Vec<LightTarget>,
    /// How many of `emitters` the book's list names (the rest were found in the scene).
    pub listed_emitters: usize,
}

impl Lights {
    /// The scene's targets; `spherical_rectangles` makes rectangular emitters sample their solid angle
    /// uniformly (Urena et al. 2013) in `emitters`. Moving spheres are targeted at their time-0 place
    /// (unbiased under `mis`, whose material sampling covers whatever the light sampling misses).
    pub fn new(scene: &Scene, spherical_rectangles: bool) -> Lights {
        let mut lights = Lights::default();
        let emitter = |material: MaterialId| match scene.materials.get(material.index()) {
            Some(Material::DiffuseLight { two_sided, .. }) => Some(*two_sided),
            _ => None,
        };
        for t in &scene.targets {
            let (material, book) = match t {
                SceneShape::Quad(q) => (
                    q.material,
                    LightTarget::Quad {
                        quad: QuadTarget::new(q.q, q.u, q.v),
                        one_sided: false,
                    },
                ),
                SceneShape::Sphere(s) => (
                    s.material,
                    LightTarget::Sphere(SphereTarget::new(s.center, s.radius)),
                ),
            };
            lights.all.push(book);
            if emitter(material).is_none() {
                lights.others.push(book);
            }
        }
        // Every emitter placed in the scene, in world space.
        let mut found = Vec::new();
        collect_emitters(scene, GroupId(0), Transform::IDENTITY, 0, &mut found);
        for (shape, two_sided) in found {
            let target = match shape {
                LightTarget::Quad { quad, .. } => LightTarget::Quad {
                    quad: quad.with_spherical_rectangles(spherical_rectangles),
                    one_sided: !two_sided,
                },
                sphere => sphere,
            };
            let listed = scene.targets.iter().any(|t| same_shape(t, &shape));
            lights.listed_emitters += listed as usize;
            lights.emitters.push(target);
        }
        lights
    }

    /// One line for `--explain`: what next-event estimation samples.
    pub fn describe_emitters(&self) -> String {
        match self.emitters.len() {
            0 => "none (no emitter in the scene)".into(),
            n => format!(
                "{n} emitter{} ({} of them in the list of targets)",
                if n == 1 { "" } else { "s" },
                self.listed_emitters,
            ),
        }
    }
}

/// Whether a listed target is the emitter `shape` (same geometry).
fn same_shape(t: &SceneShape, shape: &LightTarget) -> bool {
    match (t, shape) {
        (SceneShape::Quad(q), LightTarget::Quad { quad, .. }) => {
            q.q == quad.q() && q.u == quad.u() && q.v == quad.v()
        }
        (SceneShape::Sphere(s), LightTarget::Sphere(sp)) => {
            s.center == sp.center() && s.radius.abs() == sp.radius()
        }
        _ => false,
    }
}

/// Groups nest at most this deep (a guard against a cycle, which the scene builder refuses anyway).
const MAX_NESTING: u32 = 64;

/// The emitting spheres and quads of group `g` placed by `to_world`, with their two-sidedness; media
/// boundaries are shapes of no material and are skipped.
fn collect_emitters(
    scene: &Scene,
    g: GroupId,
    to_world: Transform,
    depth: u32,
    out: &mut Vec<(LightTarget, bool)>,
) {
    let Some(group) = scene.groups.get(g.0 as usize) else {
        return;
    };
    if depth > MAX_NESTING {
        return;
    }
    let two_sided = |material: MaterialId| match scene.materials.get(material.index()) {
        Some(Material::DiffuseLight { two_sided, .. }) => Some(*two_sided),
        _ => None,
    };
    for o in &group.objects {
        match o {
            Object::Sphere(s) => {
                if let Some(ts) = two_sided(s.material) {
                    let target = SphereTarget::new(to_world.point(s.center), s.radius);
                    out.push((LightTarget::Sphere(target), ts));
                }
            }
            Object::Quad(q) => {
                if let Some(ts) = two_sided(q.material) {
                    let quad = QuadTarget::new(
                        to_world.point(q.q),
                        to_world.vector(q.u),
                        to_world.vector(q.v),
                    );
                    out.push((
                        LightTarget::Quad {
                            quad,
                            one_sided: false,
                        },
                        ts,
                    ));
                }
            }
            Object::Instance { transform, group } => {
                collect_emitters(scene, *group, transform.then(to_world), depth + 1, out)
            }
            Object::Group(inner) => collect_emitters(scene, *inner, to_world, depth + 1, out),
            Object::Medium(_) => {}
        }
    }
}
