//! The shapes of books 1 and 2: spheres (static or moving), quads (parallelograms), and boxes made of
//! six quads.

use crate::aabb::Aabb;
use crate::hit::{Hit, REL_ERROR, UvSource};
use crate::ray::{Interval, Ray};
use crate::vec::{Point3, Vec3};

/// A sphere of centre `center + time * motion` (a static sphere has `motion = 0`) and radius `radius`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    pub center: Point3,
    /// Displacement of the centre over the shutter interval [0, 1]; exactly zero for a static sphere.
    pub motion: Vec3,
    pub radius: f64,
    pub material: u32,
}

impl Sphere {
    pub fn new(center: Point3, radius: f64, material: u32) -> Self {
        Sphere {
            center,
            motion: Vec3::ZERO,
            radius,
            material,
        }
    }

    /// A sphere moving from `c0` at time 0 to `c1` at time 1. A sphere that moves by zero is static.
    pub fn moving(c0: Point3, c1: Point3, radius: f64, material: u32) -> Self {
        Sphere {
            center: c0,
            motion: c1 - c0,
            radius,
            material,
        }
    }

    pub fn is_moving(&self) -> bool {
        self.motion != Vec3::ZERO
    }

    #[inline]
    pub fn center_at(&self, time: f64) -> Point3 {
        if self.is_moving() {
            self.center + time * self.motion
        } else {
            self.center
        }
    }

    pub fn bounds(&self) -> Aabb {
        let r = Vec3::splat(self.radius.abs());
        let a = Aabb::from_points(self.center - r, self.center + r);
        let c1 = self.center + self.motion;
        a.union(&Aabb::from_points(c1 - r, c1 + r))
    }

    /// Ray-sphere intersection: the roots of `|o + t d - c|^2 = r^2`, computed as in pbrt-v4 and
    /// Ray Tracing Gems ch. 7 (discriminant from the ray's closest approach, the smaller root through
    /// Vieta's formula) so that neither root loses precision to cancellation. The hit point is then
    /// projected back onto the sphere, which bounds its error by the sphere's own magnitude.
    #[inline]
    pub fn hit(&self, ray: &Ray, range: Interval) -> Option<Hit> {
        let center = self.center_at(ray.time);
        let oc = center - ray.origin;
        let a = ray.direction.length_squared();
        let h = ray.direction.dot(oc);
        let r = self.radius;
        // Squared distance from the centre to the ray's line, without cancellation.
        let l = oc - (h / a) * ray.direction;
        let ll = l.length();
        let disc = a * (r - ll) * (r + ll);
        if disc < 0.0 {
            return None;
        }
        let oc_len = oc.length();
        let c = (oc_len - r) * (oc_len + r);
        let q = h + disc.sqrt().copysign(h);
        if q == 0.0 {
            return None;
        }
        let (mut t0, mut t1) = (c / q, q / a);
        if t0 > t1 {
            std::mem::swap(&mut t0, &mut t1);
        }
        let t = if range.surrounds(t0) {
            t0
        } else if range.surrounds(t1) {
            t1
        } else {
            return None;
        };
        let raw = ray.at(t);
        let outward = (raw - center) / r;
        let outward = outward.normalize();
        let p = center + r * outward;
        let (normal, front_face) = Hit::face(ray, outward);
        let err = REL_ERROR * (center.abs().max_element() + r.abs());
        Some(Hit {
            t,
            p,
            normal,
            front_face,
            err,
            material: self.material,
            uv_source: UvSource::Sphere(outward),
        })
    }
}

/// The parallelogram `{Q + a u + b v : a, b in [0, 1]}`, normal `normalize(u x v)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quad {
    pub q: Point3,
    pub u: Vec3,
    pub v: Vec3,
    /// `n / (n . n)` with `n = u x v`: turns a planar offset into coordinates `(alpha, beta)`.
    w: Vec3,
    /// Unit normal.
    pub normal: Vec3,
    /// Plane offset `normal . Q`.
    d: f64,
    /// Error bound of a hit point, from the quad's own magnitude.
    err: f64,
    pub material: u32,
}

impl Quad {
    /// The quad `(Q, u, v)`. `None` if `u` and `v` are parallel (zero area) or not finite.
    pub fn new(q: Point3, u: Vec3, v: Vec3, material: u32) -> Option<Self> {
        let n = u.cross(v);
        let nn = n.length_squared();
        if !(nn.is_finite() && nn > 0.0 && q.is_finite() && u.is_finite() && v.is_finite()) {
            return None;
        }
        let normal = n / nn.sqrt();
        let err =
            REL_ERROR * (q.abs().max_element() + u.abs().max_element() + v.abs().max_element());
        Some(Quad {
            q,
            u,
            v,
            w: n / nn,
            normal,
            d: normal.dot(q),
            err,
            material,
        })
    }

    pub fn area(&self) -> f64 {
        self.u.cross(self.v).length()
    }

    pub fn bounds(&self) -> Aabb {
        Aabb::from_points(self.q, self.q + self.u + self.v)
            .union(&Aabb::from_points(self.q + self.u, self.q + self.v))
    }

    /// Ray-plane intersection, then the point's coordinates `(alpha, beta)` in the frame `(u, v)`;
    /// inside when both lie in [0, 1]. The hit point is rebuilt as `Q + alpha u + beta v`, whose error
    /// is bounded by the quad's magnitude rather than by the ray's length.
    #[inline]
    pub fn hit(&self, ray: &Ray, range: Interval) -> Option<Hit> {
        let denom = self.normal.dot(ray.direction);
        let t = (self.d - self.normal.dot(ray.origin)) / denom;
        // A ray parallel to the plane gives t = inf or NaN; `surrounds` rejects both.
        if !range.surrounds(t) {
            return None;
        }
        let planar = ray.at(t) - self.q;
        let alpha = self.w.dot(planar.cross(self.v));
        let beta = self.w.dot(self.u.cross(planar));
        if !(0.0..=1.0).contains(&alpha) || !(0.0..=1.0).contains(&beta) {
            return None;
        }
        let p = self.q + alpha * self.u + beta * self.v;
        let (normal, front_face) = Hit::face(ray, self.normal);
        Some(Hit {
            t,
            p,
            normal,
            front_face,
            err: self.err,
            material: self.material,
            uv_source: UvSource::Uv(alpha, beta),
        })
    }
}

/// The six quads of the box with opposite corners `a` and `b`, faces pointing outwards (book 2's `box`).
/// `None` if the box is flat.
pub fn box_quads(a: Point3, b: Point3, material: u32) -> Option<[Quad; 6]> {
    let min = a.min(b);
    let max = a.max(b);
    let dx = Vec3::new(max.x - min.x, 0.0, 0.0);
    let dy = Vec3::new(0.0, max.y - min.y, 0.0);
    let dz = Vec3::new(0.0, 0.0, max.z - min.z);
    Some([
        Quad::new(Point3::new(min.x, min.y, max.z), dx, dy, material)?, // front
        Quad::new(Point3::new(max.x, min.y, max.z), -dz, dy, material)?, // right
        Quad::new(Point3::new(max.x, min.y, min.z), -dx, dy, material)?, // back
        Quad::new(Point3::new(min.x, min.y, min.z), dz, dy, material)?, // left
        Quad::new(Point3::new(min.x, max.y, max.z), dx, -dz, material)?, // top
        Quad::new(Point3::new(min.x, min.y, min.z), dx, dz, material)?, // bottom
    ])
}
