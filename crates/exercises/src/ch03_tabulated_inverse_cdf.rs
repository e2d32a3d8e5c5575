//! # Chapter 3, Inverse Transform Sampling, "The table made right": invert a tabulated CDF by binary search
//!
//! The checks of the exercise `crates/exercises/exercises/ch03_tabulated_inverse_cdf.rs`, which
//! states the task, and what that exercise is given ([`CdfTable`], [`CdfError`]).

use crate::check::{self, Arg, CheckResult, Intervals, U_MAX};
use rand::Rng;
use std::fmt;

/// A CDF tabulated at bin edges: `edges[i]` is x_i and `cdf[i]` is c_i (`cdf[0] = 0`, last = 1).
#[derive(Clone, Debug, PartialEq)]
pub struct CdfTable {
    pub edges: Vec<f64>,
    pub cdf: Vec<f64>,
}

/// Why a table or a lookup was refused.
#[derive(Clone, Debug, PartialEq)]
pub enum CdfError {
    /// `edges` must be finite and strictly increasing, one more than the weights.
    BadEdges(String),
    /// Weight `index` is negative or not finite.
    BadWeight { index: usize, weight: f64 },
    /// The weights sum to zero: there is nothing to sample.
    ZeroTotal,
    /// `u` lies outside [0, 1).
    UOutOfRange(f64),
}

impl fmt::Display for CdfError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CdfError::BadEdges(why) => write!(f, "bad bin edges: {why}"),
            CdfError::BadWeight { index, weight } => {
                write!(
                    f,
                    "weight {index} is {weight}; weights must be finite and >= 0"
                )
            }
            CdfError::ZeroTotal => write!(f, "the weights sum to 0; there is nothing to sample"),
            CdfError::UOutOfRange(u) => write!(f, "u = {u} lies outside [0, 1)"),
        }
    }
}

impl std::error::Error for CdfError {}

impl CdfTable {
    /// The CDF of the density with weight `weights[i]` on `[edges[i], edges[i+1])`.
    pub fn new(edges: &[f64], weights: &[f64]) -> Result<Self, CdfError> {
        if edges.len() != weights.len() + 1 || weights.is_empty() {
            return Err(CdfError::BadEdges(format!(
                "{} edges for {} weights; need one more edge than weights, and a weight",
                edges.len(),
                weights.len()
            )));
        }
        if let Some(i) = (0..weights.len())
            .find(|&i| edges[i].is_nan() || edges[i] >= edges[i + 1] || !edges[i + 1].is_finite())
        {
            return Err(CdfError::BadEdges(format!(
                "edges {i} and {} are not finite and increasing",
                i + 1
            )));
        }
        if let Some((index, &weight)) = weights
            .iter()
            .enumerate()
            .find(|&(_, &w)| !(w >= 0.0 && w.is_finite()))
        {
            return Err(CdfError::BadWeight { index, weight });
        }
        let total: f64 = weights.iter().sum();
        if total <= 0.0 || !total.is_finite() {
            return Err(CdfError::ZeroTotal);
        }
        let mut cdf = Vec::with_capacity(edges.len());
        let mut run = 0.0;
        cdf.push(0.0);
        for w in &weights[..weights.len() - 1] {
            run += w;
            cdf.push((run / total).min(1.0));
        }
        cdf.push(1.0);
        Ok(Self {
            edges: edges.to_vec(),
            cdf,
        })
    }
}

/// The lookup under test.
pub trait Invert: Fn(&CdfTable, f64) -> Result<f64, CdfError> {}
impl<F: Fn(&CdfTable, f64) -> Result<f64, CdfError>> Invert for F {}

fn table(edges: &[f64], weights: &[f64]) -> CdfTable {
    CdfTable::new(edges, weights).expect("the checks' tables are valid")
}

/// `invert(t, u)`, recorded so that a panic report names the table and `u`.
fn recorded(invert: &impl Invert, t: &CdfTable, u: f64) -> Result<f64, CdfError> {
    let args = [
        ("table.edges", Arg::from(t.edges.as_slice())),
        ("table.cdf", Arg::from(t.cdf.as_slice())),
        ("u", Arg::Real(u)),
    ];
    check::calling("invert", &args, || invert(t, u))
}

fn lookup(invert: &impl Invert, t: &CdfTable, u: f64) -> Result<f64, String> {
    match recorded(invert, t, u) {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(x) => Err(format!(
            "invert(u = {}) returned {} for cdf {:?}",
            check::num(u),
            check::num(x),
            t.cdf
        )),
        Err(e) => Err(format!(
            "invert(u = {}) failed ({e}) for cdf {:?}",
            check::num(u),
            t.cdf
        )),
    }
}

