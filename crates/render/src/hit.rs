//! The hit record, and spawning rays from a hit without hitting the same surface again.
//!
//! The book starts secondary rays at `t > 0.001`, which is far too much for a scene a millimetre wide
//! and far too little for one a thousand kilometres wide. Instead every shape reports a bound on the
//! rounding error of the hit point it computed (`err`, an absolute distance that scales with the
//! shape's coordinates), and a ray leaving the surface starts from the hit point pushed along the
//! geometric normal, to the side the ray leaves on, by a multiple of that bound. The surface then lies
//! strictly behind the new origin, so the ray can start at `t > 0`. This is the idea of pbrt-v4's
//! `OffsetRayOrigin` (error bounds from the computation) and of Waechter and Binder, "A Fast and Robust
//! Method for Avoiding Self-Intersection" (Ray Tracing Gems, ch. 6): offset along the normal, never
//! along the ray, by an amount relative to the magnitude of the numbers involved.

use crate::ids::MaterialId;
use crate::ray::Ray;
use crate::vec::{Point3, Vec3};

/// Relative rounding error we allow per unit of coordinate magnitude. A handful of f64 operations
/// commit a relative error of a few `f64::EPSILON` (1.1e-16); 2^-36 (1.5e-11) is five orders of
/// magnitude above that and still invisible (a micrometre in a scene a kilometre wide).
pub const REL_ERROR: f64 = 1.0 / 68_719_476_736.0;

/// How many error bounds (`err`, per axis) a ray leaving a surface starts off it: the surface's
/// rays start `SPAWN_ERRORS * REL_ERROR` times the magnitude of its coordinates away, so light
/// nearer to it than that is not seen from it (what a scene file's sizes are checked against).
pub const SPAWN_ERRORS: f64 = 4.0;

/// Where on a surface the texture coordinates come from, kept lazily: most materials never ask.
#[derive(Clone, Copy, Debug)]
pub enum UvSource {
    /// Coordinates already known (quads: the parallelogram's own `(alpha, beta)`).
    Uv(f64, f64),
    /// A sphere's outward unit normal in object space; `(u, v)` is its longitude and latitude.
    Sphere(Vec3),
}

/// Where a ray met a surface or a medium.
#[derive(Clone, Copy, Debug)]
pub struct Hit {
    /// The ray parameter of the hit.
    pub t: f64,
    /// The hit point.
    pub p: Point3,
    /// Unit normal, turned to face the incoming ray (against its direction).
    pub normal: Vec3,
    /// Whether the ray met the surface on its front, the side the geometric (outward) normal points to.
    pub front_face: bool,
    /// Bound on the absolute error of `p` (0 for a point inside a medium, which lies on no surface).
    pub err: f64,
    /// Material index in the scene.
    pub material: MaterialId,
    pub uv_source: UvSource,
}

impl Hit {
    /// Orient the outward normal against the ray: the book's `set_face_normal`.
    #[inline]
    pub fn face(ray: &Ray, outward: Vec3) -> (Vec3, bool) {
        let front = ray.direction.dot(outward) < 0.0;
        (if front { outward } else { -outward }, front)
    }

    /// Texture coordinates `(u, v)` in [0, 1]^2. For a sphere: `u = phi / 2 pi` with
    /// `phi = atan2(-z, x) + pi`, and `v = theta / pi` with `theta = acos(-y)` (the book's mapping).
    #[inline]
    pub fn uv(&self) -> (f64, f64) {
        match self.uv_source {
            UvSource::Uv(u, v) => (u, v),
            UvSource::Sphere(n) => {
                let theta = (-n.y).clamp(-1.0, 1.0).acos();
                let phi = (-n.z).atan2(n.x) + std::f64::consts::PI;
                (
                    phi / (2.0 * std::f64::consts::PI),
                    theta / std::f64::consts::PI,
                )
            }
        }
    }

    /// The origin for a ray leaving this hit in `direction`: the hit point pushed off the surface along
    /// the normal, to the side `direction` points to, by [`SPAWN_ERRORS`] times the error bound per
    /// axis.
    #[inline]
    pub fn spawn_origin(&self, direction: Vec3) -> Point3 {
        let d = SPAWN_ERRORS * self.err;
        let offset = self.normal * d;
        if direction.dot(self.normal) >= 0.0 {
            self.p + offset
        } else {
            self.p - offset
        }
    }

    /// A ray leaving this hit in `direction` at `time`; it may hit anything at `t > 0`.
    #[inline]
    pub fn spawn(&self, direction: Vec3, time: f64) -> Ray {
        Ray::new(self.spawn_origin(direction), direction, time)
    }
}
