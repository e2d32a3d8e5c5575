//! The alias method (Walker 1977, in the numerically careful form of Vose 1991): O(1) sampling of a
//! discrete distribution.
//!
//! Scale the probabilities so that they average 1 per bin. Repeatedly pair a bin below 1 with one
//! above 1: the small bin keeps its own share `q` of a unit column, and the rest of the column is
//! lent to the large one, its "alias". Sampling picks a column uniformly and flips a coin with
//! probability `q`: one multiply, one load, one comparison, whatever the number of bins.
//!
//! The method is not an inversion (neighbouring `u` do not give neighbouring bins), so it has no
//! `invert`: stratified or low-discrepancy `u` lose their structure through it.

use crate::{ONE_MINUS_EPSILON, Sample, SamplingError, clamp_u, tabulated::equal_edges};

/// One column: keep bin `i` with probability `q`, otherwise return `alias`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Column {
    q: f64,
    alias: u32,
}

/// Vose's alias table over bins `0..n` with probabilities proportional to the weights (a
/// probability mass function: no density, no measure but counting).
///
/// ```
/// use rtl_sampling::AliasTable;
/// let table = AliasTable::new(&[1.0, 0.0, 3.0]).unwrap();
/// assert_eq!((table.pmf(0), table.pmf(1), table.pmf(2)), (0.25, 0.0, 0.75));
/// let (bin, rest) = table.sample(0.5);
/// assert!(bin != 1 && (0.0..1.0).contains(&rest)); // a bin of weight 0 is never returned
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct AliasTable {
    columns: Vec<Column>,
    pmf: Vec<f64>,
}

impl AliasTable {
    // ANCHOR: build
    /// Builds the table; weights must be finite and `>= 0`, not all 0 (errors name the bad bin).
    /// A bin of weight 0 gets `q = 0`, so it is never returned. The weights are divided by the
    /// largest one before they are summed, so weights near `f64::MAX` (whose sum overflows) and
    /// subnormal weights are sampled in proportion like any others.
    pub fn new(weights: &[f64]) -> Result<Self, SamplingError> {
        let n = weights.len();
        if n == 0 {
            return Err(SamplingError::TooFew {
                what: "weights",
                min: 1,
                got: 0,
            });
        }
        if n > u32::MAX as usize {
            return Err(SamplingError::TooMany {
                what: "bins",
                got: n,
                max: u32::MAX as usize,
            });
        }
        let mut largest = 0.0f64;
        for (bin, &w) in weights.iter().enumerate() {
            if !(w.is_finite() && w >= 0.0) {
                return Err(SamplingError::BadWeight { bin, value: w });
            }
            largest = largest.max(w);
        }
        if largest == 0.0 {
            return Err(SamplingError::AllZero { bins: n });
        }
        // Scaled into [0, 1], the sum lies in [1, n]: it neither overflows nor underflows.
        let total: f64 = weights.iter().map(|w| w / largest).sum();
        let pmf: Vec<f64> = weights.iter().map(|w| (w / largest) / total).collect();
        // Scaled probabilities average 1; `small` holds columns below 1, `large` the rest.
        let mut scaled: Vec<f64> = pmf.iter().map(|p| p * n as f64).collect();
        let (mut small, mut large): (Vec<usize>, Vec<usize>) =
            (0..n).partition(|&i| scaled[i] < 1.0);
        let mut columns = vec![Column { q: 1.0, alias: 0 }; n];
        while let (Some(&s), Some(&l)) = (small.last(), large.last()) {
            small.pop();
            columns[s] = Column {
                q: scaled[s],
                alias: l as u32,
            };
            // The large bin gives away 1 - q of its mass to fill column s.
            scaled[l] = (scaled[l] + scaled[s]) - 1.0;
            if scaled[l] < 1.0 {
                large.pop();
                small.push(l);
            }
        }
        // What is left is 1 up to rounding. A leftover bin of weight 0 must still never be
        // returned, so it aliases the heaviest bin with q = 0.
        let heaviest = (0..n).fold(0, |m, i| if pmf[i] > pmf[m] { i } else { m });
        for i in small.into_iter().chain(large) {
            columns[i] = if pmf[i] > 0.0 {
                Column {
                    q: 1.0,
                    alias: i as u32,
                }
            } else {
                Column {
                    q: 0.0,
                    alias: heaviest as u32,
                }
            };
        }
        Ok(Self { columns, pmf })
    }
    // ANCHOR_END: build

    /// The number of bins.
    pub fn len(&self) -> usize {
        self.columns.len()
    }

    /// Never true: a table has at least one bin.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The probability of bin `i` (0 outside the table).
    #[doc(alias = "probability")]
    pub fn pmf(&self, i: usize) -> f64 {
        self.pmf.get(i).copied().unwrap_or(0.0)
    }

    // ANCHOR: sample
    /// A bin for one uniform `u` in `[0, 1)`, and a fresh uniform in `[0, 1)` made from the bits
    /// of `u` that the choice did not use (`u n = column + coin`; the coin, rescaled, is uniform
    /// again given the bin). O(1). The workspace's one vocabulary: `sample` takes the uniform number,
    /// `pmf` is the probability of what it returns (rtl-pdf's `Selection::sample` does the same by
    /// inversion, which keeps each bin's share of `[0, 1)` in one piece).
    #[doc(alias = "choose")]
    #[inline]
    pub fn sample(&self, u: f64) -> (usize, f64) {
        let n = self.columns.len();
        let scaled = clamp_u(u) * n as f64;
        let i = (scaled as usize).min(n - 1);
        let coin = (scaled - i as f64).min(ONE_MINUS_EPSILON);
        let col = self.columns[i];
        if coin < col.q {
            (i, (coin / col.q).min(ONE_MINUS_EPSILON))
        } else {
            let rest = ((coin - col.q) / (1.0 - col.q)).min(ONE_MINUS_EPSILON);
            (col.alias as usize, rest)
        }
    }
    // ANCHOR_END: sample
}

