//! Axis-aligned bounding boxes and the slab test.

use crate::vec::{Point3, Vec3};

/// The box `[min, max]` (empty when any `min > max`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    pub min: Point3,
    pub max: Point3,
}

impl Aabb {
    pub const EMPTY: Aabb = Aabb {
        min: Vec3::INFINITY,
        max: Vec3::NEG_INFINITY,
    };

    /// The box spanned by two corners in any order, padded so that it is never flat: a quad in an
    /// axis plane gets a thickness relative to its coordinates (scale-free, unlike the book's 0.0001).
    pub fn from_points(a: Point3, b: Point3) -> Self {
        Aabb {
            min: a.min(b),
            max: a.max(b),
        }
        .padded()
    }

    pub fn union(&self, o: &Aabb) -> Aabb {
        Aabb {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
        }
    }

    pub fn include(&self, p: Point3) -> Aabb {
        Aabb {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    /// Widen each side by a hair relative to the box's magnitude, so no side is degenerate.
    pub fn padded(&self) -> Aabb {
        let scale = self
            .min
            .abs()
            .max(self.max.abs())
            .max_element()
            .max(f64::MIN_POSITIVE);
        let pad = Vec3::splat(scale * 1e-9);
        Aabb {
            min: self.min - pad,
            max: self.max + pad,
        }
    }

    pub fn is_empty(&self) -> bool {
        self.min.cmpgt(self.max).any()
    }

    pub fn centroid(&self) -> Point3 {
        0.5 * (self.min + self.max)
    }

    pub fn extent(&self) -> Vec3 {
        (self.max - self.min).max(Vec3::ZERO)
    }

    /// Surface area (0 for an empty box): the cost weight of the surface-area heuristic.
    pub fn area(&self) -> f64 {
        if self.is_empty() {
            return 0.0;
        }
        let e = self.extent();
        2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
    }

    /// Slab test: does the ray `origin + t dir` (with `inv_dir = 1 / dir`) pass through the box for some
    /// `t` in `(t_min, t_max)`? Returns the entry parameter if so.
    #[inline(always)]
    pub fn hit(&self, origin: Point3, inv_dir: Vec3, t_min: f64, t_max: f64) -> Option<f64> {
        let t0 = (self.min - origin) * inv_dir;
        let t1 = (self.max - origin) * inv_dir;
        let near = t0.min(t1).max_element().max(t_min);
        // 1 + 2 gamma(3) makes the far side conservative against rounding (pbrt-v4, Bounds3::IntersectP).
        let far = t0.max(t1).min_element().min(t_max) * (1.0 + 6.0 * f64::EPSILON);
        (near <= far).then_some(near)
    }
}
