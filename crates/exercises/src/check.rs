//! The statistics every exercise's checks share: a z-test against an exact answer, a chi-square
//! goodness-of-fit test that says where the samples went wrong, exact comparisons, the seeded
//! generators, and the record of the call in progress that a panic report names (its arguments,
//! and for a generator, how to rebuild it and what the call drew: [`calling`], [`Generator`]).
//!
//! Numbers in messages are printed as a reader would write them ([`num`], [`sig`], [`count`]): 0.25
//! and 19,000, not 2.5e-1 and 1.9e4; scientific notation only for the very small or very large.

use glam::DVec3;
use rand::{RngCore, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use statrs::distribution::{ChiSquared, ContinuousCDF, Normal};
use std::cell::Cell;
use std::f64::consts::PI;
use std::fmt;

/// What a check returns: `Ok` or the reason it failed, naming the exercise and the case.
pub type CheckResult = Result<(), String>;

/// The largest `f64` a uniform draw in [0, 1) can return: 1 - 2^-53.
pub const U_MAX: f64 = 1.0 - f64::EPSILON / 2.0;

/// The false-failure rate of every z-test.
pub const Z_FALSE_FAILURE: f64 = 1e-6;

/// The family-wise significance level of the chi-square tests of one run.
pub const CHI_SQUARE_ALPHA: f64 = 0.01;

/// How many chi-square tests expected to pass one test run makes (`cargo test -p rtl-exercises
/// --features solutions`: 7 in the checks of the reference solutions of the exercises to write, 2 in
/// those of the bug museum's fixes, 2 more checking the mixture checker on a consistent mixture, 2 in
/// this module's tests; the chi-square tests that the shipped stubs and bugs must fail are not
/// counted); the Sidak correction divides [`CHI_SQUARE_ALPHA`] among them. Update it with a new test.
pub const CHI_SQUARE_TESTS: u32 = 13;

/// The seeded generator every check uses, so that a run is repeatable. The environment variable
/// `RTL_EXERCISES_SEED_OFFSET` (unset: 0) shifts every seed, to measure the checks' false-failure
/// rate over many runs (e.g. `RTL_EXERCISES_SEED_OFFSET=7 cargo test -p rtl-exercises --features
/// solutions`).
pub fn seeded(seed: u64) -> Xoshiro256PlusPlus {
    let offset = std::env::var("RTL_EXERCISES_SEED_OFFSET")
        .ok()
        .and_then(|s| s.parse::<u64>().ok())
        .unwrap_or(0);
    Xoshiro256PlusPlus::seed_from_u64(seed.wrapping_add(offset.wrapping_mul(1_000_003)))
}

/// The two-sided critical value of a z-test at [`Z_FALSE_FAILURE`] (about 4.89).
pub fn z_critical() -> f64 {
    let normal = Normal::standard();
    normal.inverse_cdf(1.0 - Z_FALSE_FAILURE / 2.0)
}

/// The per-test level of a chi-square test: 1 - (1 - alpha)^(1/m), Sidak-corrected over
/// [`CHI_SQUARE_TESTS`] tests.
pub fn sidak_alpha() -> f64 {
    1.0 - (1.0 - CHI_SQUARE_ALPHA).powf(1.0 / f64::from(CHI_SQUARE_TESTS))
}

/// Mean and standard error of the mean of `values` (Welford's running mean and variance).
pub fn mean_and_std_error(values: impl IntoIterator<Item = f64>) -> (f64, f64) {
    let (mut n, mut mean, mut m2) = (0.0_f64, 0.0_f64, 0.0_f64);
    for x in values {
        n += 1.0;
        let delta = x - mean;
        mean += delta / n;
        m2 += delta * (x - mean);
    }
    if n < 2.0 {
        return (mean, f64::INFINITY);
    }
    (mean, (m2 / (n - 1.0) / n).sqrt())
}

/// `x` as a reader would write it: plainly from 1e-4 to 1e15 (0.25, 3.141592653589793, 100000),
/// in scientific notation beyond (1e-300, 2.5e20), and 0, NaN, inf, -inf as such. The digits are the
/// shortest that give `x` back, so no two different values print alike.
///
/// ```
/// use rtl_exercises::check::num;
/// assert_eq!(num(0.25), "0.25");
/// assert_eq!(num(0.0), "0");
/// assert_eq!(num(1e-300), "1e-300");
/// ```
pub fn num(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || (1e-4..1e15).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// `x` rounded to `digits` significant digits, plainly from 1e-4 to 1e15 (0.00519, 2.67),
/// in scientific notation beyond (5.19e-12); trailing zeros are dropped (0.9, not 0.900).
///
/// ```
/// use rtl_exercises::check::sig;
/// assert_eq!(sig(0.005191234, 3), "0.00519");
/// assert_eq!(sig(2.0 / 3.0, 4), "0.6667");
/// assert_eq!(sig(1234.5, 2), "1200");
/// ```
pub fn sig(x: f64, digits: usize) -> String {
    let digits = digits.max(1);
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let exponent = x.abs().log10().floor() as i32;
    if (-4..15).contains(&exponent) {
        let decimals = (digits as i32 - 1 - exponent).max(0) as usize;
        let scale = 10f64.powi(exponent + 1 - digits as i32);
        let rounded = if decimals == 0 {
            (x / scale).round() * scale
        } else {
            x
        };
        trim_zeros(&format!("{rounded:.decimals$}"))
    } else {
        let text = format!("{x:.prec$e}", prec = digits - 1);
        let (mantissa, exponent) = text.split_once('e').unwrap_or((&text, "0"));
        format!("{}e{exponent}", trim_zeros(mantissa))
    }
}

/// "0.900" -> "0.9", "1.00" -> "1", "120" -> "120".
fn trim_zeros(text: &str) -> String {
    if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text.to_string()
    }
}

/// A p-value: 2 significant digits, or "< 1e-300" where it underflows to 0.
fn p_value(p: f64) -> String {
    if p == 0.0 {
        "< 1e-300".to_string()
    } else {
        format!("= {}", sig(p, 2))
    }
}

/// A count with thousands separators: 19,000.
pub fn count(n: u64) -> String {
    let digits = n.to_string();
    let mut out = String::with_capacity(digits.len() + digits.len() / 3);
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// An expected count: whole (19,000) from 10 on, to one decimal below (2.5).
fn expected_count(e: f64) -> String {
    if e >= 10.0 {
        count(e.round() as u64)
    } else {
        format!("{e:.1}")
    }
}

/// z-test of `estimate` against the exact `truth`, given the estimate's standard error. A standard
/// error of 0 (a zero-variance estimator) demands the truth to a relative `1e-12`.
///
/// ```
/// use rtl_exercises::check::z_test;
/// assert!(z_test("one standard error off", 0.51, 0.01, 0.5).is_ok());
/// assert!(z_test("ten standard errors off", 0.6, 0.01, 0.5).is_err());
/// ```
pub fn z_test(what: &str, estimate: f64, std_error: f64, truth: f64) -> CheckResult {
    if !estimate.is_finite() {
        return Err(format!(
            "{what}: the estimate is {}, expected about {}",
            num(estimate),
            sig(truth, 6)
        ));
    }
    if !(std_error >= 0.0 && std_error.is_finite()) {
        return Err(format!(
            "{what}: no usable standard error ({}): fewer than two values?",
            num(std_error)
        ));
    }
    if std_error == 0.0 {
        return close(what, estimate, truth, 1e-12);
    }
    let z = (estimate - truth) / std_error;
    if z.abs() < z_critical() {
        Ok(())
    } else {
        Err(format!(
            "{what}: estimate {} is {z:.1} standard errors ({}) from the exact {}",
            sig(estimate, 6),
            sig(std_error, 3),
            sig(truth, 6)
        ))
    }
}

/// z-test of the mean of `values` against `truth`, with the standard error measured from the values.
pub fn z_test_mean(what: &str, values: impl IntoIterator<Item = f64>, truth: f64) -> CheckResult {
    let (mean, se) = mean_and_std_error(values);
    z_test(what, mean, se, truth)
}

/// `got` equals `want` to a relative tolerance `rel` (absolute when `want` is 0).
pub fn close(what: &str, got: f64, want: f64, rel: f64) -> CheckResult {
    let scale = if want == 0.0 { 1.0 } else { want.abs() };
    if got.is_finite() && (got - want).abs() <= rel * scale {
        Ok(())
    } else if rel == 0.0 {
        Err(format!(
            "{what}: got {}, expected exactly {}",
            num(got),
            num(want)
        ))
    } else {
        Err(format!(
            "{what}: got {}, expected {} (to a relative {})",
            num(got),
            num(want),
            num(rel)
        ))
    }
}

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
                self::count(*count)
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

/// `v` has unit length to 1e-12 and finite components.
pub fn unit(what: &str, v: DVec3) -> CheckResult {
    if v.is_finite() && (v.length() - 1.0).abs() <= 1e-12 {
        Ok(())
    } else {
        Err(format!(
            "{what}: {v} is not a unit vector (length {})",
            v.length()
        ))
    }
}

/// Uniformly distributed unit vectors, for the checks' own integrations (not the learner's).
pub fn uniform_direction(rng: &mut dyn RngCore) -> DVec3 {
    use rand::Rng;
    let z = 1.0 - 2.0 * rng.random::<f64>();
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * rng.random::<f64>();
    DVec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// A generator that first replays a script of uniform values (each a multiple of 2^-53 in [0, 1),
/// e.g. 0 or [`U_MAX`]) as `rng.random::<f64>()` would draw them, then continues with a seeded stream.
pub struct ScriptedRng {
    script: Vec<u64>,
    next: usize,
    rest: Xoshiro256PlusPlus,
}

impl ScriptedRng {
    /// Replay `uniforms` first. rand 0.9 draws an `f64` as `(next_u64() >> 11) * 2^-53`.
    pub fn new(uniforms: &[f64], seed: u64) -> Self {
        let script = uniforms
            .iter()
            .map(|&u| {
                assert!((0.0..1.0).contains(&u), "a scripted uniform lies in [0, 1)");
                let k = (u * (1u64 << 53) as f64) as u64;
                assert_eq!(
                    k as f64,
                    u * (1u64 << 53) as f64,
                    "a scripted uniform is a multiple of 2^-53"
                );
                k << 11
            })
            .collect();
        Self {
            script,
            next: 0,
            rest: seeded(seed),
        }
    }
}

impl RngCore for ScriptedRng {
    fn next_u32(&mut self) -> u32 {
        (self.next_u64() >> 32) as u32
    }
    fn next_u64(&mut self) -> u64 {
        match self.script.get(self.next) {
            Some(&x) => {
                self.next += 1;
                x
            }
            None => self.rest.next_u64(),
        }
    }
    fn fill_bytes(&mut self, dst: &mut [u8]) {
        self.rest.fill_bytes(dst);
    }
}

/// The random-number source a check hands to the learner's code: [`seeded`]'s generator, after a
/// script of uniforms if [`Generator::scripted`], which counts what it has drawn. [`Generator::arg`]
/// names it for a panic report as a call that rebuilds it where it is (`check::replay(101, 8434)`),
/// and the uniforms that the call in progress drew are kept for the report too.
pub struct Generator {
    rng: ScriptedRng,
    seed: u64,
    script: [f64; SCRIPT_MAX],
    script_len: usize,
    drawn: u64,
}

/// The most uniforms a [`Generator`] replays before its seeded stream.
pub const SCRIPT_MAX: usize = 4;

impl Generator {
    /// The generator of [`seeded`]`(seed)`.
    pub fn new(seed: u64) -> Self {
        Self::scripted(&[], seed)
    }

    /// Replays `uniforms` (at most [`SCRIPT_MAX`], as [`ScriptedRng`] does), then [`seeded`]`(seed)`.
    pub fn scripted(uniforms: &[f64], seed: u64) -> Self {
        assert!(
            uniforms.len() <= SCRIPT_MAX,
            "a script of at most {SCRIPT_MAX} uniforms"
        );
        let mut script = [0.0; SCRIPT_MAX];
        script[..uniforms.len()].copy_from_slice(uniforms);
        Self {
            rng: ScriptedRng::new(uniforms, seed),
            seed,
            script,
            script_len: uniforms.len(),
            drawn: 0,
        }
    }

    /// This generator as it is now, as an argument of a recorded call: see [`calling`].
    pub fn arg(&self) -> Arg {
        let replayed = (self.drawn as usize).min(self.script_len);
        let mut script = [0.0; SCRIPT_MAX];
        let left = self.script_len - replayed;
        script[..left].copy_from_slice(&self.script[replayed..self.script_len]);
        Arg::Rng(RngState {
            seed: self.seed,
            script,
            script_len: left,
            skip: self.drawn - replayed as u64,
        })
    }
}

impl RngCore for Generator {
    fn next_u32(&mut self) -> u32 {
        // As Xoshiro256PlusPlus does, so that `replay` gives the same values.
        (self.next_u64() >> 32) as u32
    }
    fn next_u64(&mut self) -> u64 {
        let x = self.rng.next_u64();
        self.drawn += 1;
        DRAWS.with(|d| {
            let mut draws = d.get();
            draws.last[(draws.count % DRAWS_KEPT as u64) as usize] = x;
            draws.count += 1;
            d.set(draws);
        });
        x
    }
    fn fill_bytes(&mut self, dst: &mut [u8]) {
        rand::rand_core::impls::fill_bytes_via_next(self, dst);
    }
}

/// [`seeded`]`(seed)` after `skip` draws of 64 bits: a generator of a check where a panic report
/// found it (`replay(101, 8434)`), so that the call can be repeated in a test of one's own.
pub fn replay(seed: u64, skip: u64) -> Xoshiro256PlusPlus {
    let mut rng = seeded(seed);
    for _ in 0..skip {
        rng.next_u64();
    }
    rng
}

/// A [`Generator`] as a recorded call received it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RngState {
    seed: u64,
    /// The scripted uniforms still to come.
    script: [f64; SCRIPT_MAX],
    script_len: usize,
    /// Draws of the seeded stream already made.
    skip: u64,
}

impl fmt::Display for RngState {
    /// The expression that builds the same generator: `rtl_exercises::check::replay(101, 8434)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.script_len > 0 {
            let script: Vec<String> = self.script[..self.script_len]
                .iter()
                .map(|&u| num(u))
                .collect();
            write!(
                f,
                "rtl_exercises::check::ScriptedRng::new(&[{}], {})",
                script.join(", "),
                self.seed
            )
        } else if self.skip == 0 {
            write!(f, "rtl_exercises::check::seeded({})", self.seed)
        } else {
            write!(
                f,
                "rtl_exercises::check::replay({}, {})",
                self.seed, self.skip
            )
        }
    }
}

