//! The images the renderers write and the noise they carry.
//!
//! Every renderer's output is brought to the book's display encoding before it is compared: linear
//! radiance `x` per channel (NaN as 0) is written `floor(256 clamp(sqrt(x), 0, 0.999))` (the book's
//! `write_color`, gamma 2), and that byte `v` stands for the display value `v / 256`. So the noise of
//! every renderer is measured the same way, in gamma space, with the same quantisation.
//!
//! The noise constant of an unbiased renderer is `c = RMSE sqrt(spp)`: its per-pixel root mean square
//! error falls as `c / sqrt(spp)`. Two renders `a`, `b` of the same settings with independent seeds
//! differ by two independent errors, so `E[(a - b)^2] = 2 sigma^2` per value, and
//! `c = RMS(a - b) / sqrt(2) * sqrt(spp)`, the RMS taken over every pixel and channel.

use rtl_render::output::Transfer;
use thiserror::Error;

/// An image in display values (`v / 256` of the book's bytes), rows top to bottom, RGB interleaved.
#[derive(Clone, Debug, PartialEq)]
pub struct DisplayImage {
    pub width: usize,
    pub height: usize,
    pub values: Vec<f64>,
}

impl DisplayImage {
    /// The mean display value over every pixel and channel: a check that two renderers drew the
    /// same scene.
    pub fn mean(&self) -> f64 {
        self.values.iter().sum::<f64>() / self.values.len().max(1) as f64
    }
}

/// A malformed or unexpected image.
#[derive(Debug, Error, PartialEq)]
pub enum ImageError {
    #[error("{what}: not a {format} file (it starts with {found:?})")]
    Magic {
        what: String,
        format: &'static str,
        found: String,
    },
    #[error("{what}: header field `{field}`: {problem}")]
    Header {
        what: String,
        field: &'static str,
        problem: String,
    },
    #[error("{what}: {found} values of pixel data where {expected} were expected")]
    Truncated {
        what: String,
        expected: usize,
        found: usize,
    },
    #[error("{what}: value {index} is {value}, above the maximum {max}")]
    Range {
        what: String,
        index: usize,
        value: u64,
        max: u64,
    },
    #[error("images differ in size: {0}x{1} against {2}x{3}")]
    Size(usize, usize, usize, usize),
    #[error(
        "{what}: pixel (x {x}, y {y}), channel {channel}, is {value}: radiance is finite and never \
         negative, so this render went wrong (its noise would be measured as if it were black or white)"
    )]
    Value {
        what: String,
        x: usize,
        y: usize,
        channel: usize,
        value: f32,
    },
    #[error(
        "{what}: {extra} bytes follow the {expected} values of pixel data (a file that is not one PFM)"
    )]
    Trailing {
        what: String,
        expected: usize,
        extra: usize,
    },
}

/// The book's encoding of one linear channel (`write_color` of book 3's `color.h`): rtl's own
/// [`Transfer::Gamma2`], but for `+inf`, which the book clamps to 255 (rtl's writer, which never
/// meets one, writes 0).
pub fn book_byte(linear: f32) -> u8 {
    if linear == f32::INFINITY {
        255
    } else {
        Transfer::Gamma2.encode(linear as f64)
    }
}

/// Splits the whitespace-separated header tokens of a netpbm file, skipping `#` comments, and
/// returns them with the offset just past the single whitespace byte after the last one.
fn header_tokens(bytes: &[u8], count: usize) -> (Vec<String>, usize) {
    let mut tokens = Vec::new();
    let mut i = 0;
    while tokens.len() < count && i < bytes.len() {
        let b = bytes[i];
        if b == b'#' {
            while i < bytes.len() && bytes[i] != b'\n' {
                i += 1;
            }
        } else if b.is_ascii_whitespace() {
            i += 1;
        } else {
            let start = i;
            while i < bytes.len() && !bytes[i].is_ascii_whitespace() {
                i += 1;
            }
            tokens.push(String::from_utf8_lossy(&bytes[start..i]).into_owned());
        }
    }
    (tokens, (i + 1).min(bytes.len()))
}

