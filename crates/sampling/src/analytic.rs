//! Densities whose CDF can be inverted on paper: the book's worked examples on `[0, 2]` and the
//! exponential. Each sampler sits next to its density and its inverse, as pbrt-v4 keeps
//! `SampleLinear`, `LinearPDF` and `InvertLinearSample` together:
//!
//! * `pdf(x)`: the density `p(x)` with respect to length,
//! * `sample(u)`: `x = F⁻¹(u)` where `F(x) = ∫ p`, for `u` uniform in `[0, 1)`,
//! * `invert(x)`: `u = F(x)`, so that `invert(sample(u).x) = u` (up to rounding).
//!
//! ```
//! use rtl_sampling::analytic::Linear;
//! // The book's "Choosing our samples": p(r) = r/2, F(r) = r²/4, so r = F⁻¹(d) = sqrt(4d).
//! let s = Linear.sample(0.25);
//! assert_eq!(s.x, 1.0);
//! assert_eq!(s.pdf, 0.5);
//! assert_eq!(Linear.invert(1.0), 0.25);
//! ```

use crate::{InverseTransform, Sample, SamplingError, clamp_u, distribution_by_inversion};

/// Implements [`InverseTransform`] by the type's own (inherent) `sample`, `pdf` and `invert`.
macro_rules! inverse_transform_by_inherent {
    ($($t:ty),*) => {$(
        impl InverseTransform for $t {
            fn sample(&self, u: f64) -> Sample { <$t>::sample(self, u) }
            fn pdf(&self, x: f64) -> f64 { <$t>::pdf(self, x) }
            fn invert(&self, x: f64) -> f64 { <$t>::invert(self, x) }
        }
    )*};
}

// ANCHOR: uniform
/// The uniform density on `[a, b]`: `p(x) = 1 / (b - a)`, `F(x) = (x - a) / (b - a)`.
/// The book's first estimator uses it on `[0, 2]`, where `p = 1/2` and `F⁻¹(u) = 2u`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Uniform {
    pub a: f64,
    pub b: f64,
}

impl Uniform {
    /// `[a, b]`, checked: finite `a < b`, and a width whose density `1 / (b - a)` is a positive
    /// finite `f64` (widths beyond `f64::MAX`, as `[-1e308, 1e308]`, are fine; widths below
    /// `1 / f64::MAX`, about `5.6e-309`, are not). The fields may also be set directly, unchecked.
    pub fn new(a: f64, b: f64) -> Result<Self, SamplingError> {
        if !(a.is_finite() && b.is_finite() && a < b) {
            return Err(SamplingError::BadInterval { a, b });
        }
        let u = Self { a, b };
        let density = u.density();
        if !(density > 0.0 && density.is_finite()) {
            return Err(SamplingError::DensityOutOfRange {
                bin: 0,
                probability: 1.0,
                width: b - a,
                density,
            });
        }
        Ok(u)
    }

    /// `1 / (b - a)`, by halves where `b - a` overflows.
    #[inline]
    fn density(&self) -> f64 {
        let w = self.b - self.a;
        if w.is_finite() {
            1.0 / w
        } else {
            0.5 / (0.5 * self.b - 0.5 * self.a)
        }
    }

    /// `p(x) = 1 / (b - a)` per unit length on `[a, b]`, 0 outside.
    pub fn pdf(&self, x: f64) -> f64 {
        if (self.a..=self.b).contains(&x) {
            self.density()
        } else {
            0.0
        }
    }
    /// `x = F⁻¹(u) = (1 - u) a + u b` (exact at both ends) and `p(x)`.
    pub fn sample(&self, u: f64) -> Sample {
        let u = clamp_u(u);
        let x = (1.0 - u) * self.a + u * self.b;
        Sample {
            x,
            pdf: self.density(),
        }
    }
    /// `u = F(x) = (x - a) / (b - a)`, clamped into `[0, 1]`.
    pub fn invert(&self, x: f64) -> f64 {
        let w = self.b - self.a;
        let t = if w.is_finite() {
            (x - self.a) / w
        } else {
            (0.5 * x - 0.5 * self.a) / (0.5 * self.b - 0.5 * self.a)
        };
        t.clamp(0.0, 1.0)
    }
}
// ANCHOR_END: uniform

// ANCHOR: linear
/// The book's `p(x) = x/2` on `[0, 2]` ("Constructing a PDF"): `F(x) = x²/4`, so
/// `F⁻¹(u) = sqrt(4u) = 2 sqrt(u)`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Linear;

impl Linear {
    /// `p(x) = x / 2` per unit length on `[0, 2]`, 0 outside.
    pub fn pdf(&self, x: f64) -> f64 {
        if (0.0..=2.0).contains(&x) {
            x / 2.0
        } else {
            0.0
        }
    }
    /// `x = F⁻¹(u) = 2 sqrt(u)` and `p(x) = x / 2`.
    pub fn sample(&self, u: f64) -> Sample {
        // u = 0 would give x = 0, where the density is 0 and f(x)/p(x) is 0/0: the smallest normal u
        // instead (still within the first of the 2^53 equal steps of u).
        let x = 2.0 * clamp_u(u).max(f64::MIN_POSITIVE).sqrt();
        Sample { x, pdf: x / 2.0 }
    }
    /// `u = F(x) = x² / 4`, clamped into `[0, 1]`.
    pub fn invert(&self, x: f64) -> f64 {
        (x * x / 4.0).clamp(0.0, 1.0)
    }
}
// ANCHOR_END: linear

