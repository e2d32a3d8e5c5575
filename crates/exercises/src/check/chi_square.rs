//! Pearson's chi-square goodness-of-fit test of samples against the density they claim, over
//! cells of a line ([`Intervals`]) or of the sphere of directions ([`SphereBins`], equal areas),
//! with a message that says which cells got too many samples and which too few.

use super::format::{self, count, expected_count, p_value, sig};
use super::{CheckResult, sidak_alpha};
use glam::DVec3;
use statrs::distribution::{ChiSquared, ContinuousCDF};
use std::f64::consts::PI;
use std::fmt;

/// A part of a sampler's domain made of chi-square cells, described in the learner's terms
/// ("near the normal: cos theta in [0.9, 1]", "x in [0, 0.05)").
#[derive(Clone, Debug, PartialEq)]
pub struct Region {
    /// The cells it covers (indices into the observed and expected counts).
    pub cells: Vec<usize>,
    /// What it is, as the failure message names it.
    pub name: String,
}

/// The cells of a chi-square test, seen as parts of the sampler's domain, so that a failure can say
/// where the samples went wrong: each single cell, and groups of cells that a systematic mistake
/// would affect together (rings of equal cos theta, sectors of equal azimuth).
pub trait Cells {
    /// Every region worth naming; the failure message names the one with the largest excess and
    /// the one with the largest deficit, measured in standard deviations, (o - e) / sqrt(e).
    fn regions(&self) -> Vec<Region>;
    /// The name of cell `i` alone.
    fn cell_name(&self, i: usize) -> String;
}

/// Cells that are intervals of a line: cell i is `[edges[i], edges[i + 1])` of the variable `var`.
#[derive(Clone, Debug)]
pub struct Intervals {
    pub var: &'static str,
    pub edges: Vec<f64>,
}

impl Intervals {
    /// `n` equal intervals of [lo, hi].
    pub fn equal(var: &'static str, lo: f64, hi: f64, n: usize) -> Self {
        let edges = (0..=n)
            .map(|i| lo + (hi - lo) * i as f64 / n as f64)
            .collect();
        Self { var, edges }
    }
}

impl Cells for Intervals {
    fn regions(&self) -> Vec<Region> {
        (0..self.edges.len() - 1)
            .map(|i| Region {
                cells: vec![i],
                name: format!("at {}", self.cell_name(i)),
            })
            .collect()
    }
    fn cell_name(&self, i: usize) -> String {
        let close = if i + 2 == self.edges.len() { "]" } else { ")" };
        format!(
            "{} in [{}, {}{close}",
            self.var,
            sig(self.edges[i], 4),
            sig(self.edges[i + 1], 4)
        )
    }
}

/// Why a chi-square test could not be computed.
#[derive(Clone, Debug, PartialEq)]
pub enum ChiSquareError {
    /// `count` samples fell in `cell`, where the density (its expected count) is 0.
    WhereTheDensityIsZero { cell: usize, count: u64 },
    /// Fewer than 2 cells after pooling: no degrees of freedom.
    NoDegreesOfFreedom,
}

impl fmt::Display for ChiSquareError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ChiSquareError::WhereTheDensityIsZero { cell, count } => write!(
                f,
                "{} samples fell in cell {cell}, where the density is 0",
                format::count(*count)
            ),
            ChiSquareError::NoDegreesOfFreedom => write!(
                f,
                "fewer than 2 cells after pooling; the test has no degrees of freedom"
            ),
        }
    }
}

impl std::error::Error for ChiSquareError {}

/// Chi-square goodness-of-fit test of `observed` counts against `expected` counts, cell by cell,
/// `cells` saying what each cell is.
///
/// A sample in a cell of expected count 0 fails at once. Cells of expected count < 5 are pooled
/// (smallest first) until each pool reaches 5; a remainder joins the last pool. The p-value is
/// `ChiSquared::new(cells - 1).sf(statistic)`, rejected below [`sidak_alpha`]. A rejection names
/// the region of `cells` with the largest excess of samples and the one with the largest deficit,
/// each with its observed and expected count.
pub fn chi_square(
    what: &str,
    observed: &[u64],
    expected: &[f64],
    cells: &dyn Cells,
) -> CheckResult {
    let (statistic, dof, p) = match chi_square_p_value(observed, expected) {
        Ok(result) => result,
        Err(ChiSquareError::WhereTheDensityIsZero { cell, count }) => {
            return Err(format!(
                "{what}: {} samples fell where the density is 0 ({})",
                self::count(count),
                cells.cell_name(cell)
            ));
        }
        Err(e) => return Err(format!("{what}: {e}")),
    };
    if p >= sidak_alpha() {
        return Ok(());
    }
    let mut out = format!(
        "{what}: the samples do not follow the density (chi-square {statistic:.1} on {dof} \
         degrees of freedom, p {}, below the {} the test allows)",
        p_value(p),
        sig(sidak_alpha(), 2)
    );
    for line in where_the_samples_differ(observed, expected, cells) {
        out += "\n";
        out += &line;
    }
    Err(out)
}