/// A list handed to the learner's code, summarised for a panic report: its length, its first
/// values, and where its values that are not finite (NaN, infinite) lie.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct List {
    len: usize,
    head: [Item; LIST_HEAD],
    n_bad: usize,
    bad_at: [usize; LIST_BAD],
}

/// A value of a [`List`].
#[derive(Clone, Copy, Debug, PartialEq)]
enum Item {
    Real(f64),
    Vector(DVec3),
}

impl Item {
    fn is_finite(self) -> bool {
        match self {
            Item::Real(x) => x.is_finite(),
            Item::Vector(v) => v.is_finite(),
        }
    }
}

impl fmt::Display for Item {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Item::Real(x) => f.write_str(&num(*x)),
            Item::Vector(v) => write!(f, "{}", Arg::Vector(*v)),
        }
    }
}

/// How many reals of a [`List`] are shown (vectors: 3); a list of at most this many is shown whole.
const LIST_HEAD: usize = 6;
/// How many places of values that are not finite a [`List`] names.
const LIST_BAD: usize = 3;

impl List {
    fn of(items: impl ExactSizeIterator<Item = Item>) -> Self {
        let mut list = Self {
            len: items.len(),
            head: [Item::Real(0.0); LIST_HEAD],
            n_bad: 0,
            bad_at: [0; LIST_BAD],
        };
        for (i, item) in items.enumerate() {
            if i < LIST_HEAD {
                list.head[i] = item;
            }
            if !item.is_finite() {
                if list.n_bad < LIST_BAD {
                    list.bad_at[list.n_bad] = i;
                }
                list.n_bad += 1;
            }
        }
        list
    }

