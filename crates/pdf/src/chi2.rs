//! A chi-square goodness-of-fit test for samplers of directions, in the manner of pbrt-v4's and
//! Mitsuba 3's sampler tests.
//!
//! The samples are binned in a parametrisation of the sampler's own domain by the unit square (a
//! [`Domain`]): `(phi, cos theta)` for the sphere and hemisphere, the same inside a cone, the `(s, t)`
//! of a parallelogram. The expected count of a cell is `N` times the integral over the cell of
//! `pdf(direction(x)) * |d omega / dx|`, by adaptive Gauss-Legendre quadrature that refines cells
//! where the density jumps (at least 16 x 16 points a cell). Cells that the caller's support test
//! says lie wholly outside the support expect exactly 0 samples, and a single sample there fails the
//! test outright. The statistic itself, with cells expecting fewer than 5 pooled and the p-value from
//! the chi-square distribution (statrs), is `rtl_sampling::chi_square`'s, shared by every crate.
//! Callers reject below a Sidak-corrected significance level ([`sidak_alpha`]), so a run of many
//! tests keeps an overall false-failure rate of `alpha`.

use crate::{Onb, warp};
use glam::{DVec2, DVec3};
pub use rtl_sampling::chi_square::sidak_alpha;
use rtl_sampling::chi_square::{ChiSquareError, chi_square};
use std::f64::consts::{PI, TAU};

// ANCHOR: domain
/// A parametrisation of a set of directions by the unit square, used to bin samples.
pub trait Domain {
    /// The point of the unit square of `direction` (a unit vector), or `None` if it is outside the
    /// domain.
    fn to_square(&self, direction: DVec3) -> Option<DVec2>;
    /// The unit direction at `x` in the unit square.
    fn direction_at(&self, x: DVec2) -> DVec3;
    /// `|d omega / dx|`: steradians per unit area of the square at `x`.
    fn jacobian(&self, x: DVec2) -> f64;
}
// ANCHOR_END: domain

fn cos_theta_phi(frame: &Onb, direction: DVec3) -> (f64, f64) {
    let l = frame.to_local(direction);
    let phi = l.y.atan2(l.x) / TAU;
    let phi = if phi < 0.0 { phi + 1.0 } else { phi };
    (l.z, if phi >= 1.0 { 0.0 } else { phi })
}

fn from_cos_phi(frame: &Onb, cos_theta: f64, phi_turns: f64) -> DVec3 {
    let sin_theta = ((1.0 - cos_theta) * (1.0 + cos_theta)).max(0.0).sqrt();
    let (s, c) = (TAU * phi_turns).sin_cos();
    frame.transform(DVec3::new(sin_theta * c, sin_theta * s, cos_theta))
}

/// The whole sphere in a frame: `x = phi / 2 pi`, `y = (1 + cos theta) / 2`; `d omega = 4 pi dx dy`.
/// The horizon of the frame's `w` is the line `y = 1/2`.
#[derive(Clone, Copy, Debug)]
pub struct SphereDomain(pub Onb);

impl Domain for SphereDomain {
    fn to_square(&self, direction: DVec3) -> Option<DVec2> {
        let (c, phi) = cos_theta_phi(&self.0, direction);
        Some(DVec2::new(phi, ((1.0 + c) / 2.0).clamp(0.0, 1.0)))
    }
    fn direction_at(&self, x: DVec2) -> DVec3 {
        from_cos_phi(&self.0, 2.0 * x.y - 1.0, x.x)
    }
    fn jacobian(&self, _x: DVec2) -> f64 {
        4.0 * PI
    }
}

/// The hemisphere about a frame's `w`: `x = phi / 2 pi`, `y = cos theta`; `d omega = 2 pi dx dy`.
#[derive(Clone, Copy, Debug)]
pub struct HemisphereDomain(pub Onb);

impl Domain for HemisphereDomain {
    fn to_square(&self, direction: DVec3) -> Option<DVec2> {
        let (c, phi) = cos_theta_phi(&self.0, direction);
        (c >= 0.0).then(|| DVec2::new(phi, c.min(1.0)))
    }
    fn direction_at(&self, x: DVec2) -> DVec3 {
        from_cos_phi(&self.0, x.y, x.x)
    }
    fn jacobian(&self, _x: DVec2) -> f64 {
        TAU
    }
}

