//! Materials: how light leaves a surface (emission) and how a ray scatters off it.
//!
//! Scattering returns a record in book 3's form, so the importance-sampling strategies can plug in:
//! either a *specular* ray that skips densities (metal, glass), or the material's own density of
//! scattered directions (`ScatterPdf`: Lambertian = cosine, isotropic = uniform sphere) together with
//! its attenuation. That density's `pdf` (the book's `value`, the `Pdf` trait of rtl-pdf) is the book's
//! `scattering_pdf`, the `s(omega)` of the estimator `color * s(omega) / p(omega)`.

use crate::hit::Hit;
use crate::ids::TextureId;
use crate::ray::Ray;
use crate::sampler::Ctx;
use crate::sampler::Dimension;
use crate::texture::Texture;
use crate::vec::{Color, Vec3, reflect, refract};
use glam::DVec2;
use rtl_pdf::{CosinePdf, DirectionSample, Pdf, SpherePdf, warp};

/// A reflectance or emission: a plain colour (no texture lookup at all) or a texture of the scene.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub enum Albedo {
    Constant(Color),
    Texture(TextureId),
}

impl Albedo {
    #[inline]
    pub fn value(&self, hit: &Hit, textures: &[Texture], ctx: &mut Ctx) -> Color {
        match self {
            Albedo::Constant(c) => *c,
            Albedo::Texture(i) => {
                ctx.stats.texture_evaluations += 1;
                textures[i.index()].value(|| hit.uv(), hit.p)
            }
        }
    }
}

/// A material of books 1 to 3.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub enum Material {
    /// Ideal diffuse reflection, two-sided.
    Lambertian { albedo: Albedo },
    /// Mirror reflection perturbed by a random point in a ball of radius `fuzz`.
    Metal { albedo: Color, fuzz: f64 },
    /// Glass of refractive index `ior` inside (1 outside), reflectance by Schlick's approximation.
    Dielectric { ior: f64 },
    /// An emitter that scatters nothing; one-sided (book 3: emits on the front face only) unless
    /// `two_sided` (book 2).
    DiffuseLight { emit: Albedo, two_sided: bool },
    /// The phase function of a constant medium: every direction equally likely.
    Isotropic { albedo: Albedo },
}

// ANCHOR: scatter_pdf
/// The density a material samples its scattered directions from: the book's `scatter_record::pdf_ptr`,
/// an enum of rtl-pdf's densities instead of a pointer (static dispatch, nothing allocated).
#[derive(Clone, Copy, Debug)]
pub enum ScatterPdf {
    /// `max(0, cos theta) / pi` about the unit normal (solid-angle measure): Lambertian.
    Cosine(CosinePdf),
    /// `1 / (4 pi)` over the whole sphere: the isotropic phase function.
    Sphere(SpherePdf),
}

impl Pdf for ScatterPdf {
    #[inline]
    fn pdf(&self, direction: Vec3) -> f64 {
        match self {
            ScatterPdf::Cosine(p) => p.pdf(direction),
            ScatterPdf::Sphere(p) => p.pdf(direction),
        }
    }

    #[inline]
    fn sample(&self, u: DVec2) -> Option<DirectionSample> {
        match self {
            ScatterPdf::Cosine(p) => p.sample(u),
            ScatterPdf::Sphere(p) => p.sample(u),
        }
    }
}
impl ScatterPdf {
    /// A direction of [`Pdf::sample`] without its density: for the `cosine` strategy, whose weight
    /// `s / p` is exactly 1 (the book's `generate`).
    #[inline]
    pub fn direction(&self, u: DVec2) -> Vec3 {
        match self {
            ScatterPdf::Cosine(p) => p.direction(u),
            ScatterPdf::Sphere(_) => warp::sample_uniform_sphere(u),
        }
    }
}
// ANCHOR_END: scatter_pdf

// ANCHOR: scatter
/// The outcome of scattering: book 3's `scatter_record`.
#[derive(Clone, Copy, Debug)]
pub enum Scatter {
    /// Sample the material's density; the path's weight is `attenuation * s(omega) / p(omega)`.
    Diffuse { attenuation: Color, pdf: ScatterPdf },
    /// Follow this one direction with weight `attenuation` (a delta distribution: no density).
    Specular { attenuation: Color, direction: Vec3 },
}
// ANCHOR_END: scatter

/// Schlick's approximation of the Fresnel reflectance at incidence `cosine` with ratio `ri`.
#[inline]
pub fn schlick(cosine: f64, ri: f64) -> f64 {
    let r0 = (1.0 - ri) / (1.0 + ri);
    let r0 = r0 * r0;
    // x^5 as (x^2 x^2) x, the order of `powi(5)`'s multiplications (tested), written out so that
    // the glass vertex in the lanes (`crate::glass8`) can follow it.
    let x = 1.0 - cosine;
    let x2 = x * x;
    r0 + (1.0 - r0) * (x2 * x2 * x)
}