/// Exact values on small tables, including zero-weight bins at the start, middle and end.
pub fn check_exact(invert: impl Invert) -> CheckResult {
    let edges = [0.0, 1.0, 2.0, 3.0, 4.0];
    // cdf = [0, 1/4, 1/4, 3/4, 1]: bin 1 has zero weight.
    let t = table(&edges, &[1.0, 0.0, 2.0, 1.0]);
    for (u, want) in [
        (0.0, 0.0),
        (0.125, 0.5),
        (0.25, 2.0),
        (0.5, 2.5),
        (0.75, 3.0),
        (0.875, 3.5),
    ] {
        check::close(
            &format!("invert(u = {u}) with a zero bin [1, 2)"),
            lookup(&invert, &t, u)?,
            want,
            1e-15,
        )?;
    }
    let top = lookup(&invert, &t, U_MAX)?;
    if !(3.99..=4.0).contains(&top) {
        return Err(format!(
            "invert(u = 1 - 2^-53) = {}, expected just below 4",
            check::num(top)
        ));
    }
    // Leading zero bins: u = 0 lands at the start of the first bin of positive weight.
    let lead = table(&edges, &[0.0, 0.0, 1.0, 1.0]);
    check::close(
        "invert(u = 0) after two zero-weight bins",
        lookup(&invert, &lead, 0.0)?,
        2.0,
        0.0,
    )?;
    // Trailing zero bins: u = 1 - 2^-53 stays in the last bin of positive weight.
    let trail = table(&edges, &[1.0, 1.0, 0.0, 0.0]);
    let x = lookup(&invert, &trail, U_MAX)?;
    if !(1.99..=2.0).contains(&x) {
        return Err(format!(
            "invert(u = 1 - 2^-53) = {} with trailing zero bins, expected just below 2",
            check::num(x)
        ));
    }
    // A single bin: the identity map onto it.
    let one = table(&[-1.0, 3.0], &[5.0]);
    check::close(
        "invert(u = 0.25) on one bin [-1, 3)",
        lookup(&invert, &one, 0.25)?,
        0.0,
        0.0,
    )?;
    Ok(())
}

/// Never a zero-weight bin, never a NaN, for u at every tabulated value c_i and around it.
pub fn check_zero_bins(invert: impl Invert) -> CheckResult {
    let edges: Vec<f64> = (0..=10).map(|i| f64::from(i) * 0.5).collect();
    let weights = [0.0, 0.0, 3.0, 0.0, 1.0, 0.0, 0.0, 2.0, 0.5, 0.0];
    let t = table(&edges, &weights);
    let mut us = vec![0.0, U_MAX];
    for &c in &t.cdf[..t.cdf.len() - 1] {
        // c itself and its two neighbouring floats (c >= 0, so the bit patterns order like the values)
        us.extend([
            c,
            f64::from_bits(c.to_bits() + 1),
            f64::from_bits(c.to_bits().saturating_sub(1)),
        ]);
    }
    us.retain(|&u| u < 1.0); // the c_i of trailing zero bins are 1
    for u in us {
        let x = lookup(&invert, &t, u)?;
        let ok = (0..weights.len()).any(|i| weights[i] > 0.0 && edges[i] <= x && x <= edges[i + 1]);
        if !ok {
            return Err(format!(
                "invert(u = {}) = {} lies in a bin of zero weight (weights {weights:?})",
                check::num(u),
                check::num(x)
            ));
        }
    }
    Ok(())
}

/// `u` outside [0, 1) is a `CdfError::UOutOfRange`.
pub fn check_out_of_range(invert: impl Invert) -> CheckResult {
    let t = table(&[0.0, 1.0, 2.0], &[1.0, 1.0]);
    for u in [-0.25, 1.0, 1.5, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        match recorded(&invert, &t, u) {
            Err(CdfError::UOutOfRange(v)) if v.to_bits() == u.to_bits() => {}
            other => {
                return Err(format!(
                    "invert(u = {u}) gave {other:?}, expected Err(UOutOfRange({u}))"
                ));
            }
        }
    }
    Ok(())
}

