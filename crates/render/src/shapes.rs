//! The shapes of books 1 and 2: spheres (static or moving), quads (parallelograms), and boxes made of
//! six quads.

use crate::aabb::Aabb;
use crate::hit::{Hit, REL_ERROR, UvSource};
use crate::ids::MaterialId;
use crate::lanes::F64x4;
#[cfg(target_arch = "x86_64")]
use crate::lanes::avx::RayLanes;
use crate::ray::{Interval, Ray};
use crate::vec::{Point3, Vec3};

/// A sphere of centre `center + time * motion` (a static sphere has `motion = 0`) and radius `radius`.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Sphere {
    pub center: Point3,
    /// Displacement of the centre over the shutter interval [0, 1]; exactly zero for a static sphere.
    pub motion: Vec3,
    pub radius: f64,
    pub material: MaterialId,
}

impl Sphere {
    pub fn new(center: Point3, radius: f64, material: MaterialId) -> Self {
        Sphere {
            center,
            motion: Vec3::ZERO,
            radius,
            material,
        }
    }

    /// A sphere moving from `c0` at time 0 to `c1` at time 1. A sphere that moves by zero is static.
    pub fn moving(c0: Point3, c1: Point3, radius: f64, material: MaterialId) -> Self {
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

    /// The two roots `t0 <= t1` of `|o + t d - c|^2 = r^2` along `ray` (`None` if the line misses),
    /// computed as in pbrt-v4 and Ray Tracing Gems ch. 7: the discriminant from the ray's closest
    /// approach, here `|(c - o) x d|^2`, and the smaller root through Vieta's formula, so that
    /// neither root loses precision to cancellation and a miss costs neither a division nor a square
    /// root.
    #[inline(always)]
    pub fn roots(&self, ray: &Ray) -> Option<(f64, f64)> {
        let center = self.center_at(ray.time);
        let oc = center - ray.origin;
        let a = ray.direction.length_squared();
        let h = ray.direction.dot(oc);
        let r = self.radius;
        // a |l|^2 = |oc x d|^2, with l the offset from the centre to the ray's closest approach: the
        // quarter discriminant a (r^2 - |l|^2) without a division, a square root or cancellation in l.
        let cross = oc.cross(ray.direction);
        let disc = a * (r * r) - cross.length_squared();
        if disc < 0.0 {
            return None;
        }
        let oc_len = oc.length();
        let c = (oc_len - r) * (oc_len + r);
        let q = h + disc.sqrt().copysign(h);
        if q == 0.0 {
            return None;
        }
        let (t0, t1) = (c / q, q / a);
        Some(if t0 > t1 { (t1, t0) } else { (t0, t1) })
    }

    /// The first of the roots `t0 <= t1` inside the open interval `range`.
    #[inline(always)]
    pub fn first_root_in((t0, t1): (f64, f64), range: Interval) -> Option<f64> {
        if range.surrounds(t0) {
            Some(t0)
        } else if range.surrounds(t1) {
            Some(t1)
        } else {
            None
        }
    }

    /// The bound on the error of a point projected onto the sphere (the sphere's own magnitude; see
    /// [`Sphere::hit_at_projected`]).
    #[inline]
    pub fn hit_error(&self, time: f64) -> f64 {
        REL_ERROR * (self.center_at(time).abs().max_element() + self.radius.abs())
    }

    /// Ray-sphere intersection: the first of [`Sphere::roots`] in `range`, its record built by
    /// [`Sphere::hit_at`].
    #[inline]
    pub fn hit(&self, ray: &Ray, range: Interval) -> Option<Hit> {
        let t = self.hit_t(ray, range)?;
        Some(self.hit_at(ray, t))
    }

    /// The parameter of [`Sphere::hit`]'s hit, without its record: the traversal builds the record
    /// ([`Sphere::hit_at`]) only for the closest hit.
    #[inline(always)]
    pub fn hit_t(&self, ray: &Ray, range: Interval) -> Option<f64> {
        Self::first_root_in(self.roots(ray)?, range)
    }

    /// The record of [`Sphere::hit`]'s hit at parameter `t` (found by [`Sphere::hit_t`]): the point
    /// `p = o + t d` itself and the book's outward normal `(p - c) / r` (inward for a negative
    /// radius, book 1's hollow sphere), with no square root or division on the way from `t`.
    ///
    /// The point is not projected onto the sphere, so its error is that of `o + t d`: the sum rounds
    /// by an ulp of `|p| <= |c| + |r|` (up to the error itself), the product by an ulp of `|t d|`,
    /// and the root `t` errs by a few ulps of `t` where the ray crosses the surface steeply (where it
    /// grazes, `t` may err more, but along a direction in which the distance to the surface hardly
    /// changes). The bound ([`Sphere::point_error`]) is therefore [`REL_ERROR`] `(|c| + |r|)`, the
    /// projected point's, plus [`RAY_ERROR`] `t |d|`, 256 ulps of `t |d|` (each a largest
    /// coordinate), some 30 times what the product and the root commit
    /// (`crates/render/tests/sphere_record.rs` finds at most 1/70 of the bound). The normal's length
    /// is `|p - c| / |r|`, within `err / |r|` of 1. A sphere small beside the ray's terms
    /// (`err > 2^-20 |r|`, a normal that could be off unit length by more than 1e-6) takes the
    /// normalised normal and the projected point instead ([`Sphere::hit_at_projected`]).
    #[inline]
    pub fn hit_at(&self, ray: &Ray, t: f64) -> Hit {
        let center = self.center_at(ray.time);
        let r = self.radius;
        let err = self.point_error(ray, t);
        if err > UNIT_NORMAL * r.abs() {
            return self.hit_at_projected(ray, t);
        }
        let p = ray.at(t);
        let outward = (p - center) * (1.0 / r);
        let (normal, front_face) = Hit::face(ray, outward);
        Hit {
            t,
            p,
            normal,
            front_face,
            err,
            material: self.material,
            uv_source: UvSource::Sphere(outward),
        }
    }

    /// The bound on the error of [`Sphere::hit_at`]'s point `o + t d` (see there).
    #[inline(always)]
    pub fn point_error(&self, ray: &Ray, t: f64) -> f64 {
        let td = t.abs() * ray.direction.abs().max_element();
        REL_ERROR * (self.center_at(ray.time).abs().max_element() + self.radius.abs())
            + RAY_ERROR * td
    }

    /// The record of a hit at parameter `t` with the point projected back onto the sphere, `c + r
    /// (p - c) / |p - c|`, whose error is bounded by the sphere's own magnitude
    /// ([`Sphere::hit_error`]) and whose normal is of unit length: [`Sphere::hit_at`] for a sphere
    /// small beside the ray's terms.
    #[cold]
    pub fn hit_at_projected(&self, ray: &Ray, t: f64) -> Hit {
        let center = self.center_at(ray.time);
        let r = self.radius;
        let outward = (ray.at(t) - center).normalize() * r.signum();
        let p = center + r * outward;
        let (normal, front_face) = Hit::face(ray, outward);
        Hit {
            t,
            p,
            normal,
            front_face,
            err: self.hit_error(ray.time),
            material: self.material,
            uv_source: UvSource::Sphere(outward),
        }
    }
}

/// [`Sphere::hit_at`] takes the point `o + t d` unprojected while its error bound is at most this
/// fraction of the radius: the normal `(p - c) / r` is then of unit length within it.
pub const UNIT_NORMAL: f64 = 1.0 / 1_048_576.0;

/// The error allowed per unit of `t |d|` in a sphere's unprojected hit point `o + t d`
/// ([`Sphere::hit_at`]): 2^-44, 256 ulps.
pub const RAY_ERROR: f64 = 1.0 / 17_592_186_044_416.0;

/// The parallelogram `{Q + a u + b v : a, b in [0, 1]}`, normal `normalize(u x v)`.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Quad {
    pub q: Point3,
    pub u: Vec3,
    pub v: Vec3,
    /// The dual basis of `(u, v)` in the quad's plane: `v x w` and `w x u` with `w = n / (n . n)`,
    /// `n = u x v`. A planar offset `p` has coordinates `alpha = p . du`, `beta = p . dv` (book 2's
    /// `w . (p x v)` and `w . (u x p)`, with the triple products' fixed factors computed once).
    pub(crate) du: Vec3,
    pub(crate) dv: Vec3,
    /// Unit normal.
    pub normal: Vec3,
    /// Plane offset `normal . Q`.
    pub(crate) d: f64,
    /// Error bound of a hit point, from the quad's own magnitude.
    pub(crate) err: f64,
    pub material: MaterialId,
}

