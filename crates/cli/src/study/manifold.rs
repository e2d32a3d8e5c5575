//! `rtl study manifold`: what manifold next-event estimation does to book 2's final scene. `mis`
//! with and without its connections through the glass of the blue subsurface sphere, two seeds each:
//! the noise constant in the book's display encoding, the rate, the time to a given noise, and where
//! in the image the noise is.

use crate::bench_cmd::noise::book_byte;
use crate::plot::{Panel, image_grid};
use anyhow::Result;
use clap::Args;
use rtl_render::integrator::{MisOptions, Strategy};
use rtl_render::render::{BOOK_MIXTURE_WEIGHT, RenderSettings, render};
use rtl_render::scenes;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

#[derive(Args)]
pub struct ManifoldArgs {
    /// Directory for the CSV and the picture (default: a scratch directory, printed; the book's
    /// figures are book/src/figures).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Image width (book 2's final scene is square).
    #[arg(long, default_value_t = 200)]
    pub width: usize,
    /// Samples per pixel of each render. The noise constant in display values settles only with
    /// many samples (about 0.19 at 16 spp, 0.22 at 256 without the connections): keep it high.
    #[arg(long, default_value_t = 256)]
    pub spp: u64,
}

/// One variant's two renders: their images in display values, the seconds each took, and the
/// samples they drew.
struct Measured {
    label: &'static str,
    display: [Vec<f64>; 2],
    seconds: f64,
    samples: u64,
    connections: u64,
}

impl Measured {
    /// `c = RMS(a - b) / sqrt(2) * sqrt(spp)` over every pixel and channel.
    fn noise_constant(&self, spp: u64) -> f64 {
        let [a, b] = &self.display;
        let sum: f64 = a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum();
        (sum / a.len() as f64).sqrt() / std::f64::consts::SQRT_2 * (spp as f64).sqrt()
    }

    /// Per pixel, half the squared difference of the two renders, averaged over the channels: an
    /// estimate of one render's variance there.
    fn pixel_variance(&self) -> Vec<f64> {
        let [a, b] = &self.display;
        a.chunks(3)
            .zip(b.chunks(3))
            .map(|(x, y)| {
                x.iter()
                    .zip(y)
                    .map(|(p, q)| (p - q) * (p - q) / 2.0)
                    .sum::<f64>()
                    / 3.0
            })
            .collect()
    }

    fn rate(&self) -> f64 {
        self.samples as f64 / self.seconds
    }
}

pub fn run(args: ManifoldArgs) -> Result<()> {
    anyhow::ensure!(
        (8..=2000).contains(&args.width),
        "--width {}: the width must be 8 to 2000 pixels",
        args.width
    );
    anyhow::ensure!(args.spp >= 1, "--spp 0: at least one sample per pixel");
    let out = super::out_dir(args.out, "manifold")?;
    let builtin = scenes::find("book2-final").map_err(|e| anyhow::anyhow!(e))?;
    let built =
        (builtin.build)(&Default::default()).map_err(|e| anyhow::anyhow!("book2-final: {e}"))?;
    let scene = &built.scene;
    let variants = [
        (
            "without connections (--no-manifold)",
            MisOptions {
                manifold: false,
                ..MisOptions::DEFAULT
            },
        ),
        ("with manifold connections", MisOptions::DEFAULT),
    ];
    let mut measured = Vec::new();
    for (label, options) in variants {
        let mut display: [Vec<f64>; 2] = Default::default();
        let (mut seconds, mut samples, mut connections) = (0.0, 0, 0);
        for (i, seed) in [1u64, 2].into_iter().enumerate() {
            let settings = RenderSettings {
                width: args.width,
                max_depth: scene.max_depth,
                seed,
                strategy: Strategy::Mis(options),
                mixture_weight: BOOK_MIXTURE_WEIGHT,
            };
            let start = Instant::now();
            let (acc, stats) = render(scene, settings, args.spp);
            seconds += start.elapsed().as_secs_f64();
            samples += stats.samples;
            connections += stats.manifold_connections;
            display[i] = acc
                .image()
                .iter()
                .flat_map(|c| [c.x, c.y, c.z])
                .map(|x| book_byte(x as f32) as f64 / 256.0)
                .collect();
        }
        eprintln!("  {label}: {seconds:.1} s for two renders");
        measured.push(Measured {
            label,
            display,
            seconds,
            samples,
            connections,
        });
    }
    let threads = rayon::current_num_threads();
    let mut csv = String::from(
        "variant,width,spp,threads,seconds,samples_per_second,connections_per_sample,noise_constant,relative_time_to_equal_noise\n",
    );
    let base = {
        let m = &measured[0];
        m.noise_constant(args.spp).powi(2) / m.rate()
    };
    for m in &measured {
        let c = m.noise_constant(args.spp);
        writeln!(
            csv,
            "{},{},{},{threads},{:.3},{:.0},{:.4},{:.5},{:.4}",
            m.label,
            args.width,
            args.spp,
            m.seconds,
            m.rate(),
            m.connections as f64 / m.samples as f64,
            c,
            c * c / m.rate() / base
        )?;
        eprintln!(
            "  {}: noise constant {c:.4}, {:.0} samples/s, {:.3} of the time to equal noise",
            m.label,
            m.rate(),
            c * c / m.rate() / base
        );
    }
    std::fs::write(out.join("manifold.csv"), &csv)?;

    // Where the noise is: log10 of each pixel's variance on one scale for both.
    let maps: Vec<Vec<f64>> = measured.iter().map(|m| m.pixel_variance()).collect();
    let (lo, hi) = (-6.0f64, -1.0f64);
    let mut panels: Vec<Panel> = maps
        .iter()
        .zip(&measured)
        .map(|(v, m)| Panel {
            width: args.width,
            height: args.width,
            rgb: v
                .iter()
                .flat_map(|&x| super::render::heat((x.max(1e-12).log10() - lo) / (hi - lo)))
                .collect(),
            label: format!("noise {}: c = {:.3}", m.label, m.noise_constant(args.spp)),
        })
        .collect();
    panels.insert(
        0,
        Panel {
            width: args.width,
            height: args.width,
            rgb: measured[1].display[0]
                .iter()
                .map(|&v| (v * 256.0).min(255.0) as u8)
                .collect(),
            label: format!("book2-final, mis, {} spp", args.spp),
        },
    );
    let scale = 360usize.div_ceil(args.width).max(1);
    image_grid(
        &out.join("manifold-noise.png"),
        "book 2's final scene, light through its glass balls: each pixel's variance, 1e-6 (dark) to 1e-1 (bright)",
        &panels,
        scale,
        3,
    )?;
    eprintln!(
        "wrote manifold.csv and manifold-noise.png to {}",
        out.display()
    );
    Ok(())
}
