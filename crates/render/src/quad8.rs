//! Eight quads to a packet, for processors with AVX-512: a small flat group's quads (at most
//! [`crate::traversal::SMALL_QUADS`]) in one 8-lane pass and a 4-lane one (the tail) instead of three
//! 4-lane ones, and the closest lane of both found at once by a masked reduction.
//!
//! The arithmetic of each lane is exactly that of [`Quad::hit`] (the same `f64` operations in the same
//! order, no fused multiply-adds), so a lane's `t`, `alpha` and `beta` are bit-identical to the
//! scalar quad's and to [`crate::shapes::Quad4`]'s. The choice among the lanes is that of testing the
//! quads one after the other with the range shrinking to each hit: the least `t` inside the range, and
//! on equal `t` (`-0` equal to `+0`) the quad that comes first.

use crate::lanes::F64x8;
use crate::shapes::Quad;

/// Up to eight quads coordinate by coordinate (structure of arrays). Unused lanes have a zero normal:
/// their `t` is NaN and never counts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quad8 {
    q: [F64x8; 3],
    du: [F64x8; 3],
    dv: [F64x8; 3],
    normal: [F64x8; 3],
    d: F64x8,
}

/// The closest hit among a group's 8-lane packets: the quad's place `index` in the packets' order
/// (packet `index / 8`, lane `index % 8`), its parameter and its coordinates in the quad.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quad8Hit {
    pub index: usize,
    pub t: f64,
    pub alpha: f64,
    pub beta: f64,
}

impl Quad8 {
    /// A packet of up to eight quads, lane `i` holding `quads[i]`.
    pub fn new(quads: &[Quad]) -> Self {
        assert!(quads.len() <= 8);
        let zero = [F64x8::ZERO; 3];
        let mut p = Quad8 {
            q: zero,
            du: zero,
            dv: zero,
            normal: zero,
            d: F64x8::ZERO,
        };
        for (i, quad) in quads.iter().enumerate() {
            for a in 0..3 {
                p.q[a].0[i] = quad.q[a];
                p.du[a].0[i] = quad.du[a];
                p.dv[a].0[i] = quad.dv[a];
                p.normal[a].0[i] = quad.normal[a];
            }
            p.d.0[i] = quad.d;
        }
        p
    }

    /// The 8-lane form of `quads`: packets of eight in order, and how many quads they hold; the rest,
    /// if at most four (the packets hold a multiple of four), is left to one 4-lane packet, the
    /// tail (the Cornell room's twelve: one packet of eight and a tail of four, not two packets with
    /// four lanes unused).
    pub fn packets(quads: &[Quad]) -> (Vec<Quad8>, usize) {
        let rest = quads.len() % 8;
        let held = if (1..=4).contains(&rest) {
            quads.len() - rest
        } else {
            quads.len()
        };
        (quads[..held].chunks(8).map(Quad8::new).collect(), held)
    }
}

#[cfg(target_arch = "x86_64")]
pub use wide::RayLanes8;

#[cfg(target_arch = "x86_64")]
mod wide {
    use super::{Quad8, Quad8Hit};
    use crate::lanes::avx512::{dot, load, load3};
    use crate::ray::{Interval, Ray};
    use crate::shapes::Quad4;
    use std::arch::x86_64::*;

    /// A ray's origin and direction broadcast to all eight lanes, once per traversal.
    #[derive(Clone, Copy, Debug)]
    pub struct RayLanes8 {
        pub origin: [__m512d; 3],
        pub direction: [__m512d; 3],
    }

    impl RayLanes8 {
        /// The broadcasts of `ray`'s origin and direction.
        ///
        /// # Safety
        /// Only where the processor has AVX-512F.
        #[inline]
        #[target_feature(enable = "avx512f")]
        pub fn new(ray: &Ray) -> RayLanes8 {
            // Each coordinate broadcast from the ray itself: through a copy as an array, the
            // compiler read two of them back as one 16-byte load across two 8-byte stores, which
            // the store cannot forward (a stall of ~5% of the mixture's time).
            let (o, d) = (&ray.origin, &ray.direction);
            RayLanes8 {
                origin: [o.x, o.y, o.z].map(|c| _mm512_set1_pd(c)),
                direction: [d.x, d.y, d.z].map(|c| _mm512_set1_pd(c)),
            }
        }
    }

