//! A tabulated CDF inverted by binary search ("Approximating distributions").
//!
//! The table holds nodes `x₀ < x₁ < … < xₙ` and CDF values `0 = F₀ ≤ F₁ ≤ … ≤ Fₙ = 1`, joined by
//! straight lines. A piecewise-linear CDF is a piecewise-constant density: bin `i` has density
//! `(Fᵢ₊₁ - Fᵢ) / (xᵢ₊₁ - xᵢ)` (pbrt-v4 calls this `PiecewiseConstant1D`). Sampling finds the bin
//! with `Fᵢ ≤ u < Fᵢ₊₁` by binary search, O(log N), and moves linearly inside it.
//!
//! Because the search asks for `Fᵢ ≤ u < Fᵢ₊₁`, a bin of zero probability (`Fᵢ = Fᵢ₊₁`) can never
//! be chosen, not at `u = 0`, not at `u = 1 - 2⁻⁵³`, not on a step of the CDF; and because the
//! `x` nodes increase strictly, no segment has zero width.

use crate::{InverseTransform, Sample, SamplingError, clamp_u, distribution_by_inversion};

/// A piecewise-linear CDF (piecewise-constant density) on `[x₀, xₙ]`, sampled by binary search.
#[derive(Clone, Debug, PartialEq)]
pub struct TabulatedCdf {
    /// `n + 1` nodes, strictly increasing.
    x: Vec<f64>,
    /// `n + 1` CDF values: `cdf[0] = 0`, `cdf[n] = 1` exactly, never decreasing.
    cdf: Vec<f64>,
}

impl TabulatedCdf {
    // ANCHOR: from_points
    /// The classic table of points `(xᵢ, F(xᵢ))`. `F` may be any running total (it need not start at
    /// 0 nor end at exactly 1): it is shifted and divided by `F(xₙ) - F(x₀)`, so the last entry is
    /// exactly 1. Errors name the first bad point: non-finite values, `x` not strictly increasing,
    /// `F` decreasing, or `F` constant.
    pub fn from_points(points: &[(f64, f64)]) -> Result<Self, SamplingError> {
        if points.len() < 2 {
            return Err(SamplingError::TooFew {
                what: "points",
                min: 2,
                got: points.len(),
            });
        }
        for (index, &(x, f)) in points.iter().enumerate() {
            if !x.is_finite() || !f.is_finite() {
                return Err(SamplingError::NonFinitePoint { index, x, f });
            }
            if index > 0 {
                let (prev_x, prev_f) = points[index - 1];
                if x <= prev_x {
                    return Err(SamplingError::NotIncreasing {
                        index,
                        prev: prev_x,
                        x,
                    });
                }
                if f < prev_f {
                    return Err(SamplingError::Decreasing {
                        index,
                        prev: prev_f,
                        f,
                    });
                }
            }
        }
        let (f0, fn_) = (points[0].1, points[points.len() - 1].1);
        if fn_ <= f0 {
            return Err(SamplingError::ZeroMass { f: f0 });
        }
        // Scaled by the largest |F| first, so that F - F₀ cannot overflow (F from -1e308 to 1e308):
        // the scaled values lie in [-1, 1] and their differences in [0, 2]. (F - F₀) / total is
        // monotone in F and gives exactly 0 and exactly 1 at the ends.
        let scale = f0.abs().max(fn_.abs());
        let (g0, total) = (f0 / scale, fn_ / scale - f0 / scale);
        let cdf = points
            .iter()
            .map(|&(_, f)| (f / scale - g0) / total)
            .collect();
        let x = points.iter().map(|&(x, _)| x).collect();
        let table = Self { x, cdf };
        table.check_densities()?;
        Ok(table)
    }
    // ANCHOR_END: from_points

