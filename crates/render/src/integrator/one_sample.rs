//! The book's one-sample estimator: at each diffuse bounce one direction from the strategy's density
//! `p` (uniform, cosine, towards the targets, or their mixture), the throughput multiplied by
//! `attenuation * s(omega) / p(omega)`, emission added wherever the path meets it (book 3, chapters
//! 6-10).

use super::{Strategy, ratio};
use crate::hit::Hit;
use crate::lights::Lights;
use crate::material::{Material, Scatter, ScatterPdf};
use crate::ray::Ray;
use crate::sampler::{Ctx, Dimension};
use crate::scene::Scene;
use crate::vec::{Color, Point3, Vec3};
use rtl_pdf::{DirectionSample, HemispherePdf, MixturePdf, Pdf};

// ANCHOR: sample_diffuse
/// A scattered direction (unit) for the book's one-sample strategies and the factor
/// `s(omega) / p(omega)` the throughput is multiplied by (besides the attenuation), or `None` if the
/// sample contributes nothing further (`p = 0`, `s = 0` or a non-finite quotient). `u` is the bounce's
/// material pair ([`Dimension::Material`]); a mixture picks its part with `u.x` and hands the rest on.
#[inline]
pub fn sample_diffuse(
    strategy: Strategy,
    mixture_weight: f64,
    pdf: &ScatterPdf,
    p: Point3,
    normal: Vec3,
    lights: &Lights,
    u: glam::DVec2,
) -> Option<(Vec3, f64)> {
    // `p` of the sample is its own density, made with the direction: nothing is evaluated twice.
    let weighted = |s: DirectionSample| Some((s.direction, ratio(pdf.pdf(s.direction), s.pdf)?));
    match (strategy, pdf) {
        // Sampling s itself: s / p = 1 exactly.
        (Strategy::Cosine, _) | (Strategy::Uniform, ScatterPdf::Sphere(_)) => {
            Some((pdf.direction(u), 1.0))
        }
        (Strategy::Uniform, ScatterPdf::Cosine(_)) => {
            weighted(HemispherePdf::new(normal).sample(u)?)
        }
        (Strategy::Light, _) => match lights.towards_all(p) {
            // With no targets there is nothing to aim at: sample the material.
            None => Some((pdf.sample(u)?.direction, 1.0)),
            Some(towards) => weighted(towards.sample(u)?),
        },
        // (`mis` has its own integrator; were it asked here, it would get the mixture.)
        // `mixture_weight` was checked to be in (0, 1) when the renderer was built.
        (Strategy::Mixture, _) | (Strategy::Mis(_), _) => match lights.towards_all(p) {
            None => Some((pdf.sample(u)?.direction, 1.0)),
            Some(towards) => weighted(
                MixturePdf::with_weight(towards, *pdf, mixture_weight)
                    .ok()?
                    .sample(u)?,
            ),
        },
    }
}
// ANCHOR_END: sample_diffuse

// ANCHOR: radiance
/// The book's estimator: at each diffuse bounce one direction from the strategy's density `p`,
/// weighted by `attenuation * s / p`; emission is added wherever the path meets it.
pub(super) fn radiance_one_sample(
    scene: &Scene,
    lights: &Lights,
    ray: Ray,
    max_depth: u32,
    strategy: Strategy,
    mixture_weight: f64,
    ctx: &mut Ctx,
) -> Color {
    let mut ray = ray;
    let mut path = OneSamplePath::default();
    while path.depth < max_depth {
        ctx.stats.rays += 1;
        ctx.bounce = path.depth;
        // Borrowed where `scene.hit` left it: moving the record out copied its 112 bytes each vertex.
        let found = scene.hit(&ray, ctx);
        match path.vertex(
            scene,
            lights,
            &ray,
            found.as_ref(),
            strategy,
            mixture_weight,
            ctx,
        ) {
            Some(next) => ray = next,
            None => break,
        }
    }
    path.l
}

/// One path of the book's estimator in flight: the throughput it carries (the product of
/// `attenuation * s / p` so far), the emission it has gathered and how many times it has met the
/// scene. A path is advanced one vertex at a time, so that several can be traced side by side
/// ([`crate::paths8`]).
#[derive(Clone, Copy, Debug)]
pub struct OneSamplePath {
    pub throughput: Color,
    /// The radiance gathered so far.
    pub l: Color,
    /// Intersections so far.
    pub depth: u32,
}

