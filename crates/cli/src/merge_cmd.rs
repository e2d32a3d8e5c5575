//! `rtl merge`: placeholder until long renders land.

use clap::Args;

#[derive(Args)]
pub struct MergeArgs {
    /// Partial renders to merge.
    pub parts: Vec<std::path::PathBuf>,
}

pub fn run(_args: MergeArgs) -> anyhow::Result<()> {
    anyhow::bail!("merging is not built yet")
}
