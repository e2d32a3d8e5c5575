//! The integrator: the radiance carried back along one camera path. Book 2's recursive `ray_color`
//! (emission plus attenuation times the radiance of the scattered ray) written as a loop that carries
//! the path's throughput.
//!
//! How a diffuse bounce picks its direction is the [`Strategy`]: book 3's uniform, cosine, light and
//! mixture sampling (one direction per bounce, weighted by `s(omega) / p(omega)`; `one_sample.rs`),
//! and `mis`, next-event estimation combined with material sampling by multiple importance sampling
//! (`mis.rs`), which takes its light samples through participating media along whole path segments
//! (`media.rs`, with the equiangular density of `equiangular.rs`).

mod equiangular;
mod media;
mod mis;
mod one_sample;

pub(crate) use media::trace_shadow;
pub use media::{
    CAMERA_SEGMENT_SAMPLE_RATE, FORCED_EQUIANGULAR_SHARE, FORCED_SCATTER_BOUNCES,
    SEGMENT_MAX_OPTICAL_DEPTH, SEGMENT_SAMPLE_RATE,
};
pub(crate) use mis::{MisPath, MisStep, MisVertex, VertexPdf, with_others};
pub use mis::{
    MisVariant, OTHERS_SHARE, ROULETTE_AFTER, ROULETTE_BELOW, ROULETTE_BELOW_IN_MEDIA,
    radiance_mis_variant,
};
pub use one_sample::{Bounce, OneSamplePath, sample_diffuse};

use mis::radiance_mis;
use one_sample::radiance_one_sample;

use crate::lights::Lights;
use crate::ray::Ray;
use crate::sampler::Ctx;
use crate::scene::Scene;
use crate::vec::Color;

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
