//! Target densities with closed-form CDFs, to measure how well a table or a numerical inverse
//! reproduces them: the book's `e^(-x/2π) sin² x` on `[0, 2π]`, a standard normal truncated to
//! `[-8, 8]`, and a hard case, a narrow spike on a broad base.
//!
//! The exact quantile `F⁻¹(u)` is found by bracketed Newton on the closed-form `F` to the last
//! bit floating point allows.

use crate::numeric::NumericInverse;
use std::f64::consts::{PI, SQRT_2, TAU};

/// A normalised density on a finite interval with its exact CDF.
pub trait TargetDensity {
    /// A short name for tables and file names.
    fn name(&self) -> &'static str;
    /// The support `[a, b]`.
    fn domain(&self) -> (f64, f64);
    /// The density, normalised to integrate to 1 over the domain.
    fn density(&self, x: f64) -> f64;
    /// The exact CDF, `∫ₐˣ density`.
    fn cdf(&self, x: f64) -> f64;

    /// The exact quantile `F⁻¹(u)` for `u` in `[0, 1]`, to full precision (clamped `u`).
    fn quantile(&self, u: f64) -> f64 {
        let (a, b) = self.domain();
        let inv = NumericInverse::with_density(|x| self.cdf(x), |x| self.density(x), a, b)
            .and_then(|i| i.with_tolerance(0.0))
            .expect("a target's domain and CDF are valid");
        let (lo, hi) = inv.range();
        inv.invert(u.clamp(lo, hi))
            .expect("a target's CDF is finite")
            .x
    }
}

// ANCHOR: book_density
/// The book's density for "Approximating distributions": `e^(-x/2π) sin² x` on `[0, 2π]`,
/// normalised. Writing `a = 1/2π` and `sin² x = (1 - cos 2x)/2`, its integral is elementary:
///
/// `G(x) = (1 - e^(-ax)) / 2a - [a + e^(-ax) (2 sin 2x - a cos 2x)] / (2 (a² + 4))`,
///
/// and `F = G / G(2π)`. The density touches zero at 0, π and 2π (`sin² x ≈ (x - π)²`), where `F`
/// is locally cubic.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BookSinSquared;

impl BookSinSquared {
    const A: f64 = 1.0 / TAU;

    /// The unnormalised integral `G(x) = ∫₀ˣ e^(-t/2π) sin² t dt`.
    pub fn integral(x: f64) -> f64 {
        let a = Self::A;
        let e = (-a * x).exp();
        let first = -(-a * x).exp_m1() / (2.0 * a);
        let second =
            (a + e * (2.0 * (2.0 * x).sin() - a * (2.0 * x).cos())) / (2.0 * (a * a + 4.0));
        first - second
    }

    /// The unnormalised density `e^(-x/2π) sin² x`.
    pub fn unnormalised(x: f64) -> f64 {
        (-x / TAU).exp() * x.sin().powi(2)
    }
}

impl TargetDensity for BookSinSquared {
    fn name(&self) -> &'static str {
        "book_sin2"
    }
    fn domain(&self) -> (f64, f64) {
        (0.0, TAU)
    }
    fn density(&self, x: f64) -> f64 {
        if (0.0..=TAU).contains(&x) {
            Self::unnormalised(x) / Self::integral(TAU)
        } else {
            0.0
        }
    }
    fn cdf(&self, x: f64) -> f64 {
        (Self::integral(x.clamp(0.0, TAU)) / Self::integral(TAU)).clamp(0.0, 1.0)
    }
}
// ANCHOR_END: book_density

/// The complementary error function to about 1e-16 absolute (statrs' `erfc` errs by 1e-11 near
/// `z = 0.7`, which would swamp the u-errors this study measures). For `|z| < 3` the series
/// `erf z = (2/√π) e^(-z²) Σ 2ⁿ z^(2n+1) / (1·3·…·(2n+1))`, whose terms are all positive; beyond,
/// the continued fraction `erfc z = (e^(-z²)/√π) / (z + (1/2)/(z + 1/(z + (3/2)/(z + …))))`.
pub fn erfc(z: f64) -> f64 {
    if z < 0.0 {
        return 2.0 - erfc(-z);
    }
    if z < 3.0 {
        let (mut term, mut sum) = (z, z);
        let mut n = 0.0;
        while term > 1e-17 * sum {
            n += 1.0;
            term *= 2.0 * z * z / (2.0 * n + 1.0);
            sum += term;
        }
        1.0 - 2.0 / PI.sqrt() * (-z * z).exp() * sum
    } else {
        let mut f = z;
        for n in (1..=60).rev() {
            f = z + 0.5 * n as f64 / f;
        }
        (-z * z).exp() / PI.sqrt() / f
    }
}