fn header_number(
    what: &str,
    field: &'static str,
    token: Option<&String>,
) -> Result<usize, ImageError> {
    let token = token.ok_or_else(|| ImageError::Header {
        what: what.into(),
        field,
        problem: "missing (the file ends in its header)".into(),
    })?;
    token
        .parse::<usize>()
        .ok()
        .filter(|&n| n > 0)
        .ok_or_else(|| ImageError::Header {
            what: what.into(),
            field,
            problem: format!("expected a positive integer, got {token:?}"),
        })
}

/// `what` does not start as a `format` file does (its first bytes, shown).
fn not_a(what: &str, format: &'static str, bytes: &[u8]) -> ImageError {
    ImageError::Magic {
        what: what.into(),
        format,
        found: String::from_utf8_lossy(&bytes[..bytes.len().min(8)]).into_owned(),
    }
}

/// The number of values (three a pixel) of a `width` by `height` image, refused where it cannot be
/// counted (a header no file could fill).
fn value_count(what: &str, width: usize, height: usize) -> Result<usize, ImageError> {
    width
        .checked_mul(height)
        .and_then(|p| p.checked_mul(12))
        .map(|bytes| bytes / 4)
        .ok_or_else(|| ImageError::Header {
            what: what.into(),
            field: "width",
            problem: format!("{width}x{height} is too large"),
        })
}

/// Either image a renderer hands the harness, by its magic number: rtl's `--linear` PFM
/// ([`parse_pfm`]) or the book's PPM ([`parse_ppm`]).
pub fn parse_image(bytes: &[u8], what: &str) -> Result<DisplayImage, ImageError> {
    match bytes.get(..2) {
        Some(b"PF") => parse_pfm(bytes, what),
        Some(b"P3" | b"P6") => parse_ppm(bytes, what),
        _ => Err(not_a(what, "PPM (P3 or P6) or colour PFM (PF)", bytes)),
    }
}

/// A PPM image (`P3`, plain text, as the book writes it, or `P6`, binary), as display values
/// `v / (maxval + 1)`: with the book's maxval of 255 that is `v / 256`. `what` names the file in errors.
pub fn parse_ppm(bytes: &[u8], what: &str) -> Result<DisplayImage, ImageError> {
    let magic = bytes.get(..2).unwrap_or(bytes);
    let binary = match magic {
        b"P3" => false,
        b"P6" => true,
        _ => return Err(not_a(what, "PPM (P3 or P6)", bytes)),
    };
    let (tokens, data) = header_tokens(bytes, 4);
    let width = header_number(what, "width", tokens.get(1))?;
    let height = header_number(what, "height", tokens.get(2))?;
    let max = header_number(what, "maxval", tokens.get(3))?;
    if max > 65535 || (binary && max > 255) {
        return Err(ImageError::Header {
            what: what.into(),
            field: "maxval",
            problem: format!("{max} is not supported (at most 255 for P6, 65535 for P3)"),
        });
    }
    let expected = value_count(what, width, height)?;
    let raw: Vec<u64> = if binary {
        bytes[data..]
            .iter()
            .take(expected)
            .map(|&b| b as u64)
            .collect()
    } else {
        // No more than the file can hold: a header may claim any size.
        let mut out = Vec::with_capacity(expected.min(bytes.len() / 2));
        for (k, token) in bytes[data..]
            .split(|b| b.is_ascii_whitespace())
            .filter(|t| !t.is_empty())
            .take(expected)
            .enumerate()
        {
            let s = String::from_utf8_lossy(token);
            let v = s.parse::<u64>().map_err(|_| ImageError::Header {
                what: what.into(),
                field: "pixel data",
                problem: format!("value {k} is {s:?}, not an integer"),
            })?;
            out.push(v);
        }
        out
    };
    if raw.len() < expected {
        return Err(ImageError::Truncated {
            what: what.into(),
            expected,
            found: raw.len(),
        });
    }
    if let Some((index, &value)) = raw.iter().enumerate().find(|(_, v)| **v > max as u64) {
        return Err(ImageError::Range {
            what: what.into(),
            index,
            value,
            max: max as u64,
        });
    }
    let scale = 1.0 / (max as f64 + 1.0);
    Ok(DisplayImage {
        width,
        height,
        values: raw.into_iter().map(|v| v as f64 * scale).collect(),
    })
}

