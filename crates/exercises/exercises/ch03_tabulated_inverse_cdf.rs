//! # Chapter 3, Inverse Transform Sampling, "The table made right": invert a tabulated CDF by binary search
//!
//! **Read first:** the section "Approximating distributions" of the page Inverse Transform Sampling
//! (`book/src/ch03-inverse-transform-sampling.md`), and in it "The table made right", which shows
//! the search and the cases that break it.
//!
//! A density known only as weights w_i of bins [x_i, x_(i+1)) (constant inside each bin) has a CDF
//! tabulated at the bin edges: c_0 = 0, c_i = (w_0 + ... + w_(i-1)) / W, c_n = 1, with W the sum of
//! the weights. [`CdfTable`] builds that table (given; it rejects bad weights and edges).
//!
//! **Task.** Write [`invert`]: for `u` in [0, 1) find, by binary search (O(log n)), the bin i with
//! c_i <= u < c_(i+1), and return the x in that bin where the CDF, linear between the tabulated
//! points, equals u. That samples the piecewise-constant density.
//!
//! The hard cases: a bin of zero weight has c_i = c_(i+1); it must never be returned, and its zero
//! width (in u) must never be divided by; leading and trailing zero bins; u = 0; u = 1 - 2^-53; and a
//! `u` outside [0, 1) (or NaN) is `Err(CdfError::UOutOfRange(u))` naming the value, not a panic or
//! a NaN.
//!
//! Check your code with `cargo exercises check ch03_tabulated_inverse_cdf` (or
//! `rtl exercises check ch03_tabulated_inverse_cdf`, the same);
//! `cargo exercises hint ch03_tabulated_inverse_cdf` gives a hint.

use rtl_exercises::ch03_tabulated_inverse_cdf::{CdfError, CdfTable};

// ANCHOR: exercise
/// The sample x = P^-1(u) of the table's piecewise-constant density: the bin i with
/// c_i <= u < c_(i+1) by binary search, then the point of that bin where the piecewise-linear CDF
/// reaches u. `Err(CdfError::UOutOfRange(u))` unless 0 <= u < 1.
pub fn invert(table: &CdfTable, u: f64) -> Result<f64, CdfError> {
    let _ = (table, u);
    todo!("ch03 invert: binary-search the bin with c_i <= u < c_(i+1), interpolate inside it")
}
// ANCHOR_END: exercise
