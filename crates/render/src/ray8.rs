//! Eight rays to a packet: the closest of a small group's quads for eight rays at once, one ray in
//! each lane of an AVX-512 register and one quad at a time broadcast to all eight (the transpose of
//! [`crate::quad8`], which puts eight quads in the lanes and one ray in all of them).
//!
//! The rays come from eight paths traced side by side ([`crate::paths8`]). With one ray, the quads
//! fill the lanes, and each ray pays for the reduction to its closest lane and for a chain of
//! dependent work per packet; with eight rays, each quad's test is independent of the others', the
//! closest hit so far is kept lane by lane by masked moves, and nothing is reduced across lanes.
//!
//! The arithmetic of each lane is exactly that of [`crate::shapes::Quad::hit`] (the same `f64`
//! operations in the same order, no fused multiply-adds), and the quads are taken in their packets'
//! order with the range shrinking to each hit, so every lane finds the hit the one-ray traversal
//! finds, bit for bit: the least `t` in the open range, on equal `t` the quad that comes first.

use crate::aabb::Aabb;
use crate::lanes::F64x8;
use crate::ray::{Interval, Ray};
use crate::shapes::{Quad4, Sphere};

/// Eight rays' origins and directions coordinate by coordinate (structure of arrays), lane `i`
/// holding ray `i`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rays8 {
    pub origin: [F64x8; 3],
    pub direction: [F64x8; 3],
}

impl Default for Rays8 {
    fn default() -> Self {
        Rays8 {
            origin: [F64x8::ZERO; 3],
            direction: [F64x8::ZERO; 3],
        }
    }
}

impl Rays8 {
    /// The ray in lane `lane`, at `time`.
    #[inline(always)]
    pub fn ray(&self, lane: usize, time: f64) -> Ray {
        let (o, d) = (&self.origin, &self.direction);
        Ray::new(
            crate::vec::Point3::new(o[0].0[lane], o[1].0[lane], o[2].0[lane]),
            crate::vec::Vec3::new(d[0].0[lane], d[1].0[lane], d[2].0[lane]),
            time,
        )
    }

    /// Put `ray` in lane `lane`.
    #[inline(always)]
    pub fn set(&mut self, lane: usize, ray: &Ray) {
        let (o, d) = (ray.origin, ray.direction);
        self.origin[0].0[lane] = o.x;
        self.origin[1].0[lane] = o.y;
        self.origin[2].0[lane] = o.z;
        self.direction[0].0[lane] = d.x;
        self.direction[1].0[lane] = d.y;
        self.direction[2].0[lane] = d.z;
    }
}

/// No hit in this lane.
pub const NO_HIT: u32 = u32::MAX;
/// Set in [`Closest8::hit`] when the lane's closest hit is a sphere's (the rest of the bits: which).
pub const SPHERE: u32 = 1 << 31;

/// Each lane's closest hit: `hit[i]` is its quad's place in the packets' order (packet `hit / 4`,
/// lane `hit % 4`), or [`SPHERE`] with the sphere's place among the group's spheres, or [`NO_HIT`];
/// `t` its parameter (the range's maximum if none), `alpha` and `beta` a quad's coordinates.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Closest8 {
    pub hit: [u32; 8],
    pub t: [f64; 8],
    pub alpha: [f64; 8],
    pub beta: [f64; 8],
}

/// The closest hit of each ray of `rays` among the quads of `packets`, then the static spheres of
/// `spheres` (each tested only if the ray enters its box before the closest hit so far), with `t`
/// in the open interval `range`, lane by lane as [`Quad4::hit`], [`Aabb::hit`] and [`Sphere::hit_t`]
/// compute it: the reference the vector form is tested against.
pub fn closest_portable(
    packets: &[Quad4],
    spheres: &[(Sphere, Aabb)],
    rays: &Rays8,
    range: Interval,
) -> Closest8 {
    let mut out = Closest8 {
        hit: [NO_HIT; 8],
        t: [range.max; 8],
        alpha: [0.0; 8],
        beta: [0.0; 8],
    };
    for lane in 0..8 {
        let ray = Ray::new(
            rays.origin.map(|c| c.0[lane]).into(),
            rays.direction.map(|c| c.0[lane]).into(),
            0.0,
        );
        for (i, p) in packets.iter().enumerate() {
            let within = Interval::new(range.min, out.t[lane]);
            if let Some(h) = p.hit(&ray, within) {
                out.hit[lane] = (4 * i + h.lane) as u32;
                out.t[lane] = h.t;
                out.alpha[lane] = h.alpha;
                out.beta[lane] = h.beta;
            }
        }
        let inv = ray.direction.recip();
        for (i, (s, bounds)) in spheres.iter().enumerate() {
            if bounds
                .hit(ray.origin, inv, range.min, out.t[lane])
                .is_none()
            {
                continue;
            }
            if let Some(t) = s.hit_t(&ray, Interval::new(range.min, out.t[lane])) {
                out.hit[lane] = SPHERE | i as u32;
                out.t[lane] = t;
            }
        }
    }
    out
}

