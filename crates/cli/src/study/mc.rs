//! `rtl study mc`: how fast each Monte Carlo estimator of the book's integrals converges, in samples and
//! in time.
//!
//! For every integral and estimator, and every N = 2^4 ... 2^24 (`--quick`: ... 2^16), the estimator
//! runs R = 30 times with independent seeds. The RMS error of those R estimates against the exact
//! integral, their mean reported standard error, and the time per sample go to `DIR/mc.csv`; the log-log
//! slopes of error against N go to `DIR/mc_slopes.csv`; each integral gets a plot of error against N and
//! one of error against time per estimate, with the fitted slope in the legend.
//!
//! Jittered and Sobol estimators take their standard error from 4 independent replicates of N/4 samples
//! each (randomised QMC); all N samples count towards N and the time.

use crate::csv::{CsvError, CsvTable, csv_field};
use crate::plot;
use anyhow::{Context, Result};
use clap::Args;
use glam::DVec2;
use rand::{Rng, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;
use rayon::prelude::*;
use rtl_mc::densities::{linear_pdf, sample_linear};
use rtl_mc::{
    Estimate, Interval, McError, Rect, importance, jittered, jittered_2d, plain, plain_2d, sobol,
    sobol_2d,
};
use rtl_pdf::warp;
use std::f64::consts::PI;
use std::fmt::Write as _;
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(Args)]
pub struct McArgs {
    /// Directory for the CSV and the plots (created if missing; default: a scratch directory,
    /// printed; the book's figures are book/src/figures).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// N up to 2^16 instead of 2^24: seconds instead of minutes.
    #[arg(long)]
    pub quick: bool,
    /// Redraw the plots from the measurements already in the output directory (mc.csv), timing
    /// nothing and writing no CSV: for a change of labels or layout, or on a busy machine.
    #[arg(long, conflicts_with = "quick")]
    pub replot: bool,
}

/// Independent repetitions of every estimator at every N.
pub(crate) const REPETITIONS: u64 = 30;
/// Replicates inside one jittered or Sobol estimate (its standard error comes from their spread).
const REPLICATES: u32 = 4;
const SMALLEST_LOG2_N: u32 = 4;

pub(crate) type Rng64 = Xoshiro256PlusPlus;

/// One estimator of one integral: runs it with `n` samples in all.
pub(crate) struct Case {
    pub(crate) integral: &'static str,
    pub(crate) slug: &'static str,
    pub(crate) exact: f64,
    pub(crate) estimator: &'static str,
    pub(crate) run: fn(u64, &mut Rng64) -> Result<Estimate, McError>,
}

/// The `nx` by `ny` grid of `cells = 2^m` cells, as square as a power of two allows.
fn grid(cells: u64) -> (u64, u64) {
    let m = cells.trailing_zeros();
    (1 << m.div_ceil(2), 1 << (m / 2))
}

/// Samples per replicate when `n` samples are split into [`REPLICATES`] replicates.
fn q(n: u64) -> u64 {
    n / REPLICATES as u64
}

fn x_sq(x: f64) -> f64 {
    x * x
}

fn zero_two() -> Interval {
    Interval::new(0.0, 2.0).expect("0 < 2")
}

fn in_circle(p: [f64; 2]) -> f64 {
    if p[0] * p[0] + p[1] * p[1] < 1.0 {
        1.0
    } else {
        0.0
    }
}

fn square() -> Rect {
    Rect::new(-1.0, 1.0, -1.0, 1.0).expect("a valid square")
}

fn unit_square() -> Rect {
    Rect::new(0.0, 1.0, 0.0, 1.0).expect("a valid square")
}

// The sphere and hemisphere warps of rtl-pdf (chapter 7), which the renderer uses too. Each maps the
// unit square onto directions with a constant or known density, so an integral over directions becomes
// an integral over the unit square that jittered and Sobol points can stratify. Where a direction only
// feeds an integrand of z, `black_box` keeps the compiler from skipping its x and y, so every estimator
// pays for whole directions and the times compare fairly.

/// Uniform on the sphere; density 1 / 4 pi.
fn uniform_sphere(u: [f64; 2]) -> [f64; 3] {
    warp::sample_uniform_sphere(DVec2::from(u)).to_array()
}

/// Uniform on the hemisphere z >= 0; density 1 / 2 pi.
fn uniform_hemisphere(u: [f64; 2]) -> [f64; 3] {
    warp::sample_uniform_hemisphere(DVec2::from(u)).to_array()
}