/// The cone about a frame's `w` with `1 - cos theta <= one_minus_cos_max`: `x = phi / 2 pi`,
/// `y = (1 - cos theta) / (1 - cos theta_max)`; `d omega = 2 pi (1 - cos theta_max) dx dy`.
#[derive(Clone, Copy, Debug)]
pub struct ConeDomain {
    pub frame: Onb,
    pub one_minus_cos_max: f64,
}

impl Domain for ConeDomain {
    fn to_square(&self, direction: DVec3) -> Option<DVec2> {
        let l = self.frame.to_local(direction);
        let y = warp::one_minus_cos_theta(l) / self.one_minus_cos_max;
        let (_, phi) = cos_theta_phi(&self.frame, direction);
        (y <= 1.0).then(|| DVec2::new(phi, y))
    }
    fn direction_at(&self, x: DVec2) -> DVec3 {
        self.frame.transform(warp::sample_uniform_cone(
            DVec2::new(x.y, x.x),
            self.one_minus_cos_max,
        ))
    }
    fn jacobian(&self, _x: DVec2) -> f64 {
        TAU * self.one_minus_cos_max
    }
}

/// The directions from `origin` through the parallelogram `q + s e1 + t e2`: `x = (s, t)`;
/// `d omega = |e1 x e2| |cos theta_light| / d^2 dx`.
#[derive(Clone, Copy, Debug)]
pub struct ParallelogramDomain {
    pub origin: DVec3,
    pub q: DVec3,
    pub e1: DVec3,
    pub e2: DVec3,
}

impl Domain for ParallelogramDomain {
    fn to_square(&self, direction: DVec3) -> Option<DVec2> {
        let n = self.e1.cross(self.e2);
        let t = n.dot(self.q - self.origin) / n.dot(direction);
        if !(t > 0.0 && t.is_finite()) {
            return None;
        }
        let st = warp::invert_parallelogram_sample(
            self.origin + t * direction,
            self.q,
            self.e1,
            self.e2,
        );
        // allow rounding right at the edges
        let tol = 1e-9;
        ((-tol..=1.0 + tol).contains(&st.x) && (-tol..=1.0 + tol).contains(&st.y))
            .then(|| st.clamp(DVec2::ZERO, DVec2::ONE))
    }
    fn direction_at(&self, x: DVec2) -> DVec3 {
        (warp::sample_parallelogram(x, self.q, self.e1, self.e2) - self.origin).normalize()
    }
    fn jacobian(&self, x: DVec2) -> f64 {
        let n = self.e1.cross(self.e2);
        let to = warp::sample_parallelogram(x, self.q, self.e1, self.e2) - self.origin;
        let d2 = to.length_squared();
        n.dot(to).abs() / (d2 * d2.sqrt())
    }
}

/// The outcome of a chi-square test.
#[derive(Clone, Debug)]
pub struct Chi2Report {
    /// `sum (observed - expected)^2 / expected` over the cells after pooling.
    pub statistic: f64,
    /// Degrees of freedom: cells after pooling, minus 1.
    pub dof: usize,
    /// The probability of a statistic at least this large if the sampler is right.
    pub p_value: f64,
    /// The sum of the expected counts over `N`: the pdf's integral over the domain (1 if the domain
    /// holds its whole support).
    pub expected_fraction: f64,
    /// How many cells went into the pool of small expectations.
    pub pooled: usize,
}

/// Why a chi-square test failed outright, before any p-value.
#[derive(Clone, Debug, thiserror::Error)]
pub enum Chi2Failure {
    /// A sample fell outside the domain (where the caller said the sampler cannot go).
    #[error("chi-square: sample {direction} lies outside the domain")]
    OutsideDomain { direction: DVec3 },
    /// A sample fell in a cell that lies wholly outside the density's support.
    #[error("chi-square: sample {direction} in cell {cell:?}, which lies outside the support")]
    OutsideSupport {
        cell: (usize, usize),
        direction: DVec3,
    },
    /// The density was negative or not finite at this direction.
    #[error("chi-square: the density at {direction} is {value}")]
    BadDensity { direction: DVec3, value: f64 },
    /// A sample was not a finite unit vector.
    #[error("chi-square: sample {direction} is not a finite unit vector")]
    NotUnit { direction: DVec3 },
    /// Too few cells with enough expectation to test anything.
    #[error("chi-square: too few cells with enough expected samples to test anything")]
    NoDegreesOfFreedom,
    /// The counts were refused by the statistic (a bug in the caller).
    #[error("chi-square: {0}")]
    Statistic(ChiSquareError),
}

