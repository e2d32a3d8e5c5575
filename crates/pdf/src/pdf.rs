//! The `Pdf` trait and the densities that need no scene: uniform sphere, uniform hemisphere, cosine.

use crate::{Onb, warp};
use glam::{DVec2, DVec3};
use rand::Rng;

/// Two uniform numbers in `[0, 1)`.
#[inline]
pub(crate) fn random_unit_square<R: Rng + ?Sized>(rng: &mut R) -> DVec2 {
    DVec2::new(rng.random::<f64>(), rng.random::<f64>())
}

/// Whether `x` is positive and finite: `0 < x <= f64::MAX`, two floating-point comparisons.
///
/// The same test as `x > 0.0 && x.is_finite()`, written so that it stays two comparisons: LLVM turns
/// that form (and `x < INFINITY`) into a test of the floating-point class, which x86-64 evaluates
/// on the bits with about fifteen integer instructions. Hot: every density of a sample passes it.
#[inline]
pub(crate) fn positive_finite(x: f64) -> bool {
    x > 0.0 && x <= f64::MAX
}

/// A direction drawn by a sampler, with the density it was drawn with (per steradian).
///
/// Returning both at once is what pbrt-v4's samplers do (`SampleLi` returns `{L, wi, pdf}`): the
/// density is known where the direction is made (a spherical rectangle's `1 / S`, a cone's
/// `1 / (2 pi (1 - cos theta_max))`), so nothing is set up a second time to evaluate it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DirectionSample {
    /// A unit vector.
    pub direction: DVec3,
    /// Its density per unit solid angle, `> 0` and finite.
    pub pdf: f64,
}

impl DirectionSample {
    /// A sample if `pdf` is positive and finite, else `None` (a direction that cannot be weighted).
    #[inline]
    pub fn new(direction: DVec3, pdf: f64) -> Option<DirectionSample> {
        positive_finite(pdf).then_some(DirectionSample { direction, pdf })
    }
}

// ANCHOR: pdf_trait
/// A density over the sphere of directions, with a way to sample it (book 3, chapter 10).
///
/// `sample` and `pdf` must agree: the directions `sample(u)` returns for `u` uniform on `[0, 1)^2`
/// are distributed with density `pdf`, per steradian, and the density each sample carries is `pdf` of
/// its direction. A sampler may fail (`None`) for some `u`, a light seen from behind, say: then `pdf`
/// is a *sub*-probability density, integrating to the probability of success, and a failed sample
/// contributes nothing. That keeps an estimator unbiased; a direction drawn while `pdf` says 0 would not.
///
/// The sampler takes its uniform numbers explicitly (pbrt-v4's `Sample(u)`), instead of a random
/// number generator: so a low-discrepancy point can be fed in (stratification), a render is
/// reproducible number by number, and tests can feed chosen inputs (`u = 0`, `u -> 1`). A discrete
/// choice inside a sampler (a mixture's part, a light) uses `u.x` and hands the rest of it on, remapped
/// onto `[0, 1)`. The book's interface, `generate(rng)` and `value(d)`, is kept as thin wrappers.
///
/// The trait is used by static dispatch: mixtures are generic over their parts ([`MixturePdf<A, B>`])
/// instead of holding `Box<dyn Pdf>` as the book's `shared_ptr<pdf>` does. Nothing here allocates per
/// sample.
///
/// [`MixturePdf<A, B>`]: crate::MixturePdf
pub trait Pdf {
    /// The density per unit solid angle of `direction` (a unit vector); never negative or NaN.
    #[doc(alias = "value")]
    fn pdf(&self, direction: DVec3) -> f64;

    /// A unit direction for the uniform numbers `u` in `[0, 1)^2`, with its density [`Pdf::pdf`];
    /// `None` where this sampler has no direction to give.
    #[doc(alias = "generate")]
    fn sample(&self, u: DVec2) -> Option<DirectionSample>;

    /// The book's name for [`Pdf::pdf`].
    #[inline]
    fn value(&self, direction: DVec3) -> f64 {
        self.pdf(direction)
    }

    /// The book's `generate()`: [`Pdf::sample`] of two numbers from `rng`, the direction only (the
    /// zero vector where `sample` fails, a direction no caller can weight).
    #[inline]
    fn generate<R: Rng + ?Sized>(&self, rng: &mut R) -> DVec3
    where
        Self: Sized,
    {
        self.sample(random_unit_square(rng))
            .map_or(DVec3::ZERO, |s| s.direction)
    }
}
// ANCHOR_END: pdf_trait

impl<P: Pdf + ?Sized> Pdf for &P {
    #[inline]
    fn pdf(&self, direction: DVec3) -> f64 {
        (**self).pdf(direction)
    }
    #[inline]
    fn sample(&self, u: DVec2) -> Option<DirectionSample> {
        (**self).sample(u)
    }
}

