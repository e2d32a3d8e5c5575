//! What can go wrong when estimating an integral, named with the place it went wrong.

use thiserror::Error;

/// A clear error instead of a panic or a silent NaN estimate.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum McError {
    /// An interval `[a, b]` needs finite ends with `a < b`.
    #[error("empty or invalid interval [{a}, {b}]: need finite a < b")]
    EmptyInterval { a: f64, b: f64 },
    /// An interval wider than the largest `f64`: its length, the `1 / p` of uniform sampling, is not
    /// a number.
    #[error("interval [{a:?}, {b:?}] is wider than f64::MAX ({max:e}): b - a overflows", max = f64::MAX)]
    IntervalTooWide { a: f64, b: f64 },
    /// A rectangle whose area overflows.
    #[error(
        "rectangle of sides {width:e} x {height:e} has an area beyond f64::MAX ({max:e})",
        max = f64::MAX
    )]
    AreaTooLarge { width: f64, height: f64 },
    /// A sample or a replicate estimate, finite factors, overflows: `(b - a) f(x)`, say, beyond
    /// `f64::MAX`. The integral itself (or the sample's share of it) is not an `f64`.
    #[error("{estimator}: {what} overflows f64 (beyond {max:e}) at {at}", max = f64::MAX)]
    Overflow {
        estimator: &'static str,
        what: &'static str,
        at: String,
    },
    /// More samples than a `u64` counts (`nx * ny * replicates`).
    #[error("{estimator}: {what} samples is more than a u64 counts ({max})", max = u64::MAX)]
    TooManySamples {
        estimator: &'static str,
        what: String,
    },
    /// An estimator was asked for zero samples (or zero strata, or zero Sobol points).
    #[error("{estimator}: asked for 0 samples; need at least 1")]
    NoSamples { estimator: &'static str },
    /// Stratified and quasi-Monte Carlo estimators take their standard error from independent
    /// replicates, so they need at least two.
    #[error("{estimator}: {replicates} replicate(s); need at least 2 for a standard error")]
    TooFewReplicates {
        estimator: &'static str,
        replicates: u32,
    },
    /// The integrand returned NaN or an infinity.
    #[error("{estimator}: the integrand (or f/p) is {value} at {at}")]
    NonFiniteIntegrand {
        estimator: &'static str,
        at: String,
        value: f64,
    },
    /// The sampler produced a point where its own pdf is 0 but the integrand is not: f/p is undefined,
    /// and the pdf cannot be the density of that sampler.
    #[error(
        "{estimator}: pdf is 0 at {at} where the integrand is {value}; the sampler and its pdf disagree"
    )]
    ZeroPdf {
        estimator: &'static str,
        at: String,
        value: f64,
    },
    /// A pdf value must be finite and non-negative.
    #[error("{estimator}: pdf returned {pdf} at {at}; a density must be finite and >= 0")]
    InvalidPdf {
        estimator: &'static str,
        at: String,
        pdf: f64,
    },
    /// A confidence level must lie strictly between 0 and 1.
    #[error("confidence level {level} is not in (0, 1)")]
    BadLevel { level: f64 },
    /// A variance (and so a standard error or an interval) needs at least two values.
    #[error("a standard error needs at least 2 values; have {count}")]
    TooFewValues { count: u64 },
    /// The scrambled Sobol sequence holds 2^32 points per replicate.
    #[error("{estimator}: {points} points per replicate exceed the Sobol sequence's 2^32")]
    TooManyPoints {
        estimator: &'static str,
        points: u64,
    },
}