    /// A list of reals.
    pub fn reals(values: &[f64]) -> Self {
        Self::of(values.iter().map(|&x| Item::Real(x)))
    }

    /// A list of vectors.
    pub fn vectors(values: &[DVec3]) -> Self {
        Self::of(values.iter().map(|&v| Item::Vector(v)))
    }
}

impl fmt::Display for List {
    /// `[1, NaN]` whole; longer, `[0.25, 0.5, ...] (10,000 values; not finite at 17, 5,000, 9,999)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // Vectors are long: three of them.
        let head = match self.head[0] {
            Item::Vector(_) => 3,
            Item::Real(_) => LIST_HEAD,
        };
        let shown: Vec<String> = self.head[..self.len.min(head)]
            .iter()
            .map(Item::to_string)
            .collect();
        if self.len <= head {
            return write!(f, "[{}]", shown.join(", "));
        }
        write!(
            f,
            "[{}, ...] ({} values",
            shown.join(", "),
            count(self.len as u64)
        )?;
        if self.n_bad > 0 {
            let at: Vec<String> = self.bad_at[..self.n_bad.min(LIST_BAD)]
                .iter()
                .map(|&i| count(i as u64))
                .collect();
            let more = if self.n_bad > LIST_BAD {
                format!(" and {} more", count((self.n_bad - LIST_BAD) as u64))
            } else {
                String::new()
            };
            write!(f, "; not finite at {}{more}", at.join(", "))?;
        }
        f.write_str(")")
    }
}