impl Quad {
    /// The quad `(Q, u, v)`. `None` if `u` and `v` are parallel (zero area) or not finite.
    pub fn new(q: Point3, u: Vec3, v: Vec3, material: MaterialId) -> Option<Self> {
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
            du: v.cross(n / nn),
            dv: (n / nn).cross(u),
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
    ///
    /// The parameter is `t = (d - n . o) * (1 / (n . dir))`, a product with the reciprocal rather
    /// than the quotient (two roundings, not one): for a quad in an axis plane (`n = ±e_k`) the
    /// reciprocal is `±1 / dir_k`, which the lanes compute once per ray and share among all such
    /// quads and the bounding boxes ([`crate::ray8::QuadForm`]), bit for bit this number.
    #[inline]
    pub fn hit(&self, ray: &Ray, range: Interval) -> Option<Hit> {
        let denom = self.normal.dot(ray.direction);
        let t = (self.d - self.normal.dot(ray.origin)) * denom.recip();
        // A ray parallel to the plane gives t = inf or NaN; `surrounds` rejects both.
        if !range.surrounds(t) {
            return None;
        }
        let (alpha, beta) = self.coordinates(ray, t);
        if !(0.0..=1.0).contains(&alpha) || !(0.0..=1.0).contains(&beta) {
            return None;
        }
        Some(self.hit_at(ray, t, alpha, beta))
    }

    /// The coordinates `(alpha, beta)` of the ray's point at `t` in the frame `(u, v)`, as
    /// [`Quad::hit`] computes them: `planar = o + t dir - Q`, then its dot products with the dual
    /// basis `du`, `dv`. The lanes find only each ray's closest quad and `t`; its coordinates are
    /// these, computed afterwards (here, or in [`crate::vertex8`] eight at a time).
    #[inline(always)]
    pub fn coordinates(&self, ray: &Ray, t: f64) -> (f64, f64) {
        let planar = ray.at(t) - self.q;
        (planar.dot(self.du), planar.dot(self.dv))
    }

    /// The hit record of a hit at parameter `t` and coordinates `(alpha, beta)` found by [`Quad::hit`]
    /// or [`Quad4::hit`]: built once, for the closest hit only.
    #[inline]
    pub fn hit_at(&self, ray: &Ray, t: f64, alpha: f64, beta: f64) -> Hit {
        let p = self.q + alpha * self.u + beta * self.v;
        let (normal, front_face) = Hit::face(ray, self.normal);
        Hit {
            t,
            p,
            normal,
            front_face,
            err: self.err,
            material: self.material,
            uv_source: UvSource::Uv(alpha, beta),
        }
    }
}

/// Up to four quads stored coordinate by coordinate (structure of arrays), so that one ray is
/// intersected with all four in the same vector instructions. The arithmetic is exactly that of
/// [`Quad::hit`], lane by lane, so a packet finds bit-identical hits. Unused lanes have a zero normal:
/// their `t` is NaN and never counts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quad4 {
    pub(crate) q: [F64x4; 3],
    pub(crate) du: [F64x4; 3],
    pub(crate) dv: [F64x4; 3],
    pub(crate) normal: [F64x4; 3],
    pub(crate) d: F64x4,
    /// The index of each lane's quad in the group's objects (`u32::MAX` for an unused lane).
    pub index: [u32; 4],
}

