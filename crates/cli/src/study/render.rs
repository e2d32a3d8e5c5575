//! `rtl study render`: placeholder.

use clap::Args;
use std::path::PathBuf;

#[derive(Args)]
pub struct RenderArgs {
    /// Directory for the CSV and the plots (created if missing).
    #[arg(long)]
    pub out: PathBuf,
}

pub fn run(_args: RenderArgs) -> anyhow::Result<()> {
    anyhow::bail!("not built yet")
}
