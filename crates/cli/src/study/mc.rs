//! `rtl study mc`: placeholder.

use clap::Args;
use std::path::PathBuf;

#[derive(Args)]
pub struct McArgs {
    /// Directory for the CSV and the plots (created if missing).
    #[arg(long)]
    pub out: PathBuf,
}

pub fn run(_args: McArgs) -> anyhow::Result<()> {
    anyhow::bail!("not built yet")
}
