//! Textures: colour as a function of surface coordinates `(u, v)` and position `p`. Solid colours do
//! not go through here at all (see [`crate::material::Albedo`]), so a scene of plain colours pays
//! nothing for textures.

use crate::perlin::Perlin;
use crate::vec::{Color, Point3, floor_i64};
use std::path::Path;

/// An image in linear RGB, row 0 at the top.
#[derive(Clone, Debug, serde::Serialize)]
pub struct ImageData {
    pub width: usize,
    pub height: usize,
    pub pixels: Vec<[f32; 3]>,
}

impl ImageData {
    /// Load a PNG or JPEG and decode its 8-bit values to linear with gamma 2.2, as the book's
    /// `rtw_image` does (through stb_image's `stbi_loadf`).
    pub fn load(path: &Path) -> Result<Self, String> {
        let img =
            image::open(path).map_err(|e| format!("{}: cannot read image: {e}", path.display()))?;
        let rgb = img.to_rgb8();
        let (w, h) = rgb.dimensions();
        if w == 0 || h == 0 {
            return Err(format!("{}: image is empty", path.display()));
        }
        let lut: Vec<f32> = (0..256).map(|i| (i as f32 / 255.0).powf(2.2)).collect();
        let pixels = rgb
            .pixels()
            .map(|p| [lut[p[0] as usize], lut[p[1] as usize], lut[p[2] as usize]])
            .collect();
        Ok(ImageData {
            width: w as usize,
            height: h as usize,
            pixels,
        })
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
        ImageData {
            width: w,
            height: h,
            pixels,
        }
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