// 4-point Gauss-Legendre nodes and weights on [-1, 1].
const GL_X: [f64; 4] = [
    -0.861_136_311_594_052_6,
    -0.339_981_043_584_856_3,
    0.339_981_043_584_856_3,
    0.861_136_311_594_052_6,
];
const GL_W: [f64; 4] = [
    0.347_854_845_137_453_9,
    0.652_145_154_862_546_1,
    0.652_145_154_862_546_1,
    0.347_854_845_137_453_9,
];

/// The binning and quadrature settings.
#[derive(Clone, Copy, Debug)]
pub struct ChiSquareTest {
    /// cells along x (phi, or s)
    pub nx: usize,
    /// cells along y (cos theta, or t)
    pub ny: usize,
    /// every cell is split `2^min_depth` ways each way before adaptivity (2: 16 x 16 points a cell)
    pub min_depth: u32,
    /// deepest adaptive split
    pub max_depth: u32,
}

impl Default for ChiSquareTest {
    fn default() -> Self {
        ChiSquareTest {
            nx: 20,
            ny: 20,
            min_depth: 2,
            max_depth: 7,
        }
    }
}

struct Integrand<'a, D: Domain, F: Fn(DVec3) -> f64> {
    domain: &'a D,
    density: &'a F,
    bad: Option<(DVec3, f64)>,
}

impl<D: Domain, F: Fn(DVec3) -> f64> Integrand<'_, D, F> {
    fn gauss(&mut self, lo: DVec2, hi: DVec2) -> f64 {
        let half = (hi - lo) / 2.0;
        let mid = (hi + lo) / 2.0;
        let mut sum = 0.0;
        for (i, xi) in GL_X.iter().enumerate() {
            for (j, yj) in GL_X.iter().enumerate() {
                let x = mid + half * DVec2::new(*xi, *yj);
                let d = self.domain.direction_at(x);
                let v = (self.density)(d);
                if !(v >= 0.0 && v.is_finite()) {
                    self.bad.get_or_insert((d, v));
                    continue;
                }
                sum += GL_W[i] * GL_W[j] * v * self.domain.jacobian(x);
            }
        }
        sum * half.x * half.y
    }

    fn quadrants(lo: DVec2, hi: DVec2) -> [(DVec2, DVec2); 4] {
        let m = (lo + hi) / 2.0;
        [
            (lo, m),
            (DVec2::new(m.x, lo.y), DVec2::new(hi.x, m.y)),
            (DVec2::new(lo.x, m.y), DVec2::new(m.x, hi.y)),
            (m, hi),
        ]
    }

    /// Adaptive: compare one rule on the cell with the sum over its quadrants; split where they differ.
    fn adaptive(&mut self, lo: DVec2, hi: DVec2, tol: f64, depth: u32, cfg: &ChiSquareTest) -> f64 {
        if depth < cfg.min_depth {
            return Self::quadrants(lo, hi)
                .iter()
                .map(|&(a, b)| self.adaptive(a, b, tol / 4.0, depth + 1, cfg))
                .sum();
        }
        let coarse = self.gauss(lo, hi);
        let parts = Self::quadrants(lo, hi);
        let total: f64 = parts.iter().map(|&(a, b)| self.gauss(a, b)).sum();
        if depth >= cfg.max_depth || (total - coarse).abs() <= tol {
            return total;
        }
        parts
            .iter()
            .map(|&(a, b)| self.adaptive(a, b, tol / 4.0, depth + 1, cfg))
            .sum()
    }
}

impl ChiSquareTest {
    /// A test with `nx` by `ny` cells and the default pooling and quadrature.
    pub fn new(nx: usize, ny: usize) -> ChiSquareTest {
        ChiSquareTest {
            nx,
            ny,
            ..Default::default()
        }
    }