/// How the lanes intersect one quad of a small group ([`QuadForm::of`]): the numbers of
/// [`Quad4::hit`], bit for bit, in fewer operations where the quad lies in an axis plane, as the
/// Cornell box's walls and light do.
///
/// With a normal `n = s e_k` (`s = ±1`, the other coordinates zero), the products with the zeros
/// add only zeros, so `n . o = s o_k` and `n . d = s d_k` exactly, and `t = (d - s o_k) / (s d_k)`;
/// where the two differ, in the sign of a zero, the parameter is `±0`, `±inf` or NaN, which no
/// range with `min >= 0` holds. If also `du` and `dv` have one non-zero coordinate each (`a` and `b`),
/// then `alpha = planar_a du_a` and `beta = planar_b dv_b`; these can differ from the full dot
/// products only in the sign of a zero, so the lanes where a hit has `alpha` or `beta` zero take
/// the full products.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum QuadForm {
    /// An unused lane of its packet (a zero normal: never hit).
    Unused,
    /// The dot products in full.
    General,
    /// Normal `±e_k` (`neg`: `-e_k`), and the axes of `du` and `dv` where each has one non-zero
    /// coordinate.
    Axis {
        k: u8,
        neg: bool,
        plane: Option<(u8, u8)>,
    },
}

impl QuadForm {
    /// The form of lane `lane` of packet `p`.
    pub fn of(p: &Quad4, lane: usize) -> QuadForm {
        if p.index[lane] == u32::MAX {
            return QuadForm::Unused;
        }
        let get = |v: &[crate::lanes::F64x4; 3]| [v[0].0[lane], v[1].0[lane], v[2].0[lane]];
        // the one non-zero coordinate of `v`, if it has only one
        let axis = |v: [f64; 3]| {
            let mut nonzero = (0..3).filter(|&i| v[i] != 0.0);
            match (nonzero.next(), nonzero.next()) {
                (Some(i), None) => Some(i),
                _ => None,
            }
        };
        let n = get(&p.normal);
        match axis(n) {
            Some(k) if n[k].abs() == 1.0 => {
                let plane = match (axis(get(&p.du)), axis(get(&p.dv))) {
                    (Some(a), Some(b)) if a != k && b != k && a != b => Some((a as u8, b as u8)),
                    _ => None,
                };
                QuadForm::Axis {
                    k: k as u8,
                    neg: n[k] < 0.0,
                    plane,
                }
            }
            _ => QuadForm::General,
        }
    }

    /// The forms of the quads of `packets`, four to a packet.
    pub fn all(packets: &[Quad4]) -> Vec<QuadForm> {
        packets
            .iter()
            .flat_map(|p| (0..4).map(move |lane| QuadForm::of(p, lane)))
            .collect()
    }
}

#[cfg(target_arch = "x86_64")]
pub use wide::{closest_avx2, closest_avx512};

#[cfg(target_arch = "x86_64")]
mod wide {
    use super::{Closest8, NO_HIT, QuadForm, Rays8, SPHERE};
    use crate::aabb::Aabb;
    use crate::ray::Interval;
    use crate::shapes::{Quad4, Sphere};
    use crate::wide8::*;

