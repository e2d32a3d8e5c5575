//! A tabulated CDF laid out for the cache: Eytzinger (breadth-first) order and a branchless search.
//!
//! A binary search over a sorted array of 10⁷ entries touches about 24 cache lines, each far from the
//! last, and the processor cannot guess which one comes next. Stored in Eytzinger order (the root at
//! 1, the children of `k` at `2k` and `2k + 1`, as in a binary heap), the first levels of the tree
//! share a few cache lines that stay hot, the next levels are a known distance ahead so they can be
//! prefetched, and the loop has no data-dependent branch (Khuong and Morin, "Array layouts for
//! comparison-based searching", 2017).
//!
//! Each node stores the pair `(Fₖ, xₖ)`: the search ends knowing the nodes just left and right of
//! `u`, which are the ends of the bin, so sampling needs no further memory access.

use crate::{
    InverseTransform, Sample, SamplingError, TabulatedCdf, clamp_u, distribution_by_inversion,
};

/// One node of the tree: a CDF value and its `x`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Node {
    cdf: f64,
    x: f64,
}

/// Four nodes, one cache line: the line a prefetch fetches.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C, align(64))]
struct Line([Node; 4]);

/// A tabulated CDF whose interior nodes are stored in Eytzinger order: the same piecewise-constant
/// density (per unit length) and the same `x = F⁻¹(u)` as the [`TabulatedCdf`] it was built from.
///
/// ```
/// use rtl_sampling::{EytzingerCdf, TabulatedCdf};
/// let table = TabulatedCdf::from_weights(0.0, 4.0, &[1.0, 0.0, 2.0, 1.0]).unwrap();
/// let tree = EytzingerCdf::new(&table);
/// for u in [0.0, 0.25, 0.5, 0.9] {
///     assert_eq!(tree.sample(u), table.sample(u));
/// }
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct EytzingerCdf {
    /// Node `k` (1-based) lives at `lines[k / 4].0[k % 4]`; slot 0 is unused.
    lines: Vec<Line>,
    /// The depth `d` of the complete tree of `2ᵈ - 1` nodes.
    depth: u32,
    first: Node,
    last: Node,
}

impl EytzingerCdf {
    /// Reorders the interior nodes `(F₁, x₁) … (Fₙ₋₁, xₙ₋₁)` of `table` breadth-first. The tree is
    /// padded to a complete one (`2ᵈ - 1` nodes) with copies of the last node `(1, xₙ)`, which sort
    /// after every interior node: every search then takes exactly `d` steps, and the loop's exit is
    /// never mispredicted.
    pub fn new(table: &TabulatedCdf) -> Self {
        let (x, cdf) = (table.nodes(), table.cdf_values());
        let n = table.len();
        let last = Node { cdf: 1.0, x: x[n] };
        let count = n.next_power_of_two() - 1; // the smallest 2ᵈ - 1 >= n - 1
        let sorted = |i: usize| {
            if i < n {
                Node {
                    cdf: cdf[i],
                    x: x[i],
                }
            } else {
                last
            }
        };
        let mut lines = vec![Line::default(); (count + 1).div_ceil(4)];
        // An in-order walk of the implicit tree visits the sorted nodes in order.
        let mut next = 1; // the next sorted node to place
        let mut k = 1usize; // the tree position being visited
        let mut stack = Vec::new();
        loop {
            while k <= count {
                stack.push(k);
                k *= 2;
            }
            let Some(top) = stack.pop() else { break };
            lines[top / 4].0[top % 4] = sorted(next);
            next += 1;
            k = 2 * top + 1;
        }
        Self {
            lines,
            depth: (count + 1).trailing_zeros(),
            first: Node { cdf: 0.0, x: x[0] },
            last,
        }
    }

    #[inline(always)]
    fn node(&self, k: usize) -> Node {
        self.lines[k / 4].0[k % 4]
    }

