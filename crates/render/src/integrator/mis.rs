//! `mis`: next-event estimation combined with material sampling by the power heuristic (Veach 1997,
//! ch. 9), a path advanced one vertex at a time ([`MisPath`]) so that the lanes can trace several side
//! by side; the deliberately wrong variants the unbiasedness tests must catch ([`MisVariant`]).

use super::media::{
    CAMERA_SEGMENT_SAMPLE_RATE, FORCED_SCATTER_BOUNCES, SEGMENT_SAMPLE_RATE, trace_shadow,
    trace_through_media,
};
use super::{MisOptions, ratio};
use crate::connection::{self, Through};
use crate::hit::Hit;
use crate::lights::{LightTarget, Lights};
use crate::material::{Material, Scatter, ScatterPdf};
use crate::metal_pdf::FuzzyMetalPdf;
use crate::ray::Ray;
use crate::sampler::{Ctx, Dimension};
use crate::scene::Scene;
use crate::vec::{Color, Point3, Vec3};
use rtl_pdf::{DirectionSample, HittablePdf, MixturePdf, Pdf, power_heuristic};

/// The bounce from which Russian roulette may end a path (0 = the camera ray's hit).
pub const ROULETTE_AFTER: u32 = 2;
/// Russian roulette gambles only with paths whose throughput (largest channel) is below this: a path
/// survives with probability `min(1, throughput / ROULETTE_BELOW)`. pbrt's choice is 1; on the Cornell
/// box 1/8 gives the RMSE of no roulette at 63% of its rays (`rtl study render`), while 1 more than
/// doubles the variance of a sample (noise constant 0.139 -> 0.206) for 25% fewer rays: the walls
/// reflect 73%, so light a few bounces deep still matters.
pub const ROULETTE_BELOW: f64 = 0.125;
/// [`ROULETTE_BELOW`] for a path that has just scattered in a medium: pbrt's 1. Paths in a dense
/// medium are long (book 2's blue subsurface sphere: density 0.2 in a ball of radius 70, albedo up to
/// 0.9) and each of their vertices adds little; on book2-final 1 instead of 1/8 costs 1.6% in the
/// noise constant for 17% more samples per second (400 x 400, 16 spp).
pub const ROULETTE_BELOW_IN_MEDIA: f64 = 1.0;

/// The share of `mis`'s material sampling drawn towards the targets that do not emit
/// ([`Lights::others`], the Cornell box's glass sphere): directions come from the mixture
/// `OTHERS_SHARE p_others + (1 - OTHERS_SHARE) p_material`. They are there for the caustic the sphere
/// focuses, light reached through glass, which no shadow ray follows; the rest of the indirect light
/// is sampled better by the material's own density. The book's mixture gives the targets half; on
/// the Cornell box (600 x 600, 16 spp x 2 seeds, `rtl bench compare`) that left the noise constant at
/// c = 0.2075, where 0.2, 0.15 and 0.1 give 0.157, 0.153 and 0.151 for 1.2-1.25x the time per sample:
/// 1.5x sooner to a given noise, and flat over 0.1-0.2 (render-speed.md, "Issue 16, seventh round").
pub const OTHERS_SHARE: f64 = 0.15;
const _: () = assert!(0.0 <= OTHERS_SHARE && OTHERS_SHARE <= 1.0);

/// `mis`'s material sampling from `hit`: the material's density mixed with the non-emitting
/// targets by [`OTHERS_SHARE`].
#[inline]
pub(crate) fn with_others<'a>(
    towards_others: HittablePdf<'a, LightTarget>,
    pdf: VertexPdf,
) -> MixturePdf<HittablePdf<'a, LightTarget>, VertexPdf> {
    MixturePdf::with_weight(towards_others, pdf, OTHERS_SHARE).expect("OTHERS_SHARE is in [0, 1]")
}

