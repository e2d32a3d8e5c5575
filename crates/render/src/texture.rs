//! Textures: colour as a function of surface coordinates `(u, v)` and position `p`. Solid colours do
//! not go through here at all (see [`crate::material::Albedo`]), so a scene of plain colours pays
//! nothing for textures.

use crate::limits::{self, Bytes, MAX_TEXTURE_FILE_BYTES, MAX_TEXTURE_PIXELS};
use crate::perlin::Perlin;
use crate::scene::Scene;
use crate::vec::{Color, Point3, floor_i64};
use image::{ColorType, DynamicImage, ImageDecoder, ImageFormat, ImageReader};
use std::io::Cursor;
use std::path::Path;

/// An image in linear RGB, row 0 at the top.
///
/// It serialises (for the scene's identity, [`crate::checkpoint::scene_hash`]) as its size and a
/// 64-bit digest of its pixels taken once when it is made, not as its pixels: hashing 100 million
/// numbers a byte at a time cost every render of an 8192 x 4096 texture 3.6 s.
#[derive(Clone, Debug)]
pub struct ImageData {
    pub width: usize,
    pub height: usize,
    pixels: Vec<[f32; 3]>,
    digest: u64,
}

impl serde::Serialize for ImageData {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let mut st = s.serialize_struct("ImageData", 3)?;
        st.serialize_field("width", &self.width)?;
        st.serialize_field("height", &self.height)?;
        st.serialize_field("digest", &self.digest)?;
        st.end()
    }
}

/// 64-bit digest of an image's pixels: four streams over pairs of `f32` bit patterns (so that
/// consecutive steps do not wait on each other), each step `h -> rotl((h xor w) k, 29)`, a bijection
/// of the state for each word and of the word for each state, so a change of any one component
/// changes the digest; then the size and the four streams in one. About 20 ms for 8192 x 4096.
fn digest(width: usize, height: usize, pixels: &[[f32; 3]]) -> u64 {
    const K: u64 = 0x9e37_79b9_7f4a_7c15;
    #[inline(always)]
    fn step(h: u64, w: u64) -> u64 {
        (h ^ w).wrapping_mul(K).rotate_left(29)
    }
    let pair = |a: f32, b: f32| a.to_bits() as u64 | (b.to_bits() as u64) << 32;
    let flat = pixels.as_flattened();
    let mut lanes = [1u64, 2, 3, 4];
    let mut chunks = flat.chunks_exact(8);
    for c in &mut chunks {
        lanes[0] = step(lanes[0], pair(c[0], c[1]));
        lanes[1] = step(lanes[1], pair(c[2], c[3]));
        lanes[2] = step(lanes[2], pair(c[4], c[5]));
        lanes[3] = step(lanes[3], pair(c[6], c[7]));
    }
    let mut h = step(step(0x6a09_e667_f3bc_c908, width as u64), height as u64);
    for x in chunks.remainder() {
        h = step(h, x.to_bits() as u64);
    }
    for l in lanes {
        h = step(h, l);
    }
    h
}

impl ImageData {
    /// An image of `width x height` pixels (`pixels` row by row from the top; there must be
    /// `width * height` of them).
    pub fn new(width: usize, height: usize, pixels: Vec<[f32; 3]>) -> Self {
        assert_eq!(
            pixels.len(),
            width * height,
            "an image of {width} x {height} pixels"
        );
        let digest = digest(width, height, &pixels);
        ImageData {
            width,
            height,
            pixels,
            digest,
        }
    }

    /// The pixels, row by row from the top.
    pub fn pixels(&self) -> &[[f32; 3]] {
        &self.pixels
    }

    /// The digest of the pixels and the size that the image serialises as.
    pub fn digest(&self) -> u64 {
        self.digest
    }

    /// The memory the pixels take, in bytes.
    pub fn bytes(&self) -> u64 {
        (self.pixels.len() * std::mem::size_of::<[f32; 3]>()) as u64
    }

