//! A scene: objects grouped into lists, each list with its own BVH (the top level too), instances
//! that place a list with a rigid transform, constant media, materials, textures, camera and
//! background. Geometry is a plain enum and every reference is an index, so intersection is static
//! dispatch over flat arrays.

use crate::aabb::Aabb;
use crate::bvh::{Bvh, ItemCost};
use crate::camera::CameraSettings;
use crate::material::Material;
use crate::ray::Ray;
use crate::shapes::{Quad, Sphere, box_quads};
use crate::texture::Texture;
use crate::vec::{Color, Point3, Vec3};
use glam::DMat3;

pub use crate::traversal::{Accel, LeafItems};

/// A rigid transform `x -> R x + t` (rotation then translation), as book 2's `translate(rotate_y(..))`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    pub rotation: DMat3,
    pub translation: Vec3,
}

impl Transform {
    pub const IDENTITY: Transform = Transform {
        rotation: DMat3::IDENTITY,
        translation: Vec3::ZERO,
    };

    /// Rotation by `degrees` about +y: `x' = cos x + sin z`, `z' = -sin x + cos z`.
    pub fn rotate_y(degrees: f64) -> Self {
        Transform {
            rotation: DMat3::from_rotation_y(degrees.to_radians()),
            translation: Vec3::ZERO,
        }
    }

    pub fn translate(offset: Vec3) -> Self {
        Transform {
            rotation: DMat3::IDENTITY,
            translation: offset,
        }
    }

    /// This transform followed by `next`.
    pub fn then(self, next: Transform) -> Self {
        Transform {
            rotation: next.rotation * self.rotation,
            translation: next.rotation * self.translation + next.translation,
        }
    }

    #[inline]
    pub fn point(&self, p: Point3) -> Point3 {
        self.rotation * p + self.translation
    }

    #[inline]
    pub fn vector(&self, v: Vec3) -> Vec3 {
        self.rotation * v
    }

    /// The inverse map of a point (`R^T (p - t)`, rotations being orthogonal).
    #[inline]
    pub fn inverse_point(&self, p: Point3) -> Point3 {
        self.rotation.transpose() * (p - self.translation)
    }

    #[inline]
    pub fn inverse_vector(&self, v: Vec3) -> Vec3 {
        self.rotation.transpose() * v
    }

    /// The bounding box of a transformed box (its eight transformed corners).
    pub fn bounds(&self, b: &Aabb) -> Aabb {
        let mut out = Aabb::EMPTY;
        for i in 0..8 {
            let c = Vec3::new(
                if i & 1 == 0 { b.min.x } else { b.max.x },
                if i & 2 == 0 { b.min.y } else { b.max.y },
                if i & 4 == 0 { b.min.z } else { b.max.z },
            );
            out = out.include(self.point(c));
        }
        out.padded()
    }
}

/// Index of a group (a list of objects with its own BVH) in the scene; group 0 is the world.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GroupId(pub u32);

/// Index of a material in the scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MaterialId(pub u32);

/// Index of a texture in the scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TextureId(pub u32);

/// A constant-density medium filling a closed boundary (book 2): a ray inside travels a distance drawn
/// from the exponential distribution of rate `density` before it scatters by the phase function.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConstantMedium {
    pub boundary: GroupId,
    pub neg_inv_density: f64,
    pub phase: u32,
}

/// Something a ray can hit.
#[derive(Clone, Copy, Debug, PartialEq)]
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
    fn cost(&self) -> ItemCost {
        match self {
            Object::Quad(_) => ItemCost::Packed,
            Object::Sphere(_) => ItemCost::Single(1.0),
            Object::Instance { .. } | Object::Group(_) => ItemCost::Single(4.0),
            Object::Medium(_) => ItemCost::Single(8.0),
        }
    }
}

/// A list of objects and the BVH over them (objects stored in the BVH's leaf order).
#[derive(Clone, Debug, Default)]
pub struct Group {
    pub objects: Vec<Object>,
    /// What the ray is traced through: the BVH collapsed to 4-wide nodes, with each leaf's quads in
    /// packets of four and its other objects listed.
    pub accel: Accel,
}