/// An argument of a call to the learner's code, kept so that a panic report can name it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Arg {
    Real(f64),
    Vector(DVec3),
    Count(usize),
    /// A slice, summarised.
    List(List),
    /// A random-number source ([`Generator::arg`]).
    Rng(RngState),
    /// A value the check states as code, such as a function: `|x| x * x`.
    Text(&'static str),
}

impl fmt::Display for Arg {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Arg::Real(x) => f.write_str(&num(*x)),
            Arg::Vector(v) => write!(f, "[{}, {}, {}]", num(v.x), num(v.y), num(v.z)),
            Arg::Count(n) => write!(f, "{n}"),
            Arg::List(list) => write!(f, "{list}"),
            Arg::Rng(rng) => write!(f, "{rng}"),
            Arg::Text(text) => f.write_str(text),
        }
    }
}

impl From<f64> for Arg {
    fn from(x: f64) -> Self {
        Arg::Real(x)
    }
}

impl From<DVec3> for Arg {
    fn from(v: DVec3) -> Self {
        Arg::Vector(v)
    }
}

impl From<usize> for Arg {
    fn from(n: usize) -> Self {
        Arg::Count(n)
    }
}

impl From<&[f64]> for Arg {
    fn from(values: &[f64]) -> Self {
        Arg::List(List::reals(values))
    }
}

