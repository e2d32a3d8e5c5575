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
    pixel00: Point3,
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
        let upper_left = s.lookfrom - s.focus_dist * w - viewport_u / 2.0 - viewport_v / 2.0;
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
        let target = self.pixel00 + (i as f64 + sx) * self.delta_u + (j as f64 + sy) * self.delta_v;
        let origin = if self.has_lens {
            ctx.stats.lens_samples += 1;
            // Uniform on the unit disk by rtl-pdf's concentric map (area-preserving, low distortion,
            // so a stratified pair stays stratified on the lens).
            let d = warp::sample_uniform_disk_concentric(ctx.sample_2d(Dimension::Lens));
            self.center + d.x * self.defocus_u + d.y * self.defocus_v
        } else {
            self.center
        };
        let time = if self.has_time {
            ctx.stats.time_samples += 1;
            ctx.sample_1d(Dimension::Time)
        } else {
            0.0
        };
        Ray::new(origin, target - origin, time)
    }
}
