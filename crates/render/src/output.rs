//! Writing images: 8-bit PNG (the book's gamma 2, or sRGB), and linear HDR as PFM or OpenEXR. Every
//! file is written to a temporary name beside the target and renamed into place, so an interrupted run
//! never leaves a half-written image.

use crate::vec::Color;
use std::io::Write;
use std::path::{Path, PathBuf};

/// How linear radiance becomes an 8-bit value.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Transfer {
    /// The book's `linear_to_gamma`: the square root, clamped to [0, 0.999], times 256.
    Gamma2,
    /// The sRGB transfer function (IEC 61966-2-1), rounded.
    Srgb,
}

impl Transfer {
    #[inline]
    pub fn encode(self, x: f64) -> u8 {
        let x = if x.is_finite() { x.max(0.0) } else { 0.0 };
        match self {
            Transfer::Gamma2 => (256.0 * x.sqrt().clamp(0.0, 0.999)) as u8,
            Transfer::Srgb => {
                let x = x.min(1.0);
                let v = if x <= 0.003_130_8 {
                    12.92 * x
                } else {
                    1.055 * x.powf(1.0 / 2.4) - 0.055
                };
                (255.0 * v + 0.5) as u8
            }
        }
    }
}

fn temp_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.tmp{}", std::process::id()))
}

/// Write with `write` to a temporary file, then rename it to `path`.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&Path) -> Result<(), String>,
) -> Result<(), String> {
    let tmp = temp_path(path);
    if let Err(e) = write(&tmp) {
        let _ = std::fs::remove_file(&tmp);
        return Err(e);
    }
    std::fs::rename(&tmp, path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        format!("{}: cannot rename into place: {e}", path.display())
    })
}

/// The 8-bit RGB bytes of an image (rows from the top).
pub fn to_rgb8(pixels: &[Color], transfer: Transfer) -> Vec<u8> {
    pixels
        .iter()
        .flat_map(|c| {
            [
                transfer.encode(c.x),
                transfer.encode(c.y),
                transfer.encode(c.z),
            ]
        })
        .collect()
}

/// Write a PNG.
pub fn write_png(
    path: &Path,
    width: usize,
    height: usize,
    pixels: &[Color],
    transfer: Transfer,
) -> Result<(), String> {
    let bytes = to_rgb8(pixels, transfer);
    write_atomically(path, |tmp| {
        image::save_buffer_with_format(
            tmp,
            &bytes,
            width as u32,
            height as u32,
            image::ColorType::Rgb8,
            image::ImageFormat::Png,
        )
        .map_err(|e| format!("{}: cannot write PNG: {e}", path.display()))
    })
}

/// The bytes of a colour PFM: header `PF\n<w> <h>\n-1.0\n` (negative scale: little-endian), then
/// float32 RGB rows from the bottom of the image to the top.
pub fn pfm_bytes(width: usize, height: usize, pixels: &[Color]) -> Vec<u8> {
    let mut out = format!("PF\n{width} {height}\n-1.0\n").into_bytes();
    out.reserve(width * height * 12);
    for j in (0..height).rev() {
        for c in &pixels[j * width..(j + 1) * width] {
            for x in [c.x, c.y, c.z] {
                out.extend_from_slice(&(x as f32).to_le_bytes());
            }
        }
    }
    out
}

/// The first pixel with a channel that a 32-bit float cannot hold (beyond `f32::MAX`, or NaN),
/// which a linear file would store as an infinity or NaN: its index and colour.
pub fn beyond_f32(pixels: &[Color]) -> Option<(usize, Color)> {
    pixels
        .iter()
        .position(|c| !c.to_array().iter().all(|&v| (v as f32).is_finite()))
        .map(|i| (i, pixels[i]))
}

