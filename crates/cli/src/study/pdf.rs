//! `rtl study pdf`: the book's integrals over the sphere of directions (chapters 4 and 7), each
//! estimated with several densities from `rtl-pdf`, RMS error against time.
//!
//! - chapter 4: `integral over the sphere of cos^2 theta = 4 pi / 3`, sampled uniformly over the sphere,
//!   by the two-sided cosine mixture `(|cos theta| / 2 pi)`, and by the book's 50/50 cosine + sphere mixture;
//! - chapter 7: `integral over the hemisphere of cos^3 theta = pi / 2`, sampled uniformly over the
//!   sphere, uniformly over the hemisphere, by the cosine density, and by the 50/50 mixture.
//!
//! For each `N` (powers of 4) the estimate `mean of f(d) / p(d)` is repeated with independent seeds
//! (at least 40 times, and at least 2^17 samples in all);
//! the CSV holds the RMS error over the repetitions and the time per estimate, and the plots show
//! error against time: a better density reaches an error sooner, even if each sample costs more.

use crate::csv::{CsvError, CsvTable, csv_field};
use crate::plot::{Series, loglog};
use anyhow::{Context, Result};
use clap::Args;
use glam::DVec3;
use rand::SeedableRng;
use rand_xoshiro::Xoshiro256PlusPlus;
use rtl_mc::RunningStats;
use rtl_pdf::{CosinePdf, HemispherePdf, MixturePdf, Pdf, SpherePdf};
use std::f64::consts::PI;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(Args)]
pub struct PdfArgs {
    /// Directory for the CSV and the plots (created if missing; default: a scratch directory,
    /// printed; the book's figures are book/src/figures).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Fewer and smaller runs (a few seconds), for a quick look or CI.
    #[arg(long)]
    pub quick: bool,
    /// Redraw the plots from the measurements already in the output directory (pdf.csv), timing
    /// nothing and writing no CSV: for a change of labels or layout, or on a busy machine.
    #[arg(long, conflicts_with = "quick")]
    pub replot: bool,
}

/// One row of the study: a line of pdf.csv (whose `ns_per_sample` is `seconds_per_estimate / n`).
#[derive(Clone, Debug, PartialEq)]
struct Row {
    integral: String,
    pdf: String,
    n: usize,
    reps: usize,
    rms_error: f64,
    seconds_per_estimate: f64,
    /// the mean over repetitions of the sample variance of f/p: the variance of one sample
    variance_per_sample: f64,
}

// ANCHOR: estimate
/// The Monte Carlo estimate of `integral f` with `n` directions from `pdf`, and the sample variance
/// of `f / p`. A direction with `p = 0` (on the boundary of the support) contributes 0.
fn estimate<P: Pdf>(
    pdf: &P,
    f: &impl Fn(DVec3) -> f64,
    n: usize,
    rng: &mut Xoshiro256PlusPlus,
) -> (f64, f64) {
    // Welford's running mean and variance (chapter 2), not the cancellation-prone `sum x^2 - n mean^2`.
    let mut stats = RunningStats::new();
    for _ in 0..n {
        // black_box: the whole direction is made, as a renderer needs it, even where `f` reads only z
        let d = std::hint::black_box(pdf.generate(rng));
        let p = pdf.value(d);
        stats.push(if p > 0.0 { f(d) / p } else { 0.0 });
    }
    (stats.mean(), stats.variance().unwrap_or(0.0))
}
// ANCHOR_END: estimate

#[allow(clippy::too_many_arguments)]
fn series<P: Pdf>(
    rows: &mut Vec<Row>,
    integral: &'static str,
    truth: f64,
    f: impl Fn(DVec3) -> f64,
    name: &'static str,
    pdf: P,
    sizes: &[usize],
    reps: usize,
    seed: u64,
) {
    for (k, &n) in sizes.iter().enumerate() {
        // small N: more repetitions, so the RMS error and the time per estimate are both averaged
        // over at least 2^17 samples
        let reps = reps.max((1 << 17) / n);
        let (mut se2, mut var) = (0.0, 0.0);
        let start = Instant::now();
        for r in 0..reps {
            let mut rng = Xoshiro256PlusPlus::seed_from_u64(seed ^ ((k as u64) << 32) ^ r as u64);
            let (est, v) = estimate(&pdf, &f, n, &mut rng);
            se2 += (est - truth) * (est - truth);
            var += v;
        }
        let seconds = start.elapsed().as_secs_f64() / reps as f64;
        rows.push(Row {
            integral: integral.to_string(),
            pdf: name.to_string(),
            n,
            reps,
            rms_error: (se2 / reps as f64).sqrt(),
            seconds_per_estimate: seconds,
            variance_per_sample: var / reps as f64,
        });
    }
}

