//! The integrator: the radiance carried back along one camera path. Book 2's recursive `ray_color`
//! (emission plus attenuation times the radiance of the scattered ray) written as a loop that carries
//! the path's throughput.
//!
//! How a diffuse bounce picks its direction is the [`Strategy`]: book 3's uniform, cosine, light and
//! mixture sampling (one direction per bounce, weighted by `s(omega) / p(omega)`), and `mis`, next-event
//! estimation combined with material sampling by multiple importance sampling.

use crate::hit::Hit;
use crate::lights::{LightTarget, Lights};
use crate::material::{Material, Scatter, ScatterPdf};
use crate::ray::{Interval, Ray};
use crate::sampler::{Ctx, Dimension, MediumMode};
use crate::scene::{GroupId, Scene};
use crate::vec::{Color, Point3, Vec3};
use rtl_pdf::{DirectionSample, HemispherePdf, HittablePdf, MixturePdf, Pdf, power_heuristic};

// ANCHOR: mis_options
/// The extras of the `mis` strategy, each unbiased and each switchable off to measure its share.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub struct MisOptions {
    /// End paths that carry little at random after a few bounces and reweight the survivors (Russian
    /// roulette; see [`ROULETTE_BELOW`]).
    pub russian_roulette: bool,
    /// Sample rectangular lights uniformly in solid angle (spherical rectangles) instead of by area.
    pub spherical_rectangles: bool,
    /// Take every dimension after the pixel position (lens, time, light, material, roulette) from
    /// low-discrepancy (padded Owen-scrambled Sobol) points instead of independent random numbers.
    pub low_discrepancy: bool,
}

impl MisOptions {
    /// What `mis` uses by default: the extras that pay on the Cornell box (see `rtl study render`).
    /// Spherical rectangles cost more per sample (four `acos` per evaluation) than they save in
    /// variance for a light as small as the box's, so they are off.
    pub const DEFAULT: MisOptions = MisOptions {
        russian_roulette: true,
        spherical_rectangles: false,
        low_discrepancy: true,
    };
}

impl Default for MisOptions {
    fn default() -> Self {
        MisOptions::DEFAULT
    }
}
// ANCHOR_END: mis_options

/// The bounce from which Russian roulette may end a path (0 = the camera ray's hit).
pub const ROULETTE_AFTER: u32 = 2;
/// Russian roulette gambles only with paths whose throughput (largest channel) is below this: a path
/// survives with probability `min(1, throughput / ROULETTE_BELOW)`. pbrt's choice is 1; on the Cornell
/// box 1/8 gives the same RMSE as no roulette at less than half the rays (`rtl study render`), while 1
/// adds 70% to the variance: the walls reflect 73%, so light a few bounces deep still matters.
pub const ROULETTE_BELOW: f64 = 0.125;

// ANCHOR: strategy
/// How a diffuse bounce chooses its scattered direction.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub enum Strategy {
    /// Uniform over the hemisphere about the normal (`p = 1 / 2 pi`): book 3's starting point.
    Uniform,
    /// The material's own density (cosine for Lambertian, uniform sphere for isotropic): what book 2's
    /// `lambertian::scatter` does.
    Cosine,
    /// Towards the importance targets only (chapter 9's experiment). Biased: directions that meet no
    /// target are never sampled, so light arriving from anywhere else is missed.
    Light,
    /// The book's final method: a mixture of the targets' density and the material's, 50/50 in the
    /// book; the share of the targets is the render settings' `mixture_weight`.
    Mixture,
    /// Next-event estimation to every emitter of the scene, listed or not (through media with their
    /// transmittance), combined with material sampling (mixed with the non-emitting targets) by the
    /// power heuristic, plus the extras of [`MisOptions`].
    Mis(MisOptions),
}
// ANCHOR_END: strategy

impl Default for Strategy {
    fn default() -> Self {
        Strategy::Mis(MisOptions::default())
    }
}