/// "too many ..." and "too few ...": the regions of `cells` with the largest standardised excess
/// and deficit of samples, (o - e) / sqrt(e), if beyond one standard deviation.
fn where_the_samples_differ(observed: &[u64], expected: &[f64], cells: &dyn Cells) -> Vec<String> {
    let mut most: Option<(f64, u64, f64, String)> = None;
    let mut fewest: Option<(f64, u64, f64, String)> = None;
    for region in cells.regions() {
        let o: u64 = region.cells.iter().map(|&i| observed[i]).sum();
        let e: f64 = region.cells.iter().map(|&i| expected[i]).sum();
        if e <= 0.0 {
            continue;
        }
        let r = (o as f64 - e) / e.sqrt();
        if r > 1.0 && most.as_ref().is_none_or(|m| r > m.0) {
            most = Some((r, o, e, region.name.clone()));
        }
        if r < -1.0 && fewest.as_ref().is_none_or(|m| r < m.0) {
            fewest = Some((r, o, e, region.name));
        }
    }
    let mut lines = Vec::new();
    for (words, found) in [("too few", fewest), ("too many", most)] {
        if let Some((_, o, e, name)) = found {
            lines.push(format!(
                "{words} {name}: {} samples, {} expected",
                count(o),
                expected_count(e)
            ));
        }
    }
    lines
}

/// The chi-square statistic, degrees of freedom and p-value of [`chi_square`], or why there is none
/// (a sample where the density is 0, or no degrees of freedom).
pub fn chi_square_p_value(
    observed: &[u64],
    expected: &[f64],
) -> Result<(f64, f64, f64), ChiSquareError> {
    assert_eq!(
        observed.len(),
        expected.len(),
        "one expected count per cell"
    );
    for (i, (&o, &e)) in observed.iter().zip(expected).enumerate() {
        if e == 0.0 && o > 0 {
            return Err(ChiSquareError::WhereTheDensityIsZero { cell: i, count: o });
        }
    }
    let mut cells: Vec<(f64, f64)> = observed
        .iter()
        .zip(expected)
        .filter(|&(_, &e)| e > 0.0)
        .map(|(&o, &e)| (e, o as f64))
        .collect();
    cells.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut pooled: Vec<(f64, f64)> = Vec::with_capacity(cells.len());
    let mut pool = (0.0, 0.0);
    for (e, o) in cells {
        if e >= 5.0 && pool.0 == 0.0 {
            pooled.push((e, o));
            continue;
        }
        pool = (pool.0 + e, pool.1 + o);
        if pool.0 >= 5.0 {
            pooled.push(pool);
            pool = (0.0, 0.0);
        }
    }
    if pool.0 > 0.0 {
        match pooled.last_mut() {
            Some(last) => *last = (last.0 + pool.0, last.1 + pool.1),
            None => pooled.push(pool),
        }
    }
    if pooled.len() < 2 {
        return Err(ChiSquareError::NoDegreesOfFreedom);
    }
    let statistic: f64 = pooled.iter().map(|&(e, o)| (o - e) * (o - e) / e).sum();
    let dof = (pooled.len() - 1) as f64;
    let p = ChiSquared::new(dof).expect("dof >= 1").sf(statistic);
    Ok((statistic, dof, p))
}

/// Cells on the sphere of directions, or a zone of it, of equal area: `n_phi` equal steps of the
/// azimuth phi in [0, 2 pi) times `n_z` equal steps of z = cos theta in [z_min, z_max]
/// (solid angle d omega = d phi dz, so equal steps are equal areas). Cell `i_z * n_phi + i_phi`.
#[derive(Clone, Copy, Debug)]
pub struct SphereBins {
    pub n_phi: usize,
    pub n_z: usize,
    pub z_min: f64,
    pub z_max: f64,
    /// What +z is to the learner ("the normal", "+z"), for the failure messages.
    pub pole: &'static str,
}

impl SphereBins {
    /// The hemisphere about the normal (+z) in 16 sectors of azimuth and 10 rings of equal cos theta,
    /// the cells of the exercises' direction samplers.
    pub fn hemisphere() -> Self {
        Self {
            n_phi: 16,
            n_z: 10,
            z_min: 0.0,
            z_max: 1.0,
            pole: "the normal",
        }
    }

