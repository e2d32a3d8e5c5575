//! The integrator: the radiance carried back along one camera path. Book 2's recursive `ray_color`
//! (emission plus attenuation times the radiance of the scattered ray) written as a loop that carries
//! the path's throughput.
//!
//! How a diffuse bounce picks its direction is the [`Strategy`]: book 3's uniform, cosine, light and
//! mixture sampling (one direction per bounce, weighted by `s(omega) / p(omega)`), and `mis`, next-event
//! estimation combined with material sampling by multiple importance sampling.

use crate::connection::{self, Through};
use crate::hit::Hit;
use crate::lights::{LightTarget, Lights};
use crate::material::{Material, Scatter, ScatterPdf};
use crate::metal_pdf::FuzzyMetalPdf;
use crate::ray::{Interval, Ray};
use crate::sampler::{Ctx, Dimension, MediaCrossed, MediumMode};
use crate::scene::{GroupId, Scene};
use crate::traversal::free_point_surely_beyond;
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
    /// Inside a dielectric sphere, connect to the emitters through its surface by manifold
    /// next-event estimation ([`crate::manifold`]), where the scene has such a sphere holding
    /// something that scatters.
    pub manifold: bool,
}

impl MisOptions {
    /// What `mis` uses by default: the extras that pay on the Cornell box (see `rtl study render`).
    /// Spherical rectangles cost more per sample (four `acos` per evaluation) than they save in
    /// variance for a light as small as the box's, so they are off.
    pub const DEFAULT: MisOptions = MisOptions {
        russian_roulette: true,
        spherical_rectangles: false,
        low_discrepancy: true,
        manifold: true,
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
                     transmittance) + material sampling mixed with the other targets ({:.0}% \
                     towards them), power heuristic; Russian roulette {}, spherical rectangles \
                     {}, low-discrepancy samples {}, manifold connections {}",
                    100.0 * OTHERS_SHARE,
                    on_off(o.russian_roulette),
                    on_off(o.spherical_rectangles),
                    on_off(o.low_discrepancy),
                    on_off(o.manifold)
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
    // `r <= MAX` is `r.is_finite()` here (`r` is not negative): two comparisons, where LLVM makes a
    // class test on the bits of `is_finite`.
    (p > 0.0 && s > 0.0 && r <= f64::MAX).then_some(r)
}

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
pub(crate) fn trace_shadow(scene: &Scene, ray: &Ray, ctx: &mut Ctx) -> Option<(Hit, f64)> {
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

/// The light sample of a vertex at `hit` whose material samples `pdf` (mixed with `towards_others`):
/// the shadow ray towards the emitters in a direction drawn with `u`, and the factor `w_l s / p_l`
/// (power heuristic weight, the material's density over the light's) its emission counts with,
/// times the transmittance of the media the ray crosses ([`MisPath::shadow_arrived`]).
#[inline]
fn light_sample(
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

/// How often a path segment through media takes its light sample: with probability
/// `min(1, SEGMENT_SAMPLE_RATE tau)` for a segment of optical depth `tau` (the survivors reweighted by
/// the inverse), about as often as the path scatters there (`1 - exp(-tau) ~ tau`). On book2-final
/// (400 x 400, 16 spp; its fog has `tau` about 0.5 along a camera ray) rates 1, 2 and 4 give noise
/// constants 0.222, 0.212, 0.211 at 734-760k, 655-662k, 622-654k samples/s per core: 1 is soonest
/// to a given noise, by a little.
pub const SEGMENT_SAMPLE_RATE: f64 = 1.0;
/// [`SEGMENT_SAMPLE_RATE`] for the camera ray's segment: every camera ray through book2-final's fog
/// alone (`tau` about 0.5) takes its light sample, the ones to a surface (shorter) 2 `tau` of the
/// time. On book2-final (400 x 400, 16 spp) rate 2 on the camera ray lowers the noise constant from
/// 0.2231 to 0.2141 for 3-5% of the rate; 100 (every camera segment) gives 0.2137 for 20%.
pub const CAMERA_SEGMENT_SAMPLE_RATE: f64 = 2.0;
/// The largest optical depth of a segment that takes its light sample at an equiangular point. The
/// equiangular density ignores the transmittance: in a medium much denser than the segment is long
/// the light is scattered from a skin of depth `1 / sigma` where the segment enters, which it almost
/// never draws a point in (and at density 1e30 cannot: the ulp of `t` is wider than the skin). Such a
/// segment's scattering point takes its own light sample instead, as before segment sampling. At
/// `tau` 8 the transmittance ends at 3e-4: the equiangular points are still where the light is.
pub const SEGMENT_MAX_OPTICAL_DEPTH: f64 = 8.0;
/// The emitters whose centres the equiangular density of a segment is mixed from (the first ones
/// of the scene; any density that covers the segment is unbiased, these make it a good one).
const EQUIANGULAR_CENTRES: usize = 4;

// ANCHOR: equiangular
/// The equiangular density about a point (Kulla and Fajardo 2012) along a ray: with `delta` the ray
/// parameter of the point's foot on the line and `h > 0` its distance from the line (in units of the
/// ray parameter), `t = delta + h tan(theta)` with `theta` uniform, i.e. `q(t) = h / ((t - delta)^2 + h^2)`
/// per unit of `theta`'s range. It cancels the inverse square of the distance to the point.
#[derive(Clone, Copy, Default)]
struct Equiangular {
    delta: f64,
    h: f64,
    /// `theta`'s range summed over the stretches (the density's normalisation).
    mass: f64,
}

impl Equiangular {
    fn about(ray: &Ray, c: Point3) -> Equiangular {
        let dd = ray.direction.length_squared();
        let oc = c - ray.origin;
        let delta = oc.dot(ray.direction) / dd;
        let h2 = (oc.length_squared() / dd - delta * delta).max(0.0);
        // a ray through the point: keep the density finite
        let h = h2.sqrt().max(1e-9 * (delta.abs() + 1.0));
        Equiangular {
            delta,
            h,
            mass: 0.0,
        }
    }
    /// `x = (t - delta) / h = tan(theta)`.
    #[inline]
    fn x(&self, t: f64) -> f64 {
        (t - self.delta) / self.h
    }
    /// `theta`'s range over `t0..t1` (`t0 <= t1`). On one side of the foot as
    /// `atan((x1 - x0) / (1 + x0 x1))` with `x1 - x0 = (t1 - t0) / h`: the difference of the two
    /// angles cancels to rounding when they are alike (an emitter far from a short stretch: at 1e20
    /// units away the stretch's angle is below the angles' rounding, and read as 0).
    #[inline]
    fn angle(&self, t0: f64, t1: f64) -> f64 {
        let (x0, x1) = (self.x(t0), self.x(t1));
        if x0 * x1 >= 0.0 {
            ((t1 - t0) / self.h / (1.0 + x0 * x1)).atan()
        } else {
            x1.atan() - x0.atan()
        }
    }
    /// The `t` in `t0..t1` whose angle from `t0` is `phi` (in `0..=angle(t0, t1)`). On one side of
    /// the foot by the tangent's addition formula, as an offset from `t0`:
    /// `t - t0 = h tan(phi) (1 + x0^2) / (1 - x0 tan(phi))` (for the same reason as [`Self::angle`]).
    #[inline]
    fn at_angle(&self, t0: f64, t1: f64, phi: f64) -> f64 {
        let (x0, x1) = (self.x(t0), self.x(t1));
        let t = if x0 * x1 >= 0.0 {
            let tau = phi.tan();
            let den = 1.0 - x0 * tau;
            // (positive for phi within the range; rounding at the pole ends at t1)
            if den > 0.0 {
                t0 + self.h * tau * (1.0 + x0 * x0) / den
            } else {
                t1
            }
        } else {
            self.delta + self.h * (x0.atan() + phi).tan()
        };
        t.clamp(t0, t1)
    }
    #[inline]
    fn q(&self, t: f64) -> f64 {
        let x = t - self.delta;
        self.h / (x * x + self.h * self.h) / self.mass
    }
}
// ANCHOR_END: equiangular

/// Camera rays (bounce 0; bounces `0..FORCED_SCATTER_BOUNCES`) that would otherwise leave the scene
/// through a medium scatter in it on every path (the forced scattering of `trace_through_media`). On
/// book2-final a camera ray that meets only the fog (optical depth about 0.5) scatters 39% of the time
/// by distance sampling, so the light such a pixel gets from beyond its segment is a Bernoulli draw.
/// Forcing the later bounces too costs more than it saves (book/src/figures/render-speed.md, fog5).
pub const FORCED_SCATTER_BOUNCES: u32 = 1;
// (forced scattering takes the roulette's dimension: the two never meet at one bounce)
const _: () = assert!(FORCED_SCATTER_BOUNCES <= ROULETTE_AFTER);
/// The share of the equiangular density in the density a forced scattering point is drawn from (the
/// rest is the exponential of distance sampling, truncated to the stretch): near the emitters, where
/// the light is, and never less than `1 - FORCED_EQUIANGULAR_SHARE` times the exponential's density
/// anywhere, so the weight `sigma T / p` stays below `(1 - exp(-tau)) / (1 - share)`.
pub const FORCED_EQUIANGULAR_SHARE: f64 = 0.8;

/// What a path segment through media gives the path: its next vertex, whether that vertex takes a
/// light sample itself, the light scattered along the segment towards the ray's origin, and, when
/// the path was forced to scatter, how the throughput is split between the vertex and the background.
pub(crate) struct Segment {
    pub vertex: Option<Hit>,
    pub samples_lights: bool,
    pub in_scattered: Color,
    /// `Some((w, T))` when the path was forced to scatter before leaving the scene: the vertex carries
    /// `w = sigma T(t) / p(t)` of the throughput, the background is seen with `T = exp(-tau)`.
    pub forced: Option<(f64, f64)>,
}

/// The path's next vertex along `ray` when the scene has media, and the light the segment scatters
/// towards the ray's origin (to be multiplied by the path's throughput).
///
/// One traversal records the media the ray crosses up to the first surface (as a shadow ray does);
/// the path then scatters in medium `i` at the exponentially distributed distance of its density
/// `sigma_i` (the first such point before the surface wins: book 2's distance sampling, per medium).
/// The light scattered along the segment, `sum_i int sigma_i T(t) L_s,i(t) dt` (`T` the transmittance
/// from the origin, `L_s` what a light sample at `ray(t)` estimates), is estimated at one point drawn
/// from an equiangular density about the emitters' centres, over the stretches in media, not at the
/// scattering point: a thin fog lit by a nearby light varies along the ray as the inverse square of
/// the distance to the light, which the distance sampling ignores (and it scatters on few rays).
/// The point scattered at then takes no light sample of its own; the emission its material-sampled
/// direction meets keeps its power-heuristic weight, which with the segment's weight sums to 1 at
/// every point and direction, so the two estimate complementary parts of the same integral.
///
/// With `force` set, a ray that meets no surface and crosses one medium always scatters in it
/// ([`forced_scatter`]); that point takes the light sample itself.
///
/// Returns the vertex, whether it takes a light sample itself (a surface; a forced point; a medium
/// point when more media were crossed than can be recorded and the ray was traced again with book 2's
/// scattering, or when the segment is deeper than [`SEGMENT_MAX_OPTICAL_DEPTH`]), the segment's
/// in-scattered light and the forced split.
#[inline]
#[allow(clippy::too_many_arguments)] // the segment's parts, each used once
fn trace_through_media(
    scene: &Scene,
    lights: &Lights,
    ray: &Ray,
    sample_segment: bool,
    segment_rate: f64,
    force: bool,
    variant: MisVariant,
    ctx: &mut Ctx,
) -> Segment {
    ctx.media = MediumMode::Record;
    ctx.crossed.clear();
    let surface = scene.hit(ray, ctx);
    ctx.media = MediumMode::Scatter;
    if ctx.crossed.overflow {
        ctx.stats.rays += 1;
        return Segment {
            vertex: scene.hit(ray, ctx),
            samples_lights: true,
            in_scattered: Color::ZERO,
            forced: None,
        };
    }
    let crossed = ctx.crossed;
    let t_surface = surface.as_ref().map_or(f64::INFINITY, |h| h.t);
    let tau = crossed.optical_depth(t_surface);
    if force
        && surface.is_none()
        && crossed.len() == 1
        && tau > 0.0
        && let Some(segment) = forced_scatter(lights, ray, &crossed, tau, variant, ctx)
    {
        return segment;
    }
    // (NaN counts as dense: the point then samples the lights itself)
    let dense = (tau > SEGMENT_MAX_OPTICAL_DEPTH || tau.is_nan())
        && variant != MisVariant::SegmentsAtAnyDepth;
    let in_scattered = if sample_segment && !dense {
        segment_light(
            scene,
            lights,
            ray,
            &crossed,
            t_surface,
            tau,
            segment_rate,
            variant,
            ctx,
        )
    } else {
        Color::ZERO
    };
    // Distance sampling, medium by medium.
    let mut closest = t_surface;
    let mut phase = None;
    for ((t0, t1, density), m) in crossed.stretches() {
        let t1 = t1.min(t_surface);
        if t0 < t1 {
            let u = ctx.uniform();
            // `-ln(1 - u) >= u`: a `u` that reaches past the stretch or the closest point so far
            // decides without the logarithm, exactly as it would with it.
            if free_point_surely_beyond(u, t0, density, t1.min(closest)) {
                continue;
            }
            // 1 - u lies in (0, 1], so the logarithm is finite.
            let t = t0 - (1.0 - u).ln() / density;
            if t < t1 && t < closest {
                closest = t;
                phase = Some(m);
            }
        }
    }
    match phase {
        None => Segment {
            vertex: surface,
            samples_lights: true,
            in_scattered,
            forced: None,
        },
        Some(m) => Segment {
            vertex: Some(medium_point(ray, closest, m)),
            samples_lights: dense,
            in_scattered,
            forced: None,
        },
    }
}

/// A point of the medium (phase function `material`) at `ray(t)`.
#[inline]
fn medium_point(ray: &Ray, t: f64, material: u32) -> Hit {
    Hit {
        t,
        p: ray.at(t),
        normal: Vec3::X,
        front_face: true,
        err: 0.0,
        material: crate::ids::MaterialId(material),
        uv_source: crate::hit::UvSource::Uv(0.0, 0.0),
    }
}

// ANCHOR: forced_scatter
/// Forced scattering on a ray that leaves the scene through one medium's stretch `t0..t1` (density
/// `sigma`, optical depth `tau`): what reaches the ray's origin is
/// `int_t0^t1 sigma T(t) L_s(t) dt + T(t1) L_background`. Distance sampling estimates the integral by
/// scattering with probability `1 - exp(-tau)` and shows the background otherwise; here the background
/// term is added as it is (times `T = exp(-tau)`) and the integral by a point drawn on every path from
/// `p(t) = a q(t) + (1 - a) sigma T(t) / (1 - exp(-tau))` (`a` = [`FORCED_EQUIANGULAR_SHARE`], `q`
/// the equiangular density about the emitters' centres over the stretch, the second term the
/// exponential truncated to the stretch), weighted `sigma T(t) / p(t)`: with `a = 0` exactly
/// `1 - exp(-tau)`. The point takes its own light sample (weighted by the power heuristic against the
/// phase function's direction, as at a surface): the segment's equiangular sample would be a second
/// shadow ray for the same light.
///
/// `None` (and book 2's distance sampling) if the point comes out non-finite (an unbounded stretch).
#[inline]
fn forced_scatter(
    lights: &Lights,
    ray: &Ray,
    crossed: &MediaCrossed,
    tau: f64,
    variant: MisVariant,
    ctx: &mut Ctx,
) -> Option<Segment> {
    let ((t0, t1, density), m) = crossed.stretches().next()?;
    // 1 - exp(-tau), exact for a thin medium
    let scatters = -(-tau).exp_m1();
    let n = lights.emitters.len().min(EQUIANGULAR_CENTRES);
    let mut centres = [Equiangular::default(); EQUIANGULAR_CENTRES];
    let mut equiangular = n > 0 && t1.is_finite();
    if equiangular {
        for (e, target) in centres.iter_mut().zip(&lights.emitters) {
            *e = Equiangular::about(ray, emitter_centre(target));
            e.mass = e.angle(t0, t1);
            equiangular &= e.mass > 0.0 && e.mass.is_finite();
        }
    }
    let a = if equiangular {
        FORCED_EQUIANGULAR_SHARE
    } else {
        0.0
    };
    let centres = &centres[..n];
    // One stratified number picks the density, the centre and the point: `[0, a)` the equiangular
    // densities (`n` equal parts, one a centre), `[a, 1)` the exponential, each part rescaled to
    // `[0, 1)`, so the pixel's samples are spread along the ray.
    let u = ctx.sample_1d(Dimension::Scatter(ctx.bounce));
    let t = if u < a {
        let v = u / a * n as f64;
        let i = (v as usize).min(n - 1);
        let e = centres[i];
        e.at_angle(t0, t1, (v - i as f64).clamp(0.0, 1.0) * e.mass)
    } else {
        let v = ((u - a) / (1.0 - a)).clamp(0.0, 1.0);
        // the inverse of the truncated exponential's distribution; ln_1p's argument is in [-1, 0]
        (t0 - (v * (-tau).exp_m1()).ln_1p() / density).clamp(t0, t1)
    };
    if !t.is_finite() {
        return None;
    }
    let weight = if a > 0.0 {
        // sigma T(t), T from the stretch's start (the ray meets nothing else)
        let sigma_t = density * (-density * (t - t0)).exp();
        let q = centres.iter().map(|e| e.q(t)).sum::<f64>() / n as f64;
        sigma_t / (a * q + (1.0 - a) * sigma_t / scatters)
    } else {
        scatters
    };
    let weight = match variant {
        MisVariant::WrongForcedScatterWeight => weight / scatters,
        _ => weight,
    };
    let through = match variant {
        MisVariant::WrongForcedBackground => 0.0,
        _ => (-tau).exp(),
    };
    Some(Segment {
        vertex: Some(medium_point(ray, t, m)),
        samples_lights: true,
        in_scattered: Color::ZERO,
        forced: Some((weight, through)),
    })
}
// ANCHOR_END: forced_scatter

/// The point an emitter's equiangular density is centred on.
#[inline]
fn emitter_centre(target: &LightTarget) -> Point3 {
    match target {
        LightTarget::Quad { quad, .. } => quad.q() + 0.5 * (quad.u() + quad.v()),
        LightTarget::Sphere(s) => s.center(),
    }
}

/// One equiangular point on the media stretches of `ray` before `t_surface` (of optical depth `tau`)
/// and its light sample, weighted `sigma T(t) / (P q(t))` (`P = min(1, rate tau)` the probability the
/// segment is sampled at all).
#[inline]
#[allow(clippy::too_many_arguments)] // the segment's parts, each used once
fn segment_light(
    scene: &Scene,
    lights: &Lights,
    ray: &Ray,
    crossed: &MediaCrossed,
    t_surface: f64,
    tau: f64,
    rate: f64,
    variant: MisVariant,
    ctx: &mut Ctx,
) -> Color {
    if lights.emitters.is_empty() || tau.is_nan() || tau <= 0.0 {
        return Color::ZERO;
    }
    let chance = (rate * tau).min(1.0);
    if ctx.uniform() >= chance {
        return Color::ZERO;
    }
    let mut centres = [Equiangular::default(); EQUIANGULAR_CENTRES];
    let n = lights.emitters.len().min(EQUIANGULAR_CENTRES);
    for (e, target) in centres.iter_mut().zip(&lights.emitters) {
        *e = Equiangular::about(ray, emitter_centre(target));
        e.mass = crossed
            .stretches()
            .map(|((t0, t1, _), _)| {
                let t1 = t1.min(t_surface);
                if t1 > t0 { e.angle(t0, t1) } else { 0.0 }
            })
            .sum();
    }
    let centres = &centres[..n];
    if centres.iter().any(|e| e.mass.is_nan() || e.mass <= 0.0) {
        return Color::ZERO; // no stretch of positive length before the surface
    }
    // A centre, then a stretch by its share of the centre's angle, then the angle within it.
    let e = centres[((ctx.uniform() * n as f64) as usize).min(n - 1)];
    let mut pick = ctx.uniform() * e.mass;
    let mut chosen = None;
    let one = crossed.len() == 1;
    for ((t0, t1, density), m) in crossed.stretches() {
        let t1 = t1.min(t_surface);
        // one stretch: its angle is the mass, already taken (the same arctangent)
        let range = if one {
            e.mass
        } else if t1 > t0 {
            e.angle(t0, t1)
        } else {
            0.0
        };
        if range > 0.0 {
            chosen = Some((range, t0, t1, density, m));
            if pick < range {
                break;
            }
            pick -= range;
        }
    }
    let Some((range, t0, t1, density, m)) = chosen else {
        return Color::ZERO;
    };
    let t = e.at_angle(t0, t1, pick.clamp(0.0, range));
    let q = centres.iter().map(|e| e.q(t)).sum::<f64>() / n as f64;
    let hit = Hit {
        t,
        p: ray.at(t),
        normal: Vec3::X,
        front_face: true,
        err: 0.0,
        material: crate::ids::MaterialId(m),
        uv_source: crate::hit::UvSource::Uv(0.0, 0.0),
    };
    let material = &scene.materials[hit.material.index()];
    let Some(Scatter::Diffuse { attenuation, pdf }) =
        material.scatter(ray, &hit, &scene.textures, ctx)
    else {
        return Color::ZERO;
    };
    if attenuation == Color::ZERO {
        return Color::ZERO; // a black medium (book 2's smoke): its shadow ray would add nothing
    }
    let towards_others = HittablePdf::new(hit.p, &lights.others);
    let u = glam::DVec2::new(ctx.uniform(), ctx.uniform());
    let Some((to_light, weight)) = light_sample(
        lights,
        &hit,
        ray.time,
        &VertexPdf::Material(pdf),
        towards_others.as_ref(),
        u,
    ) else {
        return Color::ZERO;
    };
    let seen = trace_shadow(scene, &to_light, ctx);
    let Some((emitted, weight)) =
        emitter_seen(scene, seen.as_ref().map(|(h, t)| (h, *t)), weight, ctx)
    else {
        return Color::ZERO;
    };
    let transmittance = match variant {
        MisVariant::WrongSegmentTransmittance => 1.0,
        _ => (-crossed.optical_depth(t)).exp(),
    };
    let f = density * transmittance / (chance * q);
    if !f.is_finite() {
        return Color::ZERO;
    }
    attenuation * emitted * (weight * f)
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
fn emitter_seen(
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

#[cfg(test)]
mod tests {
    use super::Equiangular;

    /// `angle` is the difference of the angles, and `at_angle` its inverse, for a point near the
    /// stretch and for one 1e20 away (where the plain difference `atan(x1) - atan(x0)` of two angles
    /// near pi/4 is all rounding). (Not for `h` near the floor of 1e-9: there the ulp of `t` itself
    /// is a sizeable angle.)
    #[test]
    fn equiangular_angles_and_their_inverse_hold_near_and_far() {
        for (delta, h) in [
            (0.5, 2.0),
            (-3.0, 0.1),
            (1e20, 1e20),
            (-1e20, 1e18),
            (4.0, 1e-4),
        ] {
            let e = Equiangular {
                delta,
                h,
                mass: 1.0,
            };
            for (t0, t1) in [(0.0, 1.0), (2.0, 9.0), (3.9, 4.1)] {
                let range = e.angle(t0, t1);
                let plain = e.x(t1).atan() - e.x(t0).atan();
                assert!(range >= 0.0);
                if h < 1e10 {
                    assert!((range - plain).abs() <= 1e-12 * plain.abs().max(1e-300) + 1e-15);
                }
                for f in [0.1, 0.5, 0.9] {
                    let t = e.at_angle(t0, t1, f * range);
                    assert!((t0..=t1).contains(&t));
                    let back = e.angle(t0, t);
                    assert!(
                        (back - f * range).abs() <= 1e-9 * range,
                        "{delta} {h} {t0}..{t1}: {back} vs {}",
                        f * range
                    );
                }
            }
        }
        // The plain difference loses the far stretch: it is what the density was built from before.
        let far = Equiangular {
            delta: 1e20,
            h: 1e20,
            mass: 1.0,
        };
        let plain = far.x(1.0).atan() - far.x(0.0).atan();
        assert!((plain - far.angle(0.0, 1.0)).abs() > 0.5 * far.angle(0.0, 1.0));
    }
}
