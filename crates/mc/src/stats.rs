//! Running statistics: mean and variance in one pass, mergeable, with standard error and confidence
//! intervals.

use crate::McError;
use statrs::distribution::{ContinuousCDF, StudentsT};

// ANCHOR: running_stats
/// Count, mean and sum of squared deviations `M2 = sum (x_i - mean)^2` of a stream of values, updated
/// one value at a time by Welford's method (Welford 1962, as in Knuth TAOCP vol. 2, 4.2.2).
///
/// The naive `sum x^2 / n - mean^2` subtracts two huge, nearly equal numbers when the values sit far
/// from zero (1e9 + small noise) and loses every digit of the variance; Welford's update only ever
/// handles deviations from the running mean. Two partial statistics merge exactly by the parallel
/// formula of Chan, Golub and LeVeque (1979), so threads can each keep their own and combine at the end.
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
    mean: f64,
    m2: f64,
}

impl RunningStats {
    /// No values yet.
    pub const fn new() -> Self {
        Self {
            count: 0,
            mean: 0.0,
            m2: 0.0,
        }
    }

    /// Adds one value: `mean += (x - mean) / n`, `M2 += (x - mean_old)(x - mean_new)`.
    #[inline]
    pub fn push(&mut self, x: f64) {
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
        let count = self.count + other.count;
        let (na, nb, n) = (self.count as f64, other.count as f64, count as f64);
        let delta = other.mean - self.mean;
        Self {
            count,
            mean: self.mean + delta * (nb / n),
            m2: self.m2 + other.m2 + delta * delta * (na * nb / n),
        }
    }
    // ANCHOR_END: running_stats

    /// How many values were pushed.
    pub fn count(&self) -> u64 {
        self.count
    }

    /// The sample mean (0 before any value).
    pub fn mean(&self) -> f64 {
        self.mean
    }

    /// The unbiased sample variance `M2 / (n - 1)`; `None` with fewer than two values.
    pub fn variance(&self) -> Option<f64> {
        (self.count >= 2).then(|| self.m2 / (self.count - 1) as f64)
    }

    /// The standard error of the mean, `sqrt(variance / n)`; `None` with fewer than two values.
    pub fn std_error(&self) -> Option<f64> {
        self.variance().map(|v| (v / self.count as f64).sqrt())
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
        let t = student_t_quantile(0.5 + level / 2.0, self.count - 1);
        Ok((self.mean - t * se, self.mean + t * se))
    }
    // ANCHOR_END: confidence_interval
}

/// The `p` quantile of Student's t distribution with `dof >= 1` degrees of freedom.
pub fn student_t_quantile(p: f64, dof: u64) -> f64 {
    StudentsT::new(0.0, 1.0, dof as f64)
        .expect("location 0, scale 1 and dof >= 1 are valid parameters")
        .inverse_cdf(p)
}
