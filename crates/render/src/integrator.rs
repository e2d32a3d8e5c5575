//! The integrator: the radiance carried back along one camera path. Book 2's recursive `ray_color`
//! (emission plus attenuation times the radiance of the scattered ray) written as a loop that carries
//! the path's throughput.
//!
//! How a diffuse bounce picks its direction is the [`Strategy`]: book 3's uniform, cosine, light and
//! mixture sampling (one direction per bounce, weighted by `s(omega) / p(omega)`), and `mis`, next-event
//! estimation combined with material sampling by multiple importance sampling.

use crate::lights::{LightTarget, Lights};
use crate::material::{Material, Scatter, ScatterPdf};
use crate::ray::Ray;
use crate::sampler::{Ctx, Preset};
use crate::scene::Scene;
use crate::vec::{Color, Point3, Vec3};
use rand::RngCore;
use rtl_pdf::{HemispherePdf, HittablePdf, MixturePdf, Pdf, power_heuristic};

// ANCHOR: mis_options
/// The extras of the `mis` strategy, each unbiased and each switchable off to measure its share.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize)]
pub struct MisOptions {
    /// End paths that carry little at random after a few bounces and reweight the survivors (Russian
    /// roulette; see [`ROULETTE_BELOW`]).
    pub russian_roulette: bool,
    /// Sample rectangular lights uniformly in solid angle (spherical rectangles) instead of by area.
    pub spherical_rectangles: bool,
    /// Take the light and material directions from low-discrepancy (padded Owen-scrambled Sobol)
    /// points instead of independent random numbers.
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
    /// The book's final method: a 50/50 mixture of the targets' density and the material's.
    Mixture,
    /// Next-event estimation to the emitters combined with material sampling (mixed with the
    /// non-emitting targets) by the power heuristic, plus the extras of [`MisOptions`].
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
            Strategy::Mixture => "50/50 mixture of the targets' density and the material's, \
                weighted s/p: the book's final method"
                .into(),
            Strategy::Mis(o) => {
                let on_off = |b: bool| if b { "on" } else { "off" };
                format!(
                    "next-event estimation to the emitters + material sampling mixed with the \
                     other targets, power heuristic; Russian roulette {}, spherical rectangles {}, \
                     low-discrepancy samples {}",
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
/// sample contributes nothing further (`p = 0`, `s = 0` or a non-finite quotient).
#[inline]
fn sample_diffuse(
    strategy: Strategy,
    pdf: &ScatterPdf,
    p: Point3,
    normal: Vec3,
    lights: &Lights,
    ctx: &mut Ctx,
) -> Option<(Vec3, f64)> {
    let rng = &mut ctx.rng;
    match (strategy, pdf) {
        // Sampling s itself: s / p = 1 exactly.
        (Strategy::Cosine, _) | (Strategy::Uniform, ScatterPdf::Sphere(_)) => {
            Some((pdf.generate(rng), 1.0))
        }
        (Strategy::Uniform, ScatterPdf::Cosine(_)) => {
            let hemisphere = HemispherePdf::new(normal);
            let d = hemisphere.generate(rng);
            Some((d, ratio(pdf.value(d), hemisphere.value(d))?))
        }
        (Strategy::Light, _) => match HittablePdf::new(p, &lights.all) {
            // With no targets there is nothing to aim at: sample the material.
            None => Some((pdf.generate(rng), 1.0)),
            Some(towards) => {
                let d = towards.generate(rng);
                Some((d, ratio(pdf.value(d), towards.value(d))?))
            }
        },
        // (`mis` has its own integrator; were it asked here, it would get the book's mixture.)
        (Strategy::Mixture, _) | (Strategy::Mis(_), _) => match HittablePdf::new(p, &lights.all) {
            None => Some((pdf.generate(rng), 1.0)),
            Some(towards) => {
                let mixed = MixturePdf::new(towards, *pdf);
                let d = mixed.generate(rng);
                Some((d, ratio(pdf.value(d), mixed.value(d))?))
            }
        },
    }
}
// ANCHOR_END: sample_diffuse

/// The radiance arriving along `ray`, estimated by one path of at most `max_depth` intersections.
#[inline]
pub fn radiance(
    scene: &Scene,
    lights: &Lights,
    ray: Ray,
    max_depth: u32,
    strategy: Strategy,
    ctx: &mut Ctx,
) -> Color {
    match strategy {
        Strategy::Mis(options) => radiance_mis(scene, lights, ray, max_depth, options, ctx),
        _ => radiance_one_sample(scene, lights, ray, max_depth, strategy, ctx),
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
    ctx: &mut Ctx,
) -> Color {
    let mut ray = ray;
    let mut throughput = Color::ONE;
    let mut l = Color::ZERO;
    for _ in 0..max_depth {
        ctx.stats.rays += 1;
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
                let Some((direction, weight)) =
                    sample_diffuse(strategy, &pdf, hit.p, hit.normal, lights, ctx)
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
    HittablePdf::new(origin, emitters).map_or(0.0, |h| h.value(direction))
}

// ANCHOR: radiance_mis
/// Next-event estimation with multiple importance sampling (Veach 1997, ch. 9; pbrt-v4's path
/// integrator). At every diffuse vertex two directions are drawn:
/// - towards the emitters (`p_l`): a shadow ray, whose emission counts with weight
///   `w_l = p_l^2 / (p_l^2 + p_m^2)`;
/// - from the material's density mixed 50/50 with the non-emitting targets (`p_m`): the path goes on
///   that way, and emission it meets at the next vertex counts with `w_m = p_m^2 / (p_l^2 + p_m^2)`.
///
/// The two weights of every direction sum to 1, so light reaching a vertex directly is counted once in
/// expectation, by whichever strategy sees it better. After a specular (delta) bounce only the material
/// could have found the emitter: full weight.
fn radiance_mis(
    scene: &Scene,
    lights: &Lights,
    ray: Ray,
    max_depth: u32,
    options: MisOptions,
    ctx: &mut Ctx,
) -> Color {
    let mut ray = ray;
    let mut throughput = Color::ONE;
    let mut l = Color::ZERO;
    // The previous diffuse vertex and its material-sampling density of `ray.direction`; `None` after
    // the camera or a specular bounce.
    let mut previous: Option<(Point3, f64)> = None;
    for depth in 0..max_depth {
        ctx.stats.rays += 1;
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
                throughput *= attenuation;
                ray = hit.spawn(direction, ray.time);
                previous = None;
                continue;
            }
            Some(Scatter::Diffuse { attenuation, pdf }) => (attenuation, pdf),
        };
        let towards_others = HittablePdf::new(hit.p, &lights.others);
        let material_pdf = |d: Vec3| match &towards_others {
            Some(t) => MixturePdf::new(*t, pdf).value(d),
            None => pdf.value(d),
        };
        let dim = 2 + 2 * depth;

        // Next-event estimation: only if the shadow ray's hit is within the path's depth.
        if depth + 1 < max_depth
            && let Some(towards_lights) = HittablePdf::new(hit.p, &lights.emitters)
        {
            let u = ctx.sample_2d(dim);
            let d = towards_lights.generate(&mut Preset::new(&u, &mut ctx.rng));
            let p_light = towards_lights.value(d);
            let s = pdf.value(d);
            if let Some(s_over_p) = ratio(s, p_light) {
                ctx.stats.rays += 1;
                if let Some(lh) = scene.hit(&hit.spawn(d, ray.time), ctx) {
                    let m: &Material = &scene.materials[lh.material.index()];
                    if m.is_emitter() {
                        let emitted = m.emitted(&lh, &scene.textures, ctx);
                        let w = power_heuristic(1.0, p_light, 1.0, material_pdf(d));
                        l += throughput * attenuation * emitted * (w * s_over_p);
                    }
                }
            }
        }

        // Material sampling (mixed with the non-emitting targets): the path goes on this way.
        let u = ctx.sample_2d(dim + 1);
        let d = match &towards_others {
            Some(t) => {
                let choice = ctx.rng.next_u64();
                MixturePdf::new(*t, pdf)
                    .generate(&mut Preset::new(&[choice, u[0], u[1]], &mut ctx.rng))
            }
            None => pdf.generate(&mut Preset::new(&u, &mut ctx.rng)),
        };
        let p_material = material_pdf(d);
        let Some(s_over_p) = ratio(pdf.value(d), p_material) else {
            break;
        };
        throughput *= attenuation * s_over_p;
        previous = Some((hit.p, p_material));
        ray = hit.spawn(d, ray.time);

        // Russian roulette: survive with probability q = min(1, max throughput / ROULETTE_BELOW),
        // reweight by 1 / q.
        if options.russian_roulette && depth >= ROULETTE_AFTER {
            let q = (throughput.max_element() / ROULETTE_BELOW).min(1.0);
            if q < 1.0 {
                if q <= 0.0 || ctx.uniform() >= q {
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
