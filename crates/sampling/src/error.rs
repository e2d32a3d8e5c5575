//! What can be wrong with a table, a density or a query: each error names the place (bin, point,
//! cell) and the offending value, so a bad input is found without a debugger.

/// Why a distribution could not be built, or a query could not be answered.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SamplingError {
    /// A weight (the mass of one bin) is negative, NaN or infinite.
    #[error("weight of bin {bin} is {value}: weights must be finite and >= 0")]
    BadWeight { bin: usize, value: f64 },
    /// A weight of a 2D table is negative, NaN or infinite.
    #[error("weight of cell (row {row}, column {col}) is {value}: weights must be finite and >= 0")]
    BadCellWeight { row: usize, col: usize, value: f64 },
    /// Every weight is zero: there is nothing to sample.
    #[error("all {bins} weights are zero: there is no probability to sample")]
    AllZero { bins: usize },
    /// The density returned a negative or non-finite value inside a bin.
    #[error("density at x = {x} (bin {bin}) is {value}: a density must be finite and >= 0")]
    BadDensity { bin: usize, x: f64, value: f64 },
    /// Too few points, bins or cells.
    #[error("need at least {min} {what}, got {got}")]
    TooFew {
        what: &'static str,
        min: usize,
        got: usize,
    },
    /// More bins (or guide cells) than a 32-bit index can name, or than a table sensibly needs.
    #[error("{got} {what} is more than this table supports ({max})")]
    TooMany {
        what: &'static str,
        got: usize,
        max: usize,
    },
    /// `nx × ny` cells are more than a `usize` can count.
    #[error("{nx} × {ny} cells is more than a table can count ({max})", max = usize::MAX)]
    CellCountOverflow { nx: usize, ny: usize },
    /// A bin (or an interval) is wider than the largest `f64`, so its width and density cannot be
    /// computed.
    #[error(
        "bin {bin} from {x0:?} to {x1:?} has a width that overflows f64 (more than {max:e})",
        max = f64::MAX
    )]
    WidthOverflow { bin: usize, x0: f64, x1: f64 },
    /// A bin of positive probability whose density, probability / width, underflows to 0 or
    /// overflows to infinity: a sample in it could not carry its density.
    #[error(
        "bin {bin} has probability {probability:e} over width {width:e}: its density is {density:e}, \
         outside the positive finite f64 range [{min:e}, {max:e}]",
        min = f64::from_bits(1), max = f64::MAX
    )]
    DensityOutOfRange {
        bin: usize,
        probability: f64,
        width: f64,
        density: f64,
    },
    /// A cell of positive probability of a 2D table whose density with respect to area underflows
    /// or overflows.
    #[error(
        "cell (row {row}, column {col}) has density {density:e} with respect to area, outside the \
         positive finite f64 range [{min:e}, {max:e}]",
        min = f64::from_bits(1), max = f64::MAX
    )]
    CellDensityOutOfRange {
        row: usize,
        col: usize,
        density: f64,
    },
    /// A parameter of an analytic density outside the range where its samples are finite and
    /// carry a positive finite density.
    #[error("{what} = {value:?} is outside [{min:e}, {max:e}]")]
    OutOfRange {
        what: &'static str,
        value: f64,
        min: f64,
        max: f64,
    },
    /// Two slices that must match in length do not.
    #[error("{what} has {got} entries, expected {expected}")]
    LengthMismatch {
        what: &'static str,
        got: usize,
        expected: usize,
    },
    /// A point (x, F(x)) of a tabulated CDF is not finite.
    #[error("point {index} (x = {x}, F = {f}) is not finite")]
    NonFinitePoint { index: usize, x: f64, f: f64 },
    /// Bin edges must increase strictly: a zero-width bin has no density.
    #[error(
        "x must increase strictly, but point {index} has x = {x} after {prev}: a zero-width segment has no density"
    )]
    NotIncreasing { index: usize, prev: f64, x: f64 },
    /// A CDF never decreases.
    #[error("F decreases at point {index}, from {prev} to {f}: a CDF never decreases")]
    Decreasing { index: usize, prev: f64, f: f64 },
    /// F is the same at the first and the last point.
    #[error("F is {f} at every point: there is no probability to sample")]
    ZeroMass { f: f64 },
    /// The interval is not finite or empty.
    #[error("[{a}, {b}] is not a finite interval with a < b")]
    BadInterval { a: f64, b: f64 },
    /// A query u lies outside the range of the CDF (or is NaN).
    #[error("u = {u} is outside the CDF's range [{lo}, {hi}]")]
    OutsideRange { u: f64, lo: f64, hi: f64 },
    /// A user CDF returned NaN or an infinity.
    #[error("the CDF returned {value} at x = {x}")]
    BadCdfValue { x: f64, value: f64 },
    /// A tolerance must be finite and >= 0.
    #[error("tolerance must be finite and >= 0, got {0}")]
    BadTolerance(f64),
}
