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
//!
//! Next-event estimation chooses its emitter per shading point ([`Lights::towards_emitters`]): in
//! proportion to an estimate of what each emitter contributes there, its radiance times the solid
//! angle it subtends ([`EmitterWeight::at`]; pbrt-v4's light samplers, Conty Estevez and Kulla 2018),
//! mixed with a uniform share so that no emitter that can contribute is left out.

use crate::light_tree::LightTree;
use crate::limits::{MAX_NESTING, WalkBudget};
use crate::manifold::{FoundShape, Manifold};
use crate::material::{Albedo, Material};
use crate::scene::{GroupId, ImportanceTarget as SceneShape, MaterialId, Object, Scene, Transform};
use crate::target_index::{INDEX_FROM, TargetIndex};
use crate::vec::{Point3, Vec3};
use glam::DVec2;
use rtl_pdf::{DirectionSample, HittablePdf, Pdf, QuadTarget, ShapeSampler, SphereTarget};
use std::collections::HashSet;
use std::f64::consts::TAU;

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
    /// Per emitter of `emitters`, what its weight in next-event estimation's choice needs.
    pub emitter_weights: Vec<EmitterWeight>,
    /// The dielectric spheres that light reaches the inside of only by refraction, and the emitters
    /// to connect to through them ([`crate::manifold`]).
    pub manifold: Manifold,
    /// A hierarchy over `emitters` when they are [`INDEX_FROM`] or more.
    pub emitter_index: Option<TargetIndex>,
    /// Next-event estimation's choice among more than [`MAX_WEIGHED_EMITTERS`] emitters: a light
    /// tree, weighed per shading point in `O(log n)` by the emitters' power and distance, mixed with
    /// [`UNIFORM_SHARE`] spread uniformly.
    pub emitter_tree: Option<LightTree>,
    /// A hierarchy over `all` when it holds [`INDEX_FROM`] targets or more.
    pub all_index: Option<TargetIndex>,
}

/// `targets` seen from `x` uniformly (`None` if empty), through `index` if there is one.
#[inline]
fn uniform<'a>(
    x: Point3,
    targets: &'a [LightTarget],
    index: &'a Option<TargetIndex>,
) -> Option<HittablePdf<'a, LightTarget>> {
    let h = HittablePdf::new(x, targets)?;
    Some(match index {
        Some(i) => h.with_index(i),
        None => h,
    })
}

/// The light tree over more than [`MAX_WEIGHED_EMITTERS`] emitters; `None` for fewer, or if the
/// powers make no distribution (then the choice is uniform).
fn tree_of(emitters: &[LightTarget], weights: &[EmitterWeight]) -> Option<LightTree> {
    if emitters.len() <= MAX_WEIGHED_EMITTERS {
        return None;
    }
    LightTree::new(emitters, weights)
}

/// A hierarchy over `targets` if the list is long enough to need one.
fn index_of(targets: &[LightTarget]) -> Option<TargetIndex> {
    (targets.len() >= INDEX_FROM).then(|| TargetIndex::new(targets))
}

/// The most emitters whose choice is weighed per shading point: their probabilities live in a
/// fixed-size array on the stack ([`EmitterPmf`]), each weighed at `O(1)`, `O(n)` a vertex. Scenes
/// with more choose through a light tree ([`Lights::emitter_tree`]), weighed per point in
/// `O(log n)`; a direction's density costs `O(n)` below [`INDEX_FROM`] emitters and about
/// `O(log n)` from there on, through [`TargetIndex`].
pub const MAX_WEIGHED_EMITTERS: usize = 16;

/// The share of next-event estimation's choice spread uniformly over the emitters that can
/// contribute at the shading point (a defensive mixture: an estimate of the importance that is too
/// small costs at most a factor `1 / UNIFORM_SHARE` in that emitter's probability against the
/// uniform choice).
pub const UNIFORM_SHARE: f64 = 0.1;

/// The probabilities of choosing each emitter at one shading point, filled by
/// [`Lights::towards_emitters`] (stack storage: nothing is allocated per vertex).
pub type EmitterPmf = [f64; MAX_WEIGHED_EMITTERS];