    /// The cell of direction `d` (normalised first), or `None` outside the zone or for non-finite `d`.
    pub fn cell(&self, d: DVec3) -> Option<usize> {
        let d = d.normalize_or_zero();
        if d == DVec3::ZERO || !d.is_finite() || d.z < self.z_min || d.z > self.z_max {
            return None;
        }
        let mut phi = d.y.atan2(d.x);
        if phi < 0.0 {
            phi += 2.0 * PI;
        }
        let i_phi = ((phi / (2.0 * PI) * self.n_phi as f64) as usize).min(self.n_phi - 1);
        let t = (d.z - self.z_min) / (self.z_max - self.z_min);
        let i_z = ((t * self.n_z as f64) as usize).min(self.n_z - 1);
        Some(i_z * self.n_phi + i_phi)
    }

    /// Counts of `dirs` per cell; a direction outside the zone is an error.
    pub fn histogram(
        &self,
        what: &str,
        dirs: impl IntoIterator<Item = DVec3>,
    ) -> Result<Vec<u64>, String> {
        let mut counts = vec![0u64; self.n_phi * self.n_z];
        for d in dirs {
            match self.cell(d) {
                Some(i) => counts[i] += 1,
                None => {
                    let why = if !d.is_finite() {
                        "is not finite".to_string()
                    } else if d == DVec3::ZERO {
                        "is the zero vector".to_string()
                    } else if self.z_min == 0.0 && d.z < 0.0 {
                        format!("lies below the horizon (cos theta = {})", sig(d.z, 3))
                    } else {
                        "lies outside the zone sampled".to_string()
                    };
                    return Err(format!("{what}: generated direction {d} {why}"));
                }
            }
        }
        Ok(counts)
    }

    /// z range of the `i_z`-th ring of cells.
    pub fn z_range(&self, i_z: usize) -> (f64, f64) {
        let dz = (self.z_max - self.z_min) / self.n_z as f64;
        (
            self.z_min + i_z as f64 * dz,
            self.z_min + (i_z + 1) as f64 * dz,
        )
    }

    /// Expected counts of `n` samples per cell: `n` times the integral of `density` (w.r.t. solid
    /// angle) over the cell by the midpoint rule on `sub x sub` points, and exactly 0 where
    /// `in_support(z_lo, z_hi)` says the ring lies outside the support.
    pub fn expected(
        &self,
        n: usize,
        density: impl Fn(DVec3) -> f64,
        in_support: impl Fn(f64, f64) -> bool,
        sub: usize,
    ) -> Vec<f64> {
        let dphi = 2.0 * PI / self.n_phi as f64;
        let mut out = vec![0.0; self.n_phi * self.n_z];
        for i_z in 0..self.n_z {
            let (z_lo, z_hi) = self.z_range(i_z);
            if !in_support(z_lo, z_hi) {
                continue;
            }
            let hz = (z_hi - z_lo) / sub as f64;
            for i_phi in 0..self.n_phi {
                let hphi = dphi / sub as f64;
                let mut sum = 0.0;
                for a in 0..sub {
                    let z = z_lo + (a as f64 + 0.5) * hz;
                    let r = (1.0 - z * z).max(0.0).sqrt();
                    for b in 0..sub {
                        let phi = i_phi as f64 * dphi + (b as f64 + 0.5) * hphi;
                        sum += density(DVec3::new(r * phi.cos(), r * phi.sin(), z));
                    }
                }
                out[i_z * self.n_phi + i_phi] = n as f64 * sum * hz * hphi;
            }
        }
        out
    }

    /// Ring `i_z` in the learner's terms: "near the normal: cos theta in [0.9, 1]".
    fn ring_name(&self, i_z: usize) -> String {
        let (lo, hi) = self.z_range(i_z);
        let range = format!("cos theta in [{}, {}]", sig(lo, 3), sig(hi, 3));
        if hi >= 1.0 {
            format!("near {}: {range}", self.pole)
        } else if lo <= -1.0 {
            format!("opposite {}: {range}", self.pole)
        } else if self.z_min == 0.0 && lo == 0.0 {
            format!("near the horizon: {range}")
        } else {
            format!("at {range}")
        }
    }

    /// Sector `i_phi`: "phi in [0, 22.5) degrees".
    fn sector_name(&self, i_phi: usize) -> String {
        let step = 360.0 / self.n_phi as f64;
        format!(
            "phi in [{}, {}) degrees",
            sig(i_phi as f64 * step, 4),
            sig((i_phi + 1) as f64 * step, 4)
        )
    }
}

impl Cells for SphereBins {
    /// The rings of equal cos theta, the sectors of equal azimuth, and the cells themselves.
    fn regions(&self) -> Vec<Region> {
        let mut out = Vec::with_capacity(self.n_z + self.n_phi + self.n_z * self.n_phi);
        for i_z in 0..self.n_z {
            out.push(Region {
                cells: (0..self.n_phi)
                    .map(|i_phi| i_z * self.n_phi + i_phi)
                    .collect(),
                name: self.ring_name(i_z),
            });
        }
        for i_phi in 0..self.n_phi {
            out.push(Region {
                cells: (0..self.n_z).map(|i_z| i_z * self.n_phi + i_phi).collect(),
                name: format!("at azimuth {}", self.sector_name(i_phi)),
            });
        }
        out.extend((0..self.n_z * self.n_phi).map(|i| Region {
            cells: vec![i],
            name: self.cell_name(i),
        }));
        out
    }

