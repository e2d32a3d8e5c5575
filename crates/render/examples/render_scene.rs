//! Render a built-in scene to a PNG with the library alone (no CLI):
//! `cargo run --release -p rtl-render --example render_scene -- cornell 200 16 out.png`.

use rtl_render::integrator::Strategy;
use rtl_render::output::{Transfer, write_png};
use rtl_render::render::{RenderSettings, render};
use rtl_render::scenes;
use std::time::Instant;

fn main() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let name = args.first().map_or("cornell", |s| s.as_str());
    let width: usize = args
        .get(1)
        .map_or(Ok(200), |s| s.parse())
        .map_err(|e| format!("width: {e}"))?;
    let spp: u64 = args
        .get(2)
        .map_or(Ok(16), |s| s.parse())
        .map_err(|e| format!("spp: {e}"))?;
    let out = args
        .get(3)
        .cloned()
        .unwrap_or_else(|| format!("{name}.png"));
    let built = (scenes::find(name)?.build)(&Default::default()).map_err(|e| e.to_string())?;
    let settings = RenderSettings {
        width,
        max_depth: built.scene.max_depth,
        seed: 1,
        strategy: Strategy::Cosine,
        mixture_weight: rtl_render::render::BOOK_MIXTURE_WEIGHT,
    };
    let start = Instant::now();
    let (acc, stats) = render(&built.scene, settings, spp);
    let secs = start.elapsed().as_secs_f64();
    let img = acc.image();
    let mean = img.iter().sum::<rtl_render::Color>() / img.len() as f64;
    println!(
        "{name}: {}x{} {spp} spp in {secs:.2} s ({:.0}k samples/s), mean {mean:.4}, {stats:?}",
        acc.width,
        acc.height,
        stats.samples as f64 / secs / 1e3
    );
    write_png(
        std::path::Path::new(&out),
        acc.width,
        acc.height,
        &img,
        Transfer::Gamma2,
    )
}
