//! A piecewise-constant density on a rectangle (an image, an environment map): sample a row from
//! the marginal density `p(y) = ∫ p(x, y) dx`, then a column from the conditional density of that
//! row, `p(x | y) = p(x, y) / p(y)`. Each is a [`TabulatedCdf`], so the map is an inversion and
//! `invert` takes a point back to its `(u₁, u₂)`. (pbrt-v4: `PiecewiseConstant2D`.)

use crate::{SamplingError, TabulatedCdf, tabulated::equal_edges};

/// A 2D sample: the point and its density with respect to area.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample2 {
    /// The point's first coordinate (the column).
    pub x: f64,
    /// The point's second coordinate (the row).
    pub y: f64,
    /// Its density `p(x, y) = p(y) p(x | y)`, per unit area.
    pub pdf: f64,
}

/// A piecewise-constant density on `[x₀, x₁] × [y₀, y₁]` with `nx × ny` equal cells: the density
/// per unit area of a cell of weight `w` is `w / (W A)`, `W` the total weight and `A` a cell's area.
///
/// ```
/// use rtl_sampling::PiecewiseConstant2D;
/// // Two rows of two cells on [0, 2] × [0, 1]; all the weight in the top row, three times as much
/// // on the right as on the left.
/// let map = PiecewiseConstant2D::new(&[0.0, 0.0, 1.0, 3.0], 2, 2, (0.0, 2.0), (0.0, 1.0)).unwrap();
/// let s = map.sample(0.5, 0.5);
/// assert!(s.y >= 0.5 && s.x >= 1.0); // top row, right cell
/// assert_eq!(s.pdf, 0.75 / 0.5); // probability 3/4 over the area 1/2
/// let (u1, u2) = map.invert(s.x, s.y);
/// assert!((u1 - 0.5).abs() < 1e-15 && (u2 - 0.5).abs() < 1e-15);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct PiecewiseConstant2D {
    /// One conditional density over x per row (a uniform one for a row of zero mass, which the
    /// marginal never selects).
    rows: Vec<TabulatedCdf>,
    marginal: TabulatedCdf,
}

impl PiecewiseConstant2D {
    // ANCHOR: build
    /// `weights` holds `ny` rows of `nx` cells, row by row (row `j` covers the `j`-th slice in y).
    /// Weights must be finite and `>= 0`, not all 0; an error names the bad cell's row and column.
    /// They are divided by the largest weight before any sum, so weights near `f64::MAX` work; a
    /// count `nx × ny` that overflows, and a cell whose density with respect to area is not a
    /// positive finite `f64`, are errors.
    pub fn new(
        weights: &[f64],
        nx: usize,
        ny: usize,
        (x0, x1): (f64, f64),
        (y0, y1): (f64, f64),
    ) -> Result<Self, SamplingError> {
        let Some(cells) = nx.checked_mul(ny) else {
            return Err(SamplingError::CellCountOverflow { nx, ny });
        };
        if weights.len() != cells {
            return Err(SamplingError::LengthMismatch {
                what: "weights",
                got: weights.len(),
                expected: cells,
            });
        }
        if nx == 0 || ny == 0 {
            return Err(SamplingError::TooFew {
                what: "cells per side",
                min: 1,
                got: 0,
            });
        }
        if let Some(k) = weights.iter().position(|w| !(w.is_finite() && *w >= 0.0)) {
            return Err(SamplingError::BadCellWeight {
                row: k / nx,
                col: k % nx,
                value: weights[k],
            });
        }
        let largest = weights.iter().copied().fold(0.0, f64::max);
        if largest == 0.0 {
            return Err(SamplingError::AllZero { bins: cells });
        }
        let x_edges = equal_edges(x0, x1, nx)?;
        let y_edges = equal_edges(y0, y1, ny)?;
        let mut rows = Vec::with_capacity(ny);
        let mut row_mass = Vec::with_capacity(ny);
        for row in weights.chunks_exact(nx) {
            // Each scaled weight is at most 1, so a row's mass is at most nx.
            let mass: f64 = row.iter().map(|w| w / largest).sum();
            row_mass.push(mass);
            rows.push(if mass > 0.0 {
                TabulatedCdf::from_edges_and_weights(&x_edges, row)?
            } else {
                TabulatedCdf::from_edges_and_weights(&x_edges, &vec![1.0; nx])?
            });
        }
        let marginal = TabulatedCdf::from_edges_and_weights(&y_edges, &row_mass)?;
        let map = Self { rows, marginal };
        map.check_cell_densities()?;
        Ok(map)
    }
    // ANCHOR_END: build

    /// Every cell that can be sampled (positive probability in the marginal and in its row) has a
    /// density `p(y) p(x | y)` that is a positive finite `f64`.
    fn check_cell_densities(&self) -> Result<(), SamplingError> {
        let density = |t: &TabulatedCdf, i: usize| {
            let x = t.nodes();
            t.bin_probability(i) / (x[i + 1] - x[i])
        };
        for (row, conditional) in self.rows.iter().enumerate() {
            if self.marginal.bin_probability(row) == 0.0 {
                continue;
            }
            let py = density(&self.marginal, row);
            for col in 0..conditional.len() {
                if conditional.bin_probability(col) > 0.0 {
                    let d = py * density(conditional, col);
                    if !(d > 0.0 && d.is_finite()) {
                        return Err(SamplingError::CellDensityOutOfRange {
                            row,
                            col,
                            density: d,
                        });
                    }
                }
            }
        }
        Ok(())
    }

    // ANCHOR: sample
    /// The point for `(u₁, u₂)` in `[0, 1)²`: `u₂` picks the row (and `y`) through the marginal, `u₁` the column
    /// (and `x`) through that row's conditional; the density is the product `p(y) p(x | y)`.
    pub fn sample(&self, u1: f64, u2: f64) -> Sample2 {
        let u2 = crate::clamp_u(u2);
        let row = self.marginal.bin(u2);
        let my = self.marginal.sample_in_bin(row, u2);
        let mx = self.rows[row].sample(u1);
        Sample2 {
            x: mx.x,
            y: my.x,
            pdf: my.pdf * mx.pdf,
        }
    }
    // ANCHOR_END: sample

    /// The row holding `y` (a row edge belongs to the row above it).
    fn row_of(&self, y: f64) -> usize {
        let e = self.marginal.nodes();
        e[1..e.len() - 1].partition_point(|&v| v <= y)
    }

    /// The density at `(x, y)` with respect to area, 0 outside the rectangle.
    pub fn pdf(&self, x: f64, y: f64) -> f64 {
        let py = self.marginal.pdf(y);
        if py == 0.0 {
            return 0.0;
        }
        py * self.rows[self.row_of(y)].pdf(x)
    }

    /// The `(u₁, u₂)` that [`sample`](Self::sample) maps to `(x, y)`.
    pub fn invert(&self, x: f64, y: f64) -> (f64, f64) {
        let (y0, y1) = self.marginal.domain();
        let row = self.row_of(y.clamp(y0, y1));
        (self.rows[row].invert(x), self.marginal.invert(y))
    }

    /// Cells per row.
    pub fn nx(&self) -> usize {
        self.rows[0].len()
    }

    /// The number of rows.
    pub fn ny(&self) -> usize {
        self.rows.len()
    }
}

impl rand::distr::Distribution<(f64, f64)> for PiecewiseConstant2D {
    fn sample<R: rand::Rng + ?Sized>(&self, rng: &mut R) -> (f64, f64) {
        let s = PiecewiseConstant2D::sample(self, rng.random(), rng.random());
        (s.x, s.y)
    }
}