/// The integrals of the study, and the plot of each.
const CH4: &str = "cos^2 over the sphere (ch. 4)";
const CH7: &str = "cos^3 over the hemisphere (ch. 7)";
const PLOTS: [(&str, &str); 2] = [(CH7, "pdf.png"), (CH4, "pdf_ch4.png")];

/// The columns of pdf.csv.
const COLUMNS: [&str; 8] = [
    "integral",
    "pdf",
    "n",
    "reps",
    "rms_error",
    "seconds_per_estimate",
    "ns_per_sample",
    "variance_per_sample",
];

/// pdf.csv's text.
fn csv(rows: &[Row]) -> String {
    let mut s = COLUMNS.join(",");
    s.push('\n');
    for r in rows {
        let _ = writeln!(
            s,
            "{},{},{},{},{:.6e},{:.6e},{:.3},{:.6e}",
            csv_field(&r.integral),
            csv_field(&r.pdf),
            r.n,
            r.reps,
            r.rms_error,
            r.seconds_per_estimate,
            r.seconds_per_estimate * 1e9 / r.n as f64,
            r.variance_per_sample
        );
    }
    s
}

/// The rows of a pdf.csv written by an earlier run. Before the names were quoted, the comma of
/// "cosine, both sides (mixture)" was written bare: a row with fields to spare has them in `pdf`.
fn read(path: &Path) -> Result<Vec<Row>, CsvError> {
    parse(&CsvTable::read(path)?)
}

fn parse(table: &CsvTable) -> Result<Vec<Row>, CsvError> {
    let [c_int, c_pdf, c_n, c_reps, c_rms, c_sec, _, c_var] = COLUMNS.map(|c| table.column(c));
    let (c_int, c_pdf, c_n, c_reps) = (c_int?, c_pdf?, c_n?, c_reps?);
    let (c_rms, c_sec, c_var) = (c_rms?, c_sec?, c_var?);
    table
        .rows()
        .map(|r| {
            let integral = r.text(c_int);
            if !PLOTS.iter().any(|(i, _)| *i == integral) {
                return Err(r.invalid(
                    c_int,
                    format!("`{integral}` is neither `{CH4}` nor `{CH7}`"),
                ));
            }
            Ok(Row {
                integral: integral.to_string(),
                pdf: r.text(c_pdf).to_string(),
                n: r.value(c_n)?,
                reps: r.value(c_reps)?,
                rms_error: r.value(c_rms)?,
                seconds_per_estimate: r.value(c_sec)?,
                variance_per_sample: r.value(c_var)?,
            })
        })
        .collect()
}

/// One plot per integral, RMS error against seconds per estimate, a series per pdf; the same from a
/// run's rows and from pdf.csv read back.
fn plots(rows: &[Row], out_dir: &Path) -> Result<()> {
    for (integral, file) in PLOTS {
        let mut names: Vec<&str> = Vec::new();
        for r in rows.iter().filter(|r| r.integral == integral) {
            if !names.contains(&r.pdf.as_str()) {
                names.push(&r.pdf);
            }
        }
        if names.is_empty() {
            anyhow::bail!("no rows for `{integral}`: nothing to plot in {file}");
        }
        let plot_series: Vec<Series> = names
            .iter()
            .map(|&name| Series {
                label: name.to_string(),
                points: rows
                    .iter()
                    .filter(|r| r.integral == integral && r.pdf == name)
                    .map(|r| (r.seconds_per_estimate, r.rms_error))
                    .collect(),
            })
            .collect();
        let path = out_dir.join(file);
        loglog(
            &path,
            &format!("{integral}: RMS error against time"),
            "seconds per estimate",
            "RMS error",
            &plot_series,
            true,
        )?;
        println!("wrote {}", path.display());
    }
    Ok(())
}