// ANCHOR: emitter_importance
/// What an emitter's weight in next-event estimation's choice needs, computed once per scene from its
/// shape and its radiance `L` (the mean of the three channels of a constant emission; 1 for a
/// textured one, not known before it is looked up).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum EmitterWeight {
    /// A sphere: its centre, radius squared and `L`.
    Sphere {
        centre: Point3,
        r2: f64,
        radiance: f64,
    },
    /// A quad: its corner `q`, centre, unit normal, area, `L`, and whether it is one-sided.
    Quad {
        q: Point3,
        centre: Point3,
        normal: Vec3,
        area: f64,
        radiance: f64,
        one_sided: bool,
    },
}

impl EmitterWeight {
    /// The weight of emitter `target` of radiance `radiance`.
    pub fn new(target: &LightTarget, radiance: f64) -> EmitterWeight {
        match target {
            LightTarget::Sphere(s) => EmitterWeight::Sphere {
                centre: s.center(),
                r2: s.radius() * s.radius(),
                radiance,
            },
            LightTarget::Quad { quad, one_sided } => EmitterWeight::Quad {
                q: quad.q(),
                centre: quad.q() + 0.5 * (quad.u() + quad.v()),
                normal: quad.normal(),
                area: quad.area(),
                radiance,
                one_sided: *one_sided,
            },
        }
    }

    /// The power the emitter sends out, up to the constant factor `pi` all share: its radiance times
    /// its emitting area (`4 pi r^2` for a sphere; a quad's area, twice for a two-sided one).
    pub fn power(&self) -> f64 {
        match *self {
            EmitterWeight::Sphere { r2, radiance, .. } => radiance * 2.0 * TAU * r2,
            EmitterWeight::Quad {
                area,
                radiance,
                one_sided,
                ..
            } => radiance * area * if one_sided { 1.0 } else { 2.0 },
        }
    }

    /// The emitter's radiance `L`.
    pub fn radiance(&self) -> f64 {
        match self {
            EmitterWeight::Sphere { radiance, .. } | EmitterWeight::Quad { radiance, .. } => {
                *radiance
            }
        }
    }