/// Write linear radiance: PFM for `.pfm`, OpenEXR (f32 RGB) for `.exr`. Refused (nothing written)
/// where a pixel does not fit a 32-bit float ([`beyond_f32`]): an image of infinities is no image.
pub fn write_linear(
    path: &Path,
    width: usize,
    height: usize,
    pixels: &[Color],
) -> Result<(), String> {
    if let Some((i, c)) = beyond_f32(pixels) {
        let (x, y) = (i % width.max(1), i / width.max(1));
        return Err(format!(
            "{}: pixel (x {x}, y {y}) is [{:e}, {:e}, {:e}], which a 32-bit float cannot hold \
             (it would be written as an infinity), so no linear file is written",
            path.display(),
            c.x,
            c.y,
            c.z
        ));
    }
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .unwrap_or_default();
    match ext.as_str() {
        "pfm" => {
            let bytes = pfm_bytes(width, height, pixels);
            write_atomically(path, |tmp| {
                std::fs::File::create(tmp)
                    .and_then(|mut f| f.write_all(&bytes).and_then(|_| f.sync_all()))
                    .map_err(|e| format!("{}: cannot write PFM: {e}", path.display()))
            })
        }
        "exr" => {
            let data: Vec<f32> = pixels
                .iter()
                .flat_map(|c| [c.x as f32, c.y as f32, c.z as f32])
                .collect();
            let img = image::Rgb32FImage::from_raw(width as u32, height as u32, data)
                .ok_or_else(|| "image size does not match its pixels".to_string())?;
            write_atomically(path, |tmp| {
                image::DynamicImage::ImageRgb32F(img)
                    .save_with_format(tmp, image::ImageFormat::OpenExr)
                    .map_err(|e| format!("{}: cannot write OpenEXR: {e}", path.display()))
            })
        }
        _ => Err(format!(
            "{}: linear output must end in .pfm or .exr",
            path.display()
        )),
    }
}

/// What a file named on the command line is written as.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OutputKind {
    /// An 8-bit PNG (`-o`): the name must end in `.png`.
    Png,
    /// Linear radiance (`--linear`): `.pfm` or `.exr`.
    Linear,
    /// A checkpoint or part (any name).
    Checkpoint,
}

/// A file the command will write, with the flag that named it (for messages).
#[derive(Clone, Debug)]
pub struct OutputFile {
    pub flag: &'static str,
    pub path: PathBuf,
    pub kind: OutputKind,
}

