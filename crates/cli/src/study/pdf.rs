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
use std::path::PathBuf;
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
}

/// One row of the study.
struct Row {
    integral: &'static str,
    pdf: &'static str,
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
            integral,
            pdf: name,
            n,
            reps,
            rms_error: (se2 / reps as f64).sqrt(),
            seconds_per_estimate: seconds,
            variance_per_sample: var / reps as f64,
        });
    }
}

pub fn run(args: PdfArgs) -> Result<()> {
    let out_dir = super::out_dir(args.out.clone(), "pdf")?;
    let (max_pow, reps) = if args.quick { (7, 12) } else { (9, 40) };
    let sizes: Vec<usize> = (2..=max_pow).map(|k| 4usize.pow(k)).collect();
    let z = DVec3::Z;
    let mut rows = Vec::new();

    // Chapter 4: the sphere integral of cos^2 theta = 4 pi / 3.
    const CH4: &str = "cos^2 over the sphere (ch. 4)";
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
    const CH7: &str = "cos^3 over the hemisphere (ch. 7)";
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

    let mut csv = String::from(
        "integral,pdf,n,reps,rms_error,seconds_per_estimate,ns_per_sample,variance_per_sample\n",
    );
    for r in &rows {
        writeln!(
            csv,
            "{},{},{},{},{:.6e},{:.6e},{:.3},{:.6e}",
            r.integral,
            r.pdf,
            r.n,
            r.reps,
            r.rms_error,
            r.seconds_per_estimate,
            r.seconds_per_estimate * 1e9 / r.n as f64,
            r.variance_per_sample
        )?;
    }
    let csv_path = out_dir.join("pdf.csv");
    std::fs::write(&csv_path, csv).with_context(|| format!("writing {}", csv_path.display()))?;

    // One plot per integral: RMS error against seconds per estimate.
    for (integral, file) in [(CH7, "pdf.png"), (CH4, "pdf_ch4.png")] {
        let mut names: Vec<&str> = rows
            .iter()
            .filter(|r| r.integral == integral)
            .map(|r| r.pdf)
            .collect();
        names.dedup();
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