/// The closest hit in a [`Quad4`]: the lane, its parameter and its coordinates in the quad.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quad4Hit {
    pub lane: usize,
    pub t: f64,
    pub alpha: f64,
    pub beta: f64,
}

impl Quad4 {
    /// A packet of up to four quads, `index[i]` naming quad `i`.
    pub fn new(quads: &[(Quad, u32)]) -> Self {
        assert!(quads.len() <= 4);
        let zero = [F64x4::ZERO; 3];
        let mut p = Quad4 {
            q: zero,
            du: zero,
            dv: zero,
            normal: zero,
            d: F64x4::ZERO,
            index: [u32::MAX; 4],
        };
        for (i, (quad, index)) in quads.iter().enumerate() {
            for a in 0..3 {
                p.q[a].0[i] = quad.q[a];
                p.du[a].0[i] = quad.du[a];
                p.dv[a].0[i] = quad.dv[a];
                p.normal[a].0[i] = quad.normal[a];
            }
            p.d.0[i] = quad.d;
            p.index[i] = *index;
        }
        p
    }

    /// The closest hit among the four quads with `t` in the open interval `range` (on equal `t`, the
    /// lowest lane, as testing the quads one after the other would find).
    #[inline(always)]
    pub fn hit(&self, ray: &Ray, range: Interval) -> Option<Quad4Hit> {
        let o = ray.origin;
        let dir = ray.direction;
        let mut t = [0.0; 4];
        let mut alpha = [0.0; 4];
        let mut beta = [0.0; 4];
        let mut inside = 0;
        let [nx, ny, nz] = &self.normal;
        let [qx, qy, qz] = &self.q;
        let [ax, ay, az] = &self.du;
        let [bx, by, bz] = &self.dv;
        for i in 0..4 {
            // As `Quad::hit`, lane by lane.
            let denom = (nx.0[i] * dir.x) + (ny.0[i] * dir.y) + (nz.0[i] * dir.z);
            let no = (nx.0[i] * o.x) + (ny.0[i] * o.y) + (nz.0[i] * o.z);
            let ti = (self.d.0[i] - no) * denom.recip();
            let px = (o.x + ti * dir.x) - qx.0[i];
            let py = (o.y + ti * dir.y) - qy.0[i];
            let pz = (o.z + ti * dir.z) - qz.0[i];
            let a = (px * ax.0[i]) + (py * ay.0[i]) + (pz * az.0[i]);
            let b = (px * bx.0[i]) + (py * by.0[i]) + (pz * bz.0[i]);
            t[i] = ti;
            alpha[i] = a;
            beta[i] = b;
            let ok = range.surrounds(ti) && (0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b);
            inside |= (ok as u32) << i;
        }
        Self::closest(inside, t, alpha, beta, range.max)
    }