    /// One packet's lanes: which hit inside the range, and their `t`, `alpha`, `beta`.
    #[derive(Clone, Copy)]
    struct Lanes {
        inside: __mmask8,
        t: __m512d,
        alpha: __m512d,
        beta: __m512d,
    }

    impl Quad4 {
        /// As [`Quad8::lanes`], in 4-lane registers (AVX-512VL's masked comparisons), the results in
        /// the low half of 8-lane ones (the high half undefined, its mask bits clear).
        #[inline(always)]
        unsafe fn lanes(&self, ray: &RayLanes8, range: Interval) -> Lanes {
            use crate::lanes::avx::{dot, load, load3};
            // SAFETY: the caller runs on a processor with AVX-512F and VL, in a function compiled
            // with them.
            unsafe {
                let half = |x: [__m512d; 3]| x.map(|x| _mm512_castpd512_pd256(x));
                let (o, dir) = (half(ray.origin), half(ray.direction));
                let n = load3(&self.normal);
                let q = load3(&self.q);
                let rcp = _mm256_div_pd(_mm256_set1_pd(1.0), dot(n, dir));
                let t = _mm256_mul_pd(_mm256_sub_pd(load(&self.d), dot(n, o)), rcp);
                let at =
                    |a: usize| _mm256_sub_pd(_mm256_add_pd(o[a], _mm256_mul_pd(t, dir[a])), q[a]);
                let planar = [at(0), at(1), at(2)];
                let alpha = dot(planar, load3(&self.du));
                let beta = dot(planar, load3(&self.dv));
                let (zero, one) = (_mm256_setzero_pd(), _mm256_set1_pd(1.0));
                let k = _mm256_cmp_pd_mask::<_CMP_LT_OQ>(_mm256_set1_pd(range.min), t);
                let k = _mm256_mask_cmp_pd_mask::<_CMP_LT_OQ>(k, t, _mm256_set1_pd(range.max));
                let k = _mm256_mask_cmp_pd_mask::<_CMP_LE_OQ>(k, zero, alpha);
                let k = _mm256_mask_cmp_pd_mask::<_CMP_LE_OQ>(k, alpha, one);
                let k = _mm256_mask_cmp_pd_mask::<_CMP_LE_OQ>(k, zero, beta);
                let inside = _mm256_mask_cmp_pd_mask::<_CMP_LE_OQ>(k, beta, one) & 0x0f;
                Lanes {
                    inside,
                    t: _mm512_castpd256_pd512(t),
                    alpha: _mm512_castpd256_pd512(alpha),
                    beta: _mm512_castpd256_pd512(beta),
                }
            }
        }
    }

    impl Quad8 {
        /// Every lane's hit, as [`crate::shapes::Quad::hit`] computes it, and the mask of the lanes
        /// inside the quad with `t` in the open interval `range`.
        #[inline(always)]
        unsafe fn lanes(&self, ray: &RayLanes8, range: Interval) -> Lanes {
            // SAFETY: the caller runs on a processor with AVX-512F and VL, in a function compiled
            // with them.
            unsafe {
                let (o, dir) = (ray.origin, ray.direction);
                let n = load3(&self.normal);
                let q = load3(&self.q);
                let rcp = _mm512_div_pd(_mm512_set1_pd(1.0), dot(n, dir));
                let t = _mm512_mul_pd(_mm512_sub_pd(load(&self.d), dot(n, o)), rcp);
                // planar = ray.at(t) - q
                let at =
                    |a: usize| _mm512_sub_pd(_mm512_add_pd(o[a], _mm512_mul_pd(t, dir[a])), q[a]);
                let planar = [at(0), at(1), at(2)];
                let alpha = dot(planar, load3(&self.du));
                let beta = dot(planar, load3(&self.dv));
                let (zero, one) = (_mm512_setzero_pd(), _mm512_set1_pd(1.0));
                // The comparisons chained through their masks: a lane stays set only while each holds
                // (ordered: NaN fails all).
                let k = _mm512_cmp_pd_mask::<_CMP_LT_OQ>(_mm512_set1_pd(range.min), t);
                let k = _mm512_mask_cmp_pd_mask::<_CMP_LT_OQ>(k, t, _mm512_set1_pd(range.max));
                let k = _mm512_mask_cmp_pd_mask::<_CMP_LE_OQ>(k, zero, alpha);
                let k = _mm512_mask_cmp_pd_mask::<_CMP_LE_OQ>(k, alpha, one);
                let k = _mm512_mask_cmp_pd_mask::<_CMP_LE_OQ>(k, zero, beta);
                let inside = _mm512_mask_cmp_pd_mask::<_CMP_LE_OQ>(k, beta, one);
                Lanes {
                    inside,
                    t,
                    alpha,
                    beta,
                }
            }
        }

