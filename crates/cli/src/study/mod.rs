//! `rtl study`: accuracy against time, as CSV tables and log-log plots.
//!
//! Each study lives in a module of its own with its own arguments; all write into `--out DIR`, or, without
//! it, into a scratch directory (printed) so that a reader never overwrites the book's committed figures
//! (book/src/figures) by accident.

mod diagrams;
mod manifold;
pub(crate) mod mc;
mod pdf;
pub(crate) mod render;
mod samples;
pub(crate) mod sampling;
mod svg;

use clap::{Args, Subcommand};
use std::path::PathBuf;

#[derive(Args)]
pub struct StudyArgs {
    #[command(subcommand)]
    pub what: StudyWhat,
}

#[derive(Subcommand)]
pub enum StudyWhat {
    /// Monte Carlo estimators of the book's integrals: error against N and against time.
    Mc(mc::McArgs),
    /// Inverse transform sampling: build time, ns/sample and error for each method and table size.
    Sampling(sampling::SamplingArgs),
    /// The book's sphere-of-directions integrals estimated with each pdf: error against time.
    Pdf(pdf::PdfArgs),
    /// Each rendering strategy against a converged reference: RMSE against time.
    Render(render::RenderArgs),
    /// The book's geometric diagrams as SVG, drawn from rtl-pdf's own warps and bases (under a second).
    Diagrams(diagrams::DiagramsArgs),
    /// Each chapter's sampler: its samples against the density it claims, as SVG histograms (seconds).
    Samples(samples::SamplesArgs),
    /// Book 2's final scene by `mis` with and without manifold connections through glass: noise,
    /// rate, and where the noise is (about a minute on 2 cores).
    Manifold(manifold::ManifoldArgs),
}

pub fn run(args: StudyArgs) -> anyhow::Result<()> {
    match args.what {
        StudyWhat::Mc(a) => mc::run(a),
        StudyWhat::Sampling(a) => sampling::run(a),
        StudyWhat::Pdf(a) => pdf::run(a),
        StudyWhat::Render(a) => render::run(a),
        StudyWhat::Diagrams(a) => diagrams::run(a),
        StudyWhat::Samples(a) => samples::run(a),
        StudyWhat::Manifold(a) => manifold::run(a),
    }
}

/// The directory a study writes to: `--out` if given, else `rtl-study/NAME` in the OS's temporary
/// directory. Created if missing, and printed either way.
pub fn out_dir(out: Option<PathBuf>, name: &str) -> anyhow::Result<PathBuf> {
    use anyhow::Context as _;
    let dir = match out {
        Some(dir) => dir,
        None => {
            let dir = std::env::temp_dir().join("rtl-study").join(name);
            eprintln!(
                "no --out given: writing to the scratch directory {} (the book's figures are in \
                 book/src/figures: pass --out book/src/figures to replace them)",
                dir.display()
            );
            dir
        }
    };
    if dir.exists() && !dir.is_dir() {
        anyhow::bail!(
            "--out {}: it is a file, not a directory (a study writes several files into it)",
            dir.display()
        );
    }
    std::fs::create_dir_all(&dir).with_context(|| format!("creating {}", dir.display()))?;
    eprintln!("output directory: {}", dir.display());
    Ok(dir)
}