    fn cell_name(&self, i: usize) -> String {
        format!(
            "{}, {}",
            self.ring_name(i / self.n_phi),
            self.sector_name(i % self.n_phi)
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::*;
    use rand::Rng;

    #[test]
    fn chi_square_accepts_a_fair_die_and_rejects_a_loaded_one() {
        let mut rng = seeded(7);
        let mut fair = vec![0u64; 6];
        let mut loaded = vec![0u64; 6];
        for _ in 0..60_000 {
            fair[rng.random_range(0..6)] += 1;
            let r: f64 = rng.random();
            loaded[if r < 0.2 { 5 } else { rng.random_range(0..6) }] += 1;
        }
        let expected = vec![10_000.0; 6];
        let faces = Intervals::equal("the face", 0.5, 6.5, 6);
        chi_square("fair die", &fair, &expected, &faces).unwrap();
        let err = chi_square("loaded die", &loaded, &expected, &faces).unwrap_err();
        // The message says where: face 6 too often, and one of the others too rarely.
        assert!(
            err.contains("too many at the face in [5.5, 6.5]: ")
                && err.contains("too few at the face in ["),
            "{err}"
        );
    }

    #[test]
    fn chi_square_says_which_ring_of_directions_has_too_few_and_too_many() {
        // Uniform directions on the hemisphere tested against the cosine density: too few near the
        // normal, too many near the horizon, each ring counted over its 16 sectors.
        let bins = SphereBins::hemisphere();
        let n = 100_000;
        let mut rng = seeded(9);
        let dirs = (0..n).map(|_| {
            let d = uniform_direction(&mut rng);
            DVec3::new(d.x, d.y, d.z.abs())
        });
        let observed = bins.histogram("uniform", dirs).unwrap();
        let expected: Vec<f64> = (0..160)
            .map(|c| {
                let (lo, hi) = bins.z_range(c / 16);
                n as f64 * (hi * hi - lo * lo) / 16.0
            })
            .collect();
        let err = chi_square("uniform as cosine", &observed, &expected, &bins).unwrap_err();
        assert!(
            err.contains("\ntoo few near the normal: cos theta in [0.9, 1]: ")
                && err.contains("19,000 expected"),
            "{err}"
        );
        assert!(
            err.contains("\ntoo many near the horizon: cos theta in [0, 0.1]: ")
                && err.contains("1,000 expected"),
            "{err}"
        );
        // A direction below the horizon is named as such.
        let below = bins
            .histogram("d", [DVec3::new(0.0, 0.6, -0.8)])
            .unwrap_err();
        assert!(below.contains("below the horizon"), "{below}");
    }

    #[test]
    fn chi_square_fails_at_once_on_a_sample_outside_the_support() {
        let cells = Intervals::equal("x", 0.0, 3.0, 3);
        let err = chi_square("support", &[10, 10, 1], &[10.5, 10.5, 0.0], &cells).unwrap_err();
        assert_eq!(
            err,
            "support: 1 samples fell where the density is 0 (x in [2, 3])"
        );
    }

    #[test]
    fn chi_square_pools_small_cells() {
        // 40 cells of expected 0.5 pool into 4 cells of 5; all 20 samples in one of them is rejected.
        let expected = vec![0.5; 40];
        let cells = Intervals::equal("x", 0.0, 1.0, 40);
        let mut observed = vec![0u64; 40];
        observed[0] = 20;
        assert!(chi_square("pooled", &observed, &expected, &cells).is_err());
        let spread: Vec<u64> = (0..40).map(|i| u64::from(i % 2 == 0)).collect();
        chi_square("pooled", &spread, &expected, &cells).unwrap();
    }

    #[test]
    fn sphere_bins_cover_the_sphere_with_equal_areas() {
        let bins = SphereBins {
            n_phi: 8,
            n_z: 5,
            z_min: -1.0,
            z_max: 1.0,
            pole: "+z",
        };
        let e = bins.expected(1000, |_| 1.0 / (4.0 * PI), |_, _| true, 8);
        for x in &e {
            assert!((x - 25.0).abs() < 1e-9, "{x}");
        }
        assert_eq!(bins.cell(DVec3::Z), Some(4 * 8));
        assert_eq!(bins.cell(DVec3::new(0.0, 0.0, -1.0)), Some(0));
        assert_eq!(bins.cell(DVec3::NAN), None);
    }
}