// ANCHOR: sphere_pdf
/// Uniform over the whole sphere: `value = 1 / (4 pi)` per steradian.
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
    fn pdf(&self, _direction: DVec3) -> f64 {
        warp::uniform_sphere_pdf()
    }
    #[inline]
    fn sample(&self, u: DVec2) -> Option<DirectionSample> {
        Some(DirectionSample {
            direction: warp::sample_uniform_sphere(u),
            pdf: warp::uniform_sphere_pdf(),
        })
    }
}
// ANCHOR_END: sphere_pdf

/// Uniform over the hemisphere about a unit normal: `value = 1 / (2 pi)` per steradian on and above
/// the horizon, 0 below.
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
    fn pdf(&self, direction: DVec3) -> f64 {
        if direction.dot(self.uvw.w()) >= 0.0 {
            warp::uniform_hemisphere_pdf()
        } else {
            0.0
        }
    }
    #[inline]
    fn sample(&self, u: DVec2) -> Option<DirectionSample> {
        Some(DirectionSample {
            direction: self.uvw.transform(warp::sample_uniform_hemisphere(u)),
            pdf: warp::uniform_hemisphere_pdf(),
        })
    }
}

// ANCHOR: cosine_pdf
/// Cosine-weighted about a unit normal: `value = max(0, cos theta) / pi` per steradian, exactly 0 at
/// and below the horizon. The ideal density for a Lambertian surface, where it cancels the `cos theta / pi` of the
/// scattering, so `f cos / p` is just the albedo.
///
/// Its value needs only the normal (`cos theta = d . n`); the basis `Onb::new(n)` that carries the
/// cosine warp to the world is built when a direction is drawn. A mixture that draws from its other
/// part (the book's: half the time towards the lights) then never builds it.
#[derive(Clone, Copy, Debug)]
pub struct CosinePdf {
    normal: DVec3,
}

impl CosinePdf {
    /// Cosine-weighted about the unit vector `normal`.
    #[inline]
    pub fn new(normal: DVec3) -> CosinePdf {
        CosinePdf { normal }
    }

    /// The direction [`Pdf::sample`] gives for `u`, without its density (for callers whose weight is
    /// exactly 1, such as a Lambertian surface sampled by its own density).
    #[inline]
    pub fn direction(&self, u: DVec2) -> DVec3 {
        Onb::new(self.normal).transform(warp::sample_cosine_hemisphere(u))
    }
}

impl Pdf for CosinePdf {
    #[inline]
    fn pdf(&self, direction: DVec3) -> f64 {
        warp::cosine_hemisphere_pdf(direction.dot(self.normal))
    }
    /// The concentric cosine warp; its density is `cos theta / pi` per steradian of the local
    /// direction. Never `None`: the warp keeps `cos theta >= warp::MIN_COS_THETA`, above the horizon,
    /// where the density is positive.
    #[inline]
    fn sample(&self, u: DVec2) -> Option<DirectionSample> {
        let local = warp::sample_cosine_hemisphere(u);
        DirectionSample::new(
            Onb::new(self.normal).transform(local),
            warp::cosine_hemisphere_pdf(local.z),
        )
    }
    /// The book's `generate`: the direction [`Pdf::sample`] draws from the same two numbers, without
    /// its density.
    #[inline]
    fn generate<R: Rng + ?Sized>(&self, rng: &mut R) -> DVec3 {
        self.direction(random_unit_square(rng))
    }
}
// ANCHOR_END: cosine_pdf

#[cfg(test)]
mod tests {
    use super::positive_finite;

    /// The values at which a finiteness test can go wrong.
    const EDGES: [f64; 14] = [
        0.0,
        -0.0,
        f64::MIN_POSITIVE,
        f64::MIN_POSITIVE / 4.0, // subnormal
        -f64::MIN_POSITIVE / 4.0,
        1.0,
        -1.0,
        f64::MAX,
        -f64::MAX,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NAN,
        -f64::NAN,
        f64::EPSILON,
    ];

    #[test]
    fn positive_finite_is_positive_and_is_finite() {
        for x in EDGES {
            assert_eq!(positive_finite(x), x > 0.0 && x.is_finite(), "{x}");
        }
    }

    #[test]
    fn the_check_sees_a_test_that_lets_zero_or_infinity_through() {
        // Deliberately wrong variants: each must disagree with `x > 0 && finite` somewhere on the edges.
        let wrong: [fn(f64) -> bool; 2] = [|x| (0.0..=f64::MAX).contains(&x), |x| x > 0.0];
        for w in wrong {
            assert!(EDGES.iter().any(|&x| w(x) != (x > 0.0 && x.is_finite())));
        }
    }
}