/// The light sample of a vertex at `hit` whose material samples `pdf` (mixed with `towards_others`):
/// the shadow ray towards the emitters in a direction drawn with `u`, and the factor `w_l s / p_l`
/// (power heuristic weight, the material's density over the light's) its emission counts with,
/// times the transmittance of the media the ray crosses ([`MisPath::shadow_arrived`]).
#[inline]
pub(super) fn light_sample(
    lights: &Lights,
    hit: &Hit,
    time: f64,
    pdf: &VertexPdf,
    towards_others: Option<&HittablePdf<'_, LightTarget>>,
    u: glam::DVec2,
) -> Option<(Ray, f64)> {
    let ls = lights.sample_emitters(hit.p, shading_normal(hit, pdf), u)?;
    let s = pdf.pdf(ls.direction);
    let s_over_p = ratio(s, ls.pdf)?;
    // The material's density of the direction is `s`, made above: not evaluated again.
    let p_material = match towards_others {
        Some(t) => with_others(*t, *pdf).pdf_given_b(ls.direction, s),
        None => s,
    };
    let w = power_heuristic(1.0, ls.pdf, 1.0, p_material);
    Some((hit.spawn(ls.direction, time), w * s_over_p))
}

/// The normal the light tree bounds the cosine at a vertex by ([`Lights::sample_emitters`]): a
/// Lambertian vertex's (its density is the cosine about `hit.normal`, 0 below that horizon);
/// `None` for a medium's point and a fuzzy metal.
#[inline]
fn shading_normal(hit: &Hit, pdf: &VertexPdf) -> Option<Vec3> {
    match pdf {
        VertexPdf::Material(ScatterPdf::Cosine(_)) => Some(hit.normal),
        _ => None,
    }
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
    /// The estimator before segment sampling in media: the light sample of a medium is taken where
    /// the path scatters in it (correct, noisier; for comparison).
    LightSampleWhereScattered,
    /// Wrong: the segment's light sample without the transmittance from the segment's start.
    WrongSegmentTransmittance,
    /// Wrong in practice: segments of any optical depth take their light sample at an equiangular
    /// point (above [`SEGMENT_MAX_OPTICAL_DEPTH`] it almost never lands where the light is).
    SegmentsAtAnyDepth,
    /// The estimator before the fuzzy metal's density: the metal is a specular bounce, sampled only by
    /// its own directions (correct, noisier; for comparison).
    MetalAsSpecular,
    /// Wrong: the fuzzy metal's density taken to be a cosine lobe about the mirror direction (right
    /// only for fuzz 1).
    WrongMetalDensity,
    /// Wrong: Russian roulette in media without reweighting the survivors.
    WrongRouletteInMedia,
    /// The estimator before forced scattering: rays that would leave the scene through a medium
    /// scatter in it only as distance sampling says (correct, noisier; for comparison).
    NoForcedScattering,
    /// Wrong: forced scattering without the truncation's `1 - exp(-tau)` in the vertex's weight (as
    /// if the point had been drawn from the whole exponential).
    WrongForcedScatterWeight,
    /// Wrong: forced scattering without the background seen through the medium.
    WrongForcedBackground,
    /// Wrong: the emission that material sampling meets weighted by the uniform choice's light density,
    /// while the light sample chooses its emitter by the per-point probabilities (the two weights of a
    /// direction no longer sum to 1).
    WrongUniformLightWeight,
    /// Wrong: the emission that material sampling meets weighted by the light tree's density without
    /// the shading normal, while the light sample's choice bounded the cosine at the vertex by it.
    WrongTreeWeightWithoutNormal,
    /// Wrong: material sampling draws towards the non-emitting targets with [`OTHERS_SHARE`] but
    /// divides by the density of the book's even mixture.
    WrongOthersShare,
    /// Wrong: the emission that material sampling meets through a dielectric sphere keeps weight 1
    /// where the manifold connection covers it too (that light counted twice).
    WrongManifoldWeight,
    /// Wrong: the manifold connection's geometry term without its rotation about the axis
    /// (`rho_x / rho_y`), the term of a flat (two-dimensional) world.
    WrongManifoldGeometry,
}

/// The density a `mis` vertex samples its direction from and weighs light samples by: a diffuse
/// material's, or the fuzzy metal's lobe ([`FuzzyMetalPdf`]).
#[derive(Clone, Copy, Debug)]
pub(crate) enum VertexPdf {
    Material(ScatterPdf),
    Metal(FuzzyMetalPdf),
    /// [`MisVariant::WrongMetalDensity`]: the metal's directions with a cosine lobe's density.
    WrongMetal(FuzzyMetalPdf),
}

