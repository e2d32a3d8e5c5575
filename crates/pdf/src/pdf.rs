//! The `Pdf` trait and the densities that need no scene: uniform sphere, uniform hemisphere, cosine.

use crate::{Onb, warp};
use glam::{DVec2, DVec3};
use rand::Rng;

/// Two uniform numbers in `[0, 1)`.
#[inline]
pub(crate) fn random_unit_square<R: Rng + ?Sized>(rng: &mut R) -> DVec2 {
    DVec2::new(rng.random::<f64>(), rng.random::<f64>())
}

// ANCHOR: pdf_trait
/// A density over the sphere of directions, with a way to sample it (book 3, chapter 10).
///
/// `value` and `generate` must agree: the directions `generate` returns are distributed with density
/// `value`, per steradian. Callers divide by `value` of the direction they got, so a mismatch is a bias.
///
/// The trait is used by static dispatch: `generate` is generic over the random number generator, so
/// `Pdf` is not object safe, and mixtures are generic over their parts ([`MixturePdf<A, B>`]) instead of
/// holding `Box<dyn Pdf>` as the book's `shared_ptr<pdf>` does. Nothing here allocates per sample.
///
/// [`MixturePdf<A, B>`]: crate::MixturePdf
pub trait Pdf {
    /// The density per unit solid angle of `direction` (a unit vector); never negative or NaN.
    fn value(&self, direction: DVec3) -> f64;
    /// A unit direction distributed with density [`Pdf::value`].
    fn generate<R: Rng + ?Sized>(&self, rng: &mut R) -> DVec3;
}
// ANCHOR_END: pdf_trait

impl<P: Pdf + ?Sized> Pdf for &P {
    #[inline]
    fn value(&self, direction: DVec3) -> f64 {
        (**self).value(direction)
    }
    #[inline]
    fn generate<R: Rng + ?Sized>(&self, rng: &mut R) -> DVec3 {
        (**self).generate(rng)
    }
}

// ANCHOR: sphere_pdf
/// Uniform over the whole sphere: `value = 1 / (4 pi)`.
///
/// ```
/// use rtl_pdf::{Pdf, SpherePdf};
/// use rand::SeedableRng;
/// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
/// let d = SpherePdf.generate(&mut rng);
/// assert!((d.length() - 1.0).abs() < 1e-12);
/// assert_eq!(SpherePdf.value(d), 1.0 / (4.0 * std::f64::consts::PI));
/// ```
#[derive(Clone, Copy, Debug, Default)]
pub struct SpherePdf;

impl Pdf for SpherePdf {
    #[inline]
    fn value(&self, _direction: DVec3) -> f64 {
        warp::uniform_sphere_pdf()
    }
    #[inline]
    fn generate<R: Rng + ?Sized>(&self, rng: &mut R) -> DVec3 {
        warp::sample_uniform_sphere(random_unit_square(rng))
    }
}
// ANCHOR_END: sphere_pdf

/// Uniform over the hemisphere about a unit normal: `value = 1 / (2 pi)` above the horizon, 0 below.
#[derive(Clone, Copy, Debug)]
pub struct HemispherePdf {
    uvw: Onb,
}

impl HemispherePdf {
    /// The hemisphere on the side of the unit vector `normal`.
    #[inline]
    pub fn new(normal: DVec3) -> HemispherePdf {
        HemispherePdf {
            uvw: Onb::new(normal),
        }
    }
}

impl Pdf for HemispherePdf {
    #[inline]
    fn value(&self, direction: DVec3) -> f64 {
        if direction.dot(self.uvw.w()) >= 0.0 {
            warp::uniform_hemisphere_pdf()
        } else {
            0.0
        }
    }
    #[inline]
    fn generate<R: Rng + ?Sized>(&self, rng: &mut R) -> DVec3 {
        self.uvw
            .transform(warp::sample_uniform_hemisphere(random_unit_square(rng)))
    }
}

// ANCHOR: cosine_pdf
/// Cosine-weighted about a unit normal: `value = max(0, cos theta) / pi`, exactly 0 at and below the
/// horizon. The ideal density for a Lambertian surface, where it cancels the `cos theta / pi` of the
/// scattering, so `f cos / p` is just the albedo.
#[derive(Clone, Copy, Debug)]
pub struct CosinePdf {
    uvw: Onb,
}

impl CosinePdf {
    /// Cosine-weighted about the unit vector `normal`.
    #[inline]
    pub fn new(normal: DVec3) -> CosinePdf {
        CosinePdf {
            uvw: Onb::new(normal),
        }
    }
}

impl Pdf for CosinePdf {
    #[inline]
    fn value(&self, direction: DVec3) -> f64 {
        warp::cosine_hemisphere_pdf(direction.dot(self.uvw.w()))
    }
    #[inline]
    fn generate<R: Rng + ?Sized>(&self, rng: &mut R) -> DVec3 {
        self.uvw
            .transform(warp::sample_cosine_hemisphere(random_unit_square(rng)))
    }
}
// ANCHOR_END: cosine_pdf
