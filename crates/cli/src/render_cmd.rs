//! `rtl render`: placeholder until the renderer lands.

use clap::Args;

#[derive(Args)]
pub struct RenderArgs {
    /// A built-in scene name or a path to a scene file.
    pub scene: Option<String>,
}

pub fn run(_args: RenderArgs) -> anyhow::Result<()> {
    anyhow::bail!("the renderer is not built yet")
}