/// A colour PFM (`PF`; negative scale: little-endian; rows bottom to top) of linear radiance, brought
/// to display values by the book's encoding ([`book_byte`]).
pub fn parse_pfm(bytes: &[u8], what: &str) -> Result<DisplayImage, ImageError> {
    if bytes.get(..2) != Some(b"PF") {
        return Err(not_a(what, "colour PFM (PF)", bytes));
    }
    let (tokens, data) = header_tokens(bytes, 4);
    let width = header_number(what, "width", tokens.get(1))?;
    let height = header_number(what, "height", tokens.get(2))?;
    let scale = tokens
        .get(3)
        .and_then(|t| t.parse::<f64>().ok())
        .filter(|s| *s != 0.0 && s.is_finite())
        .ok_or_else(|| ImageError::Header {
            what: what.into(),
            field: "scale",
            problem: match tokens.get(3) {
                Some(t) => format!("expected a finite, non-zero number, got `{t}`"),
                None => "missing (the file ends in its header)".into(),
            },
        })?;
    let little = scale < 0.0;
    let expected = value_count(what, width, height)?;
    let body = &bytes[data..];
    if body.len() < expected * 4 {
        return Err(ImageError::Truncated {
            what: what.into(),
            expected,
            found: body.len() / 4,
        });
    }
    if body.len() > expected * 4 {
        return Err(ImageError::Trailing {
            what: what.into(),
            expected,
            extra: body.len() - expected * 4,
        });
    }
    let mut values = vec![0.0; expected];
    for (k, chunk) in body.chunks_exact(4).take(expected).enumerate() {
        let b = [chunk[0], chunk[1], chunk[2], chunk[3]];
        let x = if little {
            f32::from_le_bytes(b)
        } else {
            f32::from_be_bytes(b)
        };
        let (row_from_bottom, rest) = (k / (width * 3), k % (width * 3));
        let row = height - 1 - row_from_bottom;
        if !(x.is_finite() && x >= 0.0) {
            return Err(ImageError::Value {
                what: what.into(),
                x: rest / 3,
                y: row,
                channel: rest % 3,
                value: x,
            });
        }
        values[row * width * 3 + rest] = book_byte(x) as f64 / 256.0;
    }
    Ok(DisplayImage {
        width,
        height,
        values,
    })
}

/// The noise constant `c = RMS(a - b) / sqrt(2) * sqrt(spp)` of two renders with independent seeds
/// (see the module's text).
pub fn noise_constant(a: &DisplayImage, b: &DisplayImage, spp: u64) -> Result<f64, ImageError> {
    if (a.width, a.height) != (b.width, b.height) || a.values.len() != b.values.len() {
        return Err(ImageError::Size(a.width, a.height, b.width, b.height));
    }
    let sum: f64 = a
        .values
        .iter()
        .zip(&b.values)
        .map(|(x, y)| (x - y) * (x - y))
        .sum();
    let rms = (sum / a.values.len() as f64).sqrt();
    Ok(rms / std::f64::consts::SQRT_2 * (spp as f64).sqrt())
}

/// The samples per pixel an unbiased renderer of noise constant `c` needs for per-pixel RMSE
/// `target`: `(c / target)^2`.
pub fn spp_to(c: f64, target: f64) -> f64 {
    (c / target).powi(2)
}