/// The background: what a ray that leaves the scene sees.
#[derive(Clone, Copy, Debug, PartialEq)]
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
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Target {
    Quad(Quad),
    Sphere(Sphere),
}

/// The material of a target that is only a shape to aim at: it names no material, so the target
/// never counts as an emitter.
pub const NO_MATERIAL: u32 = u32::MAX;

/// What a scene calls for, decided once when it is built, so that nothing is simulated that the scene
/// does not need.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Features {
    /// The camera has a lens (defocus blur).
    pub defocus: bool,
    /// Something moves during the shutter interval (motion blur: rays carry random times).
    pub motion: bool,
    /// Number of constant media.
    pub media: usize,
    /// Number of textures that are not a plain colour.
    pub textures: usize,
    /// Number of emitting objects (primitives with a light material, instanced copies counted once).
    pub emitters: usize,
    /// Whether some emitter is one-sided.
    pub one_sided_emitters: bool,
    /// Number of importance targets.
    pub targets: usize,
}

/// A scene ready to render.
#[derive(Clone, Debug)]
pub struct Scene {
    pub groups: Vec<Group>,
    pub materials: Vec<Material>,
    pub textures: Vec<Texture>,
    pub camera: CameraSettings,
    pub background: Background,
    /// Most intersections a path may have.
    pub max_depth: u32,
    pub targets: Vec<Target>,
    pub features: Features,
}

/// Errors in building a scene.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum SceneError {
    #[error("zero-area or non-finite quad (Q {q}, u {u}, v {v})")]
    DegenerateQuad { q: Vec3, u: Vec3, v: Vec3 },
    #[error("sphere with non-positive or non-finite radius {0} or non-finite centre")]
    BadSphere(f64),
    #[error("medium density must be positive and finite, got {0}")]
    BadDensity(f64),
    #[error("{0}")]
    Other(String),
}

/// Builds a scene object by object, the way the books' `main` functions do.
#[derive(Debug)]
pub struct SceneBuilder {
    groups: Vec<Vec<Object>>,
    pub materials: Vec<Material>,
    pub textures: Vec<Texture>,
    pub camera: CameraSettings,
    pub background: Background,
    pub max_depth: u32,
    pub targets: Vec<Target>,
}

impl Default for SceneBuilder {
    fn default() -> Self {
        Self::new()
    }
}

impl SceneBuilder {
    pub fn new() -> Self {
        SceneBuilder {
            groups: vec![Vec::new()],
            materials: Vec::new(),
            textures: Vec::new(),
            camera: CameraSettings::default(),
            background: Background::Solid(Color::ZERO),
            max_depth: 50,
            targets: Vec::new(),
        }
    }

    pub fn material(&mut self, m: Material) -> MaterialId {
        self.materials.push(m);
        MaterialId(self.materials.len() as u32 - 1)
    }

    pub fn texture(&mut self, t: Texture) -> TextureId {
        self.textures.push(t);
        TextureId(self.textures.len() as u32 - 1)
    }

    /// A new empty group (a list with its own BVH), to be filled with `add_to` and placed by instances.
    pub fn group(&mut self) -> GroupId {
        self.groups.push(Vec::new());
        GroupId(self.groups.len() as u32 - 1)
    }

    /// The world: the top-level list.
    pub fn world(&self) -> GroupId {
        GroupId(0)
    }

    pub fn add_to(&mut self, g: GroupId, o: Object) {
        self.groups[g.0 as usize].push(o);
    }

    pub fn add(&mut self, o: Object) {
        self.add_to(GroupId(0), o)
    }

    /// A sphere into group `g`.
    pub fn sphere(
        &mut self,
        g: GroupId,
        center: Point3,
        radius: f64,
        m: MaterialId,
    ) -> Result<(), SceneError> {
        if !(radius.is_finite() && radius > 0.0 && center.is_finite()) {
            return Err(SceneError::BadSphere(radius));
        }
        self.add_to(g, Object::Sphere(Sphere::new(center, radius, m.0)));
        Ok(())
    }

