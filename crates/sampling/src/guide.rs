//! A guide table (Chen and Asau, 1974): O(1) expected inversion of a tabulated CDF.
//!
//! Split `[0, 1)` into `M` equal cells; cell `j` remembers the first bin any `u` of the cell can
//! fall in. A query computes its cell `j = ⌊uM⌋`, and only the bins between `guide[j]` and
//! `guide[j + 1]` are searched. With `M ≈ N` that range holds about one bin on average, so a sample
//! costs a multiply, two loads and a short search; the worst case stays O(log N).

use crate::{
    InverseTransform, Sample, SamplingError, TabulatedCdf, clamp_u, distribution_by_inversion,
};

/// The most guide cells per bin [`GuideTable::with_cells`] accepts.
pub const MAX_CELLS_PER_BIN: usize = 64;

/// A [`TabulatedCdf`] with a guide table of `M` cells: the same piecewise-constant density (per
/// unit length) and the same `x = F⁻¹(u)` for every `u`, found in O(1) expected time.
///
/// ```
/// use rtl_sampling::{GuideTable, TabulatedCdf};
/// let table = TabulatedCdf::from_weights(0.0, 4.0, &[1.0, 0.0, 2.0, 1.0]).unwrap();
/// let guide = GuideTable::new(table.clone()).unwrap();
/// for u in [0.0, 0.25, 0.5, 0.9] {
///     assert_eq!(guide.sample(u), table.sample(u));
/// }
/// assert_eq!(guide.pdf(2.5), 0.5); // bin [2, 3) holds half the mass over a width of 1
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct GuideTable {
    table: TabulatedCdf,
    /// `M + 1` entries: `guide[j] ≤` the bin of every `u` in cell `j` `≤ guide[j + 1]`.
    guide: Vec<u32>,
    cells: f64,
}

impl GuideTable {
    /// A guide table with as many cells as the table has bins.
    pub fn new(table: TabulatedCdf) -> Result<Self, SamplingError> {
        let m = table.len();
        Self::with_cells(table, m)
    }

    // ANCHOR: build
    /// A guide table with `1 ≤ m ≤ 64 N` cells (at most `u32::MAX`). Cell `j` holds the `u` with
    /// `⌊u m⌋ = j` as computed in floating point (so rounding of `u m` can never send a query to a
    /// cell that starts after it).
    pub fn with_cells(table: TabulatedCdf, m: usize) -> Result<Self, SamplingError> {
        let n = table.len();
        if m == 0 {
            return Err(SamplingError::TooFew {
                what: "guide cells",
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
        // More cells than bins buys nothing beyond a few per bin; a count such as usize::MAX would
        // only exhaust memory (4 bytes a cell).
        let max_cells = n.saturating_mul(MAX_CELLS_PER_BIN).min(u32::MAX as usize);
        if m > max_cells {
            return Err(SamplingError::TooMany {
                what: "guide cells",
                got: m,
                max: max_cells,
            });
        }
        let cells = m as f64;
        let cell = |u: f64| ((u * cells) as usize).min(m - 1);
        let cdf = table.cdf_values();
        let mut guide = Vec::with_capacity(m + 1);
        let mut i = 0;
        for j in 0..m {
            // Advance to the first bin of positive probability whose largest u, the float just
            // below Fᵢ₊₁, lies in cell j or later.
            while i + 1 < n && (cdf[i + 1] <= cdf[i] || cell(cdf[i + 1].next_down()) < j) {
                i += 1;
            }
            guide.push(i as u32);
        }
        guide.push((n - 1) as u32);
        Ok(Self {
            table,
            guide,
            cells,
        })
    }
    // ANCHOR_END: build

    /// The underlying table.
    pub fn table(&self) -> &TabulatedCdf {
        &self.table
    }

    // ANCHOR: bin
    /// The bin `i` with `Fᵢ ≤ u < Fᵢ₊₁` for `u` in `[0, 1)`: the guide narrows the search to the
    /// bins from `guide[j]` to `guide[j + 1]`, where a short count finishes (a binary search if the
    /// range is long, so the worst case stays O(log N)).
    #[inline]
    pub fn bin(&self, u: f64) -> usize {
        let (lo, hi) = self.cell(u);
        self.bin_in(lo, hi, u)
    }

    /// The bins `guide[j] ..= guide[j + 1]` of the cell `j = ⌊u M⌋` holding `u`.
    #[inline]
    fn cell(&self, u: f64) -> (usize, usize) {
        let m = self.guide.len() - 1;
        let j = ((u * self.cells) as usize).min(m - 1);
        (self.guide[j] as usize, self.guide[j + 1] as usize)
    }

    /// The bin of `u` among `lo ..= hi`.
    #[inline]
    fn bin_in(&self, lo: usize, hi: usize, u: f64) -> usize {
        let cdf = self.table.cdf_values();
        if hi - lo <= 8 {
            // The usual case, zero to two steps to the right: count the bins passed instead of
            // stopping at the first one not passed. The CDF never decreases, so it is the same
            // number, and a count has no branch to mispredict (1.3x faster at N = 10^5).
            lo + cdf[lo + 1..=hi].iter().filter(|&&c| c <= u).count()
        } else {
            lo + cdf[lo + 1..hi + 1].partition_point(|&c| c <= u)
        }
    }
    // ANCHOR_END: bin

    /// `x = F⁻¹(u)` and its density, as [`TabulatedCdf::sample`] gives, in O(1) expected time.
    #[inline]
    pub fn sample(&self, u: f64) -> Sample {
        let u = clamp_u(u);
        let (lo, hi) = self.cell(u);
        // Load the cell's first node now, though it is used only later: in a table larger than the
        // cache, its line (usually the bin's too) is then fetched while the CDF values are
        // compared, rather than after the count (which is branch-free, so no speculation fetches
        // it early). At N = 10^7: 8.7-10.0 M samples/s with this load, 7.4-7.9 without, about 8.5
        // with a prefetch hint instead (`cargo bench -p rtl-sampling --bench sampling`).
        std::hint::black_box(self.table.nodes()[lo]);
        self.table.sample_in_bin(self.bin_in(lo, hi, u), u)
    }

    /// The density `p(x)` per unit length, the table's: its bin's, 0 outside the support.
    pub fn pdf(&self, x: f64) -> f64 {
        self.table.pdf(x)
    }

    /// `u = F(x)`, the table's piecewise-linear CDF: the inverse of [`sample`](Self::sample).
    pub fn invert(&self, x: f64) -> f64 {
        self.table.invert(x)
    }
}

impl InverseTransform for GuideTable {
    fn sample(&self, u: f64) -> Sample {
        GuideTable::sample(self, u)
    }
    fn pdf(&self, x: f64) -> f64 {
        GuideTable::pdf(self, x)
    }
    fn invert(&self, x: f64) -> f64 {
        GuideTable::invert(self, x)
    }
}
distribution_by_inversion!(GuideTable);
