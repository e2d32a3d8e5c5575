//! The statistical checks every exercise shares: a z-test against an exact answer, a chi-square
//!
//! The checks of the exercise `crates/exercises/exercises/check.rs`, which states the task, and what
//! that exercise is given.

use glam::DVec3;
use rand::{RngCore, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use statrs::distribution::{ChiSquared, ContinuousCDF, Normal};
use std::f64::consts::PI;

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
            "{what}: the estimate is {estimate}, expected about {truth}"
        ));
    }
    if !(std_error >= 0.0 && std_error.is_finite()) {
        return Err(format!(
            "{what}: no usable standard error ({std_error}): fewer than two values?"
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
            "{what}: estimate {estimate:.6} is {z:.1} standard errors ({std_error:.2e}) from the exact {truth:.6}"
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
    } else {
        Err(format!(
            "{what}: got {got:e}, expected {want:e} (relative tolerance {rel:e})"
        ))
    }
}

/// Chi-square goodness-of-fit test of `observed` counts against `expected` counts, cell by cell.
///
/// A sample in a cell of expected count 0 fails at once. Cells of expected count < 5 are pooled
/// (smallest first) until each pool reaches 5; a remainder joins the last pool. The p-value is
/// `ChiSquared::new(cells - 1).sf(statistic)`, rejected below [`sidak_alpha`].
pub fn chi_square(what: &str, observed: &[u64], expected: &[f64]) -> CheckResult {
    let (statistic, dof, p) =
        chi_square_p_value(observed, expected).map_err(|e| format!("{what}: {e}"))?;
    if p >= sidak_alpha() {
        Ok(())
    } else {
        Err(format!(
            "{what}: chi-square {statistic:.1} on {dof} degrees of freedom, p = {p:.2e} < {:.2e}: \
             the samples do not follow the density",
            sidak_alpha()
        ))
    }
}

/// The chi-square statistic, degrees of freedom and p-value of [`chi_square`], or why there is none
/// (a sample where the density is 0, or no degrees of freedom).
pub fn chi_square_p_value(observed: &[u64], expected: &[f64]) -> Result<(f64, f64, f64), String> {
    assert_eq!(
        observed.len(),
        expected.len(),
        "one expected count per cell"
    );
    for (i, (&o, &e)) in observed.iter().zip(expected).enumerate() {
        if e == 0.0 && o > 0 {
            return Err(format!(
                "{o} samples fell in cell {i}, where the density is 0"
            ));
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
        return Err(
            "fewer than 2 cells after pooling; the test has no degrees of freedom".to_string(),
        );
    }
    let statistic: f64 = pooled.iter().map(|&(e, o)| (o - e) * (o - e) / e).sum();
    let dof = (pooled.len() - 1) as f64;
    let p = ChiSquared::new(dof).expect("dof >= 1").sf(statistic);
    Ok((statistic, dof, p))
}

/// Cells on the sphere of directions, or a zone of it, of equal area: `n_phi` equal steps of the
/// azimuth phi in [0, 2 pi) times `n_z` equal steps of z = cos theta in [z_min, z_max]
/// (solid angle d omega = d phi dz, so equal steps are equal areas).
#[derive(Clone, Copy, Debug)]
pub struct SphereBins {
    pub n_phi: usize,
    pub n_z: usize,
    pub z_min: f64,
    pub z_max: f64,
}

impl SphereBins {
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
                    return Err(format!(
                        "{what}: generated direction {d} lies outside the zone sampled"
                    ));
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
        chi_square("fair die", &fair, &expected).unwrap();
        assert!(chi_square("loaded die", &loaded, &expected).is_err());
    }

    #[test]
    fn chi_square_fails_at_once_on_a_sample_outside_the_support() {
        let err = chi_square("support", &[10, 10, 1], &[10.5, 10.5, 0.0]).unwrap_err();
        assert!(err.contains("density is 0"), "{err}");
    }

    #[test]
    fn chi_square_pools_small_cells() {
        // 40 cells of expected 0.5 pool into 4 cells of 5; all 20 samples in one of them is rejected.
        let expected = vec![0.5; 40];
        let mut observed = vec![0u64; 40];
        observed[0] = 20;
        assert!(chi_square("pooled", &observed, &expected).is_err());
        let spread: Vec<u64> = (0..40).map(|i| u64::from(i % 2 == 0)).collect();
        chi_square("pooled", &spread, &expected).unwrap();
    }

    #[test]
    fn sphere_bins_cover_the_sphere_with_equal_areas() {
        let bins = SphereBins {
            n_phi: 8,
            n_z: 5,
            z_min: -1.0,
            z_max: 1.0,
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
