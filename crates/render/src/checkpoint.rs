//! Checkpoints and parts: an [`Accumulator`]'s state on disk, with what it is an image of.
//!
//! A long render saves its per-pixel sums, sample counts and dropped counts, the range of samples
//! `[start, end)` of every pixel's stream they hold, and the render's identity (the scene, the settings,
//! the image size). Because sample `k` of a pixel depends only on `(seed, pixel, k)` and each pixel adds
//! its samples in the order of `k`, continuing from a checkpoint gives exactly the sums of a render that
//! never stopped. A *part* is the same file for a range that does not start at 0: [`merge`] adds parts
//! with disjoint ranges into the accumulation of their union.
//!
//! The format is little-endian binary, streamed to a temporary file (its checksum computed on the way:
//! a file as large as the image's accumulation is never held in memory) and renamed into place (so a
//! crash leaves the old file or the new one, never half of one), and ends with a 64-bit FNV-1a checksum
//! of everything before it, so a truncated or damaged file is refused before any of it is used:
//!
//! ```text
//! magic "RTLPART\0" | version u32 | file length u64 | rtl version, scene label: strings (u32 length + UTF-8)
//! | scene hash u64 | settings: string | width u64 | height u64 | start u64 | end u64
//! | width*height pixels, rows from the top: sum r, g, b f64 | count u64 | dropped u64 | FNV-1a 64 checksum
//! ```

use crate::limits::MAX_SIDE;
use crate::render::{Accumulator, RenderSettings};
use crate::scene::Scene;
use crate::text::shown;
use crate::vec::Color;
use std::io::Write;
use std::path::{Path, PathBuf};

/// The first eight bytes of every checkpoint.
pub const MAGIC: &[u8; 8] = b"RTLPART\0";
/// The version of the format written; files of other versions are refused.
pub const VERSION: u32 = 2;

/// 64-bit FNV-1a (Fowler, Noll and Vo): `h = (h xor byte) * p` from the offset basis. Every step is a
/// bijection of the state, so any change of a single byte changes the hash.
#[derive(Clone, Copy, Debug)]
pub struct Fnv1a(pub u64);

impl Fnv1a {
    pub const OFFSET_BASIS: u64 = 0xcbf2_9ce4_8422_2325;
    pub const PRIME: u64 = 0x0000_0100_0000_01b3;

    pub fn new() -> Self {
        Fnv1a(Self::OFFSET_BASIS)
    }

    pub fn update(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0 ^ b as u64).wrapping_mul(Self::PRIME);
        }
    }

    /// The hash of `bytes`.
    pub fn hash(bytes: &[u8]) -> u64 {
        let mut h = Fnv1a::new();
        h.update(bytes);
        h.0
    }
}

impl Default for Fnv1a {
    fn default() -> Self {
        Self::new()
    }
}

impl std::io::Write for Fnv1a {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.update(buf);
        Ok(buf.len())
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// A hash of everything a scene is (shapes, materials, textures, camera, background, importance
/// targets), taken over its serde serialisation (JSON, streamed into the hasher without building the
/// text): equal scenes hash equal, and an edited scene file, another texture or another scene hashes
/// differently. What is derived from the rest (BVHs, the fixed Perlin table) is left out. An image
/// texture takes part as its size and the digest of its pixels taken when it was loaded
/// ([`ImageData::digest`](crate::texture::ImageData::digest)), not pixel by pixel: a render's
/// identity costs no more with an 8192 x 4096 texture than without.
pub fn scene_hash(scene: &Scene) -> u64 {
    let mut h = Fnv1a::new();
    // Writing into the hasher cannot fail, and every number of a scene is finite.
    serde_json::to_writer(&mut h, scene).expect("a scene serialises");
    h.0
}

/// The settings that change the image, serialised (JSON) so that every field takes part, including
/// ones added later.
pub fn settings_record(settings: &RenderSettings) -> String {
    serde_json::to_string(settings).expect("settings serialise")
}

/// What a checkpoint is an image of: two checkpoints may be continued or merged only if these are equal.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Identity {
    /// The scene's name, for messages (a built-in name or a scene file's name).
    pub scene: String,
    /// [`scene_hash`] of the scene.
    pub scene_hash: u64,
    /// [`settings_record`] of the settings.
    pub settings: String,
    pub width: usize,
    pub height: usize,
}