        /// The closest hit among `packets`, then the four lanes of `tail` if given (quads `8 n` to
        /// `8 n + 3` for `n` packets), with `t` in the open interval `range`, on equal `t` the
        /// first quad, as testing them one after the other would find; `ray` is the ray broadcast.
        /// Up to two of them (a small group's: a packet of eight and the tail of four for the
        /// Cornell room's twelve quads) are reduced together, more one after the other.
        ///
        /// # Safety
        /// Only where the processor has AVX-512F and VL, and only from a function compiled with them
        /// enabled (into which this is always inlined).
        #[inline(always)]
        pub unsafe fn closest_avx512(
            packets: &[Quad8],
            tail: Option<&Quad4>,
            ray: &RayLanes8,
            range: Interval,
        ) -> Option<Quad8Hit> {
            // SAFETY: as this function's.
            unsafe {
                match (packets, tail) {
                    ([], None) => None,
                    ([], Some(t)) => pick(t.lanes(ray, range)),
                    ([a], None) => pick(a.lanes(ray, range)),
                    ([a], Some(t)) => pick2(a.lanes(ray, range), t.lanes(ray, range)),
                    ([a, b], None) => pick2(a.lanes(ray, range), b.lanes(ray, range)),
                    // More than a small group holds: packet after packet, the range shrinking.
                    _ => {
                        let mut best: Option<Quad8Hit> = None;
                        let within = |best: Option<Quad8Hit>| {
                            Interval::new(range.min, best.map_or(range.max, |b| b.t))
                        };
                        for (i, p) in packets.iter().enumerate() {
                            if let Some(h) = pick(p.lanes(ray, within(best))) {
                                best = Some(Quad8Hit {
                                    index: 8 * i + h.index,
                                    ..h
                                });
                            }
                        }
                        if let Some(t) = tail
                            && let Some(h) = pick(t.lanes(ray, within(best)))
                        {
                            best = Some(Quad8Hit {
                                index: 8 * packets.len() + h.index,
                                ..h
                            });
                        }
                        best
                    }
                }
            }
        }
    }

    /// The lane of least `t` among the lanes set in `a`'s mask, the first on a tie: the lanes'
    /// minimum by a reduction (unset lanes `+inf`; the set ones are finite), then the first lane
    /// equal to it.
    #[inline(always)]
    unsafe fn pick(a: Lanes) -> Option<Quad8Hit> {
        // SAFETY: as `Quad8::closest_avx512`.
        unsafe {
            if a.inside == 0 {
                return None;
            }
            let ta = _mm512_mask_mov_pd(_mm512_set1_pd(f64::INFINITY), a.inside, a.t);
            let min = _mm512_set1_pd(_mm512_reduce_min_pd(ta));
            let equal = _mm512_mask_cmp_pd_mask::<_CMP_EQ_OQ>(a.inside, ta, min);
            let index = (equal as u32).trailing_zeros() as usize;
            let lane = _mm512_set1_epi64(index as i64);
            let get = |x: __m512d| _mm512_cvtsd_f64(_mm512_permutexvar_pd(lane, x));
            Some(Quad8Hit {
                index,
                t: get(a.t),
                alpha: get(a.alpha),
                beta: get(a.beta),
            })
        }
    }