    /// [`Quad4::hit`] in AVX instructions, all four lanes at once: bit-identical results.
    ///
    /// # Safety
    /// Only where the processor has AVX.
    #[cfg(target_arch = "x86_64")]
    #[inline]
    #[target_feature(enable = "avx")]
    pub fn hit_avx(&self, ray: &Ray, range: Interval) -> Option<Quad4Hit> {
        // SAFETY: this function is compiled with AVX, as `hit_avx_inline` requires.
        unsafe { self.hit_avx_inline(ray, range) }
    }

    /// [`Quad4::hit_avx`] for callers compiled with AVX enabled (the traversal's AVX2 path), into
    /// which it is always inlined: a `#[target_feature]` function cannot be, and the call and the
    /// returned record in memory cost a fifth of a packet test.
    ///
    /// # Safety
    /// Only where the processor has AVX, and only from a function compiled with AVX enabled
    /// (elsewhere its intrinsics would be calls).
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    pub unsafe fn hit_avx_inline(&self, ray: &Ray, range: Interval) -> Option<Quad4Hit> {
        // SAFETY: as this function's.
        unsafe {
            let lanes = RayLanes::new(ray.origin.to_array(), ray.direction.to_array());
            self.hit_avx_lanes(&lanes, range)
        }
    }

    /// [`Quad4::hit_avx_inline`] for a ray already broadcast to the lanes.
    ///
    /// # Safety
    /// As [`Quad4::hit_avx_inline`].
    #[cfg(target_arch = "x86_64")]
    #[inline(always)]
    pub unsafe fn hit_avx_lanes(&self, ray: &RayLanes, range: Interval) -> Option<Quad4Hit> {
        use crate::lanes::avx::{dot, load, load3, store};
        use std::arch::x86_64::*;
        // SAFETY: the caller runs on a processor with AVX, in a function compiled with it.
        unsafe {
            let (o, dir) = (ray.origin, ray.direction);
            let n = load3(&self.normal);
            let q = load3(&self.q);
            let rcp = _mm256_div_pd(_mm256_set1_pd(1.0), dot(n, dir));
            let t = _mm256_mul_pd(_mm256_sub_pd(load(&self.d), dot(n, o)), rcp);
            // planar = ray.at(t) - q
            let at = |a: usize| _mm256_sub_pd(_mm256_add_pd(o[a], _mm256_mul_pd(t, dir[a])), q[a]);
            let planar = [at(0), at(1), at(2)];
            let alpha = dot(planar, load3(&self.du));
            let beta = dot(planar, load3(&self.dv));
            let (zero, one) = (_mm256_setzero_pd(), _mm256_set1_pd(1.0));
            let inside = _mm256_and_pd(
                _mm256_and_pd(
                    _mm256_cmp_pd::<_CMP_LT_OQ>(_mm256_set1_pd(range.min), t),
                    _mm256_cmp_pd::<_CMP_LT_OQ>(t, _mm256_set1_pd(range.max)),
                ),
                _mm256_and_pd(
                    _mm256_and_pd(
                        _mm256_cmp_pd::<_CMP_LE_OQ>(zero, alpha),
                        _mm256_cmp_pd::<_CMP_LE_OQ>(alpha, one),
                    ),
                    _mm256_and_pd(
                        _mm256_cmp_pd::<_CMP_LE_OQ>(zero, beta),
                        _mm256_cmp_pd::<_CMP_LE_OQ>(beta, one),
                    ),
                ),
            );
            let inside = _mm256_movemask_pd(inside) as u32;
            if inside == 0 {
                return None;
            }
            Self::closest(inside, store(t), store(alpha), store(beta), range.max)
        }
    }