    /// [`super::closest_portable`] in the lanes, written once for both instruction sets; `forms`
    /// the quads' [`QuadForm`]s (any quad without one is taken in full).
    #[inline(always)]
    fn closest<W: Wide8>(
        packets: &[Quad4],
        forms: &[QuadForm],
        spheres: &[(Sphere, Aabb)],
        o: V3<W>,
        dir: V3<W>,
        range: Interval,
        out: &mut Closest8,
    ) {
        let (zero, one) = (o[0].zero_like(), o[0].splat_like(1.0));
        let min = o[0].splat_like(range.min);
        let mut closest = o[0].splat_like(range.max);
        let (mut alpha_best, mut beta_best) = (zero, zero);
        // which: the quad's place, or SPHERE | the sphere's, as a number (exact below 2^53)
        let mut which = o[0].splat_like(NO_HIT as f64);
        // (the axis forms hold for ranges that exclude every zero and negative parameter)
        let axis_forms = range.min >= 0.0;
        let neg_dir = [-dir[0], -dir[1], -dir[2]];
        for (i, p) in packets.iter().enumerate() {
            for lane in 0..4 {
                let form = forms
                    .get(4 * i + lane)
                    .copied()
                    .unwrap_or(QuadForm::General);
                let (t, alpha, beta, in_plane) = match form {
                    QuadForm::Unused => continue,
                    QuadForm::Axis { k, neg, plane } if axis_forms => {
                        let (d, ku) = (zero.splat_like(p.d.0[lane]), k as usize);
                        let t = if neg {
                            (d + o[ku]) / neg_dir[ku]
                        } else {
                            (d - o[ku]) / dir[ku]
                        };
                        match plane {
                            Some((a, b)) => {
                                let (au, bu) = (a as usize, b as usize);
                                let pa = (o[au] + t * dir[au]) - zero.splat_like(p.q[au].0[lane]);
                                let pb = (o[bu] + t * dir[bu]) - zero.splat_like(p.q[bu].0[lane]);
                                let alpha = pa * zero.splat_like(p.du[au].0[lane]);
                                (t, alpha, pb * zero.splat_like(p.dv[bu].0[lane]), true)
                            }
                            None => {
                                let (alpha, beta) = coordinates(p, lane, o, dir, t);
                                (t, alpha, beta, false)
                            }
                        }
                    }
                    _ => {
                        // As `Quad::hit`: t = (d - n . o) / (n . dir).
                        let n = lane3(zero, &p.normal, lane);
                        let t = (zero.splat_like(p.d.0[lane]) - dot(n, o)) / dot(n, dir);
                        let (alpha, beta) = coordinates(p, lane, o, dir, t);
                        (t, alpha, beta, false)
                    }
                };
                // Inside the range, shrunk to each lane's closest hit so far, and the quad.
                let k = min.lt(t)
                    & t.lt(closest)
                    & zero.le(alpha)
                    & alpha.le(one)
                    & zero.le(beta)
                    & beta.le(one);
                // a hit on an edge line of an axis-plane quad: the zero's sign of the full products
                let (alpha, beta) =
                    if in_plane && !(k & (alpha.eq(zero) | beta.eq(zero))).is_empty() {
                        coordinates(p, lane, o, dir, t)
                    } else {
                        (alpha, beta)
                    };
                closest = closest.select(k, t);
                alpha_best = alpha_best.select(k, alpha);
                beta_best = beta_best.select(k, beta);
                which = which.select(k, zero.splat_like((4 * i + lane) as f64));
            }
        }
        if !spheres.is_empty() {
            // `ray.direction.recip()`, as the one-ray traversal takes it for the boxes.
            let inv = [one / dir[0], one / dir[1], one / dir[2]];
            for (i, (s, bounds)) in spheres.iter().enumerate() {
                let k = enters(bounds, o, inv, min, closest);
                let (k, t) = sphere_t(s, o, dir, min, closest, k);
                closest = closest.select(k, t);
                which = which.select(k, zero.splat_like((SPHERE | i as u32) as f64));
            }
        }
        // written where the caller reads them (returned, the 224 bytes were copied by `memcpy`)
        out.t = closest.store().0;
        out.alpha = alpha_best.store().0;
        out.beta = beta_best.store().0;
        out.hit = which.store().0.map(|w| w as u32);
    }

    /// As `Quad::hit`: the plane coordinates `(alpha, beta)` of `o + t dir` in lane `lane`'s quad
    /// of `p` (`planar = o + t dir - q`, then its dot products with the dual basis).
    #[inline(always)]
    fn coordinates<W: Wide8>(p: &Quad4, lane: usize, o: V3<W>, dir: V3<W>, t: W) -> (W, W) {
        let zero = t.zero_like();
        let planar = sub3(add3(o, scale3(t, dir)), lane3(zero, &p.q, lane));
        let alpha = dot(planar, lane3(zero, &p.du, lane));
        (alpha, dot(planar, lane3(zero, &p.dv, lane)))
    }

    /// Lane `lane` of a packet's field, in every lane.
    #[inline(always)]
    fn lane3<W: Wide8>(like: W, x: &[crate::lanes::F64x4; 3], lane: usize) -> V3<W> {
        [
            like.splat_like(x[0].0[lane]),
            like.splat_like(x[1].0[lane]),
            like.splat_like(x[2].0[lane]),
        ]
    }

