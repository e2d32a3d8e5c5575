//! Inverse transform sampling (book 3, chapter 3: "Constructing a PDF", "Choosing our samples",
//! "Approximating distributions").
//!
//! To draw `x` with density `p`, take the cumulative distribution `F(x) = ∫ p` and return
//! `x = F⁻¹(u)` for a uniform `u` in `[0, 1)`. This crate does that four ways:
//!
//! | when `F⁻¹` is | use | cost per sample |
//! |---|---|---|
//! | known in closed form | [`analytic`]: `sample`, `pdf`, `invert` side by side | O(1) |
//! | a table of `(x, F(x))` | [`TabulatedCdf`] (binary search) | O(log N) |
//! | a table, queried often | [`GuideTable`] (Chen-Asau index), [`EytzingerCdf`] (cache-friendly) | O(1) expected / O(log N) with fewer cache misses |
//! | only `F` (and maybe `p`) as code | [`numeric`]: bracketed Newton or Brent to a tolerance in `u` | O(iterations) |
//!
//! A discrete distribution is sampled in O(1) by an [`AliasTable`] (Vose); images and maps by a
//! [`PiecewiseConstant2D`] (a marginal over rows and a conditional per row).
//!
//! Every continuous sampler implements [`InverseTransform`] (sample, pdf, invert, in the manner of
//! pbrt-v4's `Sample*` / `*PDF` / `Invert*` triples) and rand's
//! [`Distribution`](rand::distr::Distribution), so it works with any `Rng`. The [`chi_square`]
//! module is the goodness-of-fit checker that tests every sampler against its own density.
//!
//! ```
//! use rtl_sampling::{InverseTransform, TabulatedCdf};
//! // The book's density p(x) = x/2 on [0, 2], tabulated in 64 bins and inverted by binary search.
//! let table = TabulatedCdf::from_density(|x| x / 2.0, 0.0, 2.0, 64).unwrap();
//! let s = table.sample(0.25);
//! assert!((s.x - 1.0).abs() < 1e-3); // F(1) = 1/4
//! assert!((table.invert(s.x) - 0.25).abs() < 1e-12);
//! ```

pub mod alias;
pub mod analytic;
pub mod chi_square;
mod error;
pub mod eytzinger;
pub mod guide;
pub mod numeric;
pub mod piecewise2d;
mod quadrature;
pub mod tabulated;
pub mod targets;

pub use alias::{AliasPiecewise, AliasTable};
pub use error::SamplingError;
pub use eytzinger::EytzingerCdf;
pub use guide::GuideTable;
pub use numeric::{Inversion, NumericInverse};
pub use piecewise2d::PiecewiseConstant2D;
pub use quadrature::integrate;
pub use tabulated::TabulatedCdf;

/// The largest `f64` below 1, `1 - 2⁻⁵³`: every `u` is clamped to `[0, ONE_MINUS_EPSILON]`, the
/// range of `rng.random::<f64>()`.
pub const ONE_MINUS_EPSILON: f64 = 1.0 - f64::EPSILON / 2.0;

/// A sample `x` together with its density `p(x)` (with respect to length on the real line).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// The point drawn.
    pub x: f64,
    /// Its density `p(x)`, per unit length.
    pub pdf: f64,
}

/// A one-dimensional density sampled by inverting its CDF: `sample(u) = F⁻¹(u)`, with the density
/// and the inverse map next to it, so that `invert(sample(u).x) = u`.
pub trait InverseTransform {
    /// `x = F⁻¹(u)` for `u` in `[0, 1)` and its density `p(x)`.
    fn sample(&self, u: f64) -> Sample;
    /// The density `p(x)` (0 outside the support).
    fn pdf(&self, x: f64) -> f64;
    /// `u = F(x)`: the inverse of [`sample`](Self::sample).
    fn invert(&self, x: f64) -> f64;
}

/// Clamps `u` into `[0, ONE_MINUS_EPSILON]`; NaN becomes 0. Keeps every table index in range.
// `f64::clamp` would keep a NaN; `max` then `min` turns it into 0.
#[allow(clippy::manual_clamp)]
#[inline(always)]
pub(crate) fn clamp_u(u: f64) -> f64 {
    u.max(0.0).min(ONE_MINUS_EPSILON)
}

/// Implements rand's `Distribution<f64>` for an [`InverseTransform`]: one uniform `u` per sample.
macro_rules! distribution_by_inversion {
    ($($t:ty),* $(,)?) => {$(
        impl rand::distr::Distribution<f64> for $t {
            fn sample<R: rand::Rng + ?Sized>(&self, rng: &mut R) -> f64 {
                <$t as $crate::InverseTransform>::sample(self, rng.random::<f64>()).x
            }
        }
    )*};
}
pub(crate) use distribution_by_inversion;