/// Chi-square test of 1e5 samples of an uneven table with zero bins, in 4 sub-bins per bin.
pub fn check_distribution(invert: impl Invert) -> CheckResult {
    let edges = [0.0, 0.5, 0.75, 2.0, 2.5, 4.0, 4.25, 7.0, 8.0, 9.0];
    let weights = [0.0, 3.0, 1.0, 0.0, 2.0, 5.0, 0.5, 1.5, 0.0];
    let t = table(&edges, &weights);
    let total: f64 = weights.iter().sum();
    let (n, sub) = (100_000usize, 4usize);
    let mut observed = vec![0u64; weights.len() * sub];
    let mut rng = check::seeded(31);
    for _ in 0..n {
        let x = lookup(&invert, &t, rng.random())?;
        if !(edges[0]..=edges[edges.len() - 1]).contains(&x) {
            return Err(format!(
                "invert returned {}, outside [{}, {}]",
                check::num(x),
                edges[0],
                edges[edges.len() - 1]
            ));
        }
        let i = edges.partition_point(|&e| e <= x).clamp(1, weights.len()) - 1;
        let f = (x - edges[i]) / (edges[i + 1] - edges[i]);
        observed[i * sub + ((f * sub as f64) as usize).min(sub - 1)] += 1;
    }
    let expected: Vec<f64> = (0..weights.len() * sub)
        .map(|c| n as f64 * weights[c / sub] / total / sub as f64)
        .collect();
    let cell_edges = (0..weights.len() * sub)
        .map(|c| {
            let (i, k) = (c / sub, c % sub);
            edges[i] + (edges[i + 1] - edges[i]) * k as f64 / sub as f64
        })
        .chain([edges[edges.len() - 1]])
        .collect();
    check::chi_square(
        "invert: samples of a tabulated density",
        &observed,
        &expected,
        &Intervals {
            var: "x",
            edges: cell_edges,
        },
    )
}

/// All of this exercise's checks.
pub fn check_invert(invert: impl Invert) -> CheckResult {
    check_out_of_range(&invert)?;
    check_exact(&invert)?;
    check_zero_bins(&invert)?;
    check_distribution(&invert)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_rejects_bad_weights_and_edges() {
        let e = [0.0, 1.0, 2.0];
        assert_eq!(CdfTable::new(&e, &[0.0, 0.0]), Err(CdfError::ZeroTotal));
        assert_eq!(
            CdfTable::new(&e, &[1.0, -1.0]),
            Err(CdfError::BadWeight {
                index: 1,
                weight: -1.0
            })
        );
        assert!(matches!(
            CdfTable::new(&e, &[f64::NAN, 1.0]),
            Err(CdfError::BadWeight { index: 0, .. })
        ));
        assert!(matches!(
            CdfTable::new(&e, &[1.0]),
            Err(CdfError::BadEdges(_))
        ));
        assert!(matches!(
            CdfTable::new(&[0.0, 0.0, 1.0], &[1.0, 1.0]),
            Err(CdfError::BadEdges(_))
        ));
        assert!(matches!(
            CdfTable::new(&[], &[]),
            Err(CdfError::BadEdges(_))
        ));
        let t = CdfTable::new(&e, &[1.0, 3.0]).unwrap();
        assert_eq!(t.cdf, vec![0.0, 0.25, 1.0]);
    }

    /// Wrong: the first i with c_(i+1) >= u picks a zero bin at u = c_i and divides 0 by 0.
    fn first_bin_reaching_u(t: &CdfTable, u: f64) -> Result<f64, CdfError> {
        if !(0.0..1.0).contains(&u) {
            return Err(CdfError::UOutOfRange(u));
        }
        let i = (t.cdf.partition_point(|&c| c < u)).max(1) - 1;
        let s = (u - t.cdf[i]) / (t.cdf[i + 1] - t.cdf[i]);
        Ok(t.edges[i] + s * (t.edges[i + 1] - t.edges[i]))
    }

    /// Wrong: the right bin, but no interpolation inside it.
    fn bin_start(t: &CdfTable, u: f64) -> Result<f64, CdfError> {
        if !(0.0..1.0).contains(&u) {
            return Err(CdfError::UOutOfRange(u));
        }
        Ok(t.edges[t.cdf.partition_point(|&c| c <= u) - 1])
    }

    #[test]
    fn checks_reject_wrong_inversions() {
        assert!(check_exact(first_bin_reaching_u).is_err());
        assert!(check_zero_bins(first_bin_reaching_u).is_err());
        assert!(check_exact(bin_start).is_err());
        let err = check_distribution(bin_start).unwrap_err();
        // Every sample at the start of its bin: too many in the first quarter of a bin.
        assert!(err.contains("\ntoo many at x in ["), "{err}");
        // Wrong: accepts u = 1 (and clamps), instead of reporting it.
        let clamps = |t: &CdfTable, u: f64| bin_start(t, u.clamp(0.0, U_MAX));
        assert!(check_out_of_range(clamps).is_err());
    }

    #[test]
    fn a_panic_names_the_table_and_u() {
        let report = crate::harness::panic_of(|| {
            check_out_of_range(|_: &CdfTable, u: f64| {
                assert!(u >= 0.0, "a negative u");
                Err(CdfError::UOutOfRange(u))
            })
        });
        assert!(
            report.starts_with(
                "your code panicked in invert(table.edges = [0, 1, 2], table.cdf = [0, 0.5, 1], \
                 u = -0.25) at "
            ),
            "{report}"
        );
    }
}