impl Strategy {
    /// Every strategy, for listing (`mis` with its default extras).
    pub const ALL: &'static [Strategy] = &[
        Strategy::Uniform,
        Strategy::Cosine,
        Strategy::Light,
        Strategy::Mixture,
        Strategy::Mis(MisOptions::DEFAULT),
    ];

    pub fn name(&self) -> &'static str {
        match self {
            Strategy::Uniform => "uniform",
            Strategy::Cosine => "cosine",
            Strategy::Light => "light",
            Strategy::Mixture => "mixture",
            Strategy::Mis(_) => "mis",
        }
    }

    pub fn description(&self) -> String {
        match self {
            Strategy::Uniform => {
                "uniform directions over the hemisphere, weighted by s/p = 2 cos".into()
            }
            Strategy::Cosine => {
                "the material's own density (cosine-weighted): book 2's method".into()
            }
            Strategy::Light => "towards the importance targets only (book 3, ch. 9): BIASED, it \
                never samples directions that miss the targets, so indirect light is lost"
                .into(),
            Strategy::Mixture => {
                "mixture of the targets' density and the material's (50/50 unless weighted), \
                weighted s/p: the book's final method"
                    .into()
            }
            Strategy::Mis(o) => {
                let on_off = |b: bool| if b { "on" } else { "off" };
                format!(
                    "next-event estimation to every emitter (through media with their \
                     transmittance) + material sampling mixed with the other targets, power \
                     heuristic; Russian roulette {}, spherical rectangles {}, low-discrepancy \
                     samples {}",
                    on_off(o.russian_roulette),
                    on_off(o.spherical_rectangles),
                    on_off(o.low_discrepancy)
                )
            }
        }
    }

    /// The `mis` options, if this is `mis`.
    pub fn mis_options(&self) -> Option<MisOptions> {
        match self {
            Strategy::Mis(o) => Some(*o),
            _ => None,
        }
    }
}

impl std::str::FromStr for Strategy {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Strategy::ALL
            .iter()
            .copied()
            .find(|st| st.name() == s)
            .ok_or_else(|| {
                let names: Vec<&str> = Strategy::ALL.iter().map(|s| s.name()).collect();
                format!("unknown strategy '{s}' (available: {})", names.join(", "))
            })
    }
}

/// `s / p` if it is a usable weight: `p > 0` and the quotient finite (a pdf value of 0 never divides).
#[inline]
fn ratio(s: f64, p: f64) -> Option<f64> {
    let r = s / p;
    (p > 0.0 && s > 0.0 && r.is_finite()).then_some(r)
}

