//! `rtl study pdf`: placeholder.

use clap::Args;
use std::path::PathBuf;

#[derive(Args)]
pub struct PdfArgs {
    /// Directory for the CSV and the plots (created if missing).
    #[arg(long)]
    pub out: PathBuf,
}

pub fn run(_args: PdfArgs) -> anyhow::Result<()> {
    anyhow::bail!("not built yet")
}
