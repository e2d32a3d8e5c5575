//! Reference solution of `exercises/ch03_tabulated_inverse_cdf.rs`, compiled only with `--features solutions`: try the
//! exercise first (`cargo exercises solution ch03_tabulated_inverse_cdf` shows it once your code passes).

use rtl_exercises::ch03_tabulated_inverse_cdf::{CdfError, CdfTable};

pub fn invert(table: &CdfTable, u: f64) -> Result<f64, CdfError> {
    if !(0.0..1.0).contains(&u) {
        return Err(CdfError::UOutOfRange(u));
    }
    // The last i with c_i <= u; c_0 = 0 <= u and c_n = 1 > u, so 0 <= i < n and c_(i+1) > u >= c_i:
    // bin i has positive width in u and the division below is safe.
    let i = table.cdf.partition_point(|&c| c <= u) - 1;
    let (c0, c1) = (table.cdf[i], table.cdf[i + 1]);
    let (x0, x1) = (table.edges[i], table.edges[i + 1]);
    let t = (u - c0) / (c1 - c0);
    Ok((x0 + t * (x1 - x0)).min(x1))
}
