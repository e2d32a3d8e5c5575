//! The camera of books 1 and 2: vertical field of view, look-from/look-at/up, a thin lens for defocus
//! blur and a shutter open over the time interval [0, 1).

use crate::ray::Ray;
use crate::sampler::{Ctx, Dimension, pixel_position};
use crate::vec::{Point3, Vec3};
use rtl_pdf::warp;

/// How a scene places its camera (the book's public `camera` members).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct CameraSettings {
    /// Width over height.
    pub aspect_ratio: f64,
    /// Vertical field of view in degrees.
    pub vfov: f64,
    pub lookfrom: Point3,
    pub lookat: Point3,
    pub vup: Vec3,
    /// Angle of the cone from a pixel's point on the focus plane to the lens, in degrees; 0 = pinhole.
    pub defocus_angle: f64,
    /// Distance from the camera to the plane in perfect focus.
    pub focus_dist: f64,
}

impl Default for CameraSettings {
    fn default() -> Self {
        CameraSettings {
            aspect_ratio: 1.0,
            vfov: 90.0,
            lookfrom: Point3::ZERO,
            lookat: Point3::new(0.0, 0.0, -1.0),
            vup: Vec3::Y,
            defocus_angle: 0.0,
            focus_dist: 10.0,
        }
    }
}

/// A camera ready to generate rays for an image of `width x height` pixels.
#[derive(Clone, Copy, Debug)]
pub struct Camera {
    pub width: usize,
    pub height: usize,
    center: Point3,
    /// The upper-left corner of the viewport on the focus plane, as an offset from `center`: ray
    /// directions are formed from offsets, never as the difference of two world-space points, which
    /// would lose them where the focus distance is small beside the camera's distance from the origin.
    pixel00: Vec3,
    delta_u: Vec3,
    delta_v: Vec3,
    defocus_u: Vec3,
    defocus_v: Vec3,
    /// Whether rays start on a lens (defocus blur) or all at the centre (pinhole).
    pub has_lens: bool,
    /// Whether rays carry a random time in the shutter interval (only if something moves).
    pub has_time: bool,
}

impl Camera {
    /// The camera for an image `width` pixels wide; `has_time` says whether the scene has motion.
    pub fn new(s: &CameraSettings, width: usize, has_time: bool) -> Camera {
        let width = width.max(1);
        let height = ((width as f64 / s.aspect_ratio) as usize).max(1);
        let h = (s.vfov.to_radians() / 2.0).tan();
        let viewport_height = 2.0 * h * s.focus_dist;
        let viewport_width = viewport_height * (width as f64 / height as f64);
        let w = (s.lookfrom - s.lookat).normalize();
        let u = s.vup.cross(w).normalize();
        let v = w.cross(u);
        let viewport_u = viewport_width * u;
        let viewport_v = -viewport_height * v;
        let delta_u = viewport_u / width as f64;
        let delta_v = viewport_v / height as f64;
        let upper_left = -s.focus_dist * w - viewport_u / 2.0 - viewport_v / 2.0;
        let radius = s.focus_dist * (s.defocus_angle / 2.0).to_radians().tan();
        Camera {
            width,
            height,
            center: s.lookfrom,
            pixel00: upper_left,
            delta_u,
            delta_v,
            defocus_u: u * radius,
            defocus_v: v * radius,
            has_lens: s.defocus_angle > 0.0,
            has_time,
        }
    }

    /// The camera ray of sample `k` of pixel `(i, j)` (`j` counted from the top): through the point of the
    /// pixel square given by the pixel's scrambled Sobol sequence, from a uniform point on the lens disk
    /// ([`Dimension::Lens`]) if the camera has a lens, at a uniform time in [0, 1) ([`Dimension::Time`])
    /// if the scene moves. A pinhole camera in a
    /// static scene draws no random numbers here at all.
    #[inline]
    pub fn ray(&self, i: usize, j: usize, pixel_key: u64, k: u64, ctx: &mut Ctx) -> Ray {
        let (sx, sy) = pixel_position(pixel_key, k);
        // The point on the focus plane and the point on the lens, both as offsets from the centre:
        // their difference is the direction, without the rounding of world-space points far from the
        // origin (a lookfrom of 1e20 would swallow a focus distance of 10, and every ray be the same).
        let target = self.pixel00 + (i as f64 + sx) * self.delta_u + (j as f64 + sy) * self.delta_v;
        let lens = if self.has_lens {
            ctx.stats.lens_samples += 1;
            // Uniform on the unit disk by rtl-pdf's concentric map (area-preserving, low distortion,
            // so a stratified pair stays stratified on the lens).
            let d = warp::sample_uniform_disk_concentric(ctx.sample_2d(Dimension::Lens));
            d.x * self.defocus_u + d.y * self.defocus_v
        } else {
            Vec3::ZERO
        };
        let time = if self.has_time {
            ctx.stats.time_samples += 1;
            ctx.sample_1d(Dimension::Time)
        } else {
            0.0
        };
        Ray::new(self.center + lens, target - lens, time)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every ray of `s` (4 x 4 pixels, one sample each), from fresh random numbers.
    fn rays(s: &CameraSettings) -> Vec<Ray> {
        let camera = Camera::new(s, 4, false);
        let mut out = Vec::new();
        for j in 0..4 {
            for i in 0..4 {
                out.push(camera.ray(i, j, 7, 0, &mut Ctx::new()));
            }
        }
        out
    }

    #[test]
    fn ray_directions_do_not_depend_on_where_the_camera_stands() {
        // The same view from 5 and from 1e20 along z: the rays differ in their origins alone. (The
        // directions used to be differences of world-space points, so that at 1e20 the focus plane,
        // 10 away, rounded onto the camera: every direction was 0 along z and the image one colour.)
        for defocus_angle in [0.0, 10.0] {
            let near = CameraSettings {
                lookfrom: Point3::new(0.0, 0.0, 5.0),
                lookat: Point3::ZERO,
                defocus_angle,
                ..CameraSettings::default()
            };
            let far = CameraSettings {
                lookfrom: Point3::new(0.0, 0.0, 1e20),
                ..near
            };
            let (a, b) = (rays(&near), rays(&far));
            for (a, b) in a.iter().zip(&b) {
                assert_eq!(a.direction, b.direction, "defocus {defocus_angle}");
                assert!(a.direction.z < -9.0, "{:?}", a.direction);
                assert_eq!(b.origin.z, 1e20);
            }
            let distinct = |r: &[Ray]| {
                let mut d: Vec<_> = r.iter().map(|r| r.direction.to_array()).collect();
                d.dedup();
                d.len()
            };
            assert_eq!(distinct(&b), 16);
        }
    }

    #[test]
    fn a_pinhole_image_does_not_depend_on_the_focus_distance() {
        // A focus distance of 1e-30 (the least a scene file gives) in front of a camera 5 from the
        // origin: the focus plane used to round onto the camera, and the rays to lie in it.
        let s = CameraSettings {
            lookfrom: Point3::new(0.0, 0.0, 5.0),
            lookat: Point3::ZERO,
            ..CameraSettings::default()
        };
        let tiny = CameraSettings {
            focus_dist: 1e-30,
            ..s
        };
        for (a, b) in rays(&s).iter().zip(&rays(&tiny)) {
            let (a, b) = (a.direction.normalize(), b.direction.normalize());
            assert!((a - b).length() < 1e-12, "{a:?} {b:?}");
        }
    }
}
