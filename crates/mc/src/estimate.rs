//! Plain and importance-sampled Monte Carlo estimators, and the [`Estimate`] every estimator returns.

use crate::{Interval, McError, Rect, RunningStats};
use rand::Rng;
use std::fmt::Debug;
use std::time::{Duration, Instant};

/// The result of an estimator: running statistics over its independent units, how many times the
/// integrand was evaluated, and how long it took.
///
/// For plain and importance sampling each sample is a unit, so `stats` holds the `N` values `f(x)/p(x)`.
/// Stratified and quasi-Monte Carlo samples are not independent of each other, so those estimators run
/// `R` independent replicates and `stats` holds the `R` replicate estimates: the mean is the same, and
/// the spread of the replicates gives an honest standard error.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimate {
    /// Statistics over the independent units (samples or replicates).
    pub stats: RunningStats,
    /// Evaluations of the integrand.
    pub samples: u64,
    /// Wall-clock time of the estimator.
    pub elapsed: Duration,
}

impl Estimate {
    /// The estimate of the integral.
    pub fn value(&self) -> f64 {
        self.stats.mean()
    }

    /// Its standard error; `None` from a single unit.
    pub fn std_error(&self) -> Option<f64> {
        self.stats.std_error()
    }

    /// A confidence interval at `level` (Student's t over the units; see
    /// [`RunningStats::confidence_interval`]).
    pub fn confidence_interval(&self, level: f64) -> Result<(f64, f64), McError> {
        self.stats.confidence_interval(level)
    }

    /// Nanoseconds per integrand evaluation, all costs included.
    pub fn ns_per_sample(&self) -> f64 {
        self.elapsed.as_secs_f64() * 1e9 / self.samples.max(1) as f64
    }

    /// One line for the examples' output: the estimate beside the `exact` value, its standard error
    /// and the time it took.
    pub fn report(&self, label: &str, exact: f64) -> String {
        let se = match self.std_error() {
            Some(se) => format!("{se:.3e}"),
            None => "n/a (1 unit)".to_string(),
        };
        format!(
            "{label:<26} N = {:>9}  estimate = {:.9}  exact = {exact:.9}  std error = {se:>9}  time = {:.3} ms",
            self.samples,
            self.value(),
            self.elapsed.as_secs_f64() * 1e3
        )
    }
}

/// `Ok(v)` if `v` is finite, otherwise the error naming the estimator and the point.
#[inline]
pub(crate) fn finite<T: Debug>(estimator: &'static str, at: T, value: f64) -> Result<f64, McError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(McError::NonFiniteIntegrand {
            estimator,
            at: format!("{at:?}"),
            value,
        })
    }
}

/// `factor * value` (both finite), or [`McError::Overflow`] naming `what` overflowed and where.
#[inline]
pub(crate) fn product<T: Debug>(
    estimator: &'static str,
    what: &'static str,
    at: T,
    factor: f64,
    value: f64,
) -> Result<f64, McError> {
    let p = factor * value;
    if p.is_finite() {
        Ok(p)
    } else {
        Err(McError::Overflow {
            estimator,
            what,
            at: format!("{at:?}"),
        })
    }
}

/// `a * b * c` sample counts, or [`McError::TooManySamples`].
pub(crate) fn sample_count(
    estimator: &'static str,
    a: u64,
    b: u64,
    c: u64,
) -> Result<u64, McError> {
    a.checked_mul(b)
        .and_then(|ab| ab.checked_mul(c))
        .ok_or_else(|| McError::TooManySamples {
            estimator,
            what: format!("{a} x {b} x {c}"),
        })
}

pub(crate) fn nonzero(estimator: &'static str, n: u64) -> Result<(), McError> {
    if n == 0 {
        Err(McError::NoSamples { estimator })
    } else {
        Ok(())
    }
}