/// Seconds to per-pixel RMSE `target` on `cores` cores for an image of `pixels` pixels, at
/// `per_core` samples per second on each core: `(c / target)^2 pixels / (per_core cores)`.
pub fn seconds_to(c: f64, target: f64, pixels: usize, per_core: f64, cores: usize) -> f64 {
    spp_to(c, target) * pixels as f64 / (per_core * cores as f64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_xoshiro::Xoshiro256PlusPlus;
    use rtl_render::Color;

    fn image(values: Vec<f64>, width: usize) -> DisplayImage {
        let height = values.len() / 3 / width;
        DisplayImage {
            width,
            height,
            values,
        }
    }

    #[test]
    fn the_book_encoding_is_write_color() {
        assert_eq!(book_byte(f32::NAN), 0);
        assert_eq!(book_byte(-1.0), 0);
        assert_eq!(book_byte(0.25), 128); // sqrt = 0.5
        assert_eq!(book_byte(1.0), 255); // clamped to 0.999
        assert_eq!(book_byte(100.0), 255);
        assert_eq!(book_byte(f32::INFINITY), 255);
    }

    #[test]
    fn plain_ppm_as_the_book_writes_it() {
        let text = b"P3\n# a comment\n2 1\n255\n0 128 255\n 64 32 16\n";
        let img = parse_ppm(text, "t.ppm").unwrap();
        assert_eq!((img.width, img.height), (2, 1));
        assert_eq!(
            img.values,
            vec![0.0, 0.5, 255.0 / 256.0, 0.25, 0.125, 0.0625]
        );
    }

    #[test]
    fn binary_ppm() {
        let mut bytes = b"P6 1 2 255\n".to_vec();
        bytes.extend([0u8, 128, 255, 64, 32, 16]);
        let img = parse_ppm(&bytes, "t.ppm").unwrap();
        assert_eq!((img.width, img.height), (1, 2));
        assert_eq!(img.values[1], 0.5);
        assert_eq!(img.values[5], 0.0625);
    }

    #[test]
    fn bad_ppm_is_named() {
        let e = parse_ppm(b"P5\n1 1\n255\n0", "x.ppm").unwrap_err();
        assert!(matches!(e, ImageError::Magic { .. }), "{e}");
        let e = parse_ppm(b"P3\n2 2\n255\n1 2 3\n", "x.ppm").unwrap_err();
        assert_eq!(
            e,
            ImageError::Truncated {
                what: "x.ppm".into(),
                expected: 12,
                found: 3
            }
        );
        let e = parse_ppm(b"P3\n1 1\n255\n1 2 300\n", "x.ppm").unwrap_err();
        assert!(
            matches!(
                e,
                ImageError::Range {
                    index: 2,
                    value: 300,
                    ..
                }
            ),
            "{e}"
        );
        let e = parse_ppm(b"P3\n1 x\n255\n1 2 3\n", "x.ppm").unwrap_err();
        assert!(e.to_string().contains("`height`"), "{e}");
        let e = parse_ppm(b"P3\n1 1\n255\n1 two 3\n", "x.ppm").unwrap_err();
        assert!(e.to_string().contains("\"two\""), "{e}");
        // A header claiming more than can be counted or held is an error, not an abort.
        let huge = format!("P3\n{} 4\n255\n1 2 3\n", usize::MAX / 4);
        let e = parse_ppm(huge.as_bytes(), "x.ppm").unwrap_err();
        assert!(e.to_string().contains("too large"), "{e}");
        let e = parse_ppm(b"P3\n100000 100000\n255\n1 2 3\n", "x.ppm").unwrap_err();
        assert!(matches!(e, ImageError::Truncated { found: 3, .. }), "{e}");
        let e = parse_pfm(huge.replacen("P3", "PF", 1).as_bytes(), "x.pfm").unwrap_err();
        assert!(e.to_string().contains("too large"), "{e}");
        let e = parse_ppm(b"P3\n1 1", "x.ppm").unwrap_err();
        assert!(e.to_string().contains("maxval"), "{e}");
    }

    #[test]
    fn a_pfm_of_impossible_radiance_or_with_bytes_after_it_is_refused() {
        let good = [Color::splat(0.5), Color::splat(0.25)];
        assert!(parse_pfm(&rtl_render::output::pfm_bytes(2, 1, &good), "t.pfm").is_ok());
        for (bad, channel) in [(f64::NAN, 0), (f64::INFINITY, 1), (-1.0, 2)] {
            let mut c = [0.25; 3];
            c[channel] = bad;
            let pixels = [Color::splat(0.5), Color::from_array(c)];
            let e = parse_pfm(&rtl_render::output::pfm_bytes(2, 1, &pixels), "t.pfm").unwrap_err();
            assert!(
                matches!(e, ImageError::Value { x: 1, y: 0, channel: ch, .. } if ch == channel),
                "{e}"
            );
        }
        let mut bytes = rtl_render::output::pfm_bytes(2, 1, &good);
        bytes.extend_from_slice(b"junk");
        let e = parse_pfm(&bytes, "t.pfm").unwrap_err();
        assert!(matches!(e, ImageError::Trailing { extra: 4, .. }), "{e}");
        let e = parse_pfm(b"PF\n1 1\n0.0\n\0\0\0\0\0\0\0\0\0\0\0\0", "t.pfm").unwrap_err();
        assert!(e.to_string().ends_with("got `0.0`"), "{e}");
    }

    #[test]
    fn pfm_rows_are_flipped_and_encoded() {
        // rtl's own writer: pixel (0, 0) top-left is 0.25, the bottom row is 1.0.
        let pixels = vec![
            Color::splat(0.25),
            Color::splat(0.0),
            Color::splat(1.0),
            Color::new(0.0, 0.0, 0.25),
        ];
        let img = parse_pfm(&rtl_render::output::pfm_bytes(2, 2, &pixels), "t.pfm").unwrap();
        assert_eq!((img.width, img.height), (2, 2));
        let expected: Vec<f64> = [128, 128, 128, 0, 0, 0, 255, 255, 255, 0, 0, 128]
            .iter()
            .map(|&v| v as f64 / 256.0)
            .collect();
        assert_eq!(img.values, expected);
        let e = parse_pfm(b"PF\n2 2\n-1.0\n\0\0\0\0", "t.pfm").unwrap_err();
        assert!(
            matches!(
                e,
                ImageError::Truncated {
                    expected: 12,
                    found: 1,
                    ..
                }
            ),
            "{e}"
        );
        let e = parse_pfm(b"Pf\n2 2\n-1.0\n", "t.pfm").unwrap_err();
        assert!(matches!(e, ImageError::Magic { .. }), "{e}");
    }

    #[test]
    fn the_noise_constant_of_known_differences() {
        // a - b = +-0.02 everywhere: RMS 0.02, c = 0.02 / sqrt 2 * sqrt 16 = 0.0565...
        let a = image(vec![0.51, 0.49, 0.51, 0.49, 0.51, 0.49], 2);
        let b = image(vec![0.49, 0.51, 0.49, 0.51, 0.49, 0.51], 2);
        let c = noise_constant(&a, &b, 16).unwrap();
        assert!((c - 0.02 / 2f64.sqrt() * 4.0).abs() < 1e-12, "{c}");
        assert_eq!(noise_constant(&a, &a, 16).unwrap(), 0.0);
        let small = image(vec![0.0; 3], 1);
        assert_eq!(
            noise_constant(&a, &small, 1).unwrap_err(),
            ImageError::Size(2, 1, 1, 1)
        );
    }

    /// Two "renders" of a known per-sample standard deviation sigma: pixel values are the mean of
    /// `spp` samples of N(m, sigma^2) each, so c must come out as sigma. With n = 3 * 40,000 values
    /// the estimate's relative standard error is about 1 / sqrt(2 n) = 0.2%; the tolerance of 1.2%
    /// is 5.9 standard errors (false-failure rate below 1e-8; fixed seed).
    #[test]
    fn the_noise_constant_recovers_a_known_sigma() {
        let (sigma, spp, n) = (0.3, 16u64, 3 * 40_000);
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(7);
        let render = |rng: &mut Xoshiro256PlusPlus| {
            let values = (0..n)
                .map(|k| {
                    let mean = (k % 7) as f64 / 7.0;
                    let s: f64 = (0..spp).map(|_| gaussian(rng)).sum::<f64>() / spp as f64;
                    mean + sigma * s
                })
                .collect();
            image(values, 200)
        };
        let (a, b) = (render(&mut rng), render(&mut rng));
        let c = noise_constant(&a, &b, spp).unwrap();
        assert!((c / sigma - 1.0).abs() < 0.012, "c = {c}, sigma = {sigma}");
        // Forgetting the sqrt(2) of the difference is caught: it reads 41% high.
        let wrong = c * 2f64.sqrt();
        assert!((wrong / sigma - 1.0).abs() > 0.3);
    }

    fn gaussian(rng: &mut Xoshiro256PlusPlus) -> f64 {
        // Box-Muller.
        let u1: f64 = 1.0 - rng.random::<f64>();
        let u2: f64 = rng.random::<f64>();
        (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
    }

    #[test]
    fn projected_time() {
        // c = 1 to RMSE 0.01 is 10,000 spp; 100 pixels at 1e6 samples/s on one core: 1 s, on two 0.5 s.
        assert!((spp_to(1.0, 0.01) - 1e4).abs() < 1e-6);
        assert!((seconds_to(1.0, 0.01, 100, 1e6, 1) - 1.0).abs() < 1e-12);
        assert!((seconds_to(1.0, 0.01, 100, 1e6, 2) - 0.5).abs() < 1e-12);
        // The figure: the book's 1000 spp of c = 0.326 is RMSE 0.0103.
        assert!((0.326 / 1000f64.sqrt() - 0.0103).abs() < 1e-4);
    }
}