pub fn run(args: PdfArgs) -> Result<()> {
    let out_dir = super::out_dir(args.out.clone(), "pdf")?;
    let csv_path = out_dir.join("pdf.csv");
    if args.replot {
        plots(&read(&csv_path)?, &out_dir)?;
        println!(
            "redrew the plots from {}, timing nothing",
            csv_path.display()
        );
        return Ok(());
    }
    let (max_pow, reps) = if args.quick { (7, 12) } else { (9, 40) };
    let sizes: Vec<usize> = (2..=max_pow).map(|k| 4usize.pow(k)).collect();
    let z = DVec3::Z;
    let mut rows = Vec::new();

    // Chapter 4: the sphere integral of cos^2 theta = 4 pi / 3.
    let cos2 = |d: DVec3| d.z * d.z;
    let truth4 = 4.0 * PI / 3.0;
    series(
        &mut rows,
        CH4,
        truth4,
        cos2,
        "uniform sphere",
        SpherePdf,
        &sizes,
        reps,
        41,
    );
    let two_sided = MixturePdf::new(CosinePdf::new(z), CosinePdf::new(-z));
    series(
        &mut rows,
        CH4,
        truth4,
        cos2,
        "cosine, both sides (mixture)",
        two_sided,
        &sizes,
        reps,
        42,
    );
    let book_mix = MixturePdf::new(CosinePdf::new(z), SpherePdf);
    series(
        &mut rows,
        CH4,
        truth4,
        cos2,
        "cosine + sphere 50/50 (mixture)",
        book_mix,
        &sizes,
        reps,
        43,
    );

    // Chapter 7: the hemisphere integral of cos^3 theta = pi / 2.
    let cos3 = |d: DVec3| if d.z > 0.0 { d.z * d.z * d.z } else { 0.0 };
    let truth7 = PI / 2.0;
    series(
        &mut rows,
        CH7,
        truth7,
        cos3,
        "uniform sphere",
        SpherePdf,
        &sizes,
        reps,
        71,
    );
    series(
        &mut rows,
        CH7,
        truth7,
        cos3,
        "uniform hemisphere",
        HemispherePdf::new(z),
        &sizes,
        reps,
        72,
    );
    series(
        &mut rows,
        CH7,
        truth7,
        cos3,
        "cosine",
        CosinePdf::new(z),
        &sizes,
        reps,
        73,
    );
    series(
        &mut rows,
        CH7,
        truth7,
        cos3,
        "cosine + sphere 50/50 (mixture)",
        book_mix,
        &sizes,
        reps,
        74,
    );

    std::fs::write(&csv_path, csv(&rows))
        .with_context(|| format!("writing {}", csv_path.display()))?;
    plots(&rows, &out_dir)?;
    println!("wrote {}", csv_path.display());

    // Summary: the variance of one sample and its cost; their product is the time to a given error.
    println!(
        "\n{:<36} {:<34} {:>14} {:>10} {:>14}",
        "integral", "pdf", "var/sample", "ns/sample", "var x ns"
    );
    let largest = *sizes.last().unwrap_or(&1);
    for r in rows.iter().filter(|r| r.n == largest) {
        let ns = r.seconds_per_estimate * 1e9 / r.n as f64;
        println!(
            "{:<36} {:<34} {:>14.5} {:>10.2} {:>14.4}",
            r.integral,
            r.pdf,
            r.variance_per_sample,
            ns,
            r.variance_per_sample * ns
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn some_rows() -> Vec<Row> {
        let row = |integral: &str, pdf: &str, n| Row {
            integral: integral.into(),
            pdf: pdf.into(),
            n,
            reps: (1 << 17) / n,
            rms_error: 0.5 / n as f64,
            seconds_per_estimate: 3.7e-7 * (n / 16) as f64,
            variance_per_sample: 2.207759,
        };
        vec![
            row(CH4, "uniform sphere", 16),
            row(CH4, "cosine, both sides (mixture)", 16),
            row(CH4, "cosine, both sides (mixture)", 64),
            row(CH7, "a \"quoted\" name", 256),
        ]
    }

    #[test]
    fn pdf_csv_reads_back_as_the_rows_it_was_written_from() {
        let rows = some_rows();
        let text = csv(&rows);
        assert!(text.contains(",\"cosine, both sides (mixture)\",16,"));
        let table = CsvTable::parse(Path::new("pdf.csv"), &text).unwrap();
        assert_eq!(parse(&table).unwrap(), rows);
    }

    #[test]
    fn a_malformed_pdf_csv_is_an_error_naming_its_line() {
        let text = csv(&some_rows()).replace(",2048,", ",2048.5,");
        let table = CsvTable::parse(Path::new("pdf.csv"), &text).unwrap();
        let e = parse(&table).unwrap_err();
        assert_eq!(e.line(), Some(4));
        assert_eq!(
            e.to_string(),
            "pdf.csv:4: field 4 (`reps`): `2048.5` is not a whole number"
        );
        let text = csv(&some_rows()).replace("(ch. 7)", "(ch. 8)");
        let table = CsvTable::parse(Path::new("pdf.csv"), &text).unwrap();
        assert_eq!(parse(&table).unwrap_err().line(), Some(5));
    }

    /// The committed pdf.csv predates the quoting: its "cosine, both sides (mixture)" is bare.
    #[test]
    fn the_committed_pdf_csv_reads_back() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../book/src/figures/pdf.csv");
        let rows = read(&path).unwrap();
        assert!(rows.iter().any(|r| r.pdf == "cosine, both sides (mixture)"));
        let text = std::fs::read_to_string(&path).unwrap();
        assert_eq!(
            csv(&rows),
            text.replace(
                ",cosine, both sides (mixture),",
                ",\"cosine, both sides (mixture)\","
            )
        );
    }
}
