//! The direction density of the books' fuzzy metal, so that `mis` can take light samples from it and
//! weight the emission it finds.
//!
//! The metal scatters towards `r + f s`, with `r` the unit mirror direction, `f` the fuzz and `s`
//! uniform on the unit sphere, and absorbs the ray if that points below the surface. The point
//! `x = r + f s` is uniform on the sphere of radius `f` about `r` (density `1 / (4 pi f^2)` per unit
//! area); the direction `omega` meets that sphere at distances `d = c +- sqrt(f^2 - sin^2 theta)` from
//! the origin (`c = cos theta = omega . r`), where the sphere's normal makes `|cos alpha| =
//! sqrt(f^2 - sin^2 theta) / f` with `omega`. So per unit solid angle
//!
//! `p(omega) = sum_{d > 0} d^2 / (4 pi f sqrt(f^2 - sin^2 theta))`,
//!
//! two roots inside the cone `sin theta <= f` when `f < 1`, one when `f >= 1` (for `f = 1` exactly
//! `cos theta / pi`: a cosine lobe about the mirror direction). The metal's scattering function times
//! the cosine is `albedo p(omega)` above the surface and 0 below, so `s / p = 1` for the metal's own
//! directions, and a light sample `omega_l` weighs `albedo p(omega_l) / p_l(omega_l)`.

use crate::vec::Vec3;
use glam::DVec2;
use rtl_pdf::{DirectionSample, Pdf, warp};
use std::f64::consts::PI;

/// The smallest fuzz `mis` treats by its density; a metal of smaller fuzz is a mirror to it (a
/// specular bounce, sampled by its own directions alone). Below it the unit direction's rounding
/// (about 1e-16 of its angle) is no longer small against the cone's angle `f`: at fuzz 1e-12 one
/// direction the book draws in 300 reads as outside the cone, where the density is 0, and the path
/// would end. At 1e-4 and above fewer than one in a million do (`tests/review_round2.rs`).
pub const MIN_FUZZ: f64 = 1e-4;

/// The fuzzy metal's lobe about the mirror direction, cut off below the surface.
#[derive(Clone, Copy, Debug)]
pub struct FuzzyMetalPdf {
    /// The unit mirror direction `r`.
    pub reflected: Vec3,
    /// The fuzz `f > 0`.
    pub fuzz: f64,
    /// The surface's unit normal on the side the ray came from.
    pub normal: Vec3,
}

impl FuzzyMetalPdf {
    /// The lobe of a ray arriving along `incoming` at a surface of unit normal `normal` (facing the ray).
    #[inline]
    pub fn new(incoming: Vec3, normal: Vec3, fuzz: f64) -> FuzzyMetalPdf {
        FuzzyMetalPdf {
            reflected: crate::vec::reflect(incoming, normal).normalize(),
            fuzz,
            normal,
        }
    }

    /// `p(omega)` of the lobe over the whole sphere of directions (below the surface included).
    #[inline]
    pub fn lobe(&self, direction: Vec3) -> f64 {
        let f = self.fuzz;
        let c = direction.dot(self.reflected);
        // sin^2 theta as |omega x r|^2, not 1 - c^2: for the small angles of a small fuzz the
        // difference cancels to rounding (a direction the book drew read as outside its cone).
        let disc = f * f - direction.cross(self.reflected).length_squared();
        if disc <= 0.0 {
            return 0.0;
        }
        let q = disc.sqrt();
        let mut sum = 0.0;
        for d in [c + q, c - q] {
            if d > 0.0 {
                sum += d * d;
            }
        }
        sum / (4.0 * PI * f * q)
    }
}

impl Pdf for FuzzyMetalPdf {
    /// `p(omega)` above the surface, 0 below (where the metal absorbs).
    #[inline]
    fn pdf(&self, direction: Vec3) -> f64 {
        if direction.dot(self.normal) > 0.0 {
            self.lobe(direction)
        } else {
            0.0
        }
    }

    /// The book's direction `r + f s` (normalised); `None` where it points below the surface.
    #[inline]
    fn sample(&self, u: DVec2) -> Option<DirectionSample> {
        let d = self.reflected + self.fuzz * warp::sample_uniform_sphere(u);
        if d.dot(self.normal) <= 0.0 {
            return None;
        }
        let direction = d.try_normalize()?;
        let pdf = self.lobe(direction);
        (pdf > 0.0 && pdf.is_finite()).then_some(DirectionSample { direction, pdf })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_xoshiro::Xoshiro256PlusPlus;

    /// Per bin of `cos theta` about `r`: the share of the sampled directions against the share the
    /// density gives (a Monte Carlo integral over uniform directions), by a two-sample z-test on each
    /// bin's means (sample variances from the draws) at a family-wise false-failure rate of 1e-6
    /// (Bonferroni over the bins: |z| < 5.5).
    fn check(fuzz: f64, density: impl Fn(&FuzzyMetalPdf, Vec3) -> f64) -> bool {
        let normal = Vec3::Y;
        let incoming = Vec3::new(1.0, -0.4, 0.2).normalize();
        let pdf = FuzzyMetalPdf::new(incoming, normal, fuzz);
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(5);
        const BINS: usize = 16;
        let n = 400_000;
        // (sum, sum of squares) of each bin's indicator-weighted draws
        let mut expected = [(0.0, 0.0); BINS];
        let mut observed = [(0.0, 0.0); BINS];
        let bin = |c: f64| (((c + 1.0) / 2.0 * BINS as f64) as usize).min(BINS - 1);
        for _ in 0..n {
            let u = DVec2::new(rng.random(), rng.random());
            let w = warp::sample_uniform_sphere(u);
            let p = if w.dot(normal) > 0.0 {
                density(&pdf, w)
            } else {
                0.0
            };
            let e = &mut expected[bin(w.dot(pdf.reflected))];
            e.0 += p * 4.0 * PI;
            e.1 += (p * 4.0 * PI).powi(2);
            let u = DVec2::new(rng.random(), rng.random());
            if let Some(s) = pdf.sample(u) {
                assert!((s.pdf - pdf.pdf(s.direction)).abs() <= 1e-9 * s.pdf);
                let o = &mut observed[bin(s.direction.dot(pdf.reflected))];
                o.0 += 1.0;
                o.1 += 1.0;
            }
        }
        let n = n as f64;
        let mean_var = |(s, s2): (f64, f64)| (s / n, (s2 / n - (s / n).powi(2)).max(0.0) / n);
        (0..BINS).all(|b| {
            let ((me, ve), (mo, vo)) = (mean_var(expected[b]), mean_var(observed[b]));
            let se = (ve + vo).sqrt();
            // (a bin the lobe misses holds rounding residues of the roots, ~1e-30, and no samples)
            (me - mo).abs() <= 1e-12 || ((me - mo) / se).abs() < 5.5
        })
    }

    #[test]
    fn the_density_describes_the_books_directions() {
        for fuzz in [0.3, 0.7, 1.0, 1.6] {
            assert!(check(fuzz, FuzzyMetalPdf::pdf), "fuzz {fuzz}");
        }
    }

    #[test]
    fn a_cosine_lobe_is_wrong_except_at_fuzz_one() {
        let cosine = |p: &FuzzyMetalPdf, w: Vec3| w.dot(p.reflected).max(0.0) / PI;
        assert!(check(1.0, cosine));
        assert!(!check(0.5, cosine));
    }
}