impl rand::distr::Distribution<usize> for AliasTable {
    fn sample<R: rand::Rng + ?Sized>(&self, rng: &mut R) -> usize {
        AliasTable::sample(self, rng.random::<f64>()).0
    }
}

/// What one side of a column of [`AliasPiecewise`] needs to place a sample: the bin's ends, its
/// density and the factor that stretches the coin's share back to `[0, 1)`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Outcome {
    x0: f64,
    x1: f64,
    pdf: f64,
    stretch: f64,
}

/// A whole column in one record (72 bytes): one memory access per sample even when the table is
/// far larger than the cache.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct PackedColumn {
    q: f64,
    own: Outcome,
    alias: Outcome,
}

/// A piecewise-constant density sampled with an alias table: the bin in O(1), then uniformly
/// inside it with the leftover bits of `u`. The same density as a [`TabulatedCdf`](crate::TabulatedCdf)
/// with the same bins, but not an inversion.
#[derive(Clone, Debug, PartialEq)]
pub struct AliasPiecewise {
    columns: Vec<PackedColumn>,
}

impl AliasPiecewise {
    /// Bins with the given edges (strictly increasing) and weights, validated as a tabulated CDF is
    /// (the same errors). The alias table is built from that table's bin probabilities and reports
    /// its densities, so both sample the same bins with the same density: a weight too small to move
    /// the CDF (`2e-322` after a weight of 2) is a bin of probability 0 for both, never one that the
    /// alias table would sample with a density that underflowed to 0.
    pub fn new(edges: &[f64], weights: &[f64]) -> Result<Self, SamplingError> {
        let t = crate::TabulatedCdf::from_edges_and_weights(edges, weights)?;
        let probability: Vec<f64> = (0..t.len()).map(|i| t.bin_probability(i)).collect();
        let table = AliasTable::new(&probability)?;
        // positive and finite wherever the probability is positive: the table checked it
        let outcome = |i: usize, stretch: f64| Outcome {
            x0: edges[i],
            x1: edges[i + 1],
            pdf: probability[i] / (edges[i + 1] - edges[i]),
            stretch,
        };
        let columns = table
            .columns
            .iter()
            .enumerate()
            .map(|(i, c)| PackedColumn {
                q: c.q,
                own: outcome(i, if c.q > 0.0 { 1.0 / c.q } else { 0.0 }),
                alias: outcome(
                    c.alias as usize,
                    if c.q < 1.0 { 1.0 / (1.0 - c.q) } else { 0.0 },
                ),
            })
            .collect();
        Ok(Self { columns })
    }

    /// Equal bins on `[a, b]`.
    pub fn from_weights(a: f64, b: f64, weights: &[f64]) -> Result<Self, SamplingError> {
        Self::new(&equal_edges(a, b, weights.len())?, weights)
    }

    /// The same bins and masses as a tabulated CDF.
    pub fn from_tabulated(t: &crate::TabulatedCdf) -> Result<Self, SamplingError> {
        let weights: Vec<f64> = (0..t.len()).map(|i| t.bin_probability(i)).collect();
        Self::new(t.nodes(), &weights)
    }

    // ANCHOR: piecewise
    /// `x` and its density `pmf(i) / width(i)`: the column and coin as in [`AliasTable::sample`],
    /// then the coin's share, stretched to `[0, 1)`, places `x` inside the chosen bin.
    #[inline]
    pub fn sample(&self, u: f64) -> Sample {
        let n = self.columns.len();
        let scaled = clamp_u(u) * n as f64;
        let i = (scaled as usize).min(n - 1);
        let coin = (scaled - i as f64).min(ONE_MINUS_EPSILON);
        let c = &self.columns[i];
        let keep = coin < c.q;
        let (o, start) = if keep { (&c.own, 0.0) } else { (&c.alias, c.q) };
        let v = ((coin - start) * o.stretch).min(ONE_MINUS_EPSILON);
        Sample {
            x: (o.x0 + v * (o.x1 - o.x0)).min(o.x1.next_down()),
            pdf: o.pdf,
        }
    }
    // ANCHOR_END: piecewise

    /// The density `p(x)` per unit length: `pmf(i) / width(i)` of `x`'s bin, 0 outside the support.
    pub fn pdf(&self, x: f64) -> f64 {
        let n = self.columns.len();
        if !(self.columns[0].own.x0..=self.columns[n - 1].own.x1).contains(&x) {
            return 0.0;
        }
        // Column i's own outcome is bin i.
        let i = self.columns[1..].partition_point(|c| c.own.x0 <= x);
        self.columns[i].own.pdf
    }
}

impl rand::distr::Distribution<f64> for AliasPiecewise {
    fn sample<R: rand::Rng + ?Sized>(&self, rng: &mut R) -> f64 {
        AliasPiecewise::sample(self, rng.random::<f64>()).x
    }
}