impl Identity {
    /// The identity of a render of `scene` (named `name`) with `settings` at `width x height`.
    pub fn new(
        name: &str,
        scene: &Scene,
        settings: &RenderSettings,
        width: usize,
        height: usize,
    ) -> Self {
        Identity {
            scene: name.to_string(),
            scene_hash: scene_hash(scene),
            settings: settings_record(settings),
            width,
            height,
        }
    }

    /// What differs between `self` (called `a` in the phrases) and `other` (called `b`), one phrase
    /// each; empty if they are the same render.
    pub fn differences(&self, other: &Identity, a: &str, b: &str) -> Vec<String> {
        let (na, nb) = (a, b);
        let mut out = Vec::new();
        if self.scene != other.scene {
            out.push(format!(
                "scene: '{}' in {na}, '{}' in {nb}",
                shown(&self.scene),
                shown(&other.scene)
            ));
        } else if self.scene_hash != other.scene_hash {
            out.push(format!(
                "scene: '{}' differs between {na} and {nb} (the scene file was edited, or another \
                 texture or another rtl build)",
                shown(&self.scene)
            ));
        }
        if self.settings != other.settings {
            let parse = |s: &str| serde_json::from_str::<serde_json::Value>(s).ok();
            match (parse(&self.settings), parse(&other.settings)) {
                (Some(a), Some(b)) => value_differences("", &a, &b, na, nb, &mut out),
                _ => out.push(format!(
                    "settings: {} in {na}, {} in {nb}",
                    shown(&self.settings),
                    shown(&other.settings)
                )),
            }
        }
        if out.is_empty() && (self.width, self.height) != (other.width, other.height) {
            out.push(format!(
                "image size: {}x{} in {na}, {}x{} in {nb}",
                self.width, self.height, other.width, other.height
            ));
        }
        if out.is_empty() && self != other {
            out.push("the render's identity".into());
        }
        out
    }
}

/// `name: va in A, vb in B` for every field of two serialised settings that differs, descending into
/// fields that are tables on both sides (`strategy.Mis.russian_roulette: true in A, false in B`).
fn value_differences(
    path: &str,
    a: &serde_json::Value,
    b: &serde_json::Value,
    na: &str,
    nb: &str,
    out: &mut Vec<String>,
) {
    use serde_json::Value;
    let join = |k: &str| {
        if path.is_empty() {
            k.to_string()
        } else {
            format!("{path}.{k}")
        }
    };
    match (a, b) {
        (Value::Object(ma), Value::Object(mb)) => {
            for (k, va) in ma {
                match mb.get(k) {
                    Some(vb) => value_differences(&join(k), va, vb, na, nb, out),
                    None => out.push(format!(
                        "{}: {} in {na}, absent in {nb}",
                        shown(&join(k)),
                        shown(&va.to_string())
                    )),
                }
            }
            for (k, vb) in mb {
                if !ma.contains_key(k) {
                    out.push(format!(
                        "{}: absent in {na}, {} in {nb}",
                        shown(&join(k)),
                        shown(&vb.to_string())
                    ));
                }
            }
        }
        _ if a != b => out.push(format!(
            "{}: {} in {na}, {} in {nb}",
            shown(path),
            shown(&a.to_string()),
            shown(&b.to_string())
        )),
        _ => {}
    }
}

/// An accumulation of samples `[start, acc.samples)` of every pixel of one render.
#[derive(Clone, Debug, PartialEq)]
pub struct Checkpoint {
    pub identity: Identity,
    /// The version of rtl that wrote it (a different build may trace differently: noted, not refused).
    pub rtl_version: String,
    /// The first sample of every pixel's stream it holds; `acc.samples` is one past the last.
    pub start: u64,
    pub acc: Accumulator,
}

/// Why a checkpoint file cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum CheckpointError {
    /// Not read: not a regular file, larger than the memory available, or an I/O error (the
    /// message names the file, [`crate::limits::read_regular_file`]).
    #[error("{0}")]
    Read(String),
    #[error("{0} is not an rtl checkpoint (it does not start with the checkpoint signature)")]
    NotACheckpoint(PathBuf),
    #[error("{path} is a checkpoint of format version {found}; this rtl reads version {VERSION}")]
    Version { path: PathBuf, found: u32 },
    #[error("{path} is truncated: {found} of its {expected} bytes are there")]
    Truncated {
        path: PathBuf,
        found: u64,
        expected: u64,
    },
    #[error("{path} is corrupt: {what}")]
    Corrupt { path: PathBuf, what: String },
}