// ANCHOR: plain
/// Plain Monte Carlo: `(b - a) f(x)` with `x` uniform on `[a, b]`, averaged over `n` samples.
/// Its expected value is the integral of `f` over `[a, b]`; its standard error falls as `1/sqrt(n)`.
///
/// ```
/// use rtl_mc::{Interval, plain};
/// use rand::SeedableRng;
/// let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(1);
/// let est = plain(|x| x * x, Interval::new(0.0, 2.0)?, 100_000, &mut rng)?;
/// assert!((est.value() - 8.0 / 3.0).abs() < 6.0 * est.std_error().unwrap());
/// Ok::<(), rtl_mc::McError>(()) // what `?` above returns into
/// ```
pub fn plain<F, R>(f: F, domain: Interval, n: u64, rng: &mut R) -> Result<Estimate, McError>
where
    F: Fn(f64) -> f64,
    R: Rng + ?Sized,
{
    nonzero("plain", n)?;
    let start = Instant::now();
    let mut stats = RunningStats::new();
    for _ in 0..n {
        let x = domain.lerp(rng.random::<f64>());
        let fx = finite("plain", x, f(x))?;
        stats.push(product("plain", "(b - a) f(x)", x, domain.length(), fx)?);
    }
    Ok(Estimate {
        stats,
        samples: n,
        elapsed: start.elapsed(),
    })
}
// ANCHOR_END: plain

/// Plain Monte Carlo over a rectangle: `area * f(x, y)` with `(x, y)` uniform on it.
pub fn plain_2d<F, R>(f: F, domain: Rect, n: u64, rng: &mut R) -> Result<Estimate, McError>
where
    F: Fn([f64; 2]) -> f64,
    R: Rng + ?Sized,
{
    nonzero("plain_2d", n)?;
    let area = domain.checked_area()?;
    let start = Instant::now();
    let mut stats = RunningStats::new();
    for _ in 0..n {
        let p = domain.lerp(rng.random::<f64>(), rng.random::<f64>());
        let fp = finite("plain_2d", p, f(p))?;
        stats.push(product("plain_2d", "area f(x, y)", p, area, fp)?);
    }
    Ok(Estimate {
        stats,
        samples: n,
        elapsed: start.elapsed(),
    })
}

// ANCHOR: importance
/// Importance sampling: `f(x) / p(x)` with `x` drawn by `sample` from the density `pdf`, averaged over
/// `n` samples. Unbiased for the integral of `f` wherever `p > 0` covers `f != 0`, whatever the domain
/// (an interval, the sphere of directions, ...); the closer `p` is to proportional to `f`, the smaller
/// the variance, down to zero for `p = f / integral`.
///
/// A sample where `p(x) = 0` contributes 0 if `f(x) = 0` (it carries no weight either way), and is
/// an error ([`McError::ZeroPdf`]) otherwise: the sampler and its pdf disagree. A NaN, infinite or
/// negative pdf value is an error too, so no NaN can reach the estimate.
pub fn importance<T, F, S, P, R>(
    f: F,
    mut sample: S,
    pdf: P,
    n: u64,
    rng: &mut R,
) -> Result<Estimate, McError>
where
    T: Copy + Debug,
    F: Fn(T) -> f64,
    S: FnMut(&mut R) -> T,
    P: Fn(T) -> f64,
    R: Rng + ?Sized,
{
    const NAME: &str = "importance";
    nonzero(NAME, n)?;
    let start = Instant::now();
    let mut stats = RunningStats::new();
    for _ in 0..n {
        let x = sample(rng);
        let fx = finite(NAME, x, f(x))?;
        let p = pdf(x);
        let weighted = if p > 0.0 && p.is_finite() {
            fx / p
        } else if p == 0.0 && fx == 0.0 {
            0.0
        } else if p == 0.0 {
            let at = format!("{x:?}");
            return Err(McError::ZeroPdf {
                estimator: NAME,
                at,
                value: fx,
            });
        } else {
            let at = format!("{x:?}");
            return Err(McError::InvalidPdf {
                estimator: NAME,
                at,
                pdf: p,
            });
        };
        stats.push(finite(NAME, x, weighted)?);
    }
    Ok(Estimate {
        stats,
        samples: n,
        elapsed: start.elapsed(),
    })
}
// ANCHOR_END: importance
