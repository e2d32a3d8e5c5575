//! Running statistics: mean and variance in one pass, mergeable, with standard error and confidence
//! intervals.

use crate::McError;
use statrs::distribution::{ContinuousCDF, Normal, StudentsT};

// ANCHOR: running_stats
/// Count, mean and sum of squared deviations `M2 = sum (x_i - mean)^2` of a stream of values, updated
/// one value at a time by Welford's method (Welford 1962, as in Knuth TAOCP vol. 2, 4.2.2).
///
/// The naive `sum x^2 / n - mean^2` subtracts two huge, nearly equal numbers when the values sit far
/// from zero (1e9 + small noise) and loses every digit of the variance; Welford's update only ever
/// handles deviations from the running mean. Two partial statistics merge exactly by the parallel
/// formula of Chan, Golub and LeVeque (1979), so threads can each keep their own and combine at the end.
///
/// The mean and `M2` are kept in units of a power of two `scale` no smaller than half the largest
/// `|x|` seen (rescaling by a power of two is exact), so values near `f64::MAX` neither overflow a
/// deviation nor the sum of squares, and subnormal values keep their variance: the results are those
/// of the plain update wherever it does not overflow or underflow. Values must be finite (a NaN or an
/// infinity makes the statistics NaN; the estimators refuse them before they get here). The mean is
/// always finite; a variance beyond `f64::MAX` is `+inf`, while the standard error (its square root
/// over `n`) stays finite whenever it fits.
///
/// ```
/// use rtl_mc::RunningStats;
/// let mut s = RunningStats::new();
/// for x in [2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0] {
///     s.push(x);
/// }
/// assert_eq!(s.mean(), 5.0);
/// assert_eq!(s.variance(), Some(32.0 / 7.0)); // the sample variance, divided by n - 1
/// ```
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct RunningStats {
    count: u64,
    /// The mean, in units of `scale`.
    mean: f64,
    /// `M2`, in units of `scale^2`.
    m2: f64,
    /// A power of two with every `|x| < 2 scale`; 0 while every value is 0.
    scale: f64,
}

/// The largest power of two `<= x`, for finite `x > 0` (subnormals included).
#[inline]
fn power_of_two_below(x: f64) -> f64 {
    let bits = x.to_bits();
    if bits >> 52 == 0 {
        // subnormal: keep the highest set bit of the significand
        f64::from_bits(1u64 << (63 - bits.leading_zeros()))
    } else {
        f64::from_bits(bits & (0x7ff << 52))
    }
}

impl RunningStats {
    /// No values yet.
    pub const fn new() -> Self {
        Self {
            count: 0,
            mean: 0.0,
            m2: 0.0,
            scale: 0.0,
        }
    }

    /// The same statistics in units of the power of two `scale >= self.scale` (exact unless the
    /// smaller parts underflow, where they are negligible).
    #[inline]
    fn rescaled(&self, scale: f64) -> Self {
        if self.scale == scale {
            return *self;
        }
        let r = self.scale / scale; // a power of two <= 1, or 0
        Self {
            count: self.count,
            mean: self.mean * r,
            m2: self.m2 * r * r,
            scale,
        }
    }

    /// Adds one value: `mean += (x - mean) / n`, `M2 += (x - mean_old)(x - mean_new)` (in units of
    /// `scale`, grown first if `|x|` needs it).
    #[inline]
    pub fn push(&mut self, x: f64) {
        let ax = x.abs();
        if ax >= 2.0 * self.scale && ax > 0.0 && ax.is_finite() {
            *self = self.rescaled(power_of_two_below(ax));
        }
        let x = if self.scale > 0.0 { x / self.scale } else { x };
        self.count += 1;
        let delta = x - self.mean;
        self.mean += delta / self.count as f64;
        self.m2 += delta * (x - self.mean);
    }

    /// Combines two partial statistics as if all their values had been pushed into one (Chan et al.):
    /// with `d = mean_b - mean_a` and `n = n_a + n_b`,
    /// `mean = mean_a + d n_b / n` and `M2 = M2_a + M2_b + d^2 n_a n_b / n`.
    pub fn merge(&self, other: &Self) -> Self {
        if self.count == 0 {
            return *other;
        }
        if other.count == 0 {
            return *self;
        }
        let scale = self.scale.max(other.scale);
        let (a, b) = (self.rescaled(scale), other.rescaled(scale));
        let count = a.count + b.count;
        let (na, nb, n) = (a.count as f64, b.count as f64, count as f64);
        let delta = b.mean - a.mean;
        Self {
            count,
            mean: a.mean + delta * (nb / n),
            m2: a.m2 + b.m2 + delta * delta * (na * nb / n),
            scale,
        }
    }
    // ANCHOR_END: running_stats