impl Checkpoint {
    /// The samples per pixel it holds.
    pub fn spp(&self) -> u64 {
        self.acc.samples - self.start
    }

    /// The checkpoint as borrowed parts, which is all that writing it needs.
    pub fn borrowed(&self) -> CheckpointRef<'_> {
        CheckpointRef {
            identity: &self.identity,
            rtl_version: &self.rtl_version,
            start: self.start,
            acc: &self.acc,
        }
    }

    /// The file's bytes ([`CheckpointRef::to_bytes`]).
    pub fn to_bytes(&self) -> Vec<u8> {
        self.borrowed().to_bytes()
    }

    /// Parse a checkpoint, refusing anything truncated, damaged or inconsistent (`path` is for messages).
    pub fn from_bytes(bytes: &[u8], path: &Path) -> Result<Checkpoint, CheckpointError> {
        let corrupt = |what: &str| CheckpointError::Corrupt {
            path: path.into(),
            what: what.into(),
        };
        if bytes.len() < 8 || &bytes[..8] != MAGIC {
            return Err(CheckpointError::NotACheckpoint(path.into()));
        }
        let mut r = Reader { b: bytes, at: 8 };
        let truncated = |expected: u64| CheckpointError::Truncated {
            path: path.into(),
            found: bytes.len() as u64,
            expected,
        };
        let version = r.u32().ok_or_else(|| truncated(20))?;
        if version != VERSION {
            return Err(CheckpointError::Version {
                path: path.into(),
                found: version,
            });
        }
        let len = r.u64().ok_or_else(|| truncated(20))?;
        if (bytes.len() as u64) < len {
            return Err(truncated(len));
        }
        if bytes.len() as u64 > len {
            return Err(corrupt(&format!(
                "{} bytes where its header says {len}",
                bytes.len()
            )));
        }
        let (body, tail) = bytes.split_at(bytes.len() - 8);
        let stored = u64::from_le_bytes(tail.try_into().expect("8 bytes"));
        if Fnv1a::hash(body) != stored {
            return Err(corrupt("checksum mismatch (the file was damaged)"));
        }
        r.b = body;
        let bad = || corrupt("malformed header");
        let rtl_version = r.str().ok_or_else(bad)?;
        let scene = r.str().ok_or_else(bad)?;
        let scene_hash = r.u64().ok_or_else(bad)?;
        let settings = r.str().ok_or_else(bad)?;
        let width = r.u64().ok_or_else(bad)?;
        let height = r.u64().ok_or_else(bad)?;
        let start = r.u64().ok_or_else(bad)?;
        let end = r.u64().ok_or_else(bad)?;
        if end < start {
            return Err(corrupt(&format!(
                "sample range {start}..{end} is backwards"
            )));
        }
        if width == 0 || height == 0 || width > MAX_SIDE as u64 || height > MAX_SIDE as u64 {
            return Err(corrupt(&format!(
                "its image is {width}x{height} pixels: each side must be 1 to {MAX_SIDE}"
            )));
        }
        let n = width
            .checked_mul(height)
            .filter(|n| n.checked_mul(40) == Some((r.b.len() - r.at) as u64))
            .ok_or_else(|| corrupt(&format!("pixel data does not match {width}x{height}")))?
            as usize;
        let (width, height) = (width as usize, height as usize);
        let mut acc = Accumulator::new(width, height);
        acc.samples = end;
        for i in 0..n {
            let mut c = [0.0; 3];
            for v in &mut c {
                *v = f64::from_bits(r.u64().ok_or_else(bad)?);
            }
            acc.sum[i] = Color::from_array(c);
            acc.count[i] = r.u64().ok_or_else(bad)?;
            acc.dropped[i] = r.u64().ok_or_else(bad)?;
            if let Some(what) = sum_problem(acc.sum[i], acc.count[i]) {
                let (x, y) = (i % width, i / width);
                return Err(corrupt(&format!(
                    "pixel {i} (x {x}, y {y}) has the sum [{}, {}, {}] of {} samples: {what}",
                    c[0], c[1], c[2], acc.count[i]
                )));
            }
            if acc.count[i].checked_add(acc.dropped[i]) != Some(end - start) {
                return Err(corrupt(&format!(
                    "pixel {i} holds {} samples, not the {} of samples {start}..{end}",
                    acc.count[i] as u128 + acc.dropped[i] as u128,
                    end - start
                )));
            }
        }
        Ok(Checkpoint {
            identity: Identity {
                scene,
                scene_hash,
                settings,
                width,
                height,
            },
            rtl_version,
            start,
            acc,
        })
    }

    /// Read and check a checkpoint file: a regular file (not a device or a pipe, which could
    /// give bytes without end) no larger than the memory available
    /// ([`crate::limits::available_memory`]), by [`crate::limits::read_regular_file`].
    pub fn read(path: &Path) -> Result<Checkpoint, CheckpointError> {
        let max = crate::limits::available_memory().map_or(u64::MAX, |a| a.bytes);
        let bytes = crate::limits::read_regular_file(path, "checkpoint", max)
            .map_err(CheckpointError::Read)?;
        Checkpoint::from_bytes(&bytes, path)
    }

    /// Write atomically ([`CheckpointRef::write`]).
    pub fn write(&self, path: &Path) -> std::io::Result<()> {
        self.borrowed().write(path)
    }
}