// ANCHOR: sample_diffuse
/// A scattered direction (unit) for the book's one-sample strategies and the factor
/// `s(omega) / p(omega)` the throughput is multiplied by (besides the attenuation), or `None` if the
/// sample contributes nothing further (`p = 0`, `s = 0` or a non-finite quotient). `u` is the bounce's
/// material pair ([`Dimension::Material`]); a mixture picks its part with `u.x` and hands the rest on.
#[inline]
fn sample_diffuse(
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
        (Strategy::Light, _) => match HittablePdf::new(p, &lights.all) {
            // With no targets there is nothing to aim at: sample the material.
            None => Some((pdf.sample(u)?.direction, 1.0)),
            Some(towards) => weighted(towards.sample(u)?),
        },
        // (`mis` has its own integrator; were it asked here, it would get the mixture.)
        // `mixture_weight` was checked to be in (0, 1) when the renderer was built.
        (Strategy::Mixture, _) | (Strategy::Mis(_), _) => match HittablePdf::new(p, &lights.all) {
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

/// The radiance arriving along `ray`, estimated by one path of at most `max_depth` intersections;
/// `mixture_weight` (in `(0, 1)`) is `mixture`'s share of directions towards the targets.
#[inline]
pub fn radiance(
    scene: &Scene,
    lights: &Lights,
    ray: Ray,
    max_depth: u32,
    strategy: Strategy,
    mixture_weight: f64,
    ctx: &mut Ctx,
) -> Color {
    match strategy {
        Strategy::Mis(options) => radiance_mis(scene, lights, ray, max_depth, options, ctx),
        _ => radiance_one_sample(scene, lights, ray, max_depth, strategy, mixture_weight, ctx),
    }
}

// ANCHOR: radiance
/// The book's estimator: at each diffuse bounce one direction from the strategy's density `p`,
/// weighted by `attenuation * s / p`; emission is added wherever the path meets it.
fn radiance_one_sample(
    scene: &Scene,
    lights: &Lights,
    ray: Ray,
    max_depth: u32,
    strategy: Strategy,
    mixture_weight: f64,
    ctx: &mut Ctx,
) -> Color {
    let mut ray = ray;
    let mut throughput = Color::ONE;
    let mut l = Color::ZERO;
    for depth in 0..max_depth {
        ctx.stats.rays += 1;
        ctx.bounce = depth;
        let Some(hit) = scene.hit(&ray, ctx) else {
            l += throughput * scene.background.value(&ray);
            break;
        };
        let material = &scene.materials[hit.material.index()];
        if material.is_emitter() {
            l += throughput * material.emitted(&hit, &scene.textures, ctx);
        }
        match material.scatter(&ray, &hit, &scene.textures, ctx) {
            None => break,
            Some(Scatter::Specular {
                attenuation,
                direction,
            }) => {
                throughput *= attenuation;
                ray = hit.spawn(direction, ray.time);
            }
            Some(Scatter::Diffuse { attenuation, pdf }) => {
                let u = ctx.sample_2d(Dimension::Material(depth));
                let Some((direction, weight)) =
                    sample_diffuse(strategy, mixture_weight, &pdf, hit.p, hit.normal, lights, u)
                else {
                    break; // p = 0 or s = 0: the sample keeps the emission it has
                };
                throughput *= attenuation * weight;
                ray = hit.spawn(direction, ray.time);
            }
        }
        if throughput == Color::ZERO {
            break;
        }
    }
    l
}
// ANCHOR_END: radiance

/// The density with which next-event estimation from `origin` picks `direction` (0 without emitters).
#[inline]
fn light_pdf(origin: Point3, emitters: &[LightTarget], direction: Vec3) -> f64 {
    HittablePdf::new(origin, emitters).map_or(0.0, |h| h.pdf(direction))
}

// ANCHOR: shadow_ray
/// What a shadow ray meets: the first surface along `ray`, and the transmittance of the media before
/// it, `exp(-sum_i sigma_i l_i)` for constant media of density `sigma_i` crossed over length `l_i`.
///
/// The transmittance is computed exactly, not estimated: a constant medium's is known in closed form,
/// so a shadow ray needs no random number and adds no variance (a delta-tracking or track-length
/// estimate would be 0 or 1 at random, with variance `T (1 - T)`; ratio tracking is for media whose
/// density varies). One traversal: media let the ray through and record where it was inside them
/// (the BVH never skips a medium that starts before the closest surface), and the stretches are
/// clipped at the surface found. Only if more media were crossed than can be recorded without
/// allocating is the traversal repeated up to the surface.
#[inline]
fn trace_shadow(scene: &Scene, ray: &Ray, ctx: &mut Ctx) -> Option<(Hit, f64)> {
    ctx.stats.rays += 1;
    if scene.features.media == 0 {
        return scene.hit(ray, ctx).map(|h| (h, 1.0));
    }
    ctx.media = MediumMode::Record;
    ctx.crossed.clear();
    let hit = scene.hit(ray, ctx);
    let depth = match &hit {
        Some(h) if ctx.crossed.overflow => {
            ctx.crossed.clear();
            // every medium before the surface, and nothing else, up to the surface
            let _ = scene.hit_group(GroupId(0), ray, Interval::new(0.0, h.t), ctx);
            ctx.crossed.optical_depth(h.t)
        }
        Some(h) => ctx.crossed.optical_depth(h.t),
        None => 0.0,
    };
    ctx.media = MediumMode::Scatter;
    hit.map(|h| (h, (-depth).exp()))
}
// ANCHOR_END: shadow_ray

// ANCHOR: radiance_mis
/// Next-event estimation with multiple importance sampling (Veach 1997, ch. 9; pbrt-v4's path
/// integrator). At every diffuse vertex two directions are drawn:
/// - towards the emitters (`p_l`), every emitter of the scene, listed or not: a shadow ray, whose
///   emission, times the transmittance of the media it crosses, counts with weight
///   `w_l = p_l^2 / (p_l^2 + p_m^2)`;
/// - from the material's density mixed 50/50 with the non-emitting targets (`p_m`): the path goes on
///   that way, and emission it meets at the next vertex counts with `w_m = p_m^2 / (p_l^2 + p_m^2)`.
///
/// The two weights of every direction sum to 1, so light reaching a vertex directly is counted once in
/// expectation, by whichever strategy sees it better (through a medium too: the path's own rays meet
/// the emitter with the transmittance's probability, the shadow ray carries it as a factor). After a
/// specular (delta) bounce only the material could have found the emitter: full weight.
///
/// Inside a dielectric (the path refracted into one and not yet out) no light sample is taken: a
/// shadow ray from there can only meet the dielectric's boundary, a specular surface, so it would
/// cost a traversal and add nothing (book 2's blue subsurface sphere: glass filled with a dense
/// medium, where most of the path's vertices are). Emission found from such a vertex has weight 1,
/// which keeps the estimator unbiased even for an emitter inside the glass or an open dielectric.
///
/// Numbers per bounce `b`: the light choice and direction from [`Dimension::Light`]`(b)`, the
/// material's from [`Dimension::Material`]`(b)`, roulette from [`Dimension::Roulette`]`(b)`.
fn radiance_mis(
    scene: &Scene,
    lights: &Lights,
    ray: Ray,
    max_depth: u32,
    options: MisOptions,
    ctx: &mut Ctx,
) -> Color {
    radiance_mis_variant(
        scene,
        lights,
        ray,
        max_depth,
        options,
        MisVariant::Book,
        ctx,
    )
}

/// Variants of [`radiance_mis`] for the unbiasedness tests: the estimator itself, and deliberately
/// wrong ones that a test must catch.
#[doc(hidden)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MisVariant {
    /// The estimator `mis` renders with.
    Book,
    /// Wrong: skips next-event estimation inside dielectrics but still weights the emission the path
    /// meets from there by `w_m`, as if the light strategy had been used.
    WrongWeightInsideDielectrics,
}

/// [`radiance_mis`] with a [`MisVariant`] (for tests).
#[doc(hidden)]
pub fn radiance_mis_variant(
    scene: &Scene,
    lights: &Lights,
    ray: Ray,
    max_depth: u32,
    options: MisOptions,
    variant: MisVariant,
    ctx: &mut Ctx,
) -> Color {
    let mut ray = ray;
    // How many dielectric boundaries the path has passed into and not yet out of (see
    // `radiance_mis`'s notes on next-event estimation inside dielectrics).
    let mut inside_dielectrics: u32 = 0;
    let mut throughput = Color::ONE;
    let mut l = Color::ZERO;
    // The previous diffuse vertex and its material-sampling density of `ray.direction`; `None` after
    // the camera or a specular bounce.
    let mut previous: Option<(Point3, f64)> = None;
    for depth in 0..max_depth {
        ctx.stats.rays += 1;
        ctx.bounce = depth;
        let Some(hit) = scene.hit(&ray, ctx) else {
            l += throughput * scene.background.value(&ray);
            break;
        };
        let material = &scene.materials[hit.material.index()];
        if material.is_emitter() {
            let emitted = material.emitted(&hit, &scene.textures, ctx);
            if emitted != Color::ZERO {
                let weight = match previous {
                    None => 1.0,
                    Some((origin, p_material)) => {
                        let p_light = light_pdf(origin, &lights.emitters, ray.direction);
                        power_heuristic(1.0, p_material, 1.0, p_light)
                    }
                };
                l += throughput * weight * emitted;
            }
        }
        let (attenuation, pdf) = match material.scatter(&ray, &hit, &scene.textures, ctx) {
            None => break,
            Some(Scatter::Specular {
                attenuation,
                direction,
            }) => {
                // Refracted (not reflected) through a dielectric: into it from its front, out of it
                // from its back.
                if matches!(material, Material::Dielectric { .. })
                    && direction.dot(hit.normal) < 0.0
                {
                    inside_dielectrics = if hit.front_face {
                        inside_dielectrics + 1
                    } else {
                        inside_dielectrics.saturating_sub(1)
                    };
                }
                throughput *= attenuation;
                ray = hit.spawn(direction, ray.time);
                previous = None;
                continue;
            }
            Some(Scatter::Diffuse { attenuation, pdf }) => (attenuation, pdf),
        };
        // Inside a dielectric every shadow ray meets its boundary first (a specular surface, which
        // next-event estimation cannot pass): no light sample is taken there, and emission the path
        // meets from this vertex then has weight 1 (the material strategy alone).
        let light_strategy = inside_dielectrics == 0;
        let towards_others = HittablePdf::new(hit.p, &lights.others);

        // Next-event estimation: only if the shadow ray's hit is within the path's depth.
        if depth + 1 < max_depth
            && light_strategy
            && let Some(towards_lights) = HittablePdf::new(hit.p, &lights.emitters)
            && let Some(ls) = towards_lights.sample(ctx.sample_2d(Dimension::Light(depth)))
            && let Some(s_over_p) = ratio(pdf.pdf(ls.direction), ls.pdf)
            && let Some((lh, transmittance)) =
                trace_shadow(scene, &hit.spawn(ls.direction, ray.time), ctx)
        {
            let m: &Material = &scene.materials[lh.material.index()];
            if m.is_emitter() && transmittance > 0.0 {
                let emitted = m.emitted(&lh, &scene.textures, ctx);
                let p_material = match &towards_others {
                    Some(t) => MixturePdf::new(*t, pdf).pdf(ls.direction),
                    None => pdf.pdf(ls.direction),
                };
                let w = power_heuristic(1.0, ls.pdf, 1.0, p_material);
                l += throughput * attenuation * emitted * (w * s_over_p * transmittance);
            }
        }

        // Material sampling (mixed with the non-emitting targets): the path goes on this way.
        let u = ctx.sample_2d(Dimension::Material(depth));
        let sampled = match &towards_others {
            Some(t) => MixturePdf::new(*t, pdf).sample(u),
            None => pdf.sample(u),
        };
        let Some(ms) = sampled else {
            break;
        };
        let Some(s_over_p) = ratio(pdf.pdf(ms.direction), ms.pdf) else {
            break;
        };
        throughput *= attenuation * s_over_p;
        previous = (light_strategy || variant == MisVariant::WrongWeightInsideDielectrics)
            .then_some((hit.p, ms.pdf));
        ray = hit.spawn(ms.direction, ray.time);

        // Russian roulette: survive with probability q = min(1, max throughput / ROULETTE_BELOW),
        // reweight by 1 / q.
        if options.russian_roulette && depth >= ROULETTE_AFTER {
            let q = (throughput.max_element() / ROULETTE_BELOW).min(1.0);
            if q < 1.0 {
                if q <= 0.0 || ctx.sample_1d(Dimension::Roulette(depth)) >= q {
                    break;
                }
                throughput /= q;
            }
        }
        if throughput == Color::ZERO {
            break;
        }
    }
    l
}
// ANCHOR_END: radiance_mis