    /// `scale`, or 1 while every value is 0.
    #[inline]
    fn unit(&self) -> f64 {
        if self.scale > 0.0 { self.scale } else { 1.0 }
    }

    /// How many values were pushed.
    pub fn count(&self) -> u64 {
        self.count
    }

    /// The sample mean (0 before any value).
    pub fn mean(&self) -> f64 {
        self.mean * self.unit()
    }

    /// The unbiased sample variance `M2 / (n - 1)`; `None` with fewer than two values, `+inf` if it
    /// exceeds `f64::MAX` (values near `±1e308`).
    pub fn variance(&self) -> Option<f64> {
        (self.count >= 2).then(|| self.m2 / (self.count - 1) as f64 * self.unit() * self.unit())
    }

    /// The standard error of the mean, `sqrt(variance / n)`; `None` with fewer than two values.
    /// Computed in units of `scale`, so it is finite whenever it fits in an `f64`, even where the
    /// variance does not.
    pub fn std_error(&self) -> Option<f64> {
        (self.count >= 2)
            .then(|| (self.m2 / (self.count - 1) as f64 / self.count as f64).sqrt() * self.unit())
    }

    // ANCHOR: confidence_interval
    /// A two-sided confidence interval for the true mean at `level` (0.95 for 95%):
    /// `mean -/+ t * std_error`, where `t` is the `(1 + level) / 2` quantile of Student's t with `n - 1`
    /// degrees of freedom (from statrs). That is exact for normally distributed values and tends to the
    /// normal quantile (1.96 at 95%) as `n` grows, so it is also right for large samples of any
    /// distribution with finite variance (central limit theorem).
    pub fn confidence_interval(&self, level: f64) -> Result<(f64, f64), McError> {
        if !(level > 0.0 && level < 1.0) {
            return Err(McError::BadLevel { level });
        }
        let se = self
            .std_error()
            .ok_or(McError::TooFewValues { count: self.count })?;
        // The upper quantile from the tail (1 - level) / 2, which does not round to 0 for levels
        // within 2^-53 of 1, where (1 + level) / 2 would round to 1 and t to infinity (and a
        // standard error of 0 times an infinite t to NaN).
        let t = -student_t_quantile((1.0 - level) / 2.0, self.count - 1);
        let mean = self.mean();
        // An interval wider than f64::MAX has infinite ends, never NaN ones.
        let half = if se == 0.0 { 0.0 } else { t * se };
        Ok((mean - half, mean + half))
    }
    // ANCHOR_END: confidence_interval
}

/// The `p` quantile of Student's t distribution with `dof` degrees of freedom: the `t` with
/// `P(T <= t) = p`. `dof = 0` is taken as 1 (the widest t there is), so no argument panics or hangs;
/// `p` outside `[0, 1]` (or NaN) gives NaN, `p = 0` and `p = 1` give `-inf` and `+inf`.
///
/// statrs' `StudentsT::inverse_cdf` alone is not enough: it inverts `x = nu / (nu + t^2)` and takes
/// `t = sqrt(nu (1 - x) / x)`, where `1 - x` cancels for many degrees of freedom (at `p = 0.025` it
/// is 1.2e-4 off at `dof = 10^6` and gives -1.83 at `10^7`, where the answer is -1.95996), it did
/// not return within minutes from `dof = 10^8` on (a confidence interval over 10^8 samples), and far
/// in the tails it is wrong (-9.2e7 both at `p = 1e-150` with one degree of freedom, where the answer
/// is -3.2e149, and at `p = 1e-30` with three, where it is -1.0e10) or panics (below about 1e-180).
/// So, with `q = min(p, 1 - p)` (the lower tail; `1 - p` is exact for `p >= 1/2`) and the result
/// mirrored for `p > 1/2`:
///
/// * 1 and 2 degrees of freedom in closed form: `t = -cot(pi q)` (Cauchy) and
///   `t = -(1 - 2q) / sqrt(2 q (1 - q))`;
/// * up to 10^4 degrees of freedom and `q >= 1e-20`, statrs' inverse, which is
///   accurate there (its CDF at the result is `q` to 1e-12 relative);
/// * more degrees of freedom, as long as `z^2 <= nu / 40` (`z` the normal quantile of `q`): the
///   Cornish-Fisher expansion of Abramowitz and Stegun 26.7.5 in four terms,
///   `t = z + g1(z)/nu + g2(z)/nu^2 + g3(z)/nu^3 + g4(z)/nu^4` (the last term kept is at most
///   4e-10 of `t` there, and the expansion's error, against mpmath, under 1e-12 relative);
/// * anywhere else (a tail below 1e-20 with at most 10^4 degrees of freedom, or one too deep for
///   the expansion), bisection of statrs' CDF over the bits of `|t|`: 63 steps, each a CDF
///   evaluation (checked against mpmath's incomplete beta function: `F(t) = q` to 1e-12).
pub fn student_t_quantile(p: f64, dof: u64) -> f64 {
    if !(0.0..=1.0).contains(&p) {
        return f64::NAN; // statrs would panic
    }
    if p == 0.0 {
        return f64::NEG_INFINITY;
    }
    if p == 1.0 {
        return f64::INFINITY;
    }
    let (q, sign) = if p > 0.5 { (1.0 - p, 1.0) } else { (p, -1.0) };
    if q == 0.5 {
        return 0.0;
    }
    sign * lower_tail_magnitude(q, dof.max(1))
}

