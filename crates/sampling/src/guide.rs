//! A guide table (Chen and Asau, 1974): O(1) expected inversion of a tabulated CDF.
//!
//! Split `[0, 1)` into `M` equal cells; cell `j` remembers the first bin any `u` of the cell can
//! fall in. A query computes its cell `j = ⌊uM⌋`, and only the bins between `guide[j]` and
//! `guide[j + 1]` are searched. With `M ≈ N` that range holds about one bin on average, so a sample
//! costs a multiply, two loads and a short search; the worst case stays O(log N).

use crate::{
    InverseTransform, Sample, SamplingError, TabulatedCdf, clamp_u, distribution_by_inversion,
};

/// A [`TabulatedCdf`] with a guide table of `M` cells.
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
    /// A guide table with `m ≥ 1` cells. Cell `j` holds the `u` with `⌊u m⌋ = j` as computed in
    /// floating point (so rounding of `u m` can never send a query to a cell that starts after it).
    pub fn with_cells(table: TabulatedCdf, m: usize) -> Result<Self, SamplingError> {
        let n = table.len();
        if m == 0 {
            return Err(SamplingError::TooFew {
                what: "guide cells",
                min: 1,
                got: 0,
            });
        }
        if n > u32::MAX as usize || m > u32::MAX as usize {
            return Err(SamplingError::TooMany {
                got: n.max(m),
                max: u32::MAX as usize,
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
            while i + 1 < n && (cdf[i + 1] <= cdf[i] || cell(crate::next_down(cdf[i + 1])) < j) {
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
    /// bins from `guide[j]` to `guide[j + 1]`: a short scan finishes (a binary search if the
    /// range is long, so the worst case stays O(log N)).
    #[inline]
    pub fn bin(&self, u: f64) -> usize {
        let m = self.guide.len() - 1;
        let j = ((u * self.cells) as usize).min(m - 1);
        let lo = self.guide[j] as usize;
        let hi = self.guide[j + 1] as usize;
        let cdf = self.table.cdf_values();
        if hi - lo <= 8 {
            // The usual case: a step or two to the right.
            let mut i = lo;
            while i < hi && cdf[i + 1] <= u {
                i += 1;
            }
            i
        } else {
            lo + cdf[lo + 1..hi + 1].partition_point(|&c| c <= u)
        }
    }
    // ANCHOR_END: bin

    /// `x = F⁻¹(u)` and its density, as [`TabulatedCdf::sample`] gives, in O(1) expected time.
    #[inline]
    pub fn sample(&self, u: f64) -> Sample {
        let u = clamp_u(u);
        self.table.sample_in_bin(self.bin(u), u)
    }

    pub fn pdf(&self, x: f64) -> f64 {
        self.table.pdf(x)
    }

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
