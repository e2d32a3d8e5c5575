//! Building a scene the way the books' `main` functions do, object by object, then every group's BVH
//! (inner groups first) and the scene's [`Features`]; what cannot be built is a typed [`SceneError`].

use crate::aabb::Aabb;
use crate::boundary_pieces::{Piece, PieceKind, Pieces};
use crate::bvh::{Bvh, ItemCost};
use crate::camera::CameraSettings;
use crate::closed_surface::{LooseQuad, OpenQuad, closed_components, first_open};
use crate::flatten::flatten_instances_marked;
use crate::ids::{GroupId, MaterialId, TextureId};
use crate::material::{Albedo, Material};
use crate::scene::{
    Accel, Background, ConstantMedium, Features, Group, ImportanceTarget, Object, Scene,
};
use crate::shapes::{Quad, Sphere, box_quads};
use crate::texture::Texture;
use crate::transform::Transform;
use crate::vec::{Color, Num, Point3, Vec3};
use std::collections::{HashMap, HashSet};

/// Errors in building a scene.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum SceneError {
    #[error(
        "zero-area or non-finite quad (Q {}, u {}, v {})",
        Num::v3(*.q), Num::v3(*.u), Num::v3(*.v)
    )]
    DegenerateQuad { q: Vec3, u: Vec3, v: Vec3 },
    #[error(
        "sphere with non-positive or non-finite radius {} or non-finite centre",
        Num(*.0)
    )]
    BadSphere(f64),
    #[error("medium density must be positive and finite, got {}", Num(*.0))]
    BadDensity(f64),
    #[error(
        "the box with corners {} and {} is flat, or too small for its faces to have an area in \
         floating point",
        Num::v3(*.a), Num::v3(*.b)
    )]
    FlatBox { a: Point3, b: Point3 },
    #[error("{0}")]
    TextureImage(String),
    #[error("group {group} refers to group {missing}, which does not exist")]
    MissingGroup { group: u32, missing: u32 },
    #[error("group {0} contains itself")]
    Cycle(u32),
    #[error("group {0} is placed before it is complete")]
    Incomplete(u32),
    #[error("the boundary {0} of a medium is not complete")]
    IncompleteBoundary(u32),
    #[error(
        "the boundary (group {boundary}) of a medium has pieces that overlap or touch, within {} to \
         {} and within {} to {}: a ray's crossings would not alternate in and out",
        Num::v3(.a.min), Num::v3(.a.max), Num::v3(.b.min), Num::v3(.b.max)
    )]
    TouchingPieces { boundary: u32, a: Aabb, b: Aabb },
    #[error(
        "the boundary (group {0}) of a medium holds a medium: a boundary is surfaces alone (each of \
         its hits is a crossing, and a medium's hits are where it scatters)"
    )]
    MediumInBoundary(u32),
    #[error("material {index} is invalid: {what}")]
    InvalidMaterial { index: usize, what: &'static str },
    #[error("an object refers to material {0}, which does not exist")]
    UnknownMaterial(u32),
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
    pub targets: Vec<ImportanceTarget>,
    /// Whether small groups' rigid instances of quads are flattened into them at build time
    /// ([`crate::flatten`]); on by default. Off builds the scene as placed, instance by instance (the
    /// reference the flattened form is tested against).
    pub flatten: bool,
    /// The groups [`Self::box_group`] made: six quads that enclose a volume by construction.
    boxes: HashSet<u32>,
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
            flatten: true,
            boxes: HashSet::new(),
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

    /// The objects added to group `g` so far, in the order they were added (none for a group that
    /// does not exist).
    pub fn objects(&self, g: GroupId) -> &[Object] {
        self.groups.get(g.0 as usize).map_or(&[], Vec::as_slice)
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
        self.add_to(g, Object::Sphere(Sphere::new(center, radius, m)));
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
        self.add_to(g, Object::Sphere(Sphere::moving(c0, c1, radius, m)));
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
        let quad = Quad::new(q, u, v, m).ok_or(SceneError::DegenerateQuad { q, u, v })?;
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
        let quads = box_quads(a, b, m).ok_or(SceneError::FlatBox { a, b })?;
        let g = self.group();
        for q in quads {
            self.add_to(g, Object::Quad(q));
        }
        self.boxes.insert(g.0);
        Ok(g)
    }

    /// The first quad of group `g` (held directly or by the groups and instances within it) that
    /// keeps `g` from enclosing a volume, the way a medium's boundary must: `None` if it encloses
    /// one. Spheres and boxes do; so does a group or instance that encloses a volume by itself; the
    /// rest of the quads must close a surface among themselves
    /// ([`closed_surface`](crate::closed_surface): every edge of each quad an edge of exactly one
    /// other quad, corners equal to within a rounding error, so that a box written out as six
    /// quads, rotated or not, closes; no two quads at the same place). Media in `g` are left out
    /// (their own boundaries are theirs). An edge along which other quads' corners lie (a
    /// T-junction) is shared stretch by stretch, each stretch with exactly one other quad.
    pub fn open_quad(&self, g: GroupId) -> Option<OpenQuad> {
        let mut closed = HashMap::new();
        let mut quads = Vec::new();
        self.loose_quads(g, Transform::IDENTITY, &mut closed, &mut quads);
        first_open(&quads).map(|(i, problem)| OpenQuad {
            group: quads[i].group,
            index: quads[i].index,
            problem,
        })
    }

    /// The closed pieces group `g` is made of, in `g`'s coordinates
    /// ([`crate::boundary_pieces`]): each sphere, each box, and the quads by the closed surfaces
    /// they form, wherever the groups and instances within `g` place them (joined by shared edges;
    /// all as one if they do not close). At most [`crate::limits::MAX_EXPANDED_OBJECTS`] objects are
    /// looked at.
    pub fn boundary_pieces(&self, g: GroupId) -> Pieces {
        let mut out = Vec::new();
        let mut loose = Vec::new();
        let mut budget = crate::limits::MAX_EXPANDED_OBJECTS as usize;
        self.pieces_in(g, Transform::IDENTITY, &mut budget, &mut out, &mut loose);
        let mut quads = Vec::with_capacity(loose.len());
        if !loose.is_empty() {
            // the loose quads by the closed surfaces they form (all as one if they do not close)
            let component = closed_components(&loose).unwrap_or_else(|| vec![0; loose.len()]);
            let mut order: Vec<usize> = (0..loose.len()).collect();
            order.sort_by_key(|&k| component[k]);
            for surface in order.chunk_by(|&i, &j| component[i] == component[j]) {
                let first = quads.len();
                let mut bounds = Aabb::EMPTY;
                for &k in surface {
                    bounds = bounds.union(&loose[k].bounds());
                    quads.push(loose[k].parallelogram());
                }
                let count = quads.len() - first;
                out.push(Piece {
                    kind: PieceKind::Quads { first, count },
                    bounds,
                });
            }
        }
        Pieces { pieces: out, quads }
    }

    fn pieces_in(
        &self,
        g: GroupId,
        to: Transform,
        budget: &mut usize,
        out: &mut Vec<Piece>,
        loose: &mut Vec<LooseQuad>,
    ) {
        for (index, o) in self.objects(g).iter().enumerate() {
            if *budget == 0 {
                return;
            }
            *budget -= 1;
            let (inner, placed) = match o {
                Object::Sphere(s) if s.is_moving() => {
                    let (c0, c1) = (to.point(s.center_at(0.0)), to.point(s.center_at(1.0)));
                    out.push(Piece::moving_ball(c0, c1, s.radius));
                    continue;
                }
                Object::Sphere(s) => {
                    out.push(Piece::ball(to.point(s.center), s.radius));
                    continue;
                }
                Object::Quad(q) => {
                    loose.push(LooseQuad::new(q, to, g, index));
                    continue;
                }
                Object::Medium(_) => continue,
                Object::Group(inner) => (*inner, to),
                Object::Instance { transform, group } => (*group, transform.then(to)),
            };
            if self.boxes.contains(&inner.0) {
                // the box in its own coordinates (its axis-aligned faces' opposite corners), placed
                let own = (self.objects(inner).iter())
                    .filter_map(|o| match o {
                        Object::Quad(q) => Some([q.q, q.q + q.u + q.v]),
                        _ => None,
                    })
                    .flatten()
                    .fold(Aabb::EMPTY, |b, c| b.include(c));
                out.push(Piece::placed_box(
                    own.min,
                    own.max,
                    placed.rotation,
                    placed.translation,
                ));
            } else {
                self.pieces_in(inner, placed, budget, out, loose);
            }
        }
    }

    /// Whether group `g` holds a medium, directly or in the groups and instances within it: a
    /// medium's boundary must not, since its every hit counts as a crossing, and a medium's hits
    /// are where it scatters.
    pub fn holds_medium(&self, g: GroupId) -> bool {
        let mut seen = HashSet::new();
        let mut todo = vec![g.0];
        while let Some(g) = todo.pop() {
            if !seen.insert(g) {
                continue;
            }
            for o in self.groups.get(g as usize).into_iter().flatten() {
                match o {
                    Object::Medium(_) => return true,
                    Object::Group(inner) | Object::Instance { group: inner, .. } => {
                        todo.push(inner.0)
                    }
                    Object::Sphere(_) | Object::Quad(_) => {}
                }
            }
        }
        false
    }

    /// Whether group `g` is one convex piece: a sphere, a box, or a group or instance of one alone.
    /// A ray crosses such a boundary at most twice, so a medium in it has one stretch a ray.
    pub fn one_convex_piece(&self, g: GroupId) -> bool {
        if self.boxes.contains(&g.0) {
            return true;
        }
        match self.objects(g) {
            [Object::Sphere(_)] => true,
            [Object::Group(inner)] | [Object::Instance { group: inner, .. }] => {
                self.one_convex_piece(*inner)
            }
            _ => false,
        }
    }

    /// The quads of group `g` placed by `to`, but those of boxes and of groups that enclose a volume
    /// by themselves (`closed`: that, per group looked at).
    fn loose_quads(
        &self,
        g: GroupId,
        to: Transform,
        closed: &mut HashMap<u32, bool>,
        out: &mut Vec<LooseQuad>,
    ) {
        for (index, o) in self.objects(g).iter().enumerate() {
            match o {
                Object::Quad(q) => out.push(LooseQuad::new(q, to, g, index)),
                Object::Group(inner) => self.loose_if_open(*inner, to, closed, out),
                Object::Instance { transform, group } => {
                    self.loose_if_open(*group, transform.then(to), closed, out)
                }
                Object::Sphere(_) | Object::Medium(_) => {}
            }
        }
    }

    /// The quads of group `g` placed by `to`, unless it encloses a volume by itself.
    fn loose_if_open(
        &self,
        g: GroupId,
        to: Transform,
        closed: &mut HashMap<u32, bool>,
        out: &mut Vec<LooseQuad>,
    ) {
        if self.boxes.contains(&g.0) {
            return;
        }
        let is_closed = match closed.get(&g.0) {
            Some(&c) => c,
            None => {
                let mut own = Vec::new();
                self.loose_quads(g, Transform::IDENTITY, closed, &mut own);
                let c = first_open(&own).is_none();
                closed.insert(g.0, c);
                c
            }
        };
        if !is_closed {
            self.loose_quads(g, to, closed, out);
        }
    }

    /// The shapes (quads and spheres) group `g` holds, directly or in groups and instances within
    /// it (at most `budget` of them, so that instances of instances cannot make the walk long), each
    /// with the transform that places it in `g`'s space followed by `to`; stops at the first `Err`
    /// of `f`.
    pub fn each_shape<E>(
        &self,
        g: GroupId,
        to: Transform,
        budget: &mut usize,
        f: &mut impl FnMut(&Object, Transform) -> Result<(), E>,
    ) -> Result<(), E> {
        for o in self.groups.get(g.0 as usize).into_iter().flatten() {
            if *budget == 0 {
                return Ok(());
            }
            match o {
                Object::Quad(_) | Object::Sphere(_) => {
                    *budget -= 1;
                    f(o, to)?;
                }
                Object::Group(inner) => self.each_shape(*inner, to, budget, f)?,
                Object::Instance { transform, group } => {
                    self.each_shape(*group, transform.then(to), budget, f)?
                }
                Object::Medium(_) => {}
            }
        }
        Ok(())
    }

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
                phase,
                convex: false, // (decided when the scene is built, its boundary complete)
            }),
        );
        Ok(())
    }

    /// The group an object refers to (by instance, nesting or medium boundary), if any.
    fn reference(o: &Object) -> Option<usize> {
        match o {
            Object::Instance { group, .. } | Object::Group(group) => Some(group.0 as usize),
            Object::Medium(m) => Some(m.boundary.0 as usize),
            _ => None,
        }
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
            // Explicit stack of (group, index of the next object to look at) to avoid deep
            // recursion; each group's objects are scanned once, so the order takes linear time.
            let mut stack = vec![(root, 0usize)];
            state[root] = 1;
            while let Some(&mut (g, ref mut next)) = stack.last_mut() {
                let objects = &self.groups[g];
                let found = objects[*next..]
                    .iter()
                    .enumerate()
                    .find_map(|(k, o)| Self::reference(o).map(|r| (k, r)));
                if let Some((k, r)) = found {
                    *next += k + 1;
                    if r >= n {
                        return Err(SceneError::MissingGroup {
                            group: g as u32,
                            missing: r as u32,
                        });
                    }
                    match state[r] {
                        0 => {
                            state[r] = 1;
                            stack.push((r, 0));
                        }
                        1 => return Err(SceneError::Cycle(r as u32)),
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
        let mut draws_of = vec![false; n];
        let mut flattened_instances = 0;
        let order = self.build_order()?;
        // Every medium's boundary in pieces that lie apart (the scene file's loader says so first,
        // at the boundary's place; this is for scenes built in code)
        let mut boundaries: Vec<u32> = self
            .groups
            .iter()
            .flatten()
            .filter_map(|o| match o {
                Object::Medium(m) => Some(m.boundary.0),
                _ => None,
            })
            .collect();
        boundaries.sort_unstable();
        boundaries.dedup();
        for g in boundaries {
            if self.holds_medium(GroupId(g)) {
                return Err(SceneError::MediumInBoundary(g));
            }
            let pieces = self.boundary_pieces(GroupId(g));
            if let Some((i, j, _)) = pieces.first_touching() {
                return Err(SceneError::TouchingPieces {
                    boundary: g,
                    a: pieces.pieces[i].bounds,
                    b: pieces.pieces[j].bounds,
                });
            }
        }
        for &gi in &order {
            // Whether a hit in this group may draw random numbers (a medium, here or nested): its
            // objects are then tested in the tree's order, which the random stream depends on.
            let draws = self.groups[gi].iter().any(|o| match o {
                Object::Medium(_) => true,
                Object::Instance { group, .. } | Object::Group(group) => {
                    draws_of.get(group.0 as usize).copied().unwrap_or(false)
                }
                _ => false,
            });
            draws_of[gi] = draws;
            // A small group's rigid instances of quads, flattened into it (see `crate::flatten`).
            let (flattened, from_instance);
            let (objects, from) = if draws || !self.flatten {
                (&self.groups[gi], None)
            } else {
                (flattened, from_instance) =
                    flatten_instances_marked(&self.groups[gi], &self.groups, &self.materials);
                let instances = |objects: &[Object]| {
                    objects
                        .iter()
                        .filter(|o| matches!(o, Object::Instance { .. }))
                        .count()
                };
                flattened_instances += instances(&self.groups[gi]) - instances(&flattened);
                (&flattened, Some(&from_instance))
            };
            let mut bounds = Vec::with_capacity(objects.len());
            for o in objects {
                let b = match o {
                    Object::Sphere(s) => s.bounds(),
                    Object::Quad(q) => q.bounds(),
                    Object::Instance { transform, group } => {
                        let inner =
                            bounds_of[group.0 as usize].ok_or(SceneError::Incomplete(group.0))?;
                        transform.bounds(&inner)
                    }
                    Object::Group(group) => {
                        bounds_of[group.0 as usize].ok_or(SceneError::Incomplete(group.0))?
                    }
                    Object::Medium(m) => bounds_of[m.boundary.0 as usize]
                        .ok_or(SceneError::IncompleteBoundary(m.boundary.0))?,
                };
                bounds.push(b);
            }
            let costs: Vec<ItemCost> = objects.iter().map(Object::cost).collect();
            let bvh = Bvh::build_with_costs(&bounds, &costs);
            let objects_in_order: Vec<Object> = bvh
                .order
                .iter()
                .map(|&i| match objects[i as usize] {
                    Object::Medium(m) => Object::Medium(ConstantMedium {
                        convex: self.one_convex_piece(m.boundary),
                        ..m
                    }),
                    o => o,
                })
                .collect();
            let bounds_in_order: Vec<Aabb> =
                bvh.order.iter().map(|&i| bounds[i as usize]).collect();
            bounds_of[gi] = Some(bvh.bounds());
            // each object's flattened instance, if it came from one (`crate::ray8::Cluster`)
            let instance_in_order: Vec<Option<u32>> = match from {
                Some(from) => bvh.order.iter().map(|&i| from[i as usize]).collect(),
                None => vec![None; objects.len()],
            };
            built[gi] = Some(Group {
                accel: Accel::new(
                    &objects_in_order,
                    &bounds_in_order,
                    &instance_in_order,
                    &bvh,
                    draws,
                ),
                objects: objects_in_order,
            });
        }
        let groups: Vec<Group> = built
            .into_iter()
            .map(|g| g.expect("every group built"))
            .collect();
        for (index, m) in self.materials.iter().enumerate() {
            let what = match m {
                Material::Lambertian { albedo }
                | Material::Isotropic { albedo }
                | Material::DiffuseLight { emit: albedo, .. } => {
                    matches!(albedo, Albedo::Texture(t) if t.index() >= self.textures.len())
                        .then_some("it refers to a texture that does not exist")
                }
                Material::Metal { albedo, fuzz } => (!albedo.is_finite() || !fuzz.is_finite())
                    .then_some("a metal's albedo and fuzz must be finite"),
                Material::Dielectric { ior } => (!(ior.is_finite() && *ior > 0.0))
                    .then_some("the index of refraction must be positive and finite"),
            };
            if let Some(what) = what {
                return Err(SceneError::InvalidMaterial { index, what });
            }
        }
        let mut features = Features {
            defocus: self.camera.defocus_angle > 0.0,
            targets: self.targets.len(),
            flattened_instances,
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
                    Object::Medium(m) => {
                        features.media += 1;
                        features.media_in_pieces += !m.convex as usize;
                        None
                    }
                };
                if let Some(m) = mat {
                    let m = self
                        .materials
                        .get(m.index())
                        .ok_or(SceneError::UnknownMaterial(m.0))?;
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