    /// What the emitter contributes at `x`, estimated: `L Omega(x)`, its radiance times the solid
    /// angle it subtends from `x` (the irradiance of a constant emitter without the cosine at `x`,
    /// which a medium's or a metal's vertex does not have). `None` where the contribution is exactly
    /// 0: behind (or in the plane of) a one-sided quad, where its density is 0 (the same test as
    /// [`LightTarget`]'s).
    ///
    /// - Sphere of radius `r` at distance `d`: the cone's `Omega = 2 pi (1 - cos theta_max)` with
    ///   `sin^2 theta_max = s = r^2 / d^2`, written `2 pi s / (1 + sqrt(1 - s))` (no cancellation for
    ///   a far sphere); `4 pi` from inside (where a one-sided sphere sends nothing: a weight wasted, not
    ///   a bias).
    /// - Quad of area `A` whose centre is at distance `d` and whose plane is at height `h` from `x`:
    ///   `Omega ~ A |h| / d^3` (its area times the cosine at the centre over the squared distance),
    ///   at most `2 pi`, the half-space it lies in.
    ///
    /// Any weights that are positive wherever the emitter contributes give an unbiased estimator;
    /// these put the shadow rays where the light comes from.
    #[inline]
    pub fn at(&self, x: Point3) -> Option<f64> {
        match *self {
            EmitterWeight::Sphere {
                centre,
                r2,
                radiance,
            } => {
                let d2 = (centre - x).length_squared();
                let omega = if r2 >= d2 {
                    2.0 * TAU
                } else {
                    let s = r2 / d2;
                    TAU * s / (1.0 + (1.0 - s).sqrt())
                };
                Some(radiance * omega)
            }
            EmitterWeight::Quad {
                q,
                centre,
                normal,
                area,
                radiance,
                one_sided,
            } => {
                let h = normal.dot(x - q);
                if one_sided && h <= 0.0 {
                    return None;
                }
                let d2 = (centre - x).length_squared();
                // (NaN, from a point at the centre, becomes 2 pi: `min` returns the number)
                Some(radiance * (area * h.abs() / (d2 * d2.sqrt())).min(TAU))
            }
        }
    }
}
// ANCHOR_END: emitter_importance

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
        // Every emitter placed in the scene, in world space (a scene that expands to more objects
        // than a scene file may hold keeps those found within the budget).
        let mut found = Vec::new();
        let mut budget = WalkBudget::new();
        collect_emitters(
            scene,
            GroupId(0),
            Transform::IDENTITY,
            0,
            &mut budget,
            &mut found,
        );
        let placed: Vec<(FoundShape, MaterialId)> =
            found.iter().map(|f| (f.placed, f.material)).collect();
        lights.manifold = Manifold::new(scene, &placed);
        let listed: HashSet<ShapeKey> = scene.targets.iter().map(target_key).collect();
        for Found {
            target: shape,
            two_sided,
            radiance,
            ..
        } in found
        {
            let target = match shape {
                LightTarget::Quad { quad, .. } => LightTarget::Quad {
                    quad: quad.with_spherical_rectangles(spherical_rectangles),
                    one_sided: !two_sided,
                },
                sphere => sphere,
            };
            lights.listed_emitters += listed.contains(&emitter_key(&shape)) as usize;
            lights.emitters.push(target);
            lights
                .emitter_weights
                .push(EmitterWeight::new(&target, radiance));
        }
        lights.emitter_index = index_of(&lights.emitters);
        lights.emitter_tree = tree_of(&lights.emitters, &lights.emitter_weights);
        lights.all_index = index_of(&lights.all);
        lights
    }

    /// The emitters seen from `x` chosen uniformly: one emitter, or more than
    /// [`MAX_WEIGHED_EMITTERS`] whose powers make no light tree, the densities through the hierarchy
    /// if there is one. `None` without emitters.
    #[inline]
    fn uniformly(&self, x: Point3) -> Option<HittablePdf<'_, LightTarget>> {
        uniform(x, &self.emitters, &self.emitter_index)
    }

    /// The book's list seen from `x`, each target chosen with probability `1 / n` (`None` if the
    /// list is empty): what `light` and `mixture` aim at.
    #[inline]
    pub fn towards_all(&self, x: Point3) -> Option<HittablePdf<'_, LightTarget>> {
        uniform(x, &self.all, &self.all_index)
    }

    /// Whether next-event estimation weighs its choice of emitter per shading point one emitter at a
    /// time: two emitters or more, at most [`MAX_WEIGHED_EMITTERS`] (one emitter is always chosen;
    /// more go through the light tree, [`Lights::emitter_tree`]).
    pub fn weighs_emitters(&self) -> bool {
        (2..=MAX_WEIGHED_EMITTERS).contains(&self.emitters.len())
    }

    // ANCHOR: towards_emitters
    /// Next-event estimation's density of directions from `x`: emitter `i` chosen with probability
    ///
    /// `p_i(x) = (1 - a) w_i(x) / sum_j w_j(x) + a / m(x)`  (`a` = [`UNIFORM_SHARE`]),
    ///
    /// `w_i(x)` its [`EmitterWeight::at`] and `m(x)` the number of emitters that can contribute at
    /// `x` (`p_i = 0` for the others, behind a one-sided quad; `1 / m` each if every `w_i` is 0), then
    /// a direction towards it by its own density `p_i(omega | x)` (solid angle measure): the density
    /// `p(omega | x) = sum_i p_i(x) p_i(omega | x)` with respect to solid angle at `x`. The light
    /// sample at `x` and the MIS weight of emission met from `x` by material sampling both call this,
    /// so they use the same probabilities.
    ///
    /// `pmf` is where the probabilities are kept (on the caller's stack). One emitter: that one.
    /// More than [`MAX_WEIGHED_EMITTERS`]: the light tree's choice ([`Lights::emitter_tree`]), which
    /// a [`HittablePdf`] does not express: `None` then (use [`Lights::sample_emitters`] and
    /// [`Lights::emitters_pdf`], which cover every case). `None` also without emitters, or where
    /// none can contribute (every sample would fail and the density is 0).
    #[inline]
    pub fn towards_emitters<'a>(
        &'a self,
        x: Point3,
        pmf: &'a mut EmitterPmf,
    ) -> Option<HittablePdf<'a, LightTarget>> {
        if !self.weighs_emitters() {
            return match self.emitter_tree {
                Some(_) => None,
                None => self.uniformly(x),
            };
        }
        let n = self.emitters.len();
        let pmf = &mut pmf[..n];
        let (mut total, mut open) = (0.0, 0usize);
        for (p, weight) in pmf.iter_mut().zip(&self.emitter_weights) {
            *p = match weight.at(x) {
                Some(w) => {
                    open += 1;
                    total += w;
                    w
                }
                None => -1.0,
            };
        }
        if open == 0 {
            return None;
        }
        let floor = 1.0 / open as f64;
        // (every weight 0, or a sum that is not a number: the uniform choice among the open ones)
        let weighed = total > 0.0 && total.is_finite();
        let (share, scale) = (UNIFORM_SHARE * floor, (1.0 - UNIFORM_SHARE) / total);
        for p in pmf.iter_mut() {
            *p = if *p < 0.0 {
                0.0
            } else if weighed {
                share + scale * *p
            } else {
                floor
            };
        }
        HittablePdf::with_pmf(x, &self.emitters, pmf).ok()
    }
    // ANCHOR_END: towards_emitters

    /// One direction of next-event estimation from `x` for the uniform numbers `u`, drawn by
    /// [`Lights::towards_emitters`] (or the light tree), with its density; `None` without emitters,
    /// where the drawn emitter has no direction from `x`, or where the light tree's descent stops
    /// (two clusters of importance 0).
    ///
    /// `normal`: the unit normal of a surface at `x` that receives light only from the hemisphere
    /// above it (a Lambertian one), which the light tree's importance bounds the cosine by; `None`
    /// elsewhere (a medium's point, a metal). Only the light tree uses it; the MIS weight of the
    /// emission met from `x` must pass [`Lights::emitters_pdf`] the same one.
    #[inline]
    pub fn sample_emitters(
        &self,
        x: Point3,
        normal: Option<Vec3>,
        u: DVec2,
    ) -> Option<DirectionSample> {
        if self.weighs_emitters() {
            self.sample_weighed(x, u)
        } else if let Some(tree) = &self.emitter_tree {
            tree.sample(x, normal, u, &self.emitters, self.emitter_index.as_ref())
        } else {
            // (no probabilities to keep: the common case of one emitter pays nothing for them)
            self.uniformly(x)?.sample(u)
        }
    }

    /// The density with which next-event estimation from `x` with the shading normal `normal` (see
    /// [`Lights::sample_emitters`]) picks `direction` ([`Lights::towards_emitters`]; 0 without
    /// emitters).
    #[inline]
    pub fn emitters_pdf(&self, x: Point3, normal: Option<Vec3>, direction: Vec3) -> f64 {
        if self.weighs_emitters() {
            self.pdf_weighed(x, direction)
        } else if let Some(tree) = &self.emitter_tree {
            tree.pdf(
                x,
                normal,
                direction,
                &self.emitters,
                self.emitter_index.as_ref(),
                None,
            )
        } else {
            self.uniformly(x).map_or(0.0, |h| h.pdf(direction))
        }
    }

    /// [`Lights::sample_emitters`] with the probabilities (out of line: the one-emitter path stays
    /// small).
    #[inline(never)]
    fn sample_weighed(&self, x: Point3, u: DVec2) -> Option<DirectionSample> {
        let mut pmf = [0.0; MAX_WEIGHED_EMITTERS];
        self.towards_emitters(x, &mut pmf)?.sample(u)
    }

    /// [`Lights::emitters_pdf`] with the probabilities (out of line, likewise).
    #[inline(never)]
    fn pdf_weighed(&self, x: Point3, direction: Vec3) -> f64 {
        let mut pmf = [0.0; MAX_WEIGHED_EMITTERS];
        self.towards_emitters(x, &mut pmf)
            .map_or(0.0, |h| h.pdf(direction))
    }

    /// One line for `--explain`: what next-event estimation samples, and how it chooses the emitter.
    pub fn describe_emitters(&self) -> String {
        let n = self.emitters.len();
        let choice = if n < 2 {
            String::new()
        } else if self.weighs_emitters() {
            format!(
                ", each chosen per shading point in proportion to its radiance x the solid angle it \
                 subtends there ({:.0}% spread uniformly)",
                100.0 * UNIFORM_SHARE
            )
        } else {
            let choice = if self.emitter_tree.is_some() {
                format!(
                    ", chosen per shading point through a light tree by their power and distance \
                     (more than {MAX_WEIGHED_EMITTERS} emitters; {:.0}% spread uniformly)",
                    100.0 * UNIFORM_SHARE
                )
            } else {
                format!(", chosen uniformly (more than {MAX_WEIGHED_EMITTERS} emitters)")
            };
            if self.emitter_index.is_some() {
                format!(
                    "{choice}; a direction's density adds only the emitters a hierarchy over them \
                     says it may meet"
                )
            } else {
                choice
            }
        };
        match n {
            0 => "none (no emitter in the scene)".into(),
            n => format!(
                "{n} emitter{} ({} of them in the list of targets){choice}",
                if n == 1 { "" } else { "s" },
                self.listed_emitters,
            ),
        }
    }
}