/// The most degrees of freedom for which [`student_t_quantile`] asks statrs' inverse (at 10^4 it
/// agrees with the Cornish-Fisher expansion to 1e-13; at 3 10^4 it is 3e-7 off at `p = 0.025`).
const STATRS_MAX_DOF: u64 = 10_000;

/// `|t|` for the lower-tail probability `q` in `(0, 1/2)` and `nu >= 1` degrees of freedom.
fn lower_tail_magnitude(q: f64, nu: u64) -> f64 {
    use std::f64::consts::PI;
    match nu {
        // Cauchy: F(t) = 1/2 + atan(t) / pi, so t = tan(pi (q - 1/2)) = -cot(pi q)
        1 => (PI * q).cos() / (PI * q).sin(),
        // F(t) = 1/2 + t / (2 sqrt(t^2 + 2))
        2 => (1.0 - 2.0 * q) / (2.0 * q * (1.0 - q)).sqrt(),
        _ => {
            let n = nu as f64;
            if nu <= STATRS_MAX_DOF && q >= 1e-20 {
                return -StudentsT::new(0.0, 1.0, n)
                    .expect("location 0, scale 1 and dof >= 3 are valid parameters")
                    .inverse_cdf(q);
            }
            if nu > STATRS_MAX_DOF {
                let z = Normal::standard().inverse_cdf(q);
                let z2 = z * z;
                if z2 <= n / 40.0 {
                    return -cornish_fisher(z, n);
                }
            }
            bisect_cdf(q, n)
        }
    }
}

/// Abramowitz and Stegun 26.7.5: the `t` quantile from the normal quantile `z` of the same
/// probability, in powers of `1 / nu`.
fn cornish_fisher(z: f64, nu: f64) -> f64 {
    let z2 = z * z;
    let g1 = z * (z2 + 1.0) / 4.0;
    let g2 = z * ((5.0 * z2 + 16.0) * z2 + 3.0) / 96.0;
    let g3 = z * (((3.0 * z2 + 19.0) * z2 + 17.0) * z2 - 15.0) / 384.0;
    let g4 = z * ((((79.0 * z2 + 776.0) * z2 + 1482.0) * z2 - 1920.0) * z2 - 945.0) / 92160.0;
    z + (g1 + (g2 + (g3 + g4 / nu) / nu) / nu) / nu
}

/// `|t|` with `F(-|t|) = q` by bisection over the bit patterns of non-negative `f64`s (which are
/// ordered as integers): 63 steps between 0 (`F = 1/2 > q`) and `f64::MAX`, each a CDF evaluation.
fn bisect_cdf(q: f64, nu: f64) -> f64 {
    let t = StudentsT::new(0.0, 1.0, nu).expect("location 0, scale 1 and dof >= 1 are valid");
    // invariant: F(-lo) > q >= F(-hi)
    let (mut lo, mut hi) = (0u64, f64::MAX.to_bits());
    if t.cdf(-f64::MAX) > q {
        return f64::INFINITY; // q below the smallest tail probability an f64 can reach
    }
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if t.cdf(-f64::from_bits(mid)) > q {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    f64::from_bits(hi)
}