impl From<&[DVec3]> for Arg {
    fn from(values: &[DVec3]) -> Self {
        Arg::List(List::vectors(values))
    }
}

/// The most arguments a recorded call keeps.
const MAX_ARGS: usize = 5;

/// A call to the learner's code in progress: the function's name, its named arguments, and for a
/// method, the state of the value it is called on.
#[derive(Clone, Copy)]
struct Call {
    function: &'static str,
    args: [(&'static str, Arg); MAX_ARGS],
    n_args: usize,
    state: Option<(&'static str, Arg)>,
}

/// The 64-bit values a [`Generator`] handed out since the call in progress began: how many, and the
/// last [`DRAWS_KEPT`] of them (a ring).
#[derive(Clone, Copy, Default)]
struct Draws {
    count: u64,
    last: [u64; DRAWS_KEPT],
}

const DRAWS_KEPT: usize = 4;

impl Draws {
    /// "which drew u = 0.25, 0.5", as `rng.random::<f64>()` reads the values.
    fn describe(&self) -> String {
        let kept = self.count.min(DRAWS_KEPT as u64) as usize;
        let u: Vec<String> = (self.count as usize - kept..self.count as usize)
            .map(|i| num((self.last[i % DRAWS_KEPT] >> 11) as f64 / (1u64 << 53) as f64))
            .collect();
        match self.count {
            0 => "which drew nothing from rng".to_string(),
            n if n as usize <= DRAWS_KEPT => format!("which drew u = {}", u.join(", ")),
            n => format!(
                "which drew {} uniforms, the last u = {}",
                count(n),
                u.join(", ")
            ),
        }
    }
}

thread_local! {
    static CALL: Cell<Option<Call>> = const { Cell::new(None) };
    static DRAWS: Cell<Draws> = const { Cell::new(Draws { count: 0, last: [0; DRAWS_KEPT] }) };
}

/// Calls `f`, which calls the learner's `function` with `args` (name, value), and records the call
/// while it runs, so that a panic inside it is reported with the input that caused it
/// ("while calling sample_linear(u = 0.5)"; see [`call_in_progress`]). An argument of
/// [`Generator::arg`] is reported as the expression that rebuilds the generator, with the uniforms
/// the call drew from it. Costs a few stores of a thread-local: cheap enough for every sample of a
/// chi-square test.
pub fn calling<T>(
    function: &'static str,
    args: &[(&'static str, Arg)],
    f: impl FnOnce() -> T,
) -> T {
    record(Call::new(function, args, None), f)
}

/// [`calling`] for a method of a value that the report describes by how it came to be, `state`
/// (words, then a value): `add(sample = [NaN, 0, 0]) on PixelAccumulator::new() after adding
/// [0.5, 0.5]` is `calling_method("add", &[("sample", ...)], ("on PixelAccumulator::new() after
/// adding", list), f)`.
pub fn calling_method<T>(
    function: &'static str,
    args: &[(&'static str, Arg)],
    state: (&'static str, Arg),
    f: impl FnOnce() -> T,
) -> T {
    record(Call::new(function, args, Some(state)), f)
}

impl Call {
    fn new(
        function: &'static str,
        args: &[(&'static str, Arg)],
        state: Option<(&'static str, Arg)>,
    ) -> Self {
        let mut call = Call {
            function,
            args: [("", Arg::Count(0)); MAX_ARGS],
            n_args: args.len().min(MAX_ARGS),
            state,
        };
        call.args[..call.n_args].copy_from_slice(&args[..call.n_args]);
        call
    }
}

/// Runs `f` with `call` recorded (and a fresh record of draws), then restores the record of the
/// call around it, if any.
fn record<T>(call: Call, f: impl FnOnce() -> T) -> T {
    let outer = CALL.with(|c| c.replace(Some(call)));
    let outer_draws = DRAWS.with(|d| d.replace(Draws::default()));
    let out = f();
    CALL.with(|c| c.set(outer));
    DRAWS.with(|d| d.set(outer_draws));
    out
}

/// The recorded call in progress on this thread, as text ("sample_linear(u = 0.5)"), if any; with
/// a generator among its arguments, what the call drew from it
/// ("generate(rng = rtl_exercises::check::seeded(7)), which drew u = 0.5").
pub fn call_in_progress() -> Option<String> {
    let call = CALL.with(Cell::get)?;
    let args = &call.args[..call.n_args];
    let shown: Vec<String> = args
        .iter()
        .map(|(name, value)| format!("{name} = {value}"))
        .collect();
    let mut text = format!("{}({})", call.function, shown.join(", "));
    if let Some((words, value)) = call.state {
        text += &format!(" {words} {value}");
    }
    if args.iter().any(|(_, a)| matches!(a, Arg::Rng(_))) {
        text += ", ";
        text += &DRAWS.with(Cell::get).describe();
        text += ",";
    }
    Some(text)
}

/// Forgets the recorded call (a panic skips the end of [`calling`]).
pub fn forget_call() {
    CALL.with(|c| c.set(None));
    DRAWS.with(|d| d.set(Draws::default()));
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::Rng;

    #[test]
    fn scripted_rng_replays_zero_and_the_largest_uniform() {
        let mut rng = ScriptedRng::new(&[0.0, U_MAX, 0.5], 1);
        assert_eq!(rng.random::<f64>(), 0.0);
        assert_eq!(rng.random::<f64>(), U_MAX);
        assert_eq!(rng.random::<f64>(), 0.5);
        assert!(rng.random::<f64>() < 1.0);
    }

    #[test]
    fn z_critical_is_the_two_sided_1e_minus_6_quantile() {
        assert!((z_critical() - 4.8916).abs() < 1e-3);
    }

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
    fn numbers_print_plainly_unless_very_small_or_large() {
        assert_eq!(num(0.0), "0");
        assert_eq!(num(0.25), "0.25");
        assert_eq!(num(0.0625), "0.0625");
        assert_eq!(num(-3.0), "-3");
        assert_eq!(num(1e-9), "1e-9");
        assert_eq!(num(2.5e20), "2.5e20");
        assert_eq!(num(f64::NAN), "NaN");
        assert_eq!(sig(0.00519, 3), "0.00519");
        assert_eq!(sig(1.23456789, 6), "1.23457");
        assert_eq!(sig(5.19e-12, 3), "5.19e-12");
        assert_eq!(sig(0.9, 3), "0.9");
        assert_eq!(sig(5e-12, 3), "5e-12");
        assert_eq!(count(19_000), "19,000");
        assert_eq!(count(999), "999");
        assert_eq!(count(1_234_567), "1,234,567");
        let err = close("f(1)", 0.25, 0.5, 1e-15).unwrap_err();
        assert_eq!(err, "f(1): got 0.25, expected 0.5 (to a relative 1e-15)");
        let err = close("f(0)", 1e-300, 0.0, 0.0).unwrap_err();
        assert_eq!(err, "f(0): got 1e-300, expected exactly 0");
    }

    #[test]
    fn a_recorded_call_is_named_while_it_runs_and_forgotten_after() {
        let inside = calling(
            "f",
            &[("u", 0.5.into()), ("w", DVec3::Z.into())],
            call_in_progress,
        );
        assert_eq!(inside.as_deref(), Some("f(u = 0.5, w = [0, 0, 1])"));
        assert_eq!(call_in_progress(), None);
    }

    #[test]
    fn a_generator_is_named_as_the_expression_that_rebuilds_it() {
        let mut g = Generator::new(9);
        assert_eq!(g.arg().to_string(), "rtl_exercises::check::seeded(9)");
        for _ in 0..5 {
            g.next_u64();
        }
        g.next_u32();
        assert_eq!(g.arg().to_string(), "rtl_exercises::check::replay(9, 6)");
        // replay(9, 6) goes on as the generator does, whichever width is drawn.
        let mut r = replay(9, 6);
        assert_eq!((g.next_u64(), g.next_u32()), (r.next_u64(), r.next_u32()));
        // A script is named by what is left of it, then by the seeded stream after it.
        let mut s = Generator::scripted(&[0.0, 0.25, 0.5], 3);
        assert_eq!(
            s.arg().to_string(),
            "rtl_exercises::check::ScriptedRng::new(&[0, 0.25, 0.5], 3)"
        );
        s.next_u64();
        assert_eq!(
            s.arg().to_string(),
            "rtl_exercises::check::ScriptedRng::new(&[0.25, 0.5], 3)"
        );
        s.next_u64();
        s.next_u64();
        assert_eq!(s.arg().to_string(), "rtl_exercises::check::seeded(3)");
        s.next_u64();
        assert_eq!(s.arg().to_string(), "rtl_exercises::check::replay(3, 1)");
    }

    #[test]
    fn a_recorded_call_with_a_generator_says_what_it_drew() {
        let mut g = Generator::scripted(&[0.5, 0.25], 1);
        let args = [("rng", g.arg())];
        let drew_two = calling("f", &args, || {
            g.next_u64();
            g.next_u64();
            call_in_progress()
        });
        assert_eq!(
            drew_two.as_deref(),
            Some(
                "f(rng = rtl_exercises::check::ScriptedRng::new(&[0.5, 0.25], 1)), which drew \
                 u = 0.5, 0.25,"
            )
        );
        // Many draws: how many, and the last four. Draws before the call are not counted.
        let mut g = Generator::scripted(&[0.5, 0.25, 0.125, 0.0625], 1);
        g.next_u64();
        let args = [("n", Arg::Count(3)), ("rng", g.arg())];
        let text = calling("g", &args, || {
            let nothing = call_in_progress().unwrap();
            for _ in 0..5 {
                g.next_u64();
            }
            (nothing, call_in_progress().unwrap())
        });
        assert_eq!(
            text.0,
            "g(n = 3, rng = rtl_exercises::check::ScriptedRng::new(&[0.25, 0.125, 0.0625], 1)), \
             which drew nothing from rng,"
        );
        let mut rest = seeded(1);
        rest.next_u64();
        let u = num((rest.next_u64() >> 11) as f64 / (1u64 << 53) as f64);
        assert!(
            text.1.ends_with(&format!(
                "which drew 5 uniforms, the last u = 0.125, 0.0625, {}, {u},",
                num((seeded(1).next_u64() >> 11) as f64 / (1u64 << 53) as f64)
            )),
            "{}",
            text.1
        );
    }

    #[test]
    fn lists_are_shown_whole_when_short_and_summarised_when_long() {
        let nan = f64::NAN;
        assert_eq!(Arg::from(&[1.0, nan][..]).to_string(), "[1, NaN]");
        assert_eq!(Arg::from(&[][..] as &[f64]).to_string(), "[]");
        let mut long = vec![0.5; 1000];
        for i in [3, 17, 500, 999] {
            long[i] = f64::INFINITY;
        }
        assert_eq!(
            Arg::from(long.as_slice()).to_string(),
            "[0.5, 0.5, 0.5, inf, 0.5, 0.5, ...] (1,000 values; not finite at 3, 17, 500 and 1 more)"
        );
        let v = [DVec3::ONE, DVec3::NAN, DVec3::ZERO, DVec3::ONE];
        assert_eq!(
            Arg::from(&v[..]).to_string(),
            "[[1, 1, 1], [NaN, NaN, NaN], [0, 0, 0], ...] (4 values; not finite at 1)"
        );
    }

    #[test]
    fn a_method_call_is_named_with_the_state_of_its_value() {
        let state = ("on X::new() after adding", Arg::from(&[0.5][..]));
        let text = calling_method("add", &[("x", Arg::Real(2.0))], state, call_in_progress);
        assert_eq!(
            text.as_deref(),
            Some("add(x = 2) on X::new() after adding [0.5]")
        );
        // A call inside another restores the outer record when it ends.
        let outer = calling("outer", &[], || {
            calling("inner", &[], || {});
            call_in_progress()
        });
        assert_eq!(outer.as_deref(), Some("outer()"));
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

    #[test]
    fn z_test_rejects_a_biased_estimate_and_demands_exactness_at_zero_error() {
        z_test("ok", 1.0 + 4.0 * 0.01, 0.01, 1.0).unwrap();
        assert!(z_test("biased", 1.0 + 5.0 * 0.01, 0.01, 1.0).is_err());
        assert!(z_test("exact", 1.0 + 1e-9, 0.0, 1.0).is_err());
        assert!(z_test("nan", f64::NAN, 0.1, 1.0).is_err());
        // No data, or one value, has no standard error: never a pass.
        assert!(z_test_mean("empty", [], 0.0).is_err());
        assert!(z_test_mean("one value", [0.5], 0.5).is_err());
    }
}
