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
#[derive(Clone, Copy, Debug, PartialEq)]
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

#[cfg(target_arch = "x86_64")]
pub use wide::closest_avx512;

#[cfg(target_arch = "x86_64")]
mod wide {
    use super::{Closest8, NO_HIT, Rays8, SPHERE};
    use crate::aabb::Aabb;
    use crate::lanes::avx512::{dot, load3};
    use crate::ray::Interval;
    use crate::shapes::{Quad4, Sphere};
    use std::arch::x86_64::*;

    /// [`super::closest_portable`] in AVX-512 instructions, the eight rays in the lanes: bit-identical
    /// results.
    ///
    /// # Safety
    /// Only where the processor has AVX-512F, and only from a function compiled with it enabled
    /// (into which this is always inlined).
    #[inline(always)]
    pub unsafe fn closest_avx512(
        packets: &[Quad4],
        spheres: &[(Sphere, Aabb)],
        rays: &Rays8,
        range: Interval,
    ) -> Closest8 {
        // SAFETY: as this function's.
        unsafe {
            let o = load3(&rays.origin);
            let dir = load3(&rays.direction);
            let (zero, one) = (_mm512_setzero_pd(), _mm512_set1_pd(1.0));
            let min = _mm512_set1_pd(range.min);
            let mut closest = _mm512_set1_pd(range.max);
            let mut alpha_best = zero;
            let mut beta_best = zero;
            let mut hit = _mm512_set1_epi64(NO_HIT as i64);
            for (i, p) in packets.iter().enumerate() {
                for lane in 0..4 {
                    let b = |x: &crate::lanes::F64x4| _mm512_set1_pd(x.0[lane]);
                    let b3 = |x: &[crate::lanes::F64x4; 3]| [b(&x[0]), b(&x[1]), b(&x[2])];
                    let n = b3(&p.normal);
                    let q = b3(&p.q);
                    // As `Quad::hit`: t = (d - n . o) / (n . dir), planar = o + t dir - q.
                    let t = _mm512_div_pd(_mm512_sub_pd(b(&p.d), dot(n, o)), dot(n, dir));
                    let at = |a: usize| {
                        _mm512_sub_pd(_mm512_add_pd(o[a], _mm512_mul_pd(t, dir[a])), q[a])
                    };
                    let planar = [at(0), at(1), at(2)];
                    let alpha = dot(planar, b3(&p.du));
                    let beta = dot(planar, b3(&p.dv));
                    // Inside the range, shrunk to each lane's closest hit so far, and the quad.
                    let k = _mm512_cmp_pd_mask::<_CMP_LT_OQ>(min, t);
                    let k = _mm512_mask_cmp_pd_mask::<_CMP_LT_OQ>(k, t, closest);
                    let k = _mm512_mask_cmp_pd_mask::<_CMP_LE_OQ>(k, zero, alpha);
                    let k = _mm512_mask_cmp_pd_mask::<_CMP_LE_OQ>(k, alpha, one);
                    let k = _mm512_mask_cmp_pd_mask::<_CMP_LE_OQ>(k, zero, beta);
                    let k = _mm512_mask_cmp_pd_mask::<_CMP_LE_OQ>(k, beta, one);
                    closest = _mm512_mask_mov_pd(closest, k, t);
                    alpha_best = _mm512_mask_mov_pd(alpha_best, k, alpha);
                    beta_best = _mm512_mask_mov_pd(beta_best, k, beta);
                    hit = _mm512_mask_mov_epi64(hit, k, _mm512_set1_epi64((4 * i + lane) as i64));
                }
            }
            if !spheres.is_empty() {
                // `ray.direction.recip()`, as the one-ray traversal takes it for the boxes.
                let inv = dir.map(|d| _mm512_div_pd(one, d));
                for (i, (s, bounds)) in spheres.iter().enumerate() {
                    let k = enters(bounds, o, inv, min, closest);
                    let (k, t) = sphere_t(s, o, dir, min, closest, k);
                    closest = _mm512_mask_mov_pd(closest, k, t);
                    hit = _mm512_mask_mov_epi64(
                        hit,
                        k,
                        _mm512_set1_epi64((SPHERE | i as u32) as i64),
                    );
                }
            }
            let mut out = Closest8 {
                hit: [NO_HIT; 8],
                t: [0.0; 8],
                alpha: [0.0; 8],
                beta: [0.0; 8],
            };
            _mm512_storeu_pd(out.t.as_mut_ptr(), closest);
            _mm512_storeu_pd(out.alpha.as_mut_ptr(), alpha_best);
            _mm512_storeu_pd(out.beta.as_mut_ptr(), beta_best);
            _mm256_storeu_si256(
                out.hit.as_mut_ptr() as *mut __m256i,
                _mm512_cvtepi64_epi32(hit),
            );
            out
        }
    }