    /// A sphere moving from `c0` at time 0 to `c1` at time 1 into group `g`.
    pub fn moving_sphere(
        &mut self,
        g: GroupId,
        c0: Point3,
        c1: Point3,
        radius: f64,
        m: MaterialId,
    ) -> Result<(), SceneError> {
        if !(radius.is_finite() && radius > 0.0 && c0.is_finite() && c1.is_finite()) {
            return Err(SceneError::BadSphere(radius));
        }
        self.add_to(g, Object::Sphere(Sphere::moving(c0, c1, radius, m.0)));
        Ok(())
    }

    /// The quad `(Q, u, v)` into group `g`.
    pub fn quad(
        &mut self,
        g: GroupId,
        q: Point3,
        u: Vec3,
        v: Vec3,
        m: MaterialId,
    ) -> Result<Quad, SceneError> {
        let quad = Quad::new(q, u, v, m.0).ok_or(SceneError::DegenerateQuad { q, u, v })?;
        self.add_to(g, Object::Quad(quad));
        Ok(quad)
    }

    /// A new group holding the box with corners `a`, `b` as six quads.
    pub fn box_group(
        &mut self,
        a: Point3,
        b: Point3,
        m: MaterialId,
    ) -> Result<GroupId, SceneError> {
        let quads = box_quads(a, b, m.0).ok_or(SceneError::DegenerateQuad {
            q: a,
            u: b - a,
            v: Vec3::ZERO,
        })?;
        let g = self.group();
        for q in quads {
            self.add_to(g, Object::Quad(q));
        }
        Ok(g)
    }

    /// Place group `inner` by `transform` into group `g`.
    pub fn instance(&mut self, g: GroupId, inner: GroupId, transform: Transform) {
        self.add_to(
            g,
            Object::Instance {
                transform,
                group: inner,
            },
        );
    }

    /// Fill the closed shape `boundary` with a medium of `density` and phase material `phase` in group `g`.
    pub fn medium(
        &mut self,
        g: GroupId,
        boundary: GroupId,
        density: f64,
        phase: MaterialId,
    ) -> Result<(), SceneError> {
        if !(density.is_finite() && density > 0.0) {
            return Err(SceneError::BadDensity(density));
        }
        self.add_to(
            g,
            Object::Medium(ConstantMedium {
                boundary,
                neg_inv_density: -1.0 / density,
                phase: phase.0,
            }),
        );
        Ok(())
    }