    /// The expected probability of each cell (row-major, `y * nx + x`) for `density` in `domain`;
    /// cells for which `in_support(lo, hi)` is false are exactly 0. `n` sets the quadrature tolerance
    /// (a thousandth of a sample per cell).
    pub fn expected<D: Domain>(
        &self,
        domain: &D,
        density: impl Fn(DVec3) -> f64,
        in_support: impl Fn(DVec2, DVec2) -> bool,
        n: usize,
    ) -> Result<Vec<f64>, Chi2Failure> {
        let mut integrand = Integrand {
            domain,
            density: &density,
            bad: None,
        };
        let mut probs = vec![0.0; self.nx * self.ny];
        let size = DVec2::new(1.0 / self.nx as f64, 1.0 / self.ny as f64);
        for iy in 0..self.ny {
            for ix in 0..self.nx {
                let lo = DVec2::new(ix as f64, iy as f64) * size;
                let hi = lo + size;
                if in_support(lo, hi) {
                    probs[iy * self.nx + ix] = integrand.adaptive(lo, hi, 1e-3 / n as f64, 0, self);
                }
            }
        }
        if let Some((direction, value)) = integrand.bad {
            return Err(Chi2Failure::BadDensity { direction, value });
        }
        Ok(probs)
    }

    /// Draws `n` samples and tests them against `density`.
    pub fn run<D: Domain>(
        &self,
        domain: &D,
        density: impl Fn(DVec3) -> f64,
        in_support: impl Fn(DVec2, DVec2) -> bool,
        n: usize,
        mut sample: impl FnMut() -> DVec3,
    ) -> Result<Chi2Report, Chi2Failure> {
        let probs = self.expected(domain, &density, &in_support, n)?;
        let mut observed = vec![0u64; probs.len()];
        for _ in 0..n {
            let d = sample();
            if !(d.is_finite() && (d.length() - 1.0).abs() < 1e-9) {
                return Err(Chi2Failure::NotUnit { direction: d });
            }
            let Some(x) = domain.to_square(d) else {
                return Err(Chi2Failure::OutsideDomain { direction: d });
            };
            let ix = ((x.x * self.nx as f64) as usize).min(self.nx - 1);
            let iy = ((x.y * self.ny as f64) as usize).min(self.ny - 1);
            let cell = iy * self.nx + ix;
            if probs[cell] == 0.0 {
                return Err(Chi2Failure::OutsideSupport {
                    cell: (ix, iy),
                    direction: d,
                });
            }
            observed[cell] += 1;
        }
        let expected: Vec<f64> = probs.iter().map(|p| p * n as f64).collect();
        self.statistic(&observed, &expected, n)
    }

    /// The statistic and p-value of `observed` against `expected` counts: the pooling and the
    /// p-value are [`rtl_sampling::chi_square::chi_square`]'s (cells expecting fewer than 5 pooled,
    /// smallest first, until the pool expects at least 5).
    pub fn statistic(
        &self,
        observed: &[u64],
        expected: &[f64],
        n: usize,
    ) -> Result<Chi2Report, Chi2Failure> {
        let observed: Vec<f64> = observed.iter().map(|&o| o as f64).collect();
        let result = chi_square(&observed, expected).map_err(|e| match e {
            ChiSquareError::TooFewCells { .. } => Chi2Failure::NoDegreesOfFreedom,
            other => Chi2Failure::Statistic(other),
        })?;
        Ok(Chi2Report {
            statistic: result.statistic,
            dof: result.dof,
            p_value: result.p_value,
            expected_fraction: expected.iter().sum::<f64>() / n as f64,
            pooled: result.pooled,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn statistic_of_a_perfect_fit_is_zero_and_pools_small_cells() {
        let t = ChiSquareTest::new(2, 2);
        let r = t
            .statistic(&[50, 50, 3, 3], &[50.0, 50.0, 3.0, 3.0], 106)
            .unwrap();
        assert_eq!(r.statistic, 0.0);
        assert_eq!((r.dof, r.pooled), (2, 2)); // two cells + one pool of two
        assert!((r.p_value - 1.0).abs() < 1e-12);
    }

    #[test]
    fn quadrature_integrates_the_sphere_to_one() {
        let t = ChiSquareTest::new(7, 9);
        let p = t
            .expected(
                &SphereDomain(Onb::new(DVec3::Z)),
                |_| 1.0 / (4.0 * PI),
                |_, _| true,
                100_000,
            )
            .unwrap();
        assert!((p.iter().sum::<f64>() - 1.0).abs() < 1e-12);
    }
}