    /// The lanes whose ray enters `bounds` within `(min, closest)`: [`Aabb::hit`] lane by lane.
    /// glam's `min`, `max` and their `_element` forms are `a < b ? a : b` and `a > b ? a : b`, which
    /// are `vminpd a, b` and `vmaxpd a, b` exactly, NaN included; `f64::min` and `f64::max` against a
    /// number that is never NaN likewise, with the number second.
    #[inline(always)]
    unsafe fn enters(
        bounds: &Aabb,
        o: [__m512d; 3],
        inv: [__m512d; 3],
        min: __m512d,
        closest: __m512d,
    ) -> __mmask8 {
        // SAFETY: as `closest_avx512`.
        unsafe {
            let slab = |a: usize| {
                let t0 = _mm512_mul_pd(_mm512_sub_pd(_mm512_set1_pd(bounds.min[a]), o[a]), inv[a]);
                let t1 = _mm512_mul_pd(_mm512_sub_pd(_mm512_set1_pd(bounds.max[a]), o[a]), inv[a]);
                (_mm512_min_pd(t0, t1), _mm512_max_pd(t0, t1))
            };
            let (n0, f0) = slab(0);
            let (n1, f1) = slab(1);
            let (n2, f2) = slab(2);
            let near = _mm512_max_pd(_mm512_max_pd(n0, _mm512_max_pd(n1, n2)), min);
            let far = _mm512_min_pd(_mm512_min_pd(f0, _mm512_min_pd(f1, f2)), closest);
            let far = _mm512_mul_pd(far, _mm512_set1_pd(1.0 + 6.0 * f64::EPSILON));
            _mm512_cmp_pd_mask::<_CMP_LE_OQ>(near, far)
        }
    }

    /// Among the lanes of `k`, those whose ray meets the static sphere `s` inside `(min, closest)`,
    /// and where: [`Sphere::hit_t`] lane by lane. A line that misses (a negative discriminant) gives
    /// NaN roots here, which no range holds, where the scalar test returns early.
    #[inline(always)]
    unsafe fn sphere_t(
        s: &Sphere,
        o: [__m512d; 3],
        dir: [__m512d; 3],
        min: __m512d,
        closest: __m512d,
        k: __mmask8,
    ) -> (__mmask8, __m512d) {
        // SAFETY: as `closest_avx512`.
        unsafe {
            use _mm512_mul_pd as mul;
            use _mm512_sub_pd as sub;
            let c = [s.center.x, s.center.y, s.center.z].map(|x| _mm512_set1_pd(x));
            let oc = [sub(c[0], o[0]), sub(c[1], o[1]), sub(c[2], o[2])];
            let a = dot(dir, dir);
            let h = dot(dir, oc);
            let r = _mm512_set1_pd(s.radius);
            // oc x dir, as glam's cross
            let cross = [
                sub(mul(oc[1], dir[2]), mul(dir[1], oc[2])),
                sub(mul(oc[2], dir[0]), mul(dir[2], oc[0])),
                sub(mul(oc[0], dir[1]), mul(dir[0], oc[1])),
            ];
            let disc = sub(
                mul(a, _mm512_set1_pd(s.radius * s.radius)),
                dot(cross, cross),
            );
            let oc_len = _mm512_sqrt_pd(dot(oc, oc));
            let cc = mul(sub(oc_len, r), _mm512_add_pd(oc_len, r));
            // sqrt(disc) with the sign of h
            let sign = _mm512_set1_pd(-0.0);
            let root = _mm512_sqrt_pd(disc);
            // (as integers: the floating-point forms of these bit operations are AVX-512DQ's)
            let bits = _mm512_castpd_si512;
            let signed = _mm512_castsi512_pd(_mm512_or_si512(
                _mm512_andnot_si512(bits(sign), bits(root)),
                _mm512_and_si512(bits(sign), bits(h)),
            ));
            let q = _mm512_add_pd(h, signed);
            let k = _mm512_mask_cmp_pd_mask::<_CMP_NEQ_UQ>(k, q, _mm512_setzero_pd());
            let (t0, t1) = (_mm512_div_pd(cc, q), _mm512_div_pd(q, a));
            let swap = _mm512_cmp_pd_mask::<_CMP_GT_OQ>(t0, t1);
            let lo = _mm512_mask_mov_pd(t0, swap, t1);
            let hi = _mm512_mask_mov_pd(t1, swap, t0);
            let inside = |t: __m512d| {
                let m = _mm512_mask_cmp_pd_mask::<_CMP_LT_OQ>(k, min, t);
                _mm512_mask_cmp_pd_mask::<_CMP_LT_OQ>(m, t, closest)
            };
            let (in_lo, in_hi) = (inside(lo), inside(hi));
            let t = _mm512_mask_mov_pd(hi, in_lo, lo);
            (in_lo | in_hi, t)
        }
    }
}