/// A shape's geometry as a key: a listed target is the emitter of the same key (a quad's `q`, `u`
/// and `v`, a sphere's centre and radius, equal as numbers: -0 is 0). Looked up in a set, not
/// compared with every listed target (100,000 listed emitters were 5 * 10^9 comparisons).
type ShapeKey = (bool, [u64; 9]);

fn shape_key(sphere: bool, parts: [Vec3; 3]) -> ShapeKey {
    let mut key = [0u64; 9];
    for (k, x) in key.iter_mut().zip(parts.iter().flat_map(|v| v.to_array())) {
        *k = (x + 0.0).to_bits();
    }
    (sphere, key)
}

/// The key of a listed target.
fn target_key(t: &SceneShape) -> ShapeKey {
    match t {
        SceneShape::Quad(q) => shape_key(false, [q.q, q.u, q.v]),
        SceneShape::Sphere(s) => {
            shape_key(true, [s.center, Vec3::splat(s.radius.abs()), Vec3::ZERO])
        }
    }
}

/// The key of an emitter.
fn emitter_key(shape: &LightTarget) -> ShapeKey {
    match shape {
        LightTarget::Quad { quad, .. } => shape_key(false, [quad.q(), quad.u(), quad.v()]),
        LightTarget::Sphere(sp) => {
            shape_key(true, [sp.center(), Vec3::splat(sp.radius()), Vec3::ZERO])
        }
    }
}

