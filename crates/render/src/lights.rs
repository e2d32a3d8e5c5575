//! The scene's importance targets ("lights" in book 3, chapter 12) as rtl-pdf [`Target`]s, built once
//! per render from [`Scene::targets`](crate::scene::Scene::targets).
//!
//! A sphere is sampled by the cone of directions it subtends (uniformly over the whole sphere of
//! directions from a point inside it; never from a sphere too small to see), a quad by its area
//! converted to solid angle, or, where it pays, uniformly in its spherical rectangle. A one-sided
//! emitter can be told to have no directions from behind, where it emits nothing.

use crate::material::Material;
use crate::scene::{Scene, Target as SceneShape};
use crate::vec::{Point3, Vec3};
use rand::Rng;
use rtl_pdf::{QuadTarget, SphereTarget, Target};

// ANCHOR: light_target
/// A shape to sample directions towards: static dispatch over the two kinds the book needs.
#[derive(Clone, Copy, Debug, PartialEq)]
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

impl Target for LightTarget {
    #[inline]
    fn pdf_value(&self, origin: Point3, direction: Vec3) -> f64 {
        match self {
            LightTarget::Quad { quad, one_sided } => {
                if Self::behind(quad, *one_sided, origin) {
                    0.0
                } else {
                    quad.pdf_value(origin, direction)
                }
            }
            LightTarget::Sphere(s) => s.pdf_value(origin, direction),
        }
    }

    #[inline]
    fn random<R: Rng + ?Sized>(&self, origin: Point3, rng: &mut R) -> Vec3 {
        // From behind a one-sided quad this still returns a direction (its density is 0, so the caller
        // drops it): `random` always returns a unit vector.
        match self {
            LightTarget::Quad { quad, .. } => quad.random(origin, rng),
            LightTarget::Sphere(s) => s.random(origin, rng),
        }
    }
}
// ANCHOR_END: light_target

/// The targets of a scene, in the three lists the strategies use.
#[derive(Clone, Debug, Default)]
pub struct Lights {
    /// Every target in the scene's order, sampled as the book does (quads by area, two-sided): the
    /// `light` and `mixture` strategies.
    pub all: Vec<LightTarget>,
    /// The targets that emit (next-event estimation in `mis`), one-sided where the emitter is.
    pub emitters: Vec<LightTarget>,
    /// The targets that do not emit (the glass sphere): `mis` mixes them into its material sampling.
    pub others: Vec<LightTarget>,
}

impl Lights {
    /// The scene's targets; `spherical_rectangles` makes rectangular emitters sample their solid angle
    /// uniformly (Urena et al. 2013) in `emitters`. Moving spheres are targeted at their time-0 place.
    pub fn new(scene: &Scene, spherical_rectangles: bool) -> Lights {
        let mut lights = Lights::default();
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
            match scene.materials.get(material.index()) {
                Some(Material::DiffuseLight { two_sided, .. }) => {
                    lights.emitters.push(match book {
                        LightTarget::Quad { quad, .. } => LightTarget::Quad {
                            quad: quad.with_spherical_rectangles(spherical_rectangles),
                            one_sided: !two_sided,
                        },
                        sphere => sphere,
                    });
                }
                _ => lights.others.push(book),
            }
        }
        lights
    }
}