// ANCHOR: quadratic
/// The book's `p(x) = 3x²/8` on `[0, 2]`, the perfect importance density for `∫₀² x² dx`:
/// `F(x) = x³/8`, so `F⁻¹(u) = (8u)^(1/3) = 2 ∛u`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Quadratic;

impl Quadratic {
    /// `p(x) = 3x² / 8` per unit length on `[0, 2]`, 0 outside.
    pub fn pdf(&self, x: f64) -> f64 {
        if (0.0..=2.0).contains(&x) {
            3.0 * x * x / 8.0
        } else {
            0.0
        }
    }
    /// `x = F⁻¹(u) = 2 ∛u` and `p(x) = 3x² / 8`.
    pub fn sample(&self, u: f64) -> Sample {
        // As for `Linear`: never x = 0, where the density is 0.
        let x = 2.0 * clamp_u(u).max(f64::MIN_POSITIVE).cbrt();
        Sample {
            x,
            pdf: 3.0 * x * x / 8.0,
        }
    }
    /// `u = F(x) = x³ / 8`, clamped into `[0, 1]`.
    pub fn invert(&self, x: f64) -> f64 {
        (x * x * x / 8.0).clamp(0.0, 1.0)
    }
}
// ANCHOR_END: quadratic

// ANCHOR: exponential
/// The exponential density `p(x) = λ e^(-λx)` on `[0, ∞)`: `F(x) = 1 - e^(-λx)`, so
/// `F⁻¹(u) = -ln(1 - u) / λ`. `ln_1p` and `exp_m1` keep full precision for small `u` and `x`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Exponential {
    /// The rate `λ > 0`.
    pub rate: f64,
}

impl Exponential {
    /// The smallest rate [`Exponential::new`] accepts: below about `2e-307` the sample for
    /// `u = 1 - 2⁻⁵³`, `36.7 / λ`, overflows.
    pub const MIN_RATE: f64 = 1e-306;

    /// The exponential density of `rate`, checked: in `[MIN_RATE, f64::MAX]`, where every sample is
    /// finite and carries a positive finite density. The field may also be set directly, unchecked.
    pub fn new(rate: f64) -> Result<Self, SamplingError> {
        if (Self::MIN_RATE..=f64::MAX).contains(&rate) {
            Ok(Self { rate })
        } else {
            Err(SamplingError::OutOfRange {
                what: "rate",
                value: rate,
                min: Self::MIN_RATE,
                max: f64::MAX,
            })
        }
    }

    /// `p(x) = λ e^(-λx)` per unit length for `x >= 0`, 0 for `x < 0`.
    pub fn pdf(&self, x: f64) -> f64 {
        if x >= 0.0 {
            self.rate * (-self.rate * x).exp()
        } else {
            0.0
        }
    }
    /// `x = F⁻¹(u) = -ln(1 - u) / λ` and `p(x)`.
    pub fn sample(&self, u: f64) -> Sample {
        let x = -(-clamp_u(u)).ln_1p() / self.rate;
        Sample {
            x,
            pdf: self.pdf(x),
        }
    }
    /// `u = F(x) = 1 - e^(-λx)`; 0 for `x <= 0`.
    pub fn invert(&self, x: f64) -> f64 {
        if x <= 0.0 {
            0.0
        } else {
            -(-self.rate * x).exp_m1()
        }
    }
}
// ANCHOR_END: exponential

inverse_transform_by_inherent!(Uniform, Linear, Quadratic, Exponential);
distribution_by_inversion!(Uniform, Linear, Quadratic, Exponential);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ONE_MINUS_EPSILON;

    fn round_trip(s: &dyn InverseTransform, name: &str) {
        for k in 0..=1000 {
            let u = (k as f64 / 1000.0).min(ONE_MINUS_EPSILON);
            let back = s.invert(s.sample(u).x);
            assert!(
                (back - u).abs() <= 4.0 * f64::EPSILON,
                "{name}: u = {u} came back as {back}"
            );
        }
    }

    #[test]
    fn round_trips_return_u() {
        round_trip(&Uniform { a: 0.0, b: 2.0 }, "uniform");
        round_trip(&Linear, "linear");
        round_trip(&Quadratic, "quadratic");
        round_trip(&Exponential { rate: 1.5 }, "exponential");
    }

    #[test]
    fn samples_at_the_ends_of_u_stay_in_the_support() {
        for u in [0.0, ONE_MINUS_EPSILON, 1.0, -0.5, f64::NAN] {
            for (name, s, hi) in [
                ("linear", Linear.sample(u), 2.0),
                ("quadratic", Quadratic.sample(u), 2.0),
                ("uniform", Uniform { a: 0.0, b: 2.0 }.sample(u), 2.0),
                ("exponential", Exponential { rate: 1.0 }.sample(u), 40.0),
            ] {
                assert!(
                    s.x >= 0.0 && s.x <= hi && s.pdf.is_finite() && s.pdf > 0.0,
                    "{name} at u = {u}: {s:?}"
                );
            }
        }
    }

    #[test]
    fn the_book_inverses_match_the_book_formulas() {
        // "Choosing our samples": f(d) = sqrt(4d); the perfect density: f(d) = (8d)^(1/3).
        for d in [0.1, 0.3, 0.7, 0.9] {
            assert!((Linear.sample(d).x - (4.0f64 * d).sqrt()).abs() < 1e-15);
            assert!((Quadratic.sample(d).x - (8.0f64 * d).cbrt()).abs() < 1e-15);
        }
    }
}