impl Pdf for VertexPdf {
    #[inline]
    fn pdf(&self, direction: Vec3) -> f64 {
        match self {
            VertexPdf::Material(p) => p.pdf(direction),
            VertexPdf::Metal(p) => p.pdf(direction),
            VertexPdf::WrongMetal(p) => wrong_metal_pdf(p, direction),
        }
    }
    #[inline]
    fn sample(&self, u: glam::DVec2) -> Option<DirectionSample> {
        match self {
            VertexPdf::Material(p) => p.sample(u),
            VertexPdf::Metal(p) => p.sample(u),
            VertexPdf::WrongMetal(p) => p.sample(u).map(|s| DirectionSample {
                pdf: wrong_metal_pdf(p, s.direction),
                ..s
            }),
        }
    }
}

fn wrong_metal_pdf(p: &FuzzyMetalPdf, direction: Vec3) -> f64 {
    if direction.dot(p.normal) > 0.0 {
        direction.dot(p.reflected).max(0.0) / std::f64::consts::PI
    } else {
        0.0
    }
}

// ANCHOR: mis_loop
/// Next-event estimation with multiple importance sampling (Veach 1997, ch. 9; pbrt-v4's path
/// integrator). At every diffuse vertex two directions are drawn:
/// - towards the emitters (`p_l`), every emitter of the scene, listed or not, each chosen with a
///   probability that depends on the vertex (its radiance times the solid angle it subtends there,
///   [`Lights::towards_emitters`]; above 16 emitters through a light tree by power and distance,
///   and at a Lambertian vertex the cosine there, [`Lights::sample_emitters`]): a shadow ray, whose
///   emission, times the transmittance of the media it crosses, counts with weight
///   `w_l = p_l^2 / (p_l^2 + p_m^2)`;
/// - from the material's density mixed with the non-emitting targets by [`OTHERS_SHARE`] (`p_m`):
///   the path goes on that way, and emission it meets at the next vertex counts with
///   `w_m = p_m^2 / (p_l^2 + p_m^2)`.
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
/// The books' fuzzy metal is no specular bounce here: its directions have a density in closed form
/// ([`FuzzyMetalPdf`]), so it takes light samples and its emission hits are weighted like a diffuse
/// vertex's (a metal of fuzz below [`MIN_FUZZ`](crate::metal_pdf::MIN_FUZZ), 0 included, stays a
/// mirror).
///
/// Numbers per bounce `b`: the light choice and direction from [`Dimension::Light`]`(b)`, the
/// material's from [`Dimension::Material`]`(b)`, roulette from [`Dimension::Roulette`]`(b)`.
pub(super) fn radiance_mis(
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
    let mut path = MisPath::default();
    for depth in 0..max_depth {
        ctx.stats.rays += 1;
        ctx.bounce = depth;
        let (found, vertex_sample) =
            if scene.features.media > 0 && variant != MisVariant::LightSampleWhereScattered {
                let sample_segment = path.takes_light_samples() && depth + 1 < max_depth;
                let rate = if depth == 0 {
                    CAMERA_SEGMENT_SAMPLE_RATE
                } else {
                    SEGMENT_SAMPLE_RATE
                };
                let force = depth < FORCED_SCATTER_BOUNCES
                    && depth + 1 < max_depth
                    && variant != MisVariant::NoForcedScattering;
                let segment = trace_through_media(
                    scene,
                    lights,
                    &ray,
                    sample_segment,
                    rate,
                    force,
                    variant,
                    ctx,
                );
                path.l += path.throughput * segment.in_scattered;
                if let Some((weight, through)) = segment.forced {
                    path.l += path.throughput * through * scene.background.value(&ray);
                    path.throughput *= weight;
                }
                (segment.vertex, segment.samples_lights)
            } else {
                (scene.hit(&ray, ctx), true)
            };
        let vertex = MisVertex {
            depth,
            max_depth,
            samples_lights: vertex_sample,
            options,
            variant,
        };
        let step = path.vertex(scene, lights, &ray, found.as_ref(), vertex, ctx);
        if let Some(shadow) = &step.shadow {
            let seen = trace_shadow(scene, shadow, ctx);
            path.shadow_arrived(scene, seen.as_ref().map(|(h, t)| (h, *t)), ctx);
        }
        match step.next {
            Some(next) => ray = next,
            None => break,
        }
    }
    path.l
}
// ANCHOR_END: mis_loop