    /// Load a PNG or JPEG and decode its 8-bit values to linear with gamma 2.2, as the book's
    /// `rtw_image` does (through stb_image's `stbi_loadf`).
    ///
    /// Refused (the message names the file and the limit) before anything is decoded: a file that is
    /// not a regular file or is larger than [`MAX_TEXTURE_FILE_BYTES`], an image whose header gives
    /// more than [`MAX_TEXTURE_PIXELS`] pixels (a 445 kB PNG can decode to 12000 x 12000, 2.5 GB),
    /// or one whose decoding would take more memory than the machine has available.
    pub fn load(path: &Path) -> Result<Self, String> {
        let name = path.display();
        let bytes = limits::read_regular_file(path, "texture file", MAX_TEXTURE_FILE_BYTES)?;
        let cannot = |e: &dyn std::fmt::Display| format!("{name}: cannot read image: {e}");
        let mut reader = ImageReader::new(Cursor::new(&bytes[..]));
        if let Ok(format) = ImageFormat::from_path(path) {
            reader.set_format(format);
        }
        // The format the content shows, if any (else the extension's), then the header alone.
        let mut reader = reader.with_guessed_format().map_err(|e| cannot(&e))?;
        // The header is read without the decoder's own limits, which refuse a huge image (a PNG of
        // 2^31 - 1 x 1) as "Memory limit exceeded" before its size can be told; the size and the
        // memory are checked below, before anything is decoded.
        reader.no_limits();
        let decoder = reader.into_decoder().map_err(|e| cannot(&e))?;
        let (w, h) = decoder.dimensions();
        if w == 0 || h == 0 {
            return Err(format!("{name}: image is empty"));
        }
        let n = w as u64 * h as u64;
        if n > MAX_TEXTURE_PIXELS {
            return Err(format!(
                "{name}: the image is {w} x {h} = {n} pixels, more than the {MAX_TEXTURE_PIXELS} \
                 (8192 x 4096) a texture may have"
            ));
        }
        // Its decoding, its 8-bit RGB copy (unless it is 8-bit RGB already) and the linear pixels.
        let rgb8 = if decoder.color_type() == ColorType::Rgb8 {
            0
        } else {
            3 * n
        };
        let needed = decoder.total_bytes() + rgb8 + 12 * n;
        if let Some(available) = limits::available_memory()
            && needed > available.bytes
        {
            return Err(format!(
                "{name}: the image is {w} x {h} pixels, which needs {} of memory to decode, but \
                 {available}",
                Bytes(needed)
            ));
        }
        // (and the decoder's limits again for the decoding itself)
        let mut decoder = decoder;
        decoder
            .set_limits(image::Limits::default())
            .map_err(|e| cannot(&e))?;
        let rgb = DynamicImage::from_decoder(decoder)
            .map_err(|e| cannot(&e))?
            .into_rgb8();
        let lut: Vec<f32> = (0..256).map(|i| (i as f32 / 255.0).powf(2.2)).collect();
        let mut pixels = Vec::new();
        pixels
            .try_reserve_exact(n as usize)
            .map_err(|_| format!("{name}: no memory for its {w} x {h} pixels"))?;
        pixels.extend(
            rgb.pixels()
                .map(|p| [lut[p[0] as usize], lut[p[1] as usize], lut[p[2] as usize]]),
        );
        Ok(ImageData::new(w as usize, h as usize, pixels))
    }

    /// A stand-in for the book's `earthmap.jpg` (which is not shipped): blue oceans, green and brown
    /// continents from Perlin noise, white polar caps, on a 512 x 256 longitude-latitude grid.
    pub fn stand_in_earth() -> Self {
        let (w, h) = (512usize, 256usize);
        let noise = Perlin::new(0x5eed_ea27);
        let mut pixels = Vec::with_capacity(w * h);
        for j in 0..h {
            let lat = (0.5 - (j as f64 + 0.5) / h as f64) * std::f64::consts::PI;
            for i in 0..w {
                let lon = (i as f64 + 0.5) / w as f64 * 2.0 * std::f64::consts::PI;
                let p = Point3::new(lat.cos() * lon.cos(), lat.sin(), lat.cos() * lon.sin()) * 2.5;
                let land = noise.turbulence(p, 5) + 0.35 * noise.noise(p * 0.7);
                let c = if lat.abs() > 1.25 {
                    [0.85, 0.87, 0.9]
                } else if land > 0.45 {
                    if land > 0.62 {
                        [0.35, 0.27, 0.15]
                    } else {
                        [0.12, 0.32, 0.08]
                    }
                } else {
                    [0.02, 0.06, 0.25]
                };
                pixels.push(c);
            }
        }
        ImageData::new(w, h, pixels)
    }