    // ANCHOR: from_weights
    /// A piecewise-constant density with the given bin edges (strictly increasing, one more than
    /// the weights) and bin masses (finite, >= 0, not all 0). The masses are divided by the largest
    /// one (so that their sum cannot overflow, even for weights near `f64::MAX`), summed in `f64`
    /// with compensation (Neumaier) and divided by their total, so the last CDF entry is exactly 1.
    ///
    /// Every bin must be narrower than `f64::MAX` and every bin of positive probability must have a
    /// density `probability / width` that is a positive finite `f64`; otherwise an error names the
    /// bin, so a sample never carries a density of 0 or infinity.
    pub fn from_edges_and_weights(edges: &[f64], weights: &[f64]) -> Result<Self, SamplingError> {
        if weights.is_empty() {
            return Err(SamplingError::TooFew {
                what: "bins",
                min: 1,
                got: 0,
            });
        }
        if edges.len() != weights.len() + 1 {
            return Err(SamplingError::LengthMismatch {
                what: "edges",
                got: edges.len(),
                expected: weights.len() + 1,
            });
        }
        for (index, w) in edges.windows(2).enumerate() {
            if !w[0].is_finite() || !w[1].is_finite() {
                let bad = if w[0].is_finite() { index + 1 } else { index };
                return Err(SamplingError::NonFinitePoint {
                    index: bad,
                    x: edges[bad],
                    f: f64::NAN,
                });
            }
            if w[1] <= w[0] {
                return Err(SamplingError::NotIncreasing {
                    index: index + 1,
                    prev: w[0],
                    x: w[1],
                });
            }
        }
        let mut largest = 0.0f64;
        for (bin, &w) in weights.iter().enumerate() {
            if !(w.is_finite() && w >= 0.0) {
                return Err(SamplingError::BadWeight { bin, value: w });
            }
            largest = largest.max(w);
        }
        if largest == 0.0 {
            return Err(SamplingError::AllZero {
                bins: weights.len(),
            });
        }
        let mut cdf = Vec::with_capacity(weights.len() + 1);
        cdf.push(0.0);
        let (mut sum, mut carry) = (0.0f64, 0.0f64);
        for &w in weights {
            // In [0, 1] after scaling (exact for a power-of-two scale, correctly rounded otherwise).
            let w = w / largest;
            // Neumaier's compensated sum: `carry` keeps the low bits that `sum + w` rounds away.
            let t = sum + w;
            carry += if sum.abs() >= w {
                (sum - t) + w
            } else {
                (w - t) + sum
            };
            sum = t;
            cdf.push(sum + carry);
        }
        let total = cdf[weights.len()]; // >= 1: the largest weight scaled to 1 is in the sum
        for c in &mut cdf {
            *c /= total; // monotone, and total / total = 1 exactly
        }
        let table = Self {
            x: edges.to_vec(),
            cdf,
        };
        table.check_densities()?;
        Ok(table)
    }

    /// Every bin is narrower than `f64::MAX`, and every bin of positive probability has a density
    /// that is a positive finite `f64` (the first bin that is not is the error).
    fn check_densities(&self) -> Result<(), SamplingError> {
        for (bin, (x, c)) in self.x.windows(2).zip(self.cdf.windows(2)).enumerate() {
            let width = x[1] - x[0];
            if !width.is_finite() {
                return Err(SamplingError::WidthOverflow {
                    bin,
                    x0: x[0],
                    x1: x[1],
                });
            }
            let probability = c[1] - c[0];
            let density = probability / width;
            if probability > 0.0 && !(density > 0.0 && density.is_finite()) {
                return Err(SamplingError::DensityOutOfRange {
                    bin,
                    probability,
                    width,
                    density,
                });
            }
        }
        Ok(())
    }
    // ANCHOR_END: from_weights

    /// A piecewise-constant density on `[a, b]` with `weights.len()` equal bins.
    pub fn from_weights(a: f64, b: f64, weights: &[f64]) -> Result<Self, SamplingError> {
        Self::from_edges_and_weights(&equal_edges(a, b, weights.len())?, weights)
    }