/// Where a [`MisPath`] is: the bounce of its vertex, the path's depth limit, whether the vertex may
/// take a light sample (a medium's point takes it on its segment instead, unless the segment could
/// not be recorded), and the estimator's options and variant.
#[derive(Clone, Copy, Debug)]
pub(crate) struct MisVertex {
    pub depth: u32,
    pub max_depth: u32,
    pub samples_lights: bool,
    pub options: MisOptions,
    pub variant: MisVariant,
}

/// What a `mis` vertex asks to be traced: its light sample's shadow ray (whose emitter, if it meets
/// one, [`MisPath::shadow_arrived`] adds), and the path's next ray (`None`: the path ends).
#[derive(Clone, Copy, Debug)]
pub(crate) struct MisStep {
    pub shadow: Option<Ray>,
    pub next: Option<Ray>,
}

impl MisStep {
    const END: MisStep = MisStep {
        shadow: None,
        next: None,
    };
}

/// A `mis` path between its vertices ([`radiance_mis`]'s loop a vertex at a time, so that paths
/// traced side by side, [`crate::mis8`], can have their rays intersected together): the radiance
/// gathered so far `l`, the throughput, the previous diffuse vertex with its material-sampling
/// density of the ray that left it, how many dielectrics the path is inside, and the light sample
/// waiting for its shadow ray.
#[derive(Clone, Copy, Debug)]
pub(crate) struct MisPath {
    pub l: Color,
    pub throughput: Color,
    /// `None` after the camera or a specular bounce; else its point, the shading normal its light
    /// sample used ([`shading_normal`]) and the density.
    previous: Option<(Point3, Option<Vec3>, f64)>,
    inside_dielectrics: u32,
    /// The interface ([`crate::manifold::Manifold::interfaces`]) the path entered, while it is inside
    /// that one dielectric and no other.
    interface: Option<u16>,
    /// Since the last vertex made a manifold connection: where it was, the rest of its state, and
    /// whether the path has refracted out of the interface since (the emission it meets next is then
    /// weighed against the connection).
    through: Option<Through>,
    /// The light sample's throughput times attenuation, and its `w_l s / p_l`.
    waiting: Option<(Color, f64)>,
}

impl Default for MisPath {
    fn default() -> Self {
        MisPath {
            l: Color::ZERO,
            throughput: Color::ONE,
            previous: None,
            inside_dielectrics: 0,
            interface: None,
            through: None,
            waiting: None,
        }
    }
}

impl MisPath {
    /// Whether the path's next vertex may take a light sample: not inside a dielectric, where every
    /// shadow ray meets its boundary first (a specular surface, which next-event estimation cannot
    /// pass); emission the path meets from there has weight 1 (the material strategy alone).
    #[inline]
    pub fn takes_light_samples(&self) -> bool {
        self.inside_dielectrics == 0
    }