impl Material {
    pub fn lambertian(c: Color) -> Self {
        Material::Lambertian {
            albedo: Albedo::Constant(c),
        }
    }

    /// Light emitted towards the ray at the hit (zero for all but lights).
    #[inline]
    pub fn emitted(&self, hit: &Hit, textures: &[Texture], ctx: &mut Ctx) -> Color {
        match self {
            Material::DiffuseLight { emit, two_sided } => {
                if *two_sided || hit.front_face {
                    emit.value(hit, textures, ctx)
                } else {
                    Color::ZERO
                }
            }
            _ => Color::ZERO,
        }
    }

    /// What a Lambertian surface of `albedo` scatters at `hit`: the attenuation, and the cosine
    /// density about the normal.
    #[inline(always)]
    pub fn lambertian_at(
        albedo: &Albedo,
        hit: &Hit,
        textures: &[Texture],
        ctx: &mut Ctx,
    ) -> (Color, ScatterPdf) {
        (
            albedo.value(hit, textures, ctx),
            ScatterPdf::Cosine(CosinePdf::new(hit.normal)),
        )
    }

    /// How the ray scatters at the hit; `None` if it is absorbed. A metal's fuzz and a dielectric's
    /// coin come from [`Dimension::Material`] of bounce `ctx.bounce`.
    #[inline]
    pub fn scatter(
        &self,
        ray: &Ray,
        hit: &Hit,
        textures: &[Texture],
        ctx: &mut Ctx,
    ) -> Option<Scatter> {
        match self {
            Material::Lambertian { albedo } => {
                let (attenuation, pdf) = Self::lambertian_at(albedo, hit, textures, ctx);
                Some(Scatter::Diffuse { attenuation, pdf })
            }
            Material::Isotropic { albedo } => Some(Scatter::Diffuse {
                attenuation: albedo.value(hit, textures, ctx),
                pdf: ScatterPdf::Sphere(SpherePdf),
            }),
            Material::Metal { albedo, fuzz } => {
                let reflected = reflect(ray.direction, hit.normal).normalize();
                let direction = if *fuzz > 0.0 {
                    let u = ctx.sample_2d(Dimension::Material(ctx.bounce));
                    let d = warp::sample_uniform_sphere(u);
                    reflected + *fuzz * d
                } else {
                    reflected
                };
                (direction.dot(hit.normal) > 0.0).then_some(Scatter::Specular {
                    attenuation: *albedo,
                    direction,
                })
            }
            Material::Dielectric { ior } => {
                let ri = if hit.front_face { 1.0 / ior } else { *ior };
                let unit = ray.direction.normalize();
                let cos_theta = (-unit).dot(hit.normal).min(1.0);
                let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
                let direction = if ri * sin_theta > 1.0
                    || schlick(cos_theta, ri) > ctx.sample_1d(Dimension::Material(ctx.bounce))
                {
                    reflect(unit, hit.normal)
                } else {
                    refract(unit, hit.normal, ri)
                };
                Some(Scatter::Specular {
                    attenuation: Color::ONE,
                    direction,
                })
            }
            Material::DiffuseLight { .. } => None,
        }
    }

    /// True for materials that emit light.
    pub fn is_emitter(&self) -> bool {
        matches!(self, Material::DiffuseLight { .. })
    }
}

#[cfg(test)]
mod tests {
    use super::schlick;

    /// `schlick` writes `(1 - cos)^5` out as `(x^2 x^2) x`; `powi(5)` multiplies in that order
    /// too, so the images are those of `powi`. A different order (`x^4` as `((x x) x) x`) differs.
    #[test]
    fn schlick_takes_the_fifth_power_as_powi_does() {
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        let (mut differs, mut other_order) = (0, 0);
        for _ in 0..200_000 {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let cos = (state >> 11) as f64 / (1u64 << 53) as f64;
            let ri = 1.0 / 1.5;
            let r0 = ((1.0 - ri) / (1.0 + ri)) * ((1.0 - ri) / (1.0 + ri));
            let x: f64 = 1.0 - cos;
            let by_powi = r0 + (1.0 - r0) * x.powi(5);
            differs += (schlick(cos, ri).to_bits() != by_powi.to_bits()) as u32;
            let chained = r0 + (1.0 - r0) * ((((x * x) * x) * x) * x);
            other_order += (chained.to_bits() != by_powi.to_bits()) as u32;
        }
        assert_eq!(differs, 0);
        // (the check can fail: another order of the products gives other numbers)
        assert!(other_order > 0);
    }
}