/// Cosine-weighted on the hemisphere (Malley's method on the concentric disk); density z / pi.
fn cosine_hemisphere(u: [f64; 2]) -> [f64; 3] {
    warp::sample_cosine_hemisphere(DVec2::from(u)).to_array()
}

fn random_pair(rng: &mut Rng64) -> [f64; 2] {
    [rng.random::<f64>(), rng.random::<f64>()]
}

fn cos_sq(d: [f64; 3]) -> f64 {
    d[2] * d[2]
}

fn cos_cubed(d: [f64; 3]) -> f64 {
    d[2] * d[2] * d[2]
}

/// f/p of cos^3 under cosine sampling, as a function on the unit square.
fn cos_cubed_over_cosine(u: [f64; 2]) -> f64 {
    let d = black_box(cosine_hemisphere(u));
    cos_cubed(d) / (d[2] / PI)
}

pub(crate) fn cases() -> Vec<Case> {
    const X2: &str = "x^2 over 0..2";
    const PI_DISC: &str = "pi as the unit disc area";
    const SPHERE: &str = "cos^2 over the sphere";
    const HEMI: &str = "cos^3 over the hemisphere";
    vec![
        Case {
            integral: X2,
            slug: "x_sq",
            exact: 8.0 / 3.0,
            estimator: "uniform",
            run: |n, r| plain(x_sq, zero_two(), n, r),
        },
        Case {
            integral: X2,
            slug: "x_sq",
            exact: 8.0 / 3.0,
            estimator: "importance p = x/2",
            run: |n, r| {
                let s = |r: &mut Rng64| sample_linear(r.random::<f64>());
                importance(x_sq, s, linear_pdf, n, r)
            },
        },
        Case {
            integral: X2,
            slug: "x_sq",
            exact: 8.0 / 3.0,
            estimator: "jittered",
            run: |n, r| jittered(x_sq, zero_two(), q(n), REPLICATES, r),
        },
        Case {
            integral: X2,
            slug: "x_sq",
            exact: 8.0 / 3.0,
            estimator: "scrambled Sobol",
            run: |n, r| sobol(x_sq, zero_two(), q(n), REPLICATES, r),
        },
        Case {
            integral: PI_DISC,
            slug: "pi",
            exact: PI,
            estimator: "uniform",
            run: |n, r| plain_2d(in_circle, square(), n, r),
        },
        Case {
            integral: PI_DISC,
            slug: "pi",
            exact: PI,
            estimator: "jittered",
            run: |n, r| jittered_2d(in_circle, square(), grid(q(n)), REPLICATES, r),
        },
        Case {
            integral: PI_DISC,
            slug: "pi",
            exact: PI,
            estimator: "scrambled Sobol",
            run: |n, r| sobol_2d(in_circle, square(), q(n), REPLICATES, r),
        },
        Case {
            integral: SPHERE,
            slug: "sphere_cos_sq",
            exact: 4.0 * PI / 3.0,
            estimator: "uniform",
            run: |n, r| {
                let s = |r: &mut Rng64| uniform_sphere(random_pair(r));
                importance(cos_sq, s, |_| 1.0 / (4.0 * PI), n, r)
            },
        },
        Case {
            integral: SPHERE,
            slug: "sphere_cos_sq",
            exact: 4.0 * PI / 3.0,
            estimator: "uniform + jittered",
            run: |n, r| {
                let g = |u| 4.0 * PI * cos_sq(black_box(uniform_sphere(u)));
                jittered_2d(g, unit_square(), grid(q(n)), REPLICATES, r)
            },
        },
        Case {
            integral: SPHERE,
            slug: "sphere_cos_sq",
            exact: 4.0 * PI / 3.0,
            estimator: "uniform + scrambled Sobol",
            run: |n, r| {
                let g = |u| 4.0 * PI * cos_sq(black_box(uniform_sphere(u)));
                sobol_2d(g, unit_square(), q(n), REPLICATES, r)
            },
        },
        Case {
            integral: HEMI,
            slug: "hemisphere_cos_cubed",
            exact: PI / 2.0,
            estimator: "uniform",
            run: |n, r| {
                let s = |r: &mut Rng64| uniform_hemisphere(random_pair(r));
                importance(cos_cubed, s, |_| 1.0 / (2.0 * PI), n, r)
            },
        },
        Case {
            integral: HEMI,
            slug: "hemisphere_cos_cubed",
            exact: PI / 2.0,
            estimator: "cosine",
            run: |n, r| {
                let s = |r: &mut Rng64| cosine_hemisphere(random_pair(r));
                importance(cos_cubed, s, |d| d[2] / PI, n, r)
            },
        },
        Case {
            integral: HEMI,
            slug: "hemisphere_cos_cubed",
            exact: PI / 2.0,
            estimator: "cosine + scrambled Sobol",
            run: |n, r| sobol_2d(cos_cubed_over_cosine, unit_square(), q(n), REPLICATES, r),
        },
    ]
}