    // ANCHOR: mis_vertex
    /// The path's vertex where `ray` met `found` (`None`: it left the scene): emission met there,
    /// weighted against the light strategy of the vertex before; then the light sample's shadow
    /// ray and the next ray, from the vertex's material (mixed with the non-emitting targets).
    #[inline(always)]
    pub fn vertex(
        &mut self,
        scene: &Scene,
        lights: &Lights,
        ray: &Ray,
        found: Option<&Hit>,
        vertex: MisVertex,
        ctx: &mut Ctx,
    ) -> MisStep {
        let MisVertex {
            depth,
            max_depth,
            samples_lights,
            options,
            variant,
        } = vertex;
        let light_strategy = self.takes_light_samples();
        let Some(hit) = found else {
            self.l += self.throughput * scene.background.value(ray);
            return MisStep::END;
        };
        let material = &scene.materials[hit.material.index()];
        if material.is_emitter() {
            let emitted = material.emitted(hit, &scene.textures, ctx);
            if emitted != Color::ZERO {
                let weight = match self.previous {
                    None => match &self.through {
                        Some(t) if variant != MisVariant::WrongManifoldWeight => {
                            t.material_weight(lights, hit)
                        }
                        _ => 1.0,
                    },
                    Some((origin, normal, p_material)) => {
                        let p_light = match variant {
                            MisVariant::WrongUniformLightWeight => {
                                HittablePdf::new(origin, &lights.emitters)
                                    .map_or(0.0, |h| h.pdf(ray.direction))
                            }
                            MisVariant::WrongTreeWeightWithoutNormal => {
                                lights.emitters_pdf(origin, None, ray.direction)
                            }
                            // the light sample's own per-point probabilities, with its normal
                            _ => lights.emitters_pdf(origin, normal, ray.direction),
                        };
                        power_heuristic(1.0, p_material, 1.0, p_light)
                    }
                };
                self.l += self.throughput * weight * emitted;
            }
        }
        let fuzzy_metal = match material {
            Material::Metal { albedo, fuzz }
                if *fuzz >= crate::metal_pdf::MIN_FUZZ
                    && variant != MisVariant::MetalAsSpecular =>
            {
                let lobe = FuzzyMetalPdf::new(ray.direction, hit.normal, *fuzz);
                Some((
                    *albedo,
                    if variant == MisVariant::WrongMetalDensity {
                        VertexPdf::WrongMetal(lobe)
                    } else {
                        VertexPdf::Metal(lobe)
                    },
                ))
            }
            _ => None,
        };
        let (attenuation, pdf) = match fuzzy_metal {
            Some(metal) => metal,
            None => match material.scatter(ray, hit, &scene.textures, ctx) {
                None => return MisStep::END,
                Some(Scatter::Specular {
                    attenuation,
                    direction,
                }) => {
                    let through = self.through.take();
                    // Refracted (not reflected) through a dielectric: into it from its front, out of it
                    // from its back.
                    if matches!(material, Material::Dielectric { .. })
                        && direction.dot(hit.normal) < 0.0
                    {
                        self.interface = None;
                        self.inside_dielectrics = if hit.front_face {
                            self.inside_dielectrics + 1
                        } else {
                            self.inside_dielectrics.saturating_sub(1)
                        };
                        if hit.front_face
                            && self.inside_dielectrics == 1
                            && lights.manifold.is_active()
                        {
                            self.interface = lights.manifold.interface_at(hit);
                        }
                        // still on the kind of path a connection made: the emission met once out
                        // of the interface is weighed against it
                        self.through = through.and_then(|t| {
                            t.refracted(&lights.manifold, hit, self.inside_dielectrics)
                        });
                    }
                    self.throughput *= attenuation;
                    self.previous = None;
                    return MisStep {
                        shadow: None,
                        next: Some(hit.spawn(direction, ray.time)),
                    };
                }
                Some(Scatter::Diffuse { attenuation, pdf }) => {
                    (attenuation, VertexPdf::Material(pdf))
                }
            },
        };
        let towards_others = HittablePdf::new(hit.p, &lights.others);
        self.through = None;

        // Next-event estimation: only if the shadow ray's hit is within the path's depth.
        // (A medium's point takes it on its segment, unless the segment could not be recorded.)
        let mut shadow = None;
        if depth + 1 < max_depth
            && light_strategy
            && samples_lights
            && !lights.emitters.is_empty()
            && let Some((ray_to_light, weight)) = light_sample(
                lights,
                hit,
                ray.time,
                &pdf,
                towards_others.as_ref(),
                ctx.sample_2d(Dimension::Light(depth)),
            )
        {
            self.waiting = Some((self.throughput * attenuation, weight));
            shadow = Some(ray_to_light);
        }
        // Light that comes through a glass ball: the manifold connections, if their emitter would
        // be within the path's depth (two segments away from inside, three from outside). From
        // inside with the light sample's numbers (which no light sample uses there), from outside
        // after the material sample (the order of the lanes' vertex, [`MisPath::lambertian_from_lanes`]).
        let vertex_at = vertex;
        let vertex = connection::Vertex {
            hit,
            pdf: &pdf,
            towards_others: towards_others.as_ref(),
            time: ray.time,
        };
        let mut connected = match self.interface {
            Some(k)
                if !light_strategy
                    && options.manifold
                    && self.inside_dielectrics == 1
                    && depth + 2 < max_depth
                    && lights.manifold.interfaces[k as usize].connects_from(hit.p) =>
            {
                let u = ctx.sample_2d(Dimension::Light(depth));
                let c = connection::leaving(scene, lights, &vertex, k, u, variant, ctx);
                self.l += self.throughput * attenuation * c;
                Some((k, connection::Kind::Leaving))
            }
            _ => None,
        };
        let end = MisStep { shadow, next: None };

        // Material sampling (mixed with the non-emitting targets by OTHERS_SHARE): the path goes on
        // this way.
        let u = ctx.sample_2d(Dimension::Material(depth));
        let sampled = match &towards_others {
            Some(t) if variant == MisVariant::WrongOthersShare => {
                with_others(*t, pdf).sample(u).map(|ms| DirectionSample {
                    pdf: MixturePdf::new(*t, pdf).pdf(ms.direction),
                    ..ms
                })
            }
            Some(t) => with_others(*t, pdf).sample(u),
            None => pdf.sample(u),
        };
        if light_strategy {
            let crossed = self.cross(scene, lights, &vertex, attenuation, &vertex_at, ctx);
            connected = crossed.map(|k| (k, connection::Kind::Crossing));
        }
        let Some(ms) = sampled else {
            return end;
        };
        let Some(s_over_p) = ratio(pdf.pdf(ms.direction), ms.pdf) else {
            return end;
        };
        self.throughput *= attenuation * s_over_p;
        self.previous = (light_strategy || variant == MisVariant::WrongWeightInsideDielectrics)
            .then_some((hit.p, shading_normal(hit, &pdf), ms.pdf));
        self.through = connected.map(|(k, kind)| Through::new(hit.p, ms.pdf, k, kind));
        let next = hit.spawn(ms.direction, ray.time);

        let in_medium = matches!(material, Material::Isotropic { .. });
        if !self.survives_roulette(depth, in_medium, options, variant, ctx) {
            return end;
        }
        MisStep {
            shadow,
            next: Some(next),
        }
    }
    // ANCHOR_END: mis_vertex