/// A checkpoint to be written, its parts borrowed: a render saves its accumulation between passes
/// and at the end without copying it (a copy is 40 bytes a pixel).
#[derive(Clone, Copy, Debug)]
pub struct CheckpointRef<'a> {
    pub identity: &'a Identity,
    pub rtl_version: &'a str,
    /// The first sample of every pixel's stream it holds; `acc.samples` is one past the last.
    pub start: u64,
    pub acc: &'a Accumulator,
}

/// Bytes of a checkpoint's file before its strings: magic, version, length.
const FIXED_HEAD: u64 = 8 + 4 + 8;
/// Bytes of a checkpoint's file besides its strings and pixels: [`FIXED_HEAD`], three string
/// lengths, the scene hash, width, height, start and end, and the checksum.
const FIXED_BYTES: u64 = FIXED_HEAD + 3 * 4 + 8 + 4 * 8 + 8;
/// Bytes of one pixel in a checkpoint's file: three f64 sums and two u64 counts.
pub const FILE_BYTES_PER_PIXEL: u64 = 40;
/// How many pixels [`CheckpointRef::write_to`] encodes at a time.
const PIXELS_PER_WRITE: usize = 1024;

/// What passes through it is written on to `inner` and hashed (FNV-1a): the checksum of a file that
/// is streamed, never held whole.
struct Hashing<W> {
    inner: W,
    hash: Fnv1a,
    written: u64,
}

impl<W: Write> Write for Hashing<W> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let n = self.inner.write(buf)?;
        self.hash.update(&buf[..n]);
        self.written += n as u64;
        Ok(n)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.inner.flush()
    }
}

impl CheckpointRef<'_> {
    /// The length of the file in bytes, known before any of it is written (the header holds it).
    pub fn file_len(&self) -> u64 {
        let strings = [
            self.rtl_version,
            &self.identity.scene,
            &self.identity.settings,
        ];
        FIXED_BYTES
            + strings.iter().map(|s| s.len() as u64).sum::<u64>()
            + FILE_BYTES_PER_PIXEL * self.acc.sum.len() as u64
    }

    /// Stream the file to `w`, its checksum computed as it goes; the bytes are those of
    /// [`Self::to_bytes`], and nothing the size of the image is allocated.
    pub fn write_to(&self, w: impl Write) -> std::io::Result<()> {
        let len = self.file_len();
        let mut h = Hashing {
            inner: w,
            hash: Fnv1a::new(),
            written: 0,
        };
        h.write_all(MAGIC)?;
        h.write_all(&VERSION.to_le_bytes())?;
        h.write_all(&len.to_le_bytes())?;
        put_str(&mut h, self.rtl_version)?;
        put_str(&mut h, &self.identity.scene)?;
        h.write_all(&self.identity.scene_hash.to_le_bytes())?;
        put_str(&mut h, &self.identity.settings)?;
        for v in [
            self.identity.width as u64,
            self.identity.height as u64,
            self.start,
            self.acc.samples,
        ] {
            h.write_all(&v.to_le_bytes())?;
        }
        let acc = self.acc;
        let n = acc.sum.len();
        let mut block = [0u8; FILE_BYTES_PER_PIXEL as usize * PIXELS_PER_WRITE];
        for first in (0..n).step_by(PIXELS_PER_WRITE) {
            let last = (first + PIXELS_PER_WRITE).min(n);
            let pixels = block.chunks_exact_mut(FILE_BYTES_PER_PIXEL as usize);
            for (i, out) in (first..last).zip(pixels) {
                let s = acc.sum[i];
                let words = [
                    s.x.to_bits(),
                    s.y.to_bits(),
                    s.z.to_bits(),
                    acc.count[i],
                    acc.dropped[i],
                ];
                for (word, bytes) in words.iter().zip(out.chunks_exact_mut(8)) {
                    bytes.copy_from_slice(&word.to_le_bytes());
                }
            }
            h.write_all(&block[..(last - first) * FILE_BYTES_PER_PIXEL as usize])?;
        }
        // (the checksum covers everything before it, and so not itself)
        if h.written + 8 != len {
            return Err(std::io::Error::other(format!(
                "internal: a checkpoint of {} bytes where its header says {len}",
                h.written + 8
            )));
        }
        let sum = h.hash.0;
        h.inner.write_all(&sum.to_le_bytes())?;
        h.inner.flush()
    }

    /// The file's bytes, in a vector of exactly their length (allocated once).
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut b = Vec::with_capacity(self.file_len() as usize);
        self.write_to(&mut b)
            .expect("writing into a vector of the file's length cannot fail");
        b
    }

    /// Write atomically ([`crate::output::write_atomically`]): streamed through a buffer to a
    /// temporary file, flushed to disk, then renamed over `path`.
    pub fn write(&self, path: &Path) -> std::io::Result<()> {
        crate::output::write_atomically(path, |tmp| {
            let f = std::fs::File::create(tmp).map_err(|e| e.to_string())?;
            let mut f = std::io::BufWriter::with_capacity(1 << 16, f);
            self.write_to(&mut f).map_err(|e| e.to_string())?;
            let f = f.into_inner().map_err(|e| e.error().to_string())?;
            f.sync_all().map_err(|e| e.to_string())
        })
        .map_err(std::io::Error::other)
    }
}