/// Why an output cannot be written: found before any rendering.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    #[error("{flag} {}: a PNG file name must end in .png", path.display())]
    NotPng { flag: &'static str, path: PathBuf },
    /// `-o .png`, `--linear dir/.pfm`: a name that is all extension is a hidden file's name with
    /// no extension at all.
    #[error(
        "{flag} {}: the file name needs a name before its extension (`{}` alone is a hidden \
         file's name)",
        path.display(),
        path.file_name().unwrap_or_default().to_string_lossy()
    )]
    NoName { flag: &'static str, path: PathBuf },
    #[error("{flag} {}: linear output must end in .pfm or .exr", path.display())]
    UnknownLinear { flag: &'static str, path: PathBuf },
    #[error("{flag} {}: the directory {} does not exist", path.display(), dir.display())]
    NoDirectory {
        flag: &'static str,
        path: PathBuf,
        dir: PathBuf,
    },
    #[error("{flag} {}: it is a directory, not a file", path.display())]
    IsDirectory { flag: &'static str, path: PathBuf },
    #[error("{flag} {}: cannot write in {}: {source}", path.display(), dir.display())]
    NotWritable {
        flag: &'static str,
        path: PathBuf,
        dir: PathBuf,
        source: std::io::Error,
    },
    #[error("{flag_a} and {flag_b} both name {}: each output needs a file of its own", path.display())]
    Same {
        flag_a: &'static str,
        flag_b: &'static str,
        path: PathBuf,
    },
    #[error("{flag} {} is also an input ({input}): writing it would destroy what is read", path.display())]
    OverwritesInput {
        flag: &'static str,
        path: PathBuf,
        input: String,
    },
}

/// `path` made absolute through its directory, so that `a.png` and `./a.png` compare equal (the file
/// itself need not exist).
fn resolved(path: &Path) -> PathBuf {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let name = path.file_name().map(PathBuf::from).unwrap_or_default();
    std::fs::canonicalize(dir).map_or_else(|_| path.to_path_buf(), |d| d.join(name))
}

/// Check every output before any work: its name fits its kind, its directory exists and can be written
/// (a probe file is created there and removed), it is not a directory, no two outputs name the same
/// file, and none is one of `inputs` (`(what, path)`).
pub fn check_outputs(
    outputs: &[OutputFile],
    inputs: &[(String, PathBuf)],
) -> Result<(), OutputError> {
    for (i, o) in outputs.iter().enumerate() {
        let (flag, path) = (o.flag, o.path.clone());
        let ext = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase())
            .unwrap_or_default();
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy().to_ascii_lowercase());
        let all_extension = matches!(name.as_deref(), Some(".png" | ".pfm" | ".exr"));
        match o.kind {
            OutputKind::Png | OutputKind::Linear if all_extension => {
                return Err(OutputError::NoName { flag, path });
            }
            OutputKind::Png if ext != "png" => return Err(OutputError::NotPng { flag, path }),
            OutputKind::Linear if ext != "pfm" && ext != "exr" => {
                return Err(OutputError::UnknownLinear { flag, path });
            }
            _ => {}
        }
        if path.is_dir() || path.file_name().is_none() {
            return Err(OutputError::IsDirectory { flag, path });
        }
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
            _ => PathBuf::from("."),
        };
        if !dir.is_dir() {
            return Err(OutputError::NoDirectory { flag, path, dir });
        }
        let probe = temp_path(&path).with_extension("probe");
        match std::fs::File::create(&probe) {
            Ok(_) => {
                let _ = std::fs::remove_file(&probe);
            }
            Err(source) => {
                return Err(OutputError::NotWritable {
                    flag,
                    path,
                    dir,
                    source,
                });
            }
        }
        let here = resolved(&path);
        if let Some(other) = outputs[..i].iter().find(|p| resolved(&p.path) == here) {
            return Err(OutputError::Same {
                flag_a: other.flag,
                flag_b: flag,
                path,
            });
        }
        if let Some((what, _)) = inputs.iter().find(|(_, p)| resolved(p) == here) {
            return Err(OutputError::OverwritesInput {
                flag,
                path,
                input: what.clone(),
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pfm_rows_run_bottom_to_top() {
        let px = [Color::splat(1.0), Color::splat(2.0)]; // 1 wide, 2 high: top row 1.0, bottom 2.0
        let b = pfm_bytes(1, 2, &px);
        let header = b"PF\n1 2\n-1.0\n";
        assert_eq!(&b[..header.len()], header);
        let first = f32::from_le_bytes(b[header.len()..header.len() + 4].try_into().unwrap());
        assert_eq!(first, 2.0);
    }

    #[test]
    fn a_linear_file_of_radiance_beyond_f32_is_refused_and_not_written() {
        let dir = std::env::temp_dir().join(format!("rtl-beyond-f32-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let fits = [Color::splat(1.0), Color::new(3.0e38, 0.0, 1.0)];
        assert_eq!(beyond_f32(&fits), None);
        for ext in ["pfm", "exr"] {
            let path = dir.join(format!("m.{ext}"));
            write_linear(&path, 2, 1, &fits).unwrap();
            std::fs::remove_file(&path).unwrap();
            for bad in [Color::new(0.0, 1e300, 0.0), Color::new(f64::NAN, 0.0, 0.0)] {
                let pixels = [Color::splat(1.0), bad];
                assert_eq!(beyond_f32(&pixels).map(|(i, _)| i), Some(1));
                let e = write_linear(&path, 2, 1, &pixels).unwrap_err();
                assert!(e.contains("pixel (x 1, y 0)"), "{e}");
                assert!(!path.exists(), "{ext}: nothing may be written");
            }
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn gamma2_matches_the_book() {
        assert_eq!(Transfer::Gamma2.encode(0.25), 128);
        assert_eq!(Transfer::Gamma2.encode(4.0), 255);
        assert_eq!(Transfer::Gamma2.encode(f64::NAN), 0);
        assert_eq!(Transfer::Srgb.encode(1.0), 255);
        assert_eq!(Transfer::Srgb.encode(0.0), 0);
    }
}