    // ANCHOR: from_density
    /// Tabulates a density `p` on `[a, b]` in `n` equal bins: the mass of each bin is `∫ p` over it
    /// by 5-point Gauss-Legendre quadrature (which never evaluates the bin's ends). `p` need not be
    /// normalised. A negative or non-finite value of `p` is an error naming the bin and the `x`.
    pub fn from_density(
        p: impl Fn(f64) -> f64,
        a: f64,
        b: f64,
        n: usize,
    ) -> Result<Self, SamplingError> {
        let edges = equal_edges(a, b, n)?;
        // Where a sum or difference of edges overflows (a domain such as [-1e308, 1e308]), the
        // halves are taken first; elsewhere after, which is exact down to subnormal edges.
        let half = |s: f64, a: f64, b: f64| {
            if s.is_finite() {
                0.5 * s
            } else {
                0.5 * a + 0.5 * b
            }
        };
        let half_width = |e: &[f64]| half(e[1] - e[0], e[1], -e[0]);
        let widest = edges.windows(2).map(half_width).fold(0.0, f64::max);
        let mut weights = Vec::with_capacity(n);
        for (bin, e) in edges.windows(2).enumerate() {
            let (mid, half) = (half(e[0] + e[1], e[0], e[1]), half_width(e));
            let mut mass = 0.0;
            for (t, w) in crate::quadrature::GL5 {
                let x = (mid + half * t).clamp(e[0], e[1]);
                let value = p(x);
                if !(value.is_finite() && value >= 0.0) {
                    return Err(SamplingError::BadDensity { bin, x, value });
                }
                // The weights sum to 2, so a quarter of each term keeps the sum below f64::MAX
                // even for values near f64::MAX; the table only needs masses up to one factor.
                mass += w * (0.25 * value);
            }
            // The bins are equal up to rounding: their width relative to the widest (<= 1).
            weights.push(if widest > 0.0 {
                mass * (half / widest)
            } else {
                mass
            });
        }
        Self::from_edges_and_weights(&edges, &weights)
    }
    // ANCHOR_END: from_density

    /// The number of bins `n`.
    pub fn len(&self) -> usize {
        self.x.len() - 1
    }

    /// Never true: a table has at least one bin.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The support `[x₀, xₙ]`.
    pub fn domain(&self) -> (f64, f64) {
        (self.x[0], self.x[self.len()])
    }

    /// The nodes `x₀ … xₙ`.
    pub fn nodes(&self) -> &[f64] {
        &self.x
    }

    /// The CDF values `F₀ = 0 … Fₙ = 1` at the nodes.
    pub fn cdf_values(&self) -> &[f64] {
        &self.cdf
    }

    /// The probability of bin `i`, `Fᵢ₊₁ - Fᵢ`.
    pub fn bin_probability(&self, i: usize) -> f64 {
        self.cdf[i + 1] - self.cdf[i]
    }

    // ANCHOR: search
    /// The bin `i` with `Fᵢ ≤ u < Fᵢ₊₁`, for `u` in `[0, 1)`, by binary search: the number of
    /// interior CDF values `F₁ … Fₙ₋₁` that are `≤ u`. `Fₙ = 1 > u` need not be searched, so the
    /// result is always in `0..n` and its bin always has positive probability.
    #[inline]
    pub fn bin(&self, u: f64) -> usize {
        let n = self.len();
        self.cdf[1..n].partition_point(|&c| c <= u)
    }
    // ANCHOR_END: search

    /// The same bin as [`bin`](Self::bin), found by a linear scan from the left: O(N), the
    /// classic program's loop, kept for comparison in the study.
    pub fn bin_by_linear_scan(&self, u: f64) -> usize {
        let n = self.len();
        let mut i = 0;
        while i + 1 < n && self.cdf[i + 1] <= u {
            i += 1;
        }
        i
    }

    // ANCHOR: in_bin
    /// The sample for `u` inside bin `i` (which must satisfy `Fᵢ ≤ u < Fᵢ₊₁`): linear
    /// interpolation, `x = xᵢ + (xᵢ₊₁ - xᵢ) (u - Fᵢ) / (Fᵢ₊₁ - Fᵢ)`, and the bin's density
    /// `(Fᵢ₊₁ - Fᵢ) / (xᵢ₊₁ - xᵢ)`. Both divisors are positive by construction.
    #[inline]
    pub fn sample_in_bin(&self, i: usize, u: f64) -> Sample {
        let (c0, c1) = (self.cdf[i], self.cdf[i + 1]);
        let (x0, x1) = (self.x[i], self.x[i + 1]);
        let t = (u - c0) / (c1 - c0);
        Sample {
            x: (x0 + t * (x1 - x0)).min(x1.next_down()),
            pdf: (c1 - c0) / (x1 - x0),
        }
    }
    // ANCHOR_END: in_bin