    /// The groups a group refers to (by instance, nesting or medium boundary).
    fn references(objects: &[Object]) -> impl Iterator<Item = usize> + '_ {
        objects.iter().filter_map(|o| match o {
            Object::Instance { group, .. } | Object::Group(group) => Some(group.0 as usize),
            Object::Medium(m) => Some(m.boundary.0 as usize),
            _ => None,
        })
    }

    /// Groups in an order where every group comes after the groups it refers to (depth-first); a
    /// group that contains itself, directly or not, is an error.
    fn build_order(&self) -> Result<Vec<usize>, SceneError> {
        // 0 = not visited, 1 = on the current path, 2 = done.
        let n = self.groups.len();
        let mut state = vec![0u8; n];
        let mut order = Vec::with_capacity(n);
        for root in 0..n {
            if state[root] != 0 {
                continue;
            }
            // Explicit stack of (group, next reference index) to avoid deep recursion.
            let mut stack = vec![(root, 0usize)];
            state[root] = 1;
            while let Some(&mut (g, ref mut next)) = stack.last_mut() {
                let refs: Vec<usize> = Self::references(&self.groups[g]).collect();
                if let Some(&r) = refs.get(*next) {
                    *next += 1;
                    if r >= n {
                        return Err(SceneError::Other(format!(
                            "group {g} refers to group {r}, which does not exist"
                        )));
                    }
                    match state[r] {
                        0 => {
                            state[r] = 1;
                            stack.push((r, 0));
                        }
                        1 => return Err(SceneError::Other(format!("group {r} contains itself"))),
                        _ => {}
                    }
                } else {
                    state[g] = 2;
                    order.push(g);
                    stack.pop();
                }
            }
        }
        Ok(order)
    }

    /// Build every group's BVH (inner groups first, since instances need their bounds) and decide the
    /// scene's features.
    pub fn build(self) -> Result<Scene, SceneError> {
        let n = self.groups.len();
        let mut built: Vec<Option<Group>> = (0..n).map(|_| None).collect();
        let mut bounds_of: Vec<Option<Aabb>> = vec![None; n];
        let order = self.build_order()?;
        for &gi in &order {
            let objects = &self.groups[gi];
            let mut bounds = Vec::with_capacity(objects.len());
            for o in objects {
                let b = match o {
                    Object::Sphere(s) => s.bounds(),
                    Object::Quad(q) => q.bounds(),
                    Object::Instance { transform, group } => {
                        let inner = bounds_of[group.0 as usize].ok_or_else(|| {
                            SceneError::Other(format!(
                                "group {} is placed before it is complete",
                                group.0
                            ))
                        })?;
                        transform.bounds(&inner)
                    }
                    Object::Group(group) => bounds_of[group.0 as usize].ok_or_else(|| {
                        SceneError::Other(format!(
                            "group {} is placed before it is complete",
                            group.0
                        ))
                    })?,
                    Object::Medium(m) => bounds_of[m.boundary.0 as usize].ok_or_else(|| {
                        SceneError::Other(format!(
                            "medium boundary {} is not complete",
                            m.boundary.0
                        ))
                    })?,
                };
                bounds.push(b);
            }
            let costs: Vec<ItemCost> = objects.iter().map(Object::cost).collect();
            let bvh = Bvh::build_with_costs(&bounds, &costs);
            let objects_in_order: Vec<Object> =
                bvh.order.iter().map(|&i| objects[i as usize]).collect();
            bounds_of[gi] = Some(bvh.bounds());
            built[gi] = Some(Group {
                accel: Accel::new(&objects_in_order, &bvh),
                objects: objects_in_order,
            });
        }
        let groups: Vec<Group> = built
            .into_iter()
            .map(|g| g.expect("every group built"))
            .collect();
        for (i, m) in self.materials.iter().enumerate() {
            let bad = match m {
                Material::Lambertian { albedo }
                | Material::Isotropic { albedo }
                | Material::DiffuseLight { emit: albedo, .. } => {
                    matches!(albedo, crate::material::Albedo::Texture(t) if *t as usize >= self.textures.len())
                }
                Material::Metal { albedo, fuzz } => !albedo.is_finite() || !fuzz.is_finite(),
                Material::Dielectric { ior } => !(ior.is_finite() && *ior > 0.0),
            };
            if bad {
                return Err(SceneError::Other(format!("material {i} is invalid: {m:?}")));
            }
        }
        let mut features = Features {
            defocus: self.camera.defocus_angle > 0.0,
            targets: self.targets.len(),
            textures: self
                .textures
                .iter()
                .filter(|t| !matches!(t, Texture::Solid(_)))
                .count(),
            ..Features::default()
        };
        for g in &groups {
            for o in &g.objects {
                let mat = match o {
                    Object::Sphere(s) => {
                        features.motion |= s.is_moving();
                        Some(s.material)
                    }
                    Object::Quad(q) => Some(q.material),
                    Object::Instance { .. } | Object::Group(_) => None,
                    Object::Medium(_) => {
                        features.media += 1;
                        None
                    }
                };
                if let Some(m) = mat {
                    let m = self
                        .materials
                        .get(m as usize)
                        .ok_or_else(|| SceneError::Other(format!("unknown material {m}")))?;
                    if let Material::DiffuseLight { two_sided, .. } = m {
                        features.emitters += 1;
                        features.one_sided_emitters |= !two_sided;
                    }
                }
            }
        }
        Ok(Scene {
            groups,
            materials: self.materials,
            textures: self.textures,
            camera: self.camera,
            background: self.background,
            max_depth: self.max_depth,
            targets: self.targets,
            features,
        })
    }
}
