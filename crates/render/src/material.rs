//! Materials: how light leaves a surface (emission) and how a ray scatters off it.
//!
//! Scattering returns a record in book 3's form, so the importance-sampling strategies can plug in:
//! either a *specular* ray that skips densities (metal, glass), or the material's own density of
//! scattered directions (`ScatterPdf`: Lambertian = cosine, isotropic = uniform sphere) together with
//! its attenuation. [`Material::scattering_pdf`] is the density `s(omega)` the book's estimator
//! `color * s(omega) / p(omega)` needs.

use crate::hit::Hit;
use crate::ray::Ray;
use crate::sampler::Ctx;
use crate::texture::Texture;
use crate::vec::{Color, Frame, Vec3, reflect, refract};
use std::f64::consts::{FRAC_1_PI, PI};

/// A reflectance or emission: a plain colour (no texture lookup at all) or a texture of the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Albedo {
    Constant(Color),
    Texture(u32),
}

impl Albedo {
    #[inline]
    pub fn value(&self, hit: &Hit, textures: &[Texture], ctx: &mut Ctx) -> Color {
        match self {
            Albedo::Constant(c) => *c,
            Albedo::Texture(i) => {
                ctx.stats.texture_evaluations += 1;
                textures[*i as usize].value(|| hit.uv(), hit.p)
            }
        }
    }
}

/// A material of books 1 to 3.
#[derive(Clone, Copy, Debug, PartialEq)]
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

/// The density a material samples its scattered directions from.
#[derive(Clone, Copy, Debug)]
pub enum ScatterPdf {
    /// `cos(theta) / pi` about the unit normal, on the normal's hemisphere (solid-angle measure).
    Cosine(Vec3),
    /// `1 / (4 pi)` over the whole sphere.
    Sphere,
}

impl ScatterPdf {
    /// Draw a direction with this density (a unit vector).
    #[inline]
    pub fn generate(&self, ctx: &mut Ctx) -> Vec3 {
        let (u1, u2) = (ctx.uniform(), ctx.uniform());
        match self {
            ScatterPdf::Cosine(n) => Frame::from_w(*n).to_world(cosine_direction(u1, u2)),
            ScatterPdf::Sphere => uniform_sphere(u1, u2),
        }
    }

    /// The density of `direction` (unit), per steradian.
    #[inline]
    pub fn value(&self, direction: Vec3) -> f64 {
        match self {
            ScatterPdf::Cosine(n) => (n.dot(direction) * FRAC_1_PI).max(0.0),
            ScatterPdf::Sphere => 0.25 * FRAC_1_PI,
        }
    }
}

/// A cosine-distributed direction about +z: `p(omega) = cos(theta) / pi` (Malley's method: a uniform
/// point on the disk lifted to the hemisphere).
#[inline]
pub fn cosine_direction(u1: f64, u2: f64) -> Vec3 {
    let phi = 2.0 * PI * u1;
    let r = u2.sqrt();
    let (s, c) = phi.sin_cos();
    Vec3::new(r * c, r * s, (1.0 - u2).max(0.0).sqrt())
}

/// A uniform direction on the unit sphere: `p(omega) = 1 / (4 pi)`.
#[inline]
pub fn uniform_sphere(u1: f64, u2: f64) -> Vec3 {
    let z = 1.0 - 2.0 * u1;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let (s, c) = (2.0 * PI * u2).sin_cos();
    Vec3::new(r * c, r * s, z)
}

/// A uniform direction on the hemisphere about +z: `p(omega) = 1 / (2 pi)`.
#[inline]
pub fn uniform_hemisphere(u1: f64, u2: f64) -> Vec3 {
    let z = u1;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let (s, c) = (2.0 * PI * u2).sin_cos();
    Vec3::new(r * c, r * s, z)
}

/// The outcome of scattering.
#[derive(Clone, Copy, Debug)]
pub enum Scatter {
    /// Sample the material's density; the path's weight is `attenuation * s(omega) / p(omega)`.
    Diffuse { attenuation: Color, pdf: ScatterPdf },
    /// Follow this one direction with weight `attenuation` (a delta distribution: no density).
    Specular { attenuation: Color, direction: Vec3 },
}

/// Schlick's approximation of the Fresnel reflectance at incidence `cosine` with ratio `ri`.
#[inline]
pub fn schlick(cosine: f64, ri: f64) -> f64 {
    let r0 = (1.0 - ri) / (1.0 + ri);
    let r0 = r0 * r0;
    r0 + (1.0 - r0) * (1.0 - cosine).powi(5)
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

    /// How the ray scatters at the hit; `None` if it is absorbed.
    #[inline]
    pub fn scatter(
        &self,
        ray: &Ray,
        hit: &Hit,
        textures: &[Texture],
        ctx: &mut Ctx,
    ) -> Option<Scatter> {
        match self {
            Material::Lambertian { albedo } => Some(Scatter::Diffuse {
                attenuation: albedo.value(hit, textures, ctx),
                pdf: ScatterPdf::Cosine(hit.normal),
            }),
            Material::Isotropic { albedo } => Some(Scatter::Diffuse {
                attenuation: albedo.value(hit, textures, ctx),
                pdf: ScatterPdf::Sphere,
            }),
            Material::Metal { albedo, fuzz } => {
                let reflected = reflect(ray.direction, hit.normal).normalize();
                let direction = if *fuzz > 0.0 {
                    let d = uniform_sphere(ctx.uniform(), ctx.uniform());
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
                let direction = if ri * sin_theta > 1.0 || schlick(cos_theta, ri) > ctx.uniform() {
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

    /// The scattering density `s(omega)` of a diffuse material for the unit direction `direction`.
    #[inline]
    pub fn scattering_pdf(&self, hit: &Hit, direction: Vec3) -> f64 {
        match self {
            Material::Lambertian { .. } => (hit.normal.dot(direction) * FRAC_1_PI).max(0.0),
            Material::Isotropic { .. } => 0.25 * FRAC_1_PI,
            _ => 0.0,
        }
    }

    /// True for materials that emit light.
    pub fn is_emitter(&self) -> bool {
        matches!(self, Material::DiffuseLight { .. })
    }
}