    /// The lane of least `t` below `max` among the lanes set in `inside` (the lowest on a tie).
    #[inline(always)]
    fn closest(
        mut inside: u32,
        t: [f64; 4],
        alpha: [f64; 4],
        beta: [f64; 4],
        max: f64,
    ) -> Option<Quad4Hit> {
        let mut best: Option<Quad4Hit> = None;
        let mut closest = max;
        while inside != 0 {
            let i = inside.trailing_zeros() as usize;
            inside &= inside - 1;
            if t[i] < closest {
                closest = t[i];
                best = Some(Quad4Hit {
                    lane: i,
                    t: t[i],
                    alpha: alpha[i],
                    beta: beta[i],
                });
            }
        }
        best
    }
}

/// The six quads of the box with opposite corners `a` and `b`, faces pointing outwards (book 2's `box`).
/// `None` if the box is flat.
pub fn box_quads(a: Point3, b: Point3, material: MaterialId) -> Option<[Quad; 6]> {
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

/// Random quads and the rays aimed at them that the packet tests share (`shapes`, `quad8`).
#[cfg(test)]
pub(crate) mod quad_cases {
    use super::Quad;
    use crate::ids::MaterialId;
    use crate::ray::Ray;
    use crate::vec::Vec3;
    use rand::Rng;

    /// A direction uniform on the sphere (by rejection from the cube).
    pub fn unit<R: Rng>(rng: &mut R) -> Vec3 {
        loop {
            let v = Vec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            );
            if v.length_squared() > 1e-6 && v.length_squared() <= 1.0 {
                return v.normalize();
            }
        }
    }

    /// A quad with its corner within 3 of the origin and edges 0.1 to 3 long in random directions.
    pub fn random_quad<R: Rng>(rng: &mut R) -> Quad {
        let q = unit(rng) * rng.random_range(0.0..3.0);
        let u = unit(rng) * rng.random_range(0.1..3.0);
        let v = unit(rng) * rng.random_range(0.1..3.0);
        Quad::new(q, u, v, MaterialId(0)).unwrap()
    }

    /// A ray from 0.5 to 10 away aimed at a random point of `q`, or exactly at an edge or a corner.
    pub fn ray_at<R: Rng>(rng: &mut R, q: &Quad) -> Ray {
        let (a, b) = match rng.random_range(0..3) {
            0 => (rng.random::<f64>(), rng.random::<f64>()),
            1 => (rng.random::<f64>(), [0.0, 1.0][rng.random_range(0..2)]),
            _ => (
                [0.0, 1.0][rng.random_range(0..2)],
                [0.0, 1.0][rng.random_range(0..2)],
            ),
        };
        let target = q.q + a * q.u + b * q.v;
        let origin = target + unit(rng) * rng.random_range(0.5..10.0);
        Ray::new(origin, target - origin, 0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::quad_cases::{random_quad, ray_at};
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_xoshiro::Xoshiro256PlusPlus;

    /// The scalar tests of the quads one after the other, as the packet claims to do them.
    fn one_by_one(quads: &[Quad], ray: &Ray, range: Interval) -> Option<(usize, Hit)> {
        let mut best = None;
        let mut closest = range.max;
        for (i, q) in quads.iter().enumerate() {
            if let Some(h) = q.hit(ray, Interval::new(range.min, closest)) {
                closest = h.t;
                best = Some((i, h));
            }
        }
        best
    }

    fn check(quads: &[Quad], ray: &Ray, range: Interval) -> bool {
        let indexed: Vec<(Quad, u32)> = quads.iter().map(|q| (*q, 7)).collect();
        let packet = Quad4::new(&indexed);
        let fast = packet.hit(ray, range);
        // The AVX twin, where the processor has it, finds exactly the same.
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx") {
            // SAFETY: AVX is present, checked just above.
            assert_eq!(unsafe { packet.hit_avx(ray, range) }, fast, "{ray:?}");
        }
        let slow = one_by_one(quads, ray, range);
        match (fast, slow) {
            (None, None) => false,
            (Some(f), Some((i, h))) => {
                assert_eq!(f.lane, i, "{ray:?}");
                assert_eq!(f.t.to_bits(), h.t.to_bits());
                let built = quads[f.lane].hit_at(ray, f.t, f.alpha, f.beta);
                assert_eq!(built.p, h.p);
                assert_eq!(built.normal, h.normal);
                assert!(f.t.is_finite() && f.alpha.is_finite() && f.beta.is_finite());
                true
            }
            (f, s) => panic!("packet {f:?} but one by one {s:?} for {ray:?}"),
        }
    }

    #[test]
    fn a_packet_finds_the_same_hits_as_the_quads_one_by_one() {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(11);
        let mut hits = 0;
        for _ in 0..2_000 {
            let n = rng.random_range(1..=4);
            let quads: Vec<Quad> = (0..n).map(|_| random_quad(&mut rng)).collect();
            for _ in 0..20 {
                // Aimed at a random point of a random quad, or exactly at an edge or a corner.
                let q = &quads[rng.random_range(0..n)];
                let ray = ray_at(&mut rng, q);
                hits += check(&quads, &ray, Interval::FORWARD) as u32;
                // A range that ends before some hits.
                hits += check(&quads, &ray, Interval::new(0.0, rng.random_range(0.0..1.5))) as u32;
                // Grazing: a ray in the quad's own plane (denominator 0 or nearly).
                let grazing = Ray::new(q.q - q.u, q.u + 1e-17 * q.v, 0.0);
                check(&quads, &grazing, Interval::FORWARD);
                check(&quads, &grazing, Interval::UNIVERSE);
            }
        }
        assert!(hits > 20_000, "{hits}");
    }

    #[test]
    fn equal_distances_go_to_the_first_lane_and_unused_lanes_never_hit() {
        let q = Quad::new(Vec3::ZERO, Vec3::X, Vec3::Z, MaterialId(0)).unwrap();
        let packet = Quad4::new(&[(q, 3), (q, 4)]);
        let ray = Ray::new(Point3::new(0.5, 1.0, 0.5), Vec3::new(0.0, -1.0, 0.0), 0.0);
        let h = packet.hit(&ray, Interval::FORWARD).unwrap();
        assert_eq!((h.lane, packet.index[h.lane], h.t), (0, 3, 1.0));
        // The unused lanes' NaN parameters count nowhere, even over the whole line.
        let empty = Quad4::new(&[]);
        assert_eq!(empty.hit(&ray, Interval::UNIVERSE), None);
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx") {
            // SAFETY: AVX is present, checked just above.
            assert_eq!(unsafe { empty.hit_avx(&ray, Interval::UNIVERSE) }, None);
            assert_eq!(unsafe { packet.hit_avx(&ray, Interval::FORWARD) }, Some(h));
        }
        // And a ray parallel to every lane hits nothing.
        let parallel = Ray::new(Point3::new(0.5, 0.0, 0.5), Vec3::X, 0.0);
        assert_eq!(packet.hit(&parallel, Interval::UNIVERSE), None);
    }
}