/// What is wrong with a pixel's sum of `count` finite, non-negative radiance samples: a sum that is not
/// finite, that is negative, or that is not zero with no samples (`None` if nothing).
fn sum_problem(sum: Color, count: u64) -> Option<&'static str> {
    if !sum.is_finite() {
        Some("a sum of finite samples must be finite")
    } else if sum.min_element() < 0.0 {
        Some("radiance is never negative, so neither is its sum")
    } else if count == 0 && sum != Color::ZERO {
        Some("a pixel with no samples must have a zero sum")
    } else {
        None
    }
}

fn put_str(w: &mut impl Write, s: &str) -> std::io::Result<()> {
    w.write_all(&(s.len() as u32).to_le_bytes())?;
    w.write_all(s.as_bytes())
}

/// Bounds-checked little-endian reads: `None` past the end, never a panic.
struct Reader<'a> {
    b: &'a [u8],
    at: usize,
}

impl Reader<'_> {
    fn take(&mut self, n: usize) -> Option<&[u8]> {
        let s = self.b.get(self.at..self.at.checked_add(n)?)?;
        self.at += n;
        Some(s)
    }
    fn u32(&mut self) -> Option<u32> {
        Some(u32::from_le_bytes(self.take(4)?.try_into().ok()?))
    }
    fn u64(&mut self) -> Option<u64> {
        Some(u64::from_le_bytes(self.take(8)?.try_into().ok()?))
    }
    fn str(&mut self) -> Option<String> {
        let n = self.u32()? as usize;
        String::from_utf8(self.take(n)?.to_vec()).ok()
    }
}

/// Parts merged into one accumulation, and the samples missing from its range.
#[derive(Clone, Debug)]
pub struct Merged {
    /// The parts' sums added in the order of their sample ranges; its range runs from the first part's
    /// start to the last part's end.
    pub checkpoint: Checkpoint,
    /// Sample ranges between the parts that no part holds (empty if they join up).
    pub gaps: Vec<(u64, u64)>,
}

/// Why parts cannot be merged.
#[derive(Debug, thiserror::Error)]
pub enum MergeError {
    #[error("no parts to merge")]
    NoParts,
    #[error("{part} is not a part of the same render as {first}: {differences}")]
    OtherRender {
        part: String,
        first: String,
        differences: String,
    },
    #[error(
        "{a} (samples {}..{}) and {b} (samples {}..{}) overlap: each sample may be counted once",
        a_range.0, a_range.1, b_range.0, b_range.1
    )]
    Overlap {
        a: String,
        a_range: (u64, u64),
        b: String,
        b_range: (u64, u64),
    },
    #[error(
        "the merged sum of pixel {pixel} (x {x}, y {y}) overflows f64: the parts' radiance is too \
         large to add"
    )]
    Overflow { pixel: usize, x: usize, y: usize },
}