    /// The crossing connection ([`connection::crossing`]) of a vertex outside the dielectrics
    /// (`vertex`, of `attenuation`; `at` says where in the path it is), if one is made there: its
    /// contribution is added, and the interface it crossed returned.
    #[inline]
    fn cross(
        &mut self,
        scene: &Scene,
        lights: &Lights,
        vertex: &connection::Vertex<'_>,
        attenuation: Color,
        at: &MisVertex,
        ctx: &mut Ctx,
    ) -> Option<u16> {
        if !(at.options.manifold
            && !lights.manifold.crossable.is_empty()
            && at.depth + 3 < at.max_depth)
        {
            return None;
        }
        let (c, k) = connection::crossing(scene, lights, vertex, at.variant, ctx)?;
        self.l += self.throughput * attenuation * c;
        Some(k)
    }

    /// The crossing connection of a Lambertian vertex whose light and material samples the lanes
    /// computed ([`crate::mis_vertex8`]): `hit` its record, `albedo` its attenuation. Called before
    /// [`MisPath::lambertian_from_lanes`], which takes the interface it returns: the same numbers
    /// and sums, in the same order, as [`MisPath::vertex`].
    #[allow(clippy::too_many_arguments)]
    pub fn crossing_from_lanes(
        &mut self,
        scene: &Scene,
        lights: &Lights,
        hit: &Hit,
        albedo: Color,
        time: f64,
        at: &MisVertex,
        ctx: &mut Ctx,
    ) -> Option<u16> {
        let pdf = VertexPdf::Material(ScatterPdf::Cosine(rtl_pdf::CosinePdf::new(hit.normal)));
        let towards_others = HittablePdf::new(hit.p, &lights.others);
        let vertex = connection::Vertex {
            hit,
            pdf: &pdf,
            towards_others: towards_others.as_ref(),
            time,
        };
        self.cross(scene, lights, &vertex, albedo, at, ctx)
    }