    /// The book's nearest-pixel lookup: `u` across, `v` up (flipped to image rows), clamped to [0, 1].
    #[inline]
    pub fn lookup(&self, u: f64, v: f64) -> Color {
        let u = u.clamp(0.0, 1.0);
        let v = 1.0 - v.clamp(0.0, 1.0);
        let i = ((u * self.width as f64) as usize).min(self.width - 1);
        let j = ((v * self.height as f64) as usize).min(self.height - 1);
        let p = self.pixels[j * self.width + i];
        Color::new(p[0] as f64, p[1] as f64, p[2] as f64)
    }
}

/// The memory the image textures of `scene` take, in bytes (their linear pixels): what a render
/// holds beside its image buffers ([`limits::check_image`]).
pub fn texture_bytes(scene: &Scene) -> u64 {
    scene
        .textures
        .iter()
        .map(|t| match t {
            Texture::Image(img) => img.bytes(),
            _ => 0,
        })
        .sum()
}

/// A texture of books 1 and 2.
#[derive(Clone, Debug, serde::Serialize)]
pub enum Texture {
    /// One colour everywhere.
    Solid(Color),
    /// The 3D checker: cells of size `scale`, `even` where `floor(x/s) + floor(y/s) + floor(z/s)` is even.
    Checker {
        inv_scale: f64,
        even: Color,
        odd: Color,
    },
    /// An image mapped by `(u, v)`.
    Image(Box<ImageData>),
    /// Perlin marble: `0.5 (1 + sin(scale z + 10 turbulence(p)))` in grey, turbulence of the unscaled
    /// point with 7 octaves (book 2's current version).
    Marble {
        scale: f64,
        /// Drawn from a fixed seed: the same in every scene, so not part of a scene's content.
        #[serde(skip)]
        noise: Box<Perlin>,
    },
}

impl Texture {
    pub fn checker(scale: f64, even: Color, odd: Color) -> Self {
        Texture::Checker {
            inv_scale: 1.0 / scale,
            even,
            odd,
        }
    }

    /// Marble with the book's fixed noise table (the seed makes scenes repeatable).
    pub fn marble(scale: f64) -> Self {
        Texture::Marble {
            scale,
            noise: Box::new(Perlin::new(0x9e21_7a1e)),
        }
    }

    /// The colour at surface coordinates `(u, v)` (computed only if needed) and point `p`.
    #[inline]
    pub fn value(&self, uv: impl FnOnce() -> (f64, f64), p: Point3) -> Color {
        match self {
            Texture::Solid(c) => *c,
            Texture::Checker {
                inv_scale,
                even,
                odd,
            } => {
                let q = *inv_scale * p;
                let sum = floor_i64(q.x) + floor_i64(q.y) + floor_i64(q.z);
                if sum.rem_euclid(2) == 0 { *even } else { *odd }
            }
            Texture::Image(img) => {
                let (u, v) = uv();
                img.lookup(u, v)
            }
            Texture::Marble { scale, noise } => {
                Color::splat(0.5 * (1.0 + (scale * p.z + 10.0 * noise.turbulence(p, 7)).sin()))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checker_alternates_across_cells() {
        let t = Texture::checker(1.0, Color::ONE, Color::ZERO);
        assert_eq!(
            t.value(|| (0.0, 0.0), Point3::new(0.5, 0.5, 0.5)),
            Color::ONE
        );
        assert_eq!(
            t.value(|| (0.0, 0.0), Point3::new(1.5, 0.5, 0.5)),
            Color::ZERO
        );
        assert_eq!(
            t.value(|| (0.0, 0.0), Point3::new(-0.5, 0.5, 0.5)),
            Color::ZERO
        );
        assert_eq!(
            t.value(|| (0.0, 0.0), Point3::new(-0.5, -0.5, 0.5)),
            Color::ONE
        );
    }

    #[test]
    fn marble_stays_in_unit_range() {
        let t = Texture::marble(4.0);
        for i in 0..1000 {
            let p = Point3::new(
                i as f64 * 0.37,
                (i as f64 * 0.11).sin() * 5.0,
                i as f64 * -0.13,
            );
            let c = t.value(|| (0.0, 0.0), p);
            assert!(c.x >= 0.0 && c.x <= 1.0);
        }
    }
}