/// Add parts of one render with disjoint sample ranges, in the order of their ranges (whatever the
/// order given). `names` name the parts in messages.
///
/// Counts and dropped counts are exact. The sums are the parts' sums added left to right, so they equal
/// the sums of one render of the whole range up to rounding: one render adds sample by sample, a merge
/// adds each part's subtotal, and floating-point addition is not associative. For `n` non-negative
/// samples each way of adding is within `(n - 1) 2^-53` (relative) of the exact sum (Higham's bound for
/// recursive summation), so the two differ by at most twice that: `1e-12` at `n = 4500`, and in practice
/// far less. Merging a single part reproduces it bit for bit.
pub fn merge(parts: &[(String, Checkpoint)]) -> Result<Merged, MergeError> {
    let Some((first_name, first)) = parts.first() else {
        return Err(MergeError::NoParts);
    };
    for (name, p) in &parts[1..] {
        let d = first.identity.differences(&p.identity, first_name, name);
        if !d.is_empty() {
            return Err(MergeError::OtherRender {
                part: name.clone(),
                first: first_name.clone(),
                differences: d.join("; "),
            });
        }
    }
    let mut order: Vec<&(String, Checkpoint)> = parts.iter().collect();
    order.sort_by_key(|(_, p)| (p.start, p.acc.samples));
    let mut gaps = Vec::new();
    for w in order.windows(2) {
        let ((na, a), (nb, b)) = (w[0], w[1]);
        if b.start < a.acc.samples {
            return Err(MergeError::Overlap {
                a: na.clone(),
                a_range: (a.start, a.acc.samples),
                b: nb.clone(),
                b_range: (b.start, b.acc.samples),
            });
        }
        if b.start > a.acc.samples {
            gaps.push((a.acc.samples, b.start));
        }
    }
    let mut out = order[0].1.clone();
    for (_, p) in &order[1..] {
        for i in 0..out.acc.sum.len() {
            out.acc.sum[i] += p.acc.sum[i];
            out.acc.count[i] += p.acc.count[i];
            out.acc.dropped[i] += p.acc.dropped[i];
        }
        out.acc.samples = p.acc.samples;
    }
    // Each part's sums are finite, but two large ones may add up past f64::MAX.
    if let Some(i) = out.acc.sum.iter().position(|s| !s.is_finite()) {
        return Err(MergeError::Overflow {
            pixel: i,
            x: i % out.acc.width,
            y: i / out.acc.width,
        });
    }
    Ok(Merged {
        checkpoint: out,
        gaps,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn part(start: u64, end: u64, seed: u64) -> Checkpoint {
        let mut acc = Accumulator::new(3, 2);
        for i in 0..6 {
            acc.sum[i] = Color::new(i as f64 * 0.1, 1.0 / 3.0, start as f64);
            acc.count[i] = end - start - (i as u64 % 2).min(end - start);
            acc.dropped[i] = end - start - acc.count[i];
        }
        acc.samples = end;
        Checkpoint {
            identity: Identity {
                scene: "cornell".into(),
                scene_hash: 42,
                settings: format!(
                    r#"{{"width":3,"max_depth":50,"seed":{seed},"strategy":{{"Mis":{{"a":true,"b":[1,2]}}}}}}"#
                ),
                width: 3,
                height: 2,
            },
            rtl_version: "0.1.0".into(),
            start,
            acc,
        }
    }

    #[test]
    fn round_trip_is_exact() {
        let p = part(4, 9, 1);
        let back = Checkpoint::from_bytes(&p.to_bytes(), Path::new("p")).unwrap();
        assert_eq!(back, p);
    }

    /// The format as the module's documentation gives it, put together field by field in one vector:
    /// what the streaming writer must produce byte for byte.
    fn bytes_as_documented(c: &Checkpoint) -> Vec<u8> {
        let mut b = Vec::new();
        let text = |b: &mut Vec<u8>, s: &str| {
            b.extend_from_slice(&(s.len() as u32).to_le_bytes());
            b.extend_from_slice(s.as_bytes());
        };
        b.extend_from_slice(MAGIC);
        b.extend_from_slice(&VERSION.to_le_bytes());
        b.extend_from_slice(&0u64.to_le_bytes());
        text(&mut b, &c.rtl_version);
        text(&mut b, &c.identity.scene);
        b.extend_from_slice(&c.identity.scene_hash.to_le_bytes());
        text(&mut b, &c.identity.settings);
        for v in [
            c.identity.width as u64,
            c.identity.height as u64,
            c.start,
            c.acc.samples,
        ] {
            b.extend_from_slice(&v.to_le_bytes());
        }
        for i in 0..c.acc.sum.len() {
            let s = c.acc.sum[i];
            for v in [s.x.to_bits(), s.y.to_bits(), s.z.to_bits()] {
                b.extend_from_slice(&v.to_le_bytes());
            }
            b.extend_from_slice(&c.acc.count[i].to_le_bytes());
            b.extend_from_slice(&c.acc.dropped[i].to_le_bytes());
        }
        let len = (b.len() + 8) as u64;
        b[12..20].copy_from_slice(&len.to_le_bytes());
        let sum = Fnv1a::hash(&b);
        b.extend_from_slice(&sum.to_le_bytes());
        b
    }

    #[test]
    fn the_streamed_file_is_the_documented_format_and_its_vector_is_allocated_once() {
        // an image of more pixels than one block of the writer, and one of fewer
        for (w, h) in [(3, 2), (1000, 3)] {
            let mut c = part(7, 12, 3);
            c.identity.width = w;
            c.identity.height = h;
            let mut acc = Accumulator::new(w, h);
            for i in 0..w * h {
                acc.sum[i] = Color::new(i as f64, 0.5 / (1 + i) as f64, 1e300);
                acc.count[i] = 5 - (i as u64 % 3);
                acc.dropped[i] = i as u64 % 3;
            }
            acc.samples = 12;
            c.acc = acc;
            let want = bytes_as_documented(&c);
            let b = c.to_bytes();
            assert_eq!(b, want, "{w}x{h}");
            // the header's strings (the settings are some 170 bytes) no longer make it grow
            assert_eq!(b.capacity(), b.len(), "{w}x{h}");
            assert_eq!(c.borrowed().file_len(), b.len() as u64);
            let dir = std::env::temp_dir().join(format!("rtl-ck-stream-{}", std::process::id()));
            std::fs::create_dir_all(&dir).unwrap();
            let path = dir.join("c.ck");
            c.write(&path).unwrap();
            assert_eq!(std::fs::read(&path).unwrap(), want, "{w}x{h}");
            assert_eq!(Checkpoint::read(&path).unwrap(), c);
            let _ = std::fs::remove_dir_all(&dir);
        }
    }

    #[test]
    fn every_flipped_byte_and_every_truncation_is_refused() {
        let bytes = part(0, 5, 1).to_bytes();
        for i in 0..bytes.len() {
            let mut b = bytes.clone();
            b[i] ^= 0x10;
            assert!(
                Checkpoint::from_bytes(&b, Path::new("p")).is_err(),
                "byte {i}"
            );
            assert!(
                Checkpoint::from_bytes(&bytes[..i], Path::new("p")).is_err(),
                "cut at {i}"
            );
        }
        let e = Checkpoint::from_bytes(&bytes[..100], Path::new("ck")).unwrap_err();
        assert!(e.to_string().contains("truncated"), "{e}");
    }

    #[test]
    fn differences_name_the_field() {
        let (a, b) = (part(0, 1, 1).identity, part(0, 1, 2).identity);
        assert_eq!(a.differences(&b, "A", "B"), ["seed: 1 in A, 2 in B"]);
        let mut d = a.clone();
        d.settings = d.settings.replace("true", "false");
        assert_eq!(
            a.differences(&d, "A", "B"),
            ["strategy.Mis.a: true in A, false in B"]
        );
        assert!(a.differences(&a, "A", "B").is_empty());
        let mut c = a.clone();
        c.scene_hash = 7;
        assert!(a.differences(&c, "A", "B")[0].contains("'cornell' differs"));
        c.scene = "quads".into();
        assert_eq!(
            a.differences(&c, "A", "B"),
            ["scene: 'cornell' in A, 'quads' in B"]
        );
    }

    #[test]
    fn merge_orders_parts_and_refuses_overlaps() {
        let (a, b, c) = (part(0, 4, 1), part(4, 10, 1), part(10, 12, 1));
        let m = merge(&[
            ("c".into(), c.clone()),
            ("a".into(), a.clone()),
            ("b".into(), b.clone()),
        ])
        .unwrap();
        assert!(m.gaps.is_empty());
        assert_eq!((m.checkpoint.start, m.checkpoint.acc.samples), (0, 12));
        for i in 0..6 {
            assert_eq!(
                m.checkpoint.acc.sum[i],
                a.acc.sum[i] + b.acc.sum[i] + c.acc.sum[i]
            );
            assert_eq!(m.checkpoint.acc.count[i] + m.checkpoint.acc.dropped[i], 12);
        }
        let e = merge(&[("a".into(), a.clone()), ("x".into(), part(3, 5, 1))])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("overlap") && e.contains("a (samples 0..4)"),
            "{e}"
        );
        let e = merge(&[("a".into(), a.clone()), ("s".into(), part(4, 5, 2))])
            .unwrap_err()
            .to_string();
        assert!(e.contains("seed: 1 in a, 2 in s"), "{e}");
        let m = merge(&[("a".into(), a), ("c".into(), c)]).unwrap();
        assert_eq!(m.gaps, [(4, 10)]);
    }

    #[test]
    fn a_valid_checksum_over_lying_sums_is_refused() {
        let cases: [(Color, u64, &str); 5] = [
            (Color::new(f64::NAN, 0.0, 0.0), 5, "must be finite"),
            (Color::new(0.0, f64::INFINITY, 0.0), 5, "must be finite"),
            (Color::new(0.0, 0.0, -1.0), 5, "never negative"),
            (Color::new(0.0, 0.0, -0.0), 5, ""),
            (Color::splat(1.0), 0, "no samples must have a zero sum"),
        ];
        for (sum, count, words) in cases {
            let mut p = part(0, 5, 1);
            p.acc.sum[2] = sum;
            p.acc.count[2] = count;
            p.acc.dropped[2] = 5 - count;
            let r = Checkpoint::from_bytes(&p.to_bytes(), Path::new("ck"));
            if words.is_empty() {
                assert!(r.is_ok(), "{sum:?}");
                continue;
            }
            let e = r.unwrap_err().to_string();
            assert!(e.contains(words) && e.contains("pixel 2 (x 2, y 0)"), "{e}");
        }
    }

    #[test]
    fn counts_that_disagree_with_the_sample_range_are_refused() {
        let mut p = part(0, 5, 1);
        p.acc.count[0] += 1;
        let e = Checkpoint::from_bytes(&p.to_bytes(), Path::new("ck")).unwrap_err();
        assert!(
            e.to_string().contains("pixel 0 holds 6 samples, not the 5"),
            "{e}"
        );
    }

    #[test]
    fn an_empty_image_is_refused() {
        let mut p = part(0, 5, 1);
        p.acc = Accumulator::new(0, 2);
        p.acc.samples = 5;
        p.identity.width = 0;
        let e = Checkpoint::from_bytes(&p.to_bytes(), Path::new("ck")).unwrap_err();
        assert!(e.to_string().contains("0x2 pixels"), "{e}");
    }

    #[test]
    fn a_merge_whose_sums_overflow_is_refused_not_written_as_nan() {
        let (mut a, mut b) = (part(0, 4, 1), part(4, 8, 1));
        a.acc.sum[5] = Color::splat(1.5e308);
        b.acc.sum[5] = Color::splat(1.5e308);
        let e = merge(&[("a".into(), a), ("b".into(), b)]).unwrap_err();
        assert!(
            matches!(
                e,
                MergeError::Overflow {
                    pixel: 5,
                    x: 2,
                    y: 1
                }
            ),
            "{e}"
        );
    }

    #[test]
    fn sample_ranges_past_2_to_the_32_round_trip_and_merge_exactly() {
        let k = (1u64 << 32) - 2;
        let (a, b) = (part(k, k + 3, 1), part(k + 3, k + 7, 1));
        for p in [&a, &b] {
            let back = Checkpoint::from_bytes(&p.to_bytes(), Path::new("p")).unwrap();
            assert_eq!(&back, p);
        }
        let m = merge(&[("b".into(), b), ("a".into(), a)]).unwrap();
        assert_eq!((m.checkpoint.start, m.checkpoint.acc.samples), (k, k + 7));
        let top = u64::MAX - 1;
        let c = part(top - 5, top, 1);
        assert_eq!(
            Checkpoint::from_bytes(&c.to_bytes(), Path::new("p")).unwrap(),
            c
        );
    }
}