    /// As [`pick`] over the sixteen lanes of `a` then `b`: the reduction of their lane-wise minimum,
    /// and the chosen lane read from either by one two-source permutation.
    #[inline(always)]
    unsafe fn pick2(a: Lanes, b: Lanes) -> Option<Quad8Hit> {
        // SAFETY: as `Quad8::closest_avx512`.
        unsafe {
            if a.inside | b.inside == 0 {
                return None;
            }
            let both = a.inside as u32 | (b.inside as u32) << 8;
            // One lane inside (in the Cornell room, every ray but those that meet the box first and
            // the wall behind it): that lane, without the reduction's latency.
            let index = if both & (both - 1) == 0 {
                both.trailing_zeros() as usize
            } else {
                let inf = _mm512_set1_pd(f64::INFINITY);
                let ta = _mm512_mask_mov_pd(inf, a.inside, a.t);
                let tb = _mm512_mask_mov_pd(inf, b.inside, b.t);
                let min = _mm512_set1_pd(_mm512_reduce_min_pd(_mm512_min_pd(ta, tb)));
                let ea = _mm512_mask_cmp_pd_mask::<_CMP_EQ_OQ>(a.inside, ta, min);
                let eb = _mm512_mask_cmp_pd_mask::<_CMP_EQ_OQ>(b.inside, tb, min);
                (ea as u32 | (eb as u32) << 8).trailing_zeros() as usize
            };
            // Lanes 0-7 of the index select from the first register, 8-15 from the second.
            let lane = _mm512_set1_epi64(index as i64);
            let get = |x: __m512d, y: __m512d| _mm512_cvtsd_f64(_mm512_permutex2var_pd(x, lane, y));
            Some(Quad8Hit {
                index,
                t: get(a.t, b.t),
                alpha: get(a.alpha, b.alpha),
                beta: get(a.beta, b.beta),
            })
        }
    }

    /// [`Quad8::closest_avx512`] compiled on its own with AVX-512F, for tests.
    ///
    /// # Safety
    /// Only where the processor has AVX-512F and AVX-512VL.
    #[target_feature(enable = "avx512f,avx512vl")]
    pub unsafe fn closest(
        packets: &[Quad8],
        tail: Option<&Quad4>,
        ray: &Ray,
        range: Interval,
    ) -> Option<Quad8Hit> {
        // SAFETY: this function is compiled with AVX-512F and VL and runs where they are present.
        unsafe { Quad8::closest_avx512(packets, tail, &RayLanes8::new(ray), range) }
    }
}

