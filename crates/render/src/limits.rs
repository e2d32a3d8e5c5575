//! What the renderer accepts: one rule for each value, whether it comes from the command line or a
//! scene file, so that everything accepted renders and everything else is refused before any work.
//!
//! - **Numbers in a scene file** are finite and at most [`MAX_MAGNITUDE`] in size, and quantities that
//!   must be positive (radii, densities, scales, the index of refraction, the focus distance) are at
//!   least [`MIN_POSITIVE`]: then squares and triple products of lengths, which intersection and the
//!   solid-angle densities form, stay finite and nonzero.
//! - **Paths** have between 1 and [`MAX_DEPTH`] intersections.
//! - **Images** are at most [`MAX_SIDE`] pixels on a side, and the buffers a render needs
//!   ([`BYTES_PER_PIXEL`] per pixel) must fit in the memory the machine has available.
//! - **Threads** number at most [`MAX_THREADS`].

use std::fmt;

/// The largest magnitude of any number in a scene file.
pub const MAX_MAGNITUDE: f64 = 1e30;
/// The smallest value of a quantity that must be positive.
pub const MIN_POSITIVE: f64 = 1e-30;
/// The most intersections a path may have (book 3 uses 50).
pub const MAX_DEPTH: u32 = 10_000;
/// The largest image width or height, in pixels.
pub const MAX_SIDE: usize = 1 << 16;
/// The most worker threads.
pub const MAX_THREADS: usize = 1024;
/// The aspect ratios (width over height) a scene may ask for: one pixel by [`MAX_SIDE`] either way.
pub const ASPECT_RANGE: (f64, f64) = (1.0 / MAX_SIDE as f64, MAX_SIDE as f64);

/// What is wrong with a maximum path depth of `d` (`None` if nothing): "must be at least 1" or "must be
/// at most 10000, got 20000". The command line and scene files both ask this.
pub fn max_depth_problem(d: u32) -> Option<String> {
    if d == 0 {
        Some(
            "must be at least 1 (a path of 0 intersections sees nothing: the image would be black)"
                .into(),
        )
    } else if d > MAX_DEPTH {
        Some(format!("must be at most {MAX_DEPTH}, got {d}"))
    } else {
        None
    }
}

/// Bytes of memory one pixel of a render needs at most: the accumulation (three f64 sums and two u64
/// counts) and its copy for the pass in flight, a checkpoint's bytes, the image of means, and its
/// linear (3 f32) and 8-bit (3 u8) encodings.
pub const BYTES_PER_PIXEL: u64 = 40 + 40 + 40 + 24 + 12 + 3;

/// Why an image cannot be rendered at this size.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SizeError {
    #[error("the image would be {width}x{height} pixels: each side may be at most {MAX_SIDE}")]
    TooLarge { width: usize, height: usize },
    #[error(
        "the image would be {width}x{height} pixels, which needs {} of memory ({BYTES_PER_PIXEL} bytes \
         a pixel), but this machine has {} available (MemAvailable in /proc/meminfo)",
        Bytes(*needed),
        Bytes(*available)
    )]
    OutOfMemory {
        width: usize,
        height: usize,
        needed: u64,
        available: u64,
    },
}

/// A byte count in readable units.
pub struct Bytes(pub u64);

impl fmt::Display for Bytes {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let b = self.0 as f64;
        match self.0 {
            0..1_000 => write!(f, "{} B", self.0),
            1_000..1_000_000 => write!(f, "{:.1} kB", b / 1e3),
            1_000_000..1_000_000_000 => write!(f, "{:.1} MB", b / 1e6),
            1_000_000_000..1_000_000_000_000 => write!(f, "{:.1} GB", b / 1e9),
            _ => write!(f, "{:.1} TB", b / 1e12),
        }
    }
}

/// The memory available to a new allocation: `MemAvailable` of `/proc/meminfo`, in bytes (`None` where
/// there is no such file).
pub fn available_memory() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    mem_available(&text)
}

/// `MemAvailable` of the text of `/proc/meminfo`, in bytes.
pub fn mem_available(meminfo: &str) -> Option<u64> {
    let line = meminfo.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    kib.checked_mul(1024)
}

/// Check that a `width x height` render fits: each side at most [`MAX_SIDE`] and its buffers within
/// `available` bytes (if known). Returns the bytes it needs.
pub fn check_image(width: usize, height: usize, available: Option<u64>) -> Result<u64, SizeError> {
    if width > MAX_SIDE || height > MAX_SIDE {
        return Err(SizeError::TooLarge { width, height });
    }
    // Both sides are at most 2^16, so this cannot overflow.
    let needed = width as u64 * height as u64 * BYTES_PER_PIXEL;
    match available {
        Some(available) if needed > available => Err(SizeError::OutOfMemory {
            width,
            height,
            needed,
            available,
        }),
        _ => Ok(needed),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mem_available_reads_kib() {
        let text = "MemTotal:       16000000 kB\nMemFree:  1 kB\nMemAvailable:    8000000 kB\n";
        assert_eq!(mem_available(text), Some(8_000_000 * 1024));
        assert_eq!(mem_available("MemTotal: 5 kB\n"), None);
    }

    #[test]
    fn images_past_a_side_or_the_memory_are_refused() {
        assert!(check_image(600, 600, Some(1 << 30)).is_ok());
        assert_eq!(
            check_image(MAX_SIDE + 1, 1, None),
            Err(SizeError::TooLarge {
                width: MAX_SIDE + 1,
                height: 1
            })
        );
        let e = check_image(10_000, 10_000, Some(1 << 30)).unwrap_err();
        assert!(
            e.to_string().contains("15.9 GB") && e.to_string().contains("1.1 GB"),
            "{e}"
        );
    }
}