/// An emitter placed in the scene: its target, two-sidedness and radiance (see [`EmitterWeight`]),
/// and its shape in world space with its material.
struct Found {
    target: LightTarget,
    two_sided: bool,
    radiance: f64,
    placed: FoundShape,
    material: MaterialId,
}

/// The emitting spheres and quads of group `g` placed by `to_world`; media boundaries are shapes of
/// no material and are skipped. Groups nested deeper than [`MAX_NESTING`] (the most a scene file may
/// nest them, and a guard against a cycle, which the scene builder refuses anyway) are not entered,
/// and the walk stops once it has visited as many objects as `budget` allows (instances are walked
/// once for every place they end up in, which a small scene of instances of instances could make
/// 2^40 places; a scene file holds at most the budget).
fn collect_emitters(
    scene: &Scene,
    g: GroupId,
    to_world: Transform,
    depth: u32,
    budget: &mut WalkBudget,
    out: &mut Vec<Found>,
) {
    let Some(group) = scene.groups.get(g.0 as usize) else {
        return;
    };
    if depth > MAX_NESTING {
        return;
    }
    let two_sided = |material: MaterialId| match scene.materials.get(material.index()) {
        Some(Material::DiffuseLight { two_sided, emit }) => {
            let radiance = match emit {
                Albedo::Constant(c) => c.element_sum() / 3.0,
                Albedo::Texture(_) => 1.0,
            };
            let radiance = if radiance.is_finite() && radiance > 0.0 {
                radiance
            } else {
                0.0
            };
            Some((*two_sided, radiance))
        }
        _ => None,
    };
    for o in &group.objects {
        if !budget.visit() {
            return;
        }
        match o {
            Object::Sphere(s) => {
                if let Some((ts, radiance)) = two_sided(s.material) {
                    let centre = to_world.point(s.center);
                    out.push(Found {
                        target: LightTarget::Sphere(SphereTarget::new(centre, s.radius)),
                        two_sided: ts,
                        radiance,
                        placed: FoundShape::Sphere {
                            centre,
                            radius: s.radius,
                            moving: s.is_moving(),
                        },
                        material: s.material,
                    });
                }
            }
            Object::Quad(q) => {
                if let Some((ts, radiance)) = two_sided(q.material) {
                    let (q0, u, v) = (
                        to_world.point(q.q),
                        to_world.vector(q.u),
                        to_world.vector(q.v),
                    );
                    out.push(Found {
                        target: LightTarget::Quad {
                            quad: QuadTarget::new(q0, u, v),
                            one_sided: false,
                        },
                        two_sided: ts,
                        radiance,
                        placed: FoundShape::Quad { q: q0, u, v },
                        material: q.material,
                    });
                }
            }
            Object::Instance { transform, group } => collect_emitters(
                scene,
                *group,
                transform.then(to_world),
                depth + 1,
                budget,
                out,
            ),
            Object::Group(inner) => {
                collect_emitters(scene, *inner, to_world, depth + 1, budget, out)
            }
            Object::Medium(_) => {}
        }
    }
}