#[cfg(target_arch = "x86_64")]
pub use wide::closest as closest_avx512;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ids::MaterialId;
    use crate::ray::{Interval, Ray};
    use crate::shapes::quad_cases::{random_quad, ray_at};
    use crate::vec::{Point3, Vec3};
    use rand::{Rng, SeedableRng};
    use rand_xoshiro::Xoshiro256PlusPlus;

    /// The quads one after the other, the range shrinking to each hit: (index, t, alpha, beta) bits.
    fn one_by_one(quads: &[Quad], ray: &Ray, range: Interval) -> Option<(usize, [u64; 3])> {
        let mut best = None;
        let mut closest = range.max;
        for (i, q) in quads.iter().enumerate() {
            if let Some(h) = q.hit(ray, Interval::new(range.min, closest)) {
                closest = h.t;
                let crate::hit::UvSource::Uv(a, b) = h.uv_source else {
                    unreachable!("a quad's record has its coordinates")
                };
                best = Some((i, [h.t.to_bits(), a.to_bits(), b.to_bits()]));
            }
        }
        best
    }

    /// The 8-lane form of `quads` ([`Quad8::packets`] and the tail) tested.
    #[cfg(target_arch = "x86_64")]
    fn wide(quads: &[Quad], ray: &Ray, range: Interval) -> Option<(usize, [u64; 3])> {
        let (packets, held) = Quad8::packets(quads);
        let rest: Vec<(Quad, u32)> = quads[held..].iter().map(|q| (*q, 0)).collect();
        let tail = (!rest.is_empty()).then(|| crate::shapes::Quad4::new(&rest));
        // SAFETY: called only where AVX-512F and VL are present (checked by the tests).
        unsafe { closest_avx512(&packets, tail.as_ref(), ray, range) }.map(|h| {
            (
                h.index,
                [h.t.to_bits(), h.alpha.to_bits(), h.beta.to_bits()],
            )
        })
    }

    #[cfg(target_arch = "x86_64")]
    fn has_avx512() -> bool {
        let yes = std::arch::is_x86_feature_detected!("avx512f")
            && std::arch::is_x86_feature_detected!("avx512vl");
        if !yes {
            eprintln!("no AVX-512F on this processor: the 8-lane packets are not tested here");
        }
        yes
    }

    /// Up to twenty random quads (one, two or three packets), many of them coplanar copies (equal `t` in several lanes, across
    /// both packets), and rays aimed at their points, edges and corners, grazing rays and short
    /// ranges: `check` must agree with the quads one by one on every one.
    #[cfg(target_arch = "x86_64")]
    fn agreement(check: impl Fn(&[Quad], &Ray, Interval) -> Option<(usize, [u64; 3])>) -> usize {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(58);
        let mut wrong = 0;
        let mut hits = 0;
        for _ in 0..1_500 {
            let n = rng.random_range(1..=20);
            let mut quads: Vec<Quad> = Vec::new();
            while quads.len() < n {
                if !quads.is_empty() && rng.random_range(0..4) == 0 {
                    // A copy of an earlier quad: a tie for every ray that hits it.
                    let q = quads[rng.random_range(0..quads.len())];
                    quads.push(q);
                    continue;
                }
                quads.push(random_quad(&mut rng));
            }
            for _ in 0..12 {
                let q = &quads[rng.random_range(0..n)];
                let ray = ray_at(&mut rng, q);
                let grazing = Ray::new(q.q - q.u, q.u + 1e-17 * q.v, 0.0);
                let cases = [
                    (ray, Interval::FORWARD),
                    (ray, Interval::new(0.0, rng.random_range(0.0..1.5))),
                    (ray, Interval::UNIVERSE),
                    (grazing, Interval::FORWARD),
                    (grazing, Interval::UNIVERSE),
                ];
                for (ray, range) in cases {
                    let slow = one_by_one(&quads, &ray, range);
                    hits += slow.is_some() as usize;
                    wrong += (check(&quads, &ray, range) != slow) as usize;
                }
            }
        }
        assert!(hits > 30_000, "{hits}");
        wrong
    }

    #[test]
    #[cfg(target_arch = "x86_64")]
    fn eight_lane_packets_find_the_quads_one_by_one_bit_for_bit() {
        if has_avx512() {
            assert_eq!(agreement(wide), 0);
        }
    }

    #[test]
    #[cfg(target_arch = "x86_64")]
    fn the_check_catches_ties_given_to_the_last_quad() {
        // A wrong order: the packets of the quads reversed, so that on equal `t` the last one wins.
        if has_avx512() {
            let last = |quads: &[Quad], ray: &Ray, range: Interval| {
                let reversed: Vec<Quad> = quads.iter().rev().copied().collect();
                wide(&reversed, ray, range).map(|(i, h)| (quads.len() - 1 - i, h))
            };
            assert!(agreement(last) > 100);
        }
    }

    #[test]
    #[cfg(target_arch = "x86_64")]
    fn equal_distances_go_to_the_first_quad_and_unused_lanes_never_hit() {
        if !has_avx512() {
            return;
        }
        let floor = Quad::new(Vec3::ZERO, Vec3::X, Vec3::Z, MaterialId(0)).unwrap();
        let wall = Quad::new(Point3::new(5.0, 0.0, 0.0), Vec3::Y, Vec3::Z, MaterialId(0)).unwrap();
        let ray = Ray::new(Point3::new(0.5, 1.0, 0.5), Vec3::new(0.0, -1.0, 0.0), 0.0);
        // The floor in lane 3 and in lane 2 of the tail (quad 10): the first wins.
        let mut quads = vec![wall; 12];
        quads[3] = floor;
        quads[10] = floor;
        let h = wide(&quads, &ray, Interval::FORWARD).unwrap();
        assert_eq!((h.0, f64::from_bits(h.1[0])), (3, 1.0));
        // Only in the tail: found there.
        quads[3] = wall;
        let h = wide(&quads, &ray, Interval::FORWARD).unwrap();
        assert_eq!(h.0, 10);
        // In lane 5 of the second of two full packets.
        let mut quads = vec![wall; 16];
        quads[13] = floor;
        assert_eq!(wide(&quads, &ray, Interval::FORWARD).unwrap().0, 13);
        // The unused lanes' NaN parameters count nowhere, even over the whole line.
        // SAFETY: AVX-512F and VL are present, checked above.
        let empty = unsafe { closest_avx512(&[Quad8::new(&[])], None, &ray, Interval::UNIVERSE) };
        assert_eq!(empty, None);
        assert_eq!(wide(&[wall; 6], &ray, Interval::UNIVERSE), None);
        assert_eq!(wide(&[wall; 3], &ray, Interval::UNIVERSE), None);
    }
}