/// The measurements of one estimator at one N (a line of mc.csv without its names).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Row {
    pub(crate) n: u64,
    pub(crate) rms_error: f64,
    pub(crate) mean_std_error: f64,
    pub(crate) ns_per_sample: f64,
    pub(crate) seconds_per_estimate: f64,
}

/// A seed that depends only on the case, N and the repetition, so results do not depend on threads.
pub(crate) fn seed(case: usize, log2_n: u32, rep: u64) -> u64 {
    ((case as u64) << 48) ^ (u64::from(log2_n) << 40) ^ rep ^ 0x5eed_0000_0000_0000
}

pub(crate) fn measure(index: usize, case: &Case, log2_n: u32) -> Result<Row> {
    let n = 1u64 << log2_n;
    let runs: Vec<Estimate> = (0..REPETITIONS)
        .into_par_iter()
        .map(|rep| {
            let mut rng = Rng64::seed_from_u64(seed(index, log2_n, rep));
            (case.run)(n, &mut rng)
        })
        .collect::<Result<_, _>>()
        .with_context(|| format!("{} / {} at N = {n}", case.integral, case.estimator))?;
    let reps = runs.len() as f64;
    let mse = runs
        .iter()
        .map(|e| (e.value() - case.exact).powi(2))
        .sum::<f64>()
        / reps;
    let mean_se = runs.iter().filter_map(Estimate::std_error).sum::<f64>() / reps;
    let seconds = runs.iter().map(|e| e.elapsed.as_secs_f64()).sum::<f64>() / reps;
    Ok(Row {
        n,
        rms_error: mse.sqrt(),
        mean_std_error: mean_se,
        ns_per_sample: seconds * 1e9 / n as f64,
        seconds_per_estimate: seconds,
    })
}

