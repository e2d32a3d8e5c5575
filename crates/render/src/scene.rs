//! A scene: objects grouped into lists, each list with its own BVH (the top level too), instances
//! that place a list with a rigid transform, constant media, materials, textures, camera and
//! background. Geometry is a plain enum and every reference is an index, so intersection is static
//! dispatch over flat arrays.

pub use crate::builder::{SceneBuilder, SceneError};
use crate::bvh::ItemCost;
use crate::camera::CameraSettings;
pub use crate::ids::{GroupId, MaterialId, TextureId};
use crate::material::Material;
use crate::ray::Ray;
use crate::shapes::{Quad, Sphere};
use crate::texture::Texture;
pub use crate::transform::Transform;
pub use crate::traversal::{Accel, LeafItems};
use crate::vec::Color;

/// A constant-density medium filling a closed boundary (book 2): a ray inside travels a distance drawn
/// from the exponential distribution of rate `density` before it scatters by the phase function.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct ConstantMedium {
    pub boundary: GroupId,
    pub neg_inv_density: f64,
    pub phase: MaterialId,
    /// Whether the boundary is one convex piece (a sphere or a box, alone): a ray then crosses it
    /// at most twice, and has one stretch inside, not a sequence of them.
    pub convex: bool,
}

/// Something a ray can hit.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub enum Object {
    Sphere(Sphere),
    Quad(Quad),
    /// A group placed by a transform.
    Instance {
        transform: Transform,
        group: GroupId,
    },
    /// A group in place (a list within a list, with its own BVH).
    Group(GroupId),
    Medium(ConstantMedium),
}

impl Object {
    /// What testing the object costs, for the BVH's surface-area heuristic: quads are tested four at
    /// a time; a group (placed or not, or a medium's boundary, twice) costs a traversal of its own.
    pub(crate) fn cost(&self) -> ItemCost {
        match self {
            Object::Quad(_) => ItemCost::Packed,
            Object::Sphere(_) => ItemCost::Single(1.0),
            Object::Instance { .. } | Object::Group(_) => ItemCost::Single(4.0),
            Object::Medium(_) => ItemCost::Single(8.0),
        }
    }
}

/// A list of objects and the BVH over them (objects stored in the BVH's leaf order).
#[derive(Clone, Debug, Default, serde::Serialize)]
pub struct Group {
    pub objects: Vec<Object>,
    /// What the ray is traced through: the BVH collapsed to 4-wide nodes, with each leaf's quads in
    /// packets of four and its other objects listed. Built from `objects`, so not part of the
    /// scene's content.
    #[serde(skip)]
    pub accel: Accel,
}

#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub enum Background {
    Solid(Color),
    /// Book 1's sky: white at the bottom blending to (0.5, 0.7, 1.0) at the top, by the direction's y.
    Sky,
}

impl Background {
    #[inline]
    pub fn value(&self, ray: &Ray) -> Color {
        match self {
            Background::Solid(c) => *c,
            Background::Sky => {
                let a = 0.5 * (ray.direction.normalize().y + 1.0);
                (1.0 - a) * Color::ONE + a * Color::new(0.5, 0.7, 1.0)
            }
        }
    }
}

/// An importance target of book 3 ("lights"): a shape in world space that scattered rays may be
/// aimed at. Its material says whether it emits (then `mis` aims shadow rays at it); a shape given only
/// to aim at, not placed in the scene, has the material [`NO_MATERIAL`].
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub enum ImportanceTarget {
    Quad(Quad),
    Sphere(Sphere),
}

/// The material of a target that is only a shape to aim at: it names no material, so the target
/// never counts as an emitter.
pub const NO_MATERIAL: MaterialId = MaterialId::NONE;

/// What a scene calls for, decided once when it is built, so that nothing is simulated that the scene
/// does not need.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct Features {
    /// The camera has a lens (defocus blur).
    pub defocus: bool,
    /// Something moves during the shutter interval (motion blur: rays carry random times).
    pub motion: bool,
    /// Number of constant media.
    pub media: usize,
    /// How many of them have a boundary that is not one convex piece (several pieces, or a closed
    /// surface with a dent): a ray may cross it more than twice, and each stretch inside is taken.
    pub media_in_pieces: usize,
    /// Number of textures that are not a plain colour.
    pub textures: usize,
    /// Number of emitting objects (primitives with a light material, instanced copies counted once).
    pub emitters: usize,
    /// Whether some emitter is one-sided.
    pub one_sided_emitters: bool,
    /// Number of importance targets.
    pub targets: usize,
    /// Number of rigid instances placed in world space at build time ([`crate::flatten`]): their
    /// quads are tested in their parent's packets, no ray is moved into their frame.
    pub flattened_instances: usize,
}

/// A scene ready to render.
#[derive(Clone, Debug, serde::Serialize)]
pub struct Scene {
    pub groups: Vec<Group>,
    pub materials: Vec<Material>,
    pub textures: Vec<Texture>,
    pub camera: CameraSettings,
    pub background: Background,
    /// Most intersections a path may have.
    pub max_depth: u32,
    pub targets: Vec<ImportanceTarget>,
    pub features: Features,
}