    /// Russian roulette after the vertex at `depth` (`in_medium`: it scattered in a medium):
    /// survive with probability `q = min(1, max throughput / ROULETTE_BELOW)`
    /// (`ROULETTE_BELOW_IN_MEDIA` in a medium), reweighted by `1 / q`. Whether the path goes on
    /// (not if its throughput is 0).
    #[inline(always)]
    fn survives_roulette(
        &mut self,
        depth: u32,
        in_medium: bool,
        options: MisOptions,
        variant: MisVariant,
        ctx: &mut Ctx,
    ) -> bool {
        if options.russian_roulette && depth >= ROULETTE_AFTER {
            let below = if in_medium {
                ROULETTE_BELOW_IN_MEDIA
            } else {
                ROULETTE_BELOW
            };
            let q = (self.throughput.max_element() / below).min(1.0);
            if q < 1.0 {
                if q <= 0.0 || ctx.sample_1d(Dimension::Roulette(depth)) >= q {
                    return false;
                }
                if !(in_medium && variant == MisVariant::WrongRouletteInMedia) {
                    self.throughput /= q;
                }
            }
        }
        self.throughput != Color::ZERO
    }

    /// The rest of a Lambertian vertex at `depth` whose light sample and material sample were
    /// computed in the lanes ([`crate::mis_vertex8`]): `waiting`, the light sample's carried
    /// throughput and weight if it made a shadow ray; `bounce`, the throughput after the
    /// material sample, the vertex's point and the density the direction was drawn with, if it
    /// made one; `crossed`, the interface its crossing connection crossed
    /// ([`MisPath::crossing_from_lanes`]). Whether the path goes on (after Russian roulette).
    #[inline(always)]
    pub fn lambertian_from_lanes(
        &mut self,
        waiting: Option<(Color, f64)>,
        bounce: Option<(Color, Point3, f64)>,
        crossed: Option<u16>,
        depth: u32,
        options: MisOptions,
        ctx: &mut Ctx,
    ) -> bool {
        if waiting.is_some() {
            self.waiting = waiting;
        }
        self.through = None;
        let Some((throughput, p, pdf)) = bounce else {
            return false;
        };
        self.throughput = throughput;
        // (no normal: the lanes take a vertex only in scenes of one emitter, chosen without a light
        // tree, whose light sample and density ignore it)
        self.previous = Some((p, None, pdf));
        self.through = crossed.map(|k| Through::new(p, pdf, k, connection::Kind::Crossing));
        self.survives_roulette(depth, false, options, MisVariant::Book, ctx)
    }

    /// The shadow ray of the vertex's light sample met `emitted`, the radiance of a light of
    /// constant radiance seen from the ray's side (zero from behind a one-sided one; `None`: it
    /// met no emitter): [`MisPath::shadow_arrived`] without the hit's record.
    #[inline(always)]
    pub fn shadow_met(&mut self, emitted: Option<Color>) {
        let Some((throughput, weight)) = self.waiting.take() else {
            return;
        };
        if let Some(emitted) = emitted {
            self.l += throughput * emitted * weight;
        }
    }

    /// What the shadow ray of the vertex's light sample met (the surface and the transmittance of
    /// the media before it): its emission, if it is an emitter's, weighted as the sample said.
    #[inline(always)]
    pub fn shadow_arrived(&mut self, scene: &Scene, shadow: Option<(&Hit, f64)>, ctx: &mut Ctx) {
        let Some((throughput, weight)) = self.waiting.take() else {
            return;
        };
        if let Some((emitted, weight)) = emitter_seen(scene, shadow, weight, ctx) {
            self.l += throughput * emitted * weight;
        }
    }
}

/// The emission a light sample's shadow ray meets (`shadow`: the surface and the transmittance of
/// the media before it), if it meets an emitter, and the sample's `weight` times the transmittance.
#[inline]
pub(super) fn emitter_seen(
    scene: &Scene,
    shadow: Option<(&Hit, f64)>,
    weight: f64,
    ctx: &mut Ctx,
) -> Option<(Color, f64)> {
    let (lh, transmittance) = shadow?;
    let m: &Material = &scene.materials[lh.material.index()];
    if !m.is_emitter() || transmittance <= 0.0 {
        return None;
    }
    Some((m.emitted(lh, &scene.textures, ctx), weight * transmittance))
}
