//! `rtl study`: accuracy against time, as CSV tables and log-log plots.
//!
//! Each study lives in a module of its own with its own arguments; all write into `--out DIR`.

pub(crate) mod mc;
mod pdf;
pub(crate) mod render;
pub(crate) mod sampling;

use clap::{Args, Subcommand};

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
}

pub fn run(args: StudyArgs) -> anyhow::Result<()> {
    match args.what {
        StudyWhat::Mc(a) => mc::run(a),
        StudyWhat::Sampling(a) => sampling::run(a),
        StudyWhat::Pdf(a) => pdf::run(a),
        StudyWhat::Render(a) => render::run(a),
    }
}