    // ANCHOR: search
    /// The ends of the bin holding `u`: the last node with `F ≤ u` and the first with `F > u`.
    /// The descent appends one bit per level to `k`, 1 for "went right" (`F ≤ u`), with no branch
    /// on the data. At the end the last right turn is the lowest 1 bit of `k` and the last left
    /// turn the lowest 0 bit: shifting them out gives the two nodes (0 means "none": an end of the
    /// support).
    #[inline]
    fn bracket(&self, u: f64) -> (Node, Node) {
        let mut k = 1;
        for _ in 0..self.depth {
            for l in 0..PREFETCH_LINES {
                prefetch(&self.lines, PREFETCH_LINES * k + l);
            }
            k = 2 * k + (self.node(k).cdf <= u) as usize;
        }
        let lo = k >> (k.trailing_zeros() + 1);
        let hi = k >> (k.trailing_ones() + 1);
        (
            if lo == 0 { self.first } else { self.node(lo) },
            if hi == 0 { self.last } else { self.node(hi) },
        )
    }
    // ANCHOR_END: search

    /// `x = F⁻¹(u)` and its density, the same as [`TabulatedCdf::sample`] gives.
    #[inline]
    pub fn sample(&self, u: f64) -> Sample {
        let u = clamp_u(u);
        let (lo, hi) = self.bracket(u);
        let t = (u - lo.cdf) / (hi.cdf - lo.cdf);
        Sample {
            x: (lo.x + t * (hi.x - lo.x)).min(hi.x.next_down()),
            pdf: (hi.cdf - lo.cdf) / (hi.x - lo.x),
        }
    }

    /// The nodes left and right of `x` (a node belongs to the bin on its right).
    fn bracket_x(&self, x: f64) -> (Node, Node) {
        let mut k = 1;
        for _ in 0..self.depth {
            k = 2 * k + (self.node(k).x <= x) as usize;
        }
        let lo = k >> (k.trailing_zeros() + 1);
        let hi = k >> (k.trailing_ones() + 1);
        (
            if lo == 0 { self.first } else { self.node(lo) },
            if hi == 0 { self.last } else { self.node(hi) },
        )
    }

    /// The density `p(x)` per unit length: that of `x`'s bin, 0 outside the support.
    pub fn pdf(&self, x: f64) -> f64 {
        if !(self.first.x..=self.last.x).contains(&x) {
            return 0.0;
        }
        let (lo, hi) = self.bracket_x(x.min(self.last.x.next_down()));
        (hi.cdf - lo.cdf) / (hi.x - lo.x)
    }

    /// `u = F(x)`, the piecewise-linear CDF; 0 left of the support, 1 right of it.
    pub fn invert(&self, x: f64) -> f64 {
        if x <= self.first.x || x.is_nan() {
            return 0.0;
        }
        if x >= self.last.x {
            return 1.0;
        }
        let (lo, hi) = self.bracket_x(x);
        (lo.cdf + (hi.cdf - lo.cdf) * ((x - lo.x) / (hi.x - lo.x))).min(hi.cdf)
    }

    /// Builds the layout straight from weights (see [`TabulatedCdf::from_weights`]).
    pub fn from_weights(a: f64, b: f64, weights: &[f64]) -> Result<Self, SamplingError> {
        Ok(Self::new(&TabulatedCdf::from_weights(a, b, weights)?))
    }
}

/// How far ahead the search prefetches: the descendants of node `k` two levels down are nodes
/// `4k … 4k + 3`, one line (line `k`); four levels down they are nodes `16k … 16k + 15`, lines
/// `4k … 4k + 3`. `PREFETCH_LINES = L` fetches lines `L k … L k + L - 1`.
const PREFETCH_LINES: usize = 1;

/// Asks the processor to start loading line `l`, if there is one.
#[inline(always)]
fn prefetch(lines: &[Line], l: usize) {
    #[cfg(target_arch = "x86_64")]
    if let Some(line) = lines.get(l) {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        // SAFETY: SSE is part of every x86_64 target; a prefetch is only a hint (it reads nothing
        // and cannot fault), and `line` is a valid reference anyway.
        unsafe { _mm_prefetch::<_MM_HINT_T0>((line as *const Line).cast::<i8>()) };
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = (lines, l);
}

impl InverseTransform for EytzingerCdf {
    fn sample(&self, u: f64) -> Sample {
        EytzingerCdf::sample(self, u)
    }
    fn pdf(&self, x: f64) -> f64 {
        EytzingerCdf::pdf(self, x)
    }
    fn invert(&self, x: f64) -> f64 {
        EytzingerCdf::invert(self, x)
    }
}
distribution_by_inversion!(EytzingerCdf);
