//! The integrator: the radiance carried back along one camera path. Book 2's recursive `ray_color`
//! (emission plus attenuation times the radiance of the scattered ray) written as a loop that carries
//! the path's throughput.
//!
//! How a diffuse bounce picks its direction is the [`Strategy`]; the importance-sampling strategies of
//! book 3 are further variants of it, each a branch of [`sample_diffuse`].

use crate::material::{Scatter, ScatterPdf, uniform_hemisphere};
use crate::ray::Ray;
use crate::sampler::Ctx;
use crate::scene::Scene;
use crate::vec::{Color, Frame};
use std::f64::consts::PI;

/// How a diffuse bounce chooses its scattered direction.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Strategy {
    /// Uniform over the hemisphere about the normal (`p = 1 / 2 pi`): book 3's starting point.
    Uniform,
    /// The material's own density (cosine for Lambertian, uniform sphere for isotropic): what book 2's
    /// `lambertian::scatter` does.
    #[default]
    Cosine,
}

impl Strategy {
    /// Every strategy, for listing.
    pub const ALL: &'static [Strategy] = &[Strategy::Uniform, Strategy::Cosine];

    pub fn name(&self) -> &'static str {
        match self {
            Strategy::Uniform => "uniform",
            Strategy::Cosine => "cosine",
        }
    }

    pub fn description(&self) -> &'static str {
        match self {
            Strategy::Uniform => "uniform directions over the hemisphere, weighted by s/p = 2 cos",
            Strategy::Cosine => "the material's own density (cosine-weighted): book 2's method",
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

/// A scattered direction (unit) and the factor `s(omega) / p(omega)` the throughput is multiplied by
/// (besides the attenuation), or `None` if the sample contributes nothing further.
#[inline]
fn sample_diffuse(
    strategy: Strategy,
    pdf: &ScatterPdf,
    ctx: &mut Ctx,
) -> Option<(crate::vec::Vec3, f64)> {
    match (strategy, pdf) {
        // Sampling s itself: s / p = 1.
        (Strategy::Cosine, _) | (Strategy::Uniform, ScatterPdf::Sphere) => {
            Some((pdf.generate(ctx), 1.0))
        }
        (Strategy::Uniform, ScatterPdf::Cosine(n)) => {
            let d = Frame::from_w(*n).to_world(uniform_hemisphere(ctx.uniform(), ctx.uniform()));
            let weight = pdf.value(d) * (2.0 * PI);
            (weight > 0.0).then_some((d, weight))
        }
    }
}

/// The radiance arriving along `ray`, estimated by one path of at most `max_depth` intersections.
#[inline]
pub fn radiance(
    scene: &Scene,
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
        let material = &scene.materials[hit.material as usize];
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
                let Some((direction, weight)) = sample_diffuse(strategy, &pdf, ctx) else {
                    break;
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