    // ANCHOR: sample
    /// `x = F⁻¹(u)` and its density; `u` is clamped into `[0, 1 - 2⁻⁵³]` (NaN to 0). O(log N).
    #[inline]
    pub fn sample(&self, u: f64) -> Sample {
        let u = clamp_u(u);
        self.sample_in_bin(self.bin(u), u)
    }

    /// The checked inverse of the classic program: `F⁻¹(u)` for `u` in `[0, 1]`, and an error (not
    /// a panic, not a NaN) for any other `u`. `u = 1` gives the right end of the last bin of
    /// positive probability.
    pub fn quantile(&self, u: f64) -> Result<f64, SamplingError> {
        if !(0.0..=1.0).contains(&u) {
            return Err(SamplingError::OutsideRange {
                u,
                lo: 0.0,
                hi: 1.0,
            });
        }
        if u == 1.0 {
            return Ok(self.x[self.cdf.partition_point(|&c| c < 1.0)]);
        }
        Ok(self.sample(u).x)
    }
    // ANCHOR_END: sample

    /// The bin holding `x`: the number of interior nodes `≤ x` (so a node belongs to the bin on
    /// its right). `x` must lie in the support.
    #[inline]
    fn bin_of_x(&self, x: f64) -> usize {
        let n = self.len();
        self.x[1..n].partition_point(|&e| e <= x)
    }

    /// The density at `x`: the density of its bin, 0 outside `[x₀, xₙ]`.
    pub fn pdf(&self, x: f64) -> f64 {
        let (a, b) = self.domain();
        if !(a..=b).contains(&x) {
            return 0.0;
        }
        let i = self.bin_of_x(x);
        (self.cdf[i + 1] - self.cdf[i]) / (self.x[i + 1] - self.x[i])
    }

    /// `u = F(x)`, the tabulated (piecewise-linear) CDF; 0 left of the support, 1 right of it.
    pub fn invert(&self, x: f64) -> f64 {
        let (a, b) = self.domain();
        if x <= a || x.is_nan() {
            return 0.0;
        }
        if x >= b {
            return 1.0;
        }
        let i = self.bin_of_x(x);
        let (c0, c1) = (self.cdf[i], self.cdf[i + 1]);
        let (x0, x1) = (self.x[i], self.x[i + 1]);
        (c0 + (c1 - c0) * ((x - x0) / (x1 - x0))).min(c1)
    }
}

/// `n + 1` equal-spaced edges from `a` to exactly `b`; an error if they do not increase strictly.
pub(crate) fn equal_edges(a: f64, b: f64, n: usize) -> Result<Vec<f64>, SamplingError> {
    if !(a.is_finite() && b.is_finite() && a < b) {
        return Err(SamplingError::BadInterval { a, b });
    }
    if n == 0 {
        return Err(SamplingError::TooFew {
            what: "bins",
            min: 1,
            got: 0,
        });
    }
    // Refused before the edges are allocated (n = usize::MAX would overflow the capacity).
    if n > u32::MAX as usize {
        return Err(SamplingError::TooMany {
            what: "bins",
            got: n,
            max: u32::MAX as usize,
        });
    }
    let edges: Vec<f64> = (0..=n)
        .map(|i| {
            let t = i as f64 / n as f64;
            if i == n { b } else { (1.0 - t) * a + t * b }
        })
        .collect();
    for (index, w) in edges.windows(2).enumerate() {
        if w[1] <= w[0] {
            return Err(SamplingError::NotIncreasing {
                index: index + 1,
                prev: w[0],
                x: w[1],
            });
        }
    }
    Ok(edges)
}

impl InverseTransform for TabulatedCdf {
    fn sample(&self, u: f64) -> Sample {
        TabulatedCdf::sample(self, u)
    }
    fn pdf(&self, x: f64) -> f64 {
        TabulatedCdf::pdf(self, x)
    }
    fn invert(&self, x: f64) -> f64 {
        TabulatedCdf::invert(self, x)
    }
}
distribution_by_inversion!(TabulatedCdf);