/// The standard normal cumulative distribution `Φ(x) = erfc(-x/√2) / 2`.
fn phi_cdf(x: f64) -> f64 {
    0.5 * erfc(-x / SQRT_2)
}

/// The standard normal density.
fn phi(x: f64) -> f64 {
    (-0.5 * x * x).exp() / (2.0 * PI).sqrt()
}

/// The standard normal truncated to `[-8, 8]` (it drops `1.2e-15` of the mass).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TruncatedNormal;

impl TruncatedNormal {
    const R: f64 = 8.0;
    fn mass() -> f64 {
        phi_cdf(Self::R) - phi_cdf(-Self::R)
    }
}

impl TargetDensity for TruncatedNormal {
    fn name(&self) -> &'static str {
        "normal"
    }
    fn domain(&self) -> (f64, f64) {
        (-Self::R, Self::R)
    }
    fn density(&self, x: f64) -> f64 {
        if x.abs() <= Self::R {
            phi(x) / Self::mass()
        } else {
            0.0
        }
    }
    fn cdf(&self, x: f64) -> f64 {
        let x = x.clamp(-Self::R, Self::R);
        ((phi_cdf(x) - phi_cdf(-Self::R)) / Self::mass()).clamp(0.0, 1.0)
    }
}

/// A narrow spike on a broad base on `[0, 1]`: half the mass uniform, half a normal of standard
/// deviation `10⁻³` at `x = 0.3`. Coarse tables miss the spike entirely.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SpikeOnBase;

impl SpikeOnBase {
    const MU: f64 = 0.3;
    const SIGMA: f64 = 1e-3;
    const BASE: f64 = 0.5;
    fn spike_mass() -> f64 {
        phi_cdf((1.0 - Self::MU) / Self::SIGMA) - phi_cdf(-Self::MU / Self::SIGMA)
    }
}

impl TargetDensity for SpikeOnBase {
    fn name(&self) -> &'static str {
        "spike"
    }
    fn domain(&self) -> (f64, f64) {
        (0.0, 1.0)
    }
    fn density(&self, x: f64) -> f64 {
        if (0.0..=1.0).contains(&x) {
            let z = (x - Self::MU) / Self::SIGMA;
            Self::BASE + (1.0 - Self::BASE) * phi(z) / (Self::SIGMA * Self::spike_mass())
        } else {
            0.0
        }
    }
    fn cdf(&self, x: f64) -> f64 {
        let x = x.clamp(0.0, 1.0);
        let spike = (phi_cdf((x - Self::MU) / Self::SIGMA) - phi_cdf(-Self::MU / Self::SIGMA))
            / Self::spike_mass();
        (Self::BASE * x + (1.0 - Self::BASE) * spike).clamp(0.0, 1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate;

    #[test]
    fn erfc_matches_reference_values() {
        // erfc at 0.5, 1, 2, 3, 5 (Abramowitz and Stegun; Wolfram Alpha to 17 digits).
        for (z, e) in [
            (0.5, 0.479_500_122_186_953_5),
            (1.0, 0.157_299_207_050_285_13),
            (2.0, 4.677_734_981_047_266e-3),
            (3.0, 2.209_049_699_858_544e-5),
            (5.0, 1.537_459_794_428_035e-12),
        ] {
            assert!(
                (erfc(z) - e).abs() <= 2.5e-16,
                "erfc({z}) = {} vs {e}",
                erfc(z)
            );
            assert!((erfc(-z) - (2.0 - e)).abs() <= 5e-16); // one ulp in [1, 2]
        }
    }

    fn check(t: &dyn TargetDensity) {
        let (a, b) = t.domain();
        assert_eq!(t.cdf(a), 0.0, "{}", t.name());
        assert!((t.cdf(b) - 1.0).abs() < 1e-15, "{}", t.name());
        // The closed-form CDF agrees with quadrature of the density.
        for k in 1..20 {
            let x = a + (b - a) * k as f64 / 20.0;
            let q = integrate(|s| t.density(s), a, x, 4000);
            assert!(
                (q - t.cdf(x)).abs() < 1e-10,
                "{} at {x}: {q} vs {}",
                t.name(),
                t.cdf(x)
            );
        }
        for k in 0..=100 {
            let u = k as f64 / 100.0;
            let x = t.quantile(u);
            // As close as floats allow: F moves by about p(x) ulp(x) between neighbouring x.
            let ulp = x.abs().max(f64::MIN_POSITIVE).next_up() - x.abs();
            let best = 4.0 * f64::EPSILON + 2.0 * t.density(x) * ulp;
            assert!((t.cdf(x) - u).abs() <= best, "{} at {u}", t.name());
        }
    }

    #[test]
    fn exact_cdfs_agree_with_quadrature_and_quantiles_invert_them() {
        check(&BookSinSquared);
        check(&TruncatedNormal);
        check(&SpikeOnBase);
    }
}