pub fn run(args: McArgs) -> Result<()> {
    let out_dir = super::out_dir(args.out.clone(), "mc")?;
    let csv_path = out_dir.join("mc.csv");
    if args.replot {
        let lines = read(&csv_path)?;
        plots(&lines, &out_dir)?;
        println!(
            "redrew the plots mc_*.png in {} from {}, timing nothing",
            out_dir.display(),
            csv_path.display()
        );
        return Ok(());
    }
    let largest = if args.quick { 16 } else { 24 };
    let cases = cases();
    println!(
        "study mc: {} estimators, N = 2^{SMALLEST_LOG2_N} .. 2^{largest}, R = {REPETITIONS} repetitions each, \
         on {} threads{}",
        cases.len(),
        rayon::current_num_threads(),
        if args.quick {
            " (--quick)"
        } else {
            " (about 3 minutes on 2 cores)"
        }
    );
    let start = Instant::now();
    let mut lines: Vec<Line> = Vec::new();
    for (i, case) in cases.iter().enumerate() {
        let t = Instant::now();
        for k in SMALLEST_LOG2_N..=largest {
            lines.push(Line {
                integral: case.integral.to_string(),
                estimator: case.estimator.to_string(),
                repetitions: REPETITIONS,
                row: measure(i, case, k)?,
            });
        }
        eprintln!(
            "  {:<32} {:<26} {:.1} s",
            case.integral,
            case.estimator,
            t.elapsed().as_secs_f64()
        );
    }
    std::fs::write(&csv_path, csv(&lines))
        .with_context(|| format!("writing {}", csv_path.display()))?;

    // Slopes, and a pair of plots per integral.
    let mut slopes =
        String::from("integral,estimator,slope_error_vs_n,ns_per_sample_at_largest_n\n");
    println!(
        "\n| integral | estimator | slope of RMS error vs N | RMS error at N = 2^{largest} | ns/sample |"
    );
    println!("|---|---|---|---|---|");
    for (integral, estimator, rows) in groups(&lines) {
        let vs_n: Vec<(f64, f64)> = rows
            .iter()
            .map(|l| (l.row.n as f64, l.row.rms_error))
            .collect();
        let slope = plot::loglog_slope(&vs_n).unwrap_or(f64::NAN);
        let last = &rows.last().expect("at least one N").row;
        writeln!(
            slopes,
            "{},{},{slope:.3},{:.3}",
            csv_field(integral),
            csv_field(estimator),
            last.ns_per_sample
        )?;
        println!(
            "| {integral} | {estimator} | {slope:.2} | {:.2e} | {:.1} |",
            last.rms_error, last.ns_per_sample
        );
    }
    plots(&lines, &out_dir)?;
    let slopes_path = out_dir.join("mc_slopes.csv");
    std::fs::write(&slopes_path, slopes)
        .with_context(|| format!("writing {}", slopes_path.display()))?;
    println!(
        "\nwrote {} and plots mc_*.png in {} ({:.1} s)",
        csv_path.display(),
        out_dir.display(),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}

/// One line of mc.csv: one estimator of one integral at one N.
#[derive(Clone, Debug, PartialEq)]
struct Line {
    integral: String,
    estimator: String,
    repetitions: u64,
    row: Row,
}

/// The columns of mc.csv.
const COLUMNS: [&str; 8] = [
    "integral",
    "estimator",
    "n",
    "repetitions",
    "rms_error",
    "mean_std_error",
    "ns_per_sample",
    "seconds_per_estimate",
];

/// mc.csv's text.
fn csv(lines: &[Line]) -> String {
    let mut s = COLUMNS.join(",");
    s.push('\n');
    for l in lines {
        let r = &l.row;
        let _ = writeln!(
            s,
            "{},{},{},{},{:.6e},{:.6e},{:.3},{:.6e}",
            csv_field(&l.integral),
            csv_field(&l.estimator),
            r.n,
            l.repetitions,
            r.rms_error,
            r.mean_std_error,
            r.ns_per_sample,
            r.seconds_per_estimate
        );
    }
    s
}

/// The lines of an mc.csv written by an earlier run.
fn read(path: &Path) -> Result<Vec<Line>, CsvError> {
    parse(&CsvTable::read(path)?)
}

fn parse(table: &CsvTable) -> Result<Vec<Line>, CsvError> {
    let [c_int, c_est, c_n, c_reps, c_rms, c_se, c_ns, c_sec] = COLUMNS.map(|c| table.column(c));
    let (c_int, c_est, c_n, c_reps) = (c_int?, c_est?, c_n?, c_reps?);
    let (c_rms, c_se, c_ns, c_sec) = (c_rms?, c_se?, c_ns?, c_sec?);
    let integrals: Vec<&str> = cases().iter().map(|c| c.integral).collect();
    table
        .rows()
        .map(|r| {
            let integral = r.text(c_int);
            if !integrals.contains(&integral) {
                return Err(r.invalid(
                    c_int,
                    format!(
                        "`{integral}` is none of the study's integrals ({})",
                        integrals.join("; ")
                    ),
                ));
            }
            Ok(Line {
                integral: integral.to_string(),
                estimator: r.text(c_est).to_string(),
                repetitions: r.value(c_reps)?,
                row: Row {
                    n: r.value(c_n)?,
                    rms_error: r.value(c_rms)?,
                    mean_std_error: r.value(c_se)?,
                    ns_per_sample: r.value(c_ns)?,
                    seconds_per_estimate: r.value(c_sec)?,
                },
            })
        })
        .collect()
}

/// The lines of each (integral, estimator), in the order they first appear.
fn groups(lines: &[Line]) -> Vec<(&str, &str, Vec<&Line>)> {
    let mut groups: Vec<(&str, &str, Vec<&Line>)> = Vec::new();
    for l in lines {
        match groups
            .iter_mut()
            .find(|(i, e, _)| *i == l.integral && *e == l.estimator)
        {
            Some(g) => g.2.push(l),
            None => groups.push((&l.integral, &l.estimator, vec![l])),
        }
    }
    groups
}

/// The two plots of each integral, `mc_SLUG_error_vs_n.png` and `mc_SLUG_error_vs_time.png`, with a
/// series per estimator; the same from a run's lines and from mc.csv read back.
fn plots(lines: &[Line], out_dir: &Path) -> Result<()> {
    let cases = cases();
    let slug_of = |integral: &str| {
        cases
            .iter()
            .find(|c| c.integral == integral)
            .map_or("unknown", |c| c.slug)
    };
    let groups = groups(lines);
    let mut integrals: Vec<&str> = groups.iter().map(|g| g.0).collect();
    integrals.dedup();
    for integral in integrals {
        let mine: Vec<_> = groups.iter().filter(|g| g.0 == integral).collect();
        let series = |point: fn(&Row) -> (f64, f64)| -> Vec<plot::Series> {
            mine.iter()
                .map(|(_, estimator, rows)| plot::Series {
                    label: estimator.to_string(),
                    points: rows.iter().map(|l| point(&l.row)).collect(),
                })
                .collect()
        };
        let slug = slug_of(integral);
        let reps = mine[0].2[0].repetitions;
        plot::loglog(
            &out_dir.join(format!("mc_{slug}_error_vs_n.png")),
            &format!("{integral}: RMS error against N (R = {reps})"),
            "samples N",
            "RMS error",
            &series(|r| (r.n as f64, r.rms_error)),
            true,
        )?;
        plot::loglog(
            &out_dir.join(format!("mc_{slug}_error_vs_time.png")),
            &format!("{integral}: RMS error against time per estimate"),
            "seconds per estimate",
            "RMS error",
            &series(|r| (r.seconds_per_estimate, r.rms_error)),
            true,
        )?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_need_no_csv_quoting() {
        for c in cases() {
            assert!(!c.integral.contains([',', '"']) && !c.estimator.contains([',', '"']));
        }
    }

    fn some_lines() -> Vec<Line> {
        cases()
            .iter()
            .take(3)
            .flat_map(|c| {
                (4..7).map(|k| Line {
                    integral: c.integral.to_string(),
                    estimator: c.estimator.to_string(),
                    repetitions: REPETITIONS,
                    row: Row {
                        n: 1 << k,
                        rms_error: 2f64.powi(-k),
                        mean_std_error: 1.5e-3,
                        ns_per_sample: 6.948,
                        seconds_per_estimate: 1.5e-7 * f64::from(1 << k),
                    },
                })
            })
            .collect()
    }

    #[test]
    fn mc_csv_reads_back_as_the_lines_it_was_written_from() {
        let lines = some_lines();
        let text = csv(&lines);
        let table = CsvTable::parse(Path::new("mc.csv"), &text).unwrap();
        assert_eq!(parse(&table).unwrap(), lines);
    }

    #[test]
    fn a_malformed_mc_csv_is_an_error_naming_its_line() {
        let text = csv(&some_lines());
        let mut bad: Vec<String> = text.lines().map(String::from).collect();
        bad[3] = bad[3].replace(",30,", ",thirty,");
        let table = CsvTable::parse(Path::new("d/mc.csv"), &bad.join("\n")).unwrap();
        let e = parse(&table).unwrap_err();
        assert_eq!(e.line(), Some(4));
        assert_eq!(
            e.to_string(),
            "d/mc.csv:4: field 4 (`repetitions`): `thirty` is not a whole number"
        );
        let unknown = text.replace("x^2 over 0..2", "x^3 over 0..2");
        let table = CsvTable::parse(Path::new("mc.csv"), &unknown).unwrap();
        let e = parse(&table).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("mc.csv:2: field 1 (`integral`): `x^3 over 0..2` is none"),
            "{e}"
        );
        let short = text.replacen(",30,", ",", 1);
        let e = CsvTable::parse(Path::new("mc.csv"), &short).err().unwrap();
        assert_eq!(e.to_string(), "mc.csv:2: 7 fields, where the header has 8");
    }

    #[test]
    fn the_committed_mc_csv_reads_back() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../book/src/figures/mc.csv");
        let lines = read(&path).unwrap();
        assert!(!lines.is_empty());
        assert_eq!(csv(&lines), std::fs::read_to_string(&path).unwrap());
    }

    #[test]
    fn grids_cover_every_cell_count() {
        for m in 0..20 {
            let (nx, ny) = grid(1 << m);
            assert_eq!(nx * ny, 1 << m);
            assert!(nx == ny || nx == 2 * ny);
        }
    }

    #[test]
    fn every_case_estimates_its_integral() {
        for (i, case) in cases().iter().enumerate() {
            let mut rng = Rng64::seed_from_u64(seed(i, 12, 0));
            let est = (case.run)(1 << 12, &mut rng).unwrap();
            let t = rtl_mc::check::mean_test(&est, case.exact, 1e-6);
            assert!(t.passed, "{} / {}: {:?}", case.integral, case.estimator, t);
        }
    }
}