impl Default for OneSamplePath {
    /// A path at the camera: nothing gathered, the throughput 1.
    fn default() -> Self {
        OneSamplePath {
            throughput: Color::ONE,
            l: Color::ZERO,
            depth: 0,
        }
    }
}

impl OneSamplePath {
    /// The vertex where `ray` meets `found` (nothing: the background): its emission, then the
    /// scattered ray, or `None` if the path ends here.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub fn vertex(
        &mut self,
        scene: &Scene,
        lights: &Lights,
        ray: &Ray,
        found: Option<&Hit>,
        strategy: Strategy,
        mixture_weight: f64,
        ctx: &mut Ctx,
    ) -> Option<Ray> {
        match self.scatter(scene, ray, found, ctx)? {
            Bounce::Along(next) => Some(next),
            Bounce::Diffuse {
                attenuation,
                pdf,
                u,
            } => {
                let hit = found?;
                // p = 0 or s = 0: the sample keeps the emission it has
                let (direction, weight) =
                    sample_diffuse(strategy, mixture_weight, &pdf, hit.p, hit.normal, lights, u)?;
                self.diffuse(hit, ray, attenuation, direction, weight)
            }
        }
    }

    /// The first half of [`OneSamplePath::vertex`], up to where the strategy picks a diffuse
    /// direction: the emission met, then the material's answer (`None`: the path ends).
    #[inline(always)]
    pub fn scatter(
        &mut self,
        scene: &Scene,
        ray: &Ray,
        found: Option<&Hit>,
        ctx: &mut Ctx,
    ) -> Option<Bounce> {
        let depth = self.depth;
        self.depth += 1;
        let Some(hit) = found else {
            self.l += self.throughput * scene.background.value(ray);
            return None;
        };
        let material = &scene.materials[hit.material.index()];
        if material.is_emitter() {
            self.l += self.throughput * material.emitted(hit, &scene.textures, ctx);
        }
        if let Material::Lambertian { albedo } = material {
            // `Material::scatter`'s Lambertian answer, without its `Scatter`: through it the albedo
            // was copied to the stack and read back across the copy's stores, a stall the store
            // cannot forward (3% of `mixture` traced eight paths at a time).
            let (attenuation, pdf) = Material::lambertian_at(albedo, hit, &scene.textures, ctx);
            return Some(Bounce::Diffuse {
                attenuation,
                pdf,
                u: ctx.sample_2d(Dimension::Material(depth)),
            });
        }
        // (matched in place, like the hit)
        match &material.scatter(ray, hit, &scene.textures, ctx) {
            None => None,
            Some(Scatter::Specular {
                attenuation,
                direction,
            }) => {
                self.throughput *= *attenuation;
                (self.throughput != Color::ZERO)
                    .then(|| Bounce::Along(hit.spawn(*direction, ray.time)))
            }
            Some(Scatter::Diffuse { attenuation, pdf }) => Some(Bounce::Diffuse {
                attenuation: *attenuation,
                pdf: *pdf,
                u: ctx.sample_2d(Dimension::Material(depth)),
            }),
        }
    }

    /// The second half of a diffuse vertex: the throughput takes `attenuation * weight` (the
    /// strategy's `s / p` for `direction`), and the path goes on from `hit` along `direction`.
    #[inline(always)]
    pub fn diffuse(
        &mut self,
        hit: &Hit,
        ray: &Ray,
        attenuation: Color,
        direction: Vec3,
        weight: f64,
    ) -> Option<Ray> {
        self.throughput *= attenuation * weight;
        (self.throughput != Color::ZERO).then(|| hit.spawn(direction, ray.time))
    }
}

/// What a path does at a surface before its strategy picks a direction ([`OneSamplePath::scatter`]).
#[derive(Clone, Copy, Debug)]
pub enum Bounce {
    /// A specular bounce: the path goes on along this ray.
    Along(Ray),
    /// A diffuse bounce: a direction is to be drawn for the material's density `pdf` with the
    /// bounce's numbers `u`, and weighted by `attenuation * s / p`.
    Diffuse {
        attenuation: Color,
        pdf: ScatterPdf,
        u: glam::DVec2,
    },
}
// ANCHOR_END: radiance
