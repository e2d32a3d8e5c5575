//! `rtl merge`: add partial renders (parts) of one render into the image one process would have made.
//!
//! Each part holds samples `[K, K+N)` of every pixel (`rtl render ... --sample-offset K --spp N --part
//! FILE`). Parts must be of the same scene and settings and their sample ranges must not overlap; they
//! are added in the order of their ranges, whatever the order they are named in.

use anyhow::{Result, bail};
use clap::Args;
use rtl_render::checkpoint::{Checkpoint, merge};
use rtl_render::limits;
use rtl_render::output::{OutputFile, OutputKind, Transfer, write_linear, write_png};
use std::path::PathBuf;

#[derive(Args)]
pub struct MergeArgs {
    /// Parts (or checkpoints) of one render with disjoint sample ranges.
    #[arg(required = true, value_name = "PART")]
    pub parts: Vec<PathBuf>,
    /// Output PNG.
    #[arg(short = 'o', long = "output", default_value = "merged.png")]
    pub output: PathBuf,
    /// Also write the linear mean radiance per pixel: `.pfm` or `.exr`.
    #[arg(long)]
    pub linear: Option<PathBuf>,
    /// Encode the PNG with the sRGB transfer function instead of the book's gamma 2.
    #[arg(long)]
    pub srgb: bool,
    /// Also save the merged accumulation as one part (to merge further, or to extend with
    /// `rtl render ... --resume`).
    #[arg(long, value_name = "FILE")]
    pub part: Option<PathBuf>,
    /// Merge even if some sample ranges between the parts are missing (say, a job that failed): the
    /// image is then the mean of the samples there are.
    #[arg(long)]
    pub allow_gaps: bool,
}

/// Every file the merge writes, checked before any part is read: named right, writable, each its own
/// file, and none of them one of the parts.
fn check_merge_outputs(args: &MergeArgs) -> Result<()> {
    let mut outputs = vec![OutputFile {
        flag: "-o",
        path: args.output.clone(),
        kind: OutputKind::Png,
    }];
    if let Some(lin) = &args.linear {
        outputs.push(OutputFile {
            flag: "--linear",
            path: lin.clone(),
            kind: OutputKind::Linear,
        });
    }
    if let Some(p) = &args.part {
        outputs.push(OutputFile {
            flag: "--part",
            path: p.clone(),
            kind: OutputKind::Checkpoint,
        });
    }
    let inputs: Vec<(String, PathBuf)> = args
        .parts
        .iter()
        .map(|p| (format!("the part {}", p.display()), p.clone()))
        .collect();
    crate::render_cmd::check_output_files(&outputs, &inputs)?;
    Ok(())
}

/// The parts are held in memory together (each as its bytes while it is read and then as its
/// accumulation, about the same size), with the merged accumulation beside them
/// ([`limits::merge_need`]): refuse before reading if that does not fit in what each memory limit
/// leaves, rather than abort on allocation.
fn check_merge_memory(args: &MergeArgs) -> Result<()> {
    let mut sizes = Vec::with_capacity(args.parts.len());
    for p in &args.parts {
        let len = std::fs::metadata(p)
            .map_err(|e| anyhow::anyhow!("cannot read {}: {e}", p.display()))?
            .len();
        sizes.push(len);
    }
    let total = sizes.iter().fold(0u64, |t, &s| t.saturating_add(s));
    let need = limits::merge_need(&sizes);
    if let Some(short) = need.exceeds(&limits::memory_limits()) {
        let what = short.available.limit.counts();
        bail!(
            "the {} part(s) hold {} and merging them needs about {} of {what} (the parts, and the \
             largest once more while it is read and for the merged sums, with a tenth of margin), \
             but {}",
            args.parts.len(),
            limits::Bytes(total),
            limits::Bytes(short.needed),
            short.available,
        );
    }
    Ok(())
}

pub fn run(args: MergeArgs) -> Result<()> {
    check_merge_outputs(&args)?;
    check_merge_memory(&args)?;
    let mut parts = Vec::with_capacity(args.parts.len());
    for p in &args.parts {
        parts.push((p.display().to_string(), Checkpoint::read(p)?));
    }
    // (as `rtl render --resume` notes it: another build may trace differently)
    for (name, part) in &parts {
        if part.rtl_version != env!("CARGO_PKG_VERSION") {
            eprintln!(
                "note: {name} was written by rtl {}, this is {}",
                rtl_render::text::shown(&part.rtl_version),
                env!("CARGO_PKG_VERSION")
            );
        }
    }
    let merged = merge(&parts)?;
    // The parts are done with once merged: the image and its encodings are made without them.
    let (part_count, spp): (usize, u64) = (parts.len(), parts.iter().map(|(_, p)| p.spp()).sum());
    drop(parts);
    let ck = &merged.checkpoint;
    if ck
        .acc
        .count
        .iter()
        .zip(&ck.acc.dropped)
        .all(|(c, d)| c + d == 0)
    {
        bail!("the parts hold no samples (each covers an empty range): no image to make");
    }
    if !merged.gaps.is_empty() {
        let gaps: Vec<String> = merged
            .gaps
            .iter()
            .map(|(a, b)| format!("{a}..{b}"))
            .collect();
        if !args.allow_gaps {
            bail!(
                "no part holds samples {} (render them, or merge anyway with --allow-gaps)",
                gaps.join(", ")
            );
        }
        if args.part.is_some() {
            bail!(
                "a merge with gaps cannot be saved as one part (--part): its samples are not one range"
            );
        }
        eprintln!("note: samples {} are missing", gaps.join(", "));
    }
    // The merged part first (streamed from the accumulation), then the image of it, made without
    // the accumulation (40 bytes a pixel); the images are written even if the part could not be.
    let saved = args.part.as_ref().map(|p| {
        ck.write(p)
            .map_err(|e| anyhow::anyhow!("cannot write {}: {e}", p.display()))
    });
    let (w, h) = (ck.acc.width, ck.acc.height);
    let (scene, start, end, dropped) = (
        rtl_render::text::shown(&ck.identity.scene),
        ck.start,
        ck.acc.samples,
        ck.acc.total_dropped(),
    );
    let image = ck.acc.image();
    drop(merged);
    let transfer = if args.srgb {
        Transfer::Srgb
    } else {
        Transfer::Gamma2
    };
    write_png(&args.output, w, h, &image, transfer).map_err(anyhow::Error::msg)?;
    if let Some(lin) = &args.linear {
        write_linear(lin, w, h, &image).map_err(anyhow::Error::msg)?;
    }
    if let Some(saved) = saved {
        saved?;
    }
    eprintln!(
        "merged {part_count} part(s) of {scene} ({w}x{h}): samples {start}..{end}, {spp} spp, {dropped} non-finite samples dropped -> {}{}{}",
        args.output.display(),
        args.linear
            .as_ref()
            .map(|p| format!(", {}", p.display()))
            .unwrap_or_default(),
        args.part
            .as_ref()
            .map(|p| format!(", {}", p.display()))
            .unwrap_or_default()
    );
    Ok(())
}