    /// The entry and exit of a slab `[lo, hi]` along one axis: glam's `min` and `max` of
    /// `(lo - o) inv` and `(hi - o) inv`.
    #[inline(always)]
    fn slab<W: Wide8>(lo: f64, hi: f64, o: W, inv: W) -> (W, W) {
        let t0 = (o.splat_like(lo) - o) * inv;
        let t1 = (o.splat_like(hi) - o) * inv;
        (t0.min(t1), t0.max(t1))
    }

    /// The lanes whose ray enters `bounds` within `(min, closest)`: [`Aabb::hit`] lane by lane.
    /// glam's `min`, `max` and their `_element` forms are the lanes' `min` and `max`; `f64::min`
    /// and `f64::max` against a number that is never NaN likewise, with the number second.
    #[inline(always)]
    fn enters<W: Wide8>(bounds: &Aabb, o: V3<W>, inv: V3<W>, min: W, closest: W) -> W::Mask {
        let (n0, f0) = slab(bounds.min[0], bounds.max[0], o[0], inv[0]);
        let (n1, f1) = slab(bounds.min[1], bounds.max[1], o[1], inv[1]);
        let (n2, f2) = slab(bounds.min[2], bounds.max[2], o[2], inv[2]);
        let near = n0.max(n1.max(n2)).max(min);
        let far = f0.min(f1.min(f2)).min(closest) * min.splat_like(1.0 + 6.0 * f64::EPSILON);
        near.le(far)
    }

    /// Among the lanes of `k`, those whose ray meets the static sphere `s` inside `(min, closest)`,
    /// and where: [`Sphere::hit_t`] lane by lane. A line that misses (a negative discriminant) gives
    /// NaN roots here, which no range holds, where the scalar test returns early.
    #[inline(always)]
    fn sphere_t<W: Wide8>(
        s: &Sphere,
        o: V3<W>,
        dir: V3<W>,
        min: W,
        closest: W,
        k: W::Mask,
    ) -> (W::Mask, W) {
        let c = splat3_like(min, s.center);
        let oc = sub3(c, o);
        let a = dot(dir, dir);
        let h = dot(dir, oc);
        let r = min.splat_like(s.radius);
        let cr = cross(oc, dir);
        let disc = a * min.splat_like(s.radius * s.radius) - dot(cr, cr);
        let oc_len = dot(oc, oc).sqrt();
        let cc = (oc_len - r) * (oc_len + r);
        let q = h + disc.sqrt().copysign(h);
        let k = k & !q.eq(min.zero_like());
        let (t0, t1) = (cc / q, q / a);
        let swap = t0.gt(t1);
        let (lo, hi) = (t0.select(swap, t1), t1.select(swap, t0));
        let in_lo = k & min.lt(lo) & lo.lt(closest);
        let in_hi = k & min.lt(hi) & hi.lt(closest);
        (in_lo | in_hi, hi.select(in_lo, lo))
    }

    /// [`super::closest_portable`] in AVX-512 instructions, into `out`: bit-identical results.
    ///
    /// # Safety
    /// Only where the processor has AVX-512F.
    #[target_feature(enable = "avx512f")]
    pub unsafe fn closest_avx512(
        packets: &[Quad4],
        forms: &[QuadForm],
        spheres: &[(Sphere, Aabb)],
        rays: &Rays8,
        range: Interval,
        out: &mut Closest8,
    ) {
        // SAFETY: compiled with AVX-512F, run where the processor has it.
        let (o, dir) = unsafe {
            (
                load3::<Avx512>(&rays.origin),
                load3::<Avx512>(&rays.direction),
            )
        };
        closest(packets, forms, spheres, o, dir, range, out)
    }

    /// [`super::closest_portable`] in AVX2 instructions (four lanes to a register), into `out`:
    /// bit-identical results.
    ///
    /// # Safety
    /// Only where the processor has AVX2.
    #[target_feature(enable = "avx2")]
    pub unsafe fn closest_avx2(
        packets: &[Quad4],
        forms: &[QuadForm],
        spheres: &[(Sphere, Aabb)],
        rays: &Rays8,
        range: Interval,
        out: &mut Closest8,
    ) {
        // SAFETY: compiled with AVX2, run where the processor has it.
        let (o, dir) = unsafe { (load3::<Avx2>(&rays.origin), load3::<Avx2>(&rays.direction)) };
        closest(packets, forms, spheres, o, dir, range, out)
    }
}
