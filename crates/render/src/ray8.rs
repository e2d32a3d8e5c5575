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

/// The place of a small group's hit number `h` in a table of 32 ([`HitKinds`]): quad `k < 15` at
/// `k`, sphere `i < 15` at `16 + i`, no hit at 31.
#[inline(always)]
pub fn hit_key(h: u32) -> u32 {
    (h & 15) | ((h >> 27) & 16)
}

/// Which of a small group's hits are of one kind (a Lambertian quad, a light, a glass sphere), one
/// bit a hit at its [`hit_key`], so that the lanes' hits are sorted by kind without a load a lane.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct HitKinds(u32);

impl HitKinds {
    /// The hits whose number `is(h)` holds, among the quads `0..quads` and the spheres `0..spheres`;
    /// `None` past fifteen of either.
    pub fn new(quads: usize, spheres: usize, is: impl Fn(u32) -> bool) -> Option<HitKinds> {
        if quads > 15 || spheres > 15 {
            return None;
        }
        let numbers = (0..quads as u32).chain((0..spheres as u32).map(|i| SPHERE | i));
        Some(HitKinds(
            numbers
                .filter(|&h| is(h))
                .fold(0, |bits, h| bits | 1 << hit_key(h)),
        ))
    }

    /// Whether the hit `h` is of this kind.
    #[inline(always)]
    pub fn has(self, h: u32) -> bool {
        (self.0 >> hit_key(h)) & 1 != 0
    }

    /// The lanes whose hit in `hit` is of this kind.
    #[inline(always)]
    pub fn lanes(self, hit: &[u32; 8]) -> u8 {
        let mut lanes = 0;
        for (l, &h) in hit.iter().enumerate() {
            lanes |= (self.has(h) as u8) << l;
        }
        lanes
    }
}

/// Each lane's closest hit: `hit[i]` is its quad's place in the packets' order (packet `hit / 4`,
/// lane `hit % 4`), or [`SPHERE`] with the sphere's place among the group's spheres, or [`NO_HIT`];
/// `t` its parameter (the range's maximum if none). A quad's coordinates `(alpha, beta)` are not
/// kept: they are computed where the hit is used ([`crate::shapes::Quad::coordinates`]), once,
/// rather than kept for every closer hit found on the way.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Closest8 {
    pub hit: [u32; 8],
    pub t: [f64; 8],
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
/// add only zeros, so `n . o = s o_k` and `n . d = s d_k` exactly, and `Quad::hit`'s
/// `t = (d - n . o) * (1 / (n . d))` is `(d - s o_k) * (s / d_k)`, and that is
/// `(s d - o_k) * (1 / d_k)` (a sign moved from one factor to the other, exactly: rounding is
/// symmetric), where `1 / d_k` is the ray's reciprocal, taken once for every such quad and the
/// boxes (a division saved a quad). Where the forms differ, in the sign of a zero, the parameter
/// is `±0`, `±inf` or NaN, which no range with `min >= 0` holds. If also `du` and `dv` have one
/// non-zero coordinate each (`a` and `b`), then `alpha = planar_a du_a` and
/// `beta = planar_b dv_b`; these can differ from the full dot products only in the sign of a
/// zero, which the test `0 <= alpha, beta <= 1` does not see (the closest hit's coordinates are
/// computed in full afterwards, [`crate::shapes::Quad::coordinates`]).
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
}

/// The quads of one rigid instance placed in world space by [`crate::flatten`] (book 3's rotated
/// box: six of the Cornell room's twelve): which of a small group's quads (bit `k` for quad `k` in
/// the packets' order) and the box that bounds them. The lanes test them after the group's other
/// quads, and only where a ray enters the box before its closest hit so far, as the one-ray traversal
/// would test them behind the instance's box had they not been flattened; on equal `t` the quad that
/// comes first in the packets' order still wins, so the hits are those of testing every quad in
/// order, bit for bit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cluster {
    pub quads: u64,
    pub bounds: Aabb,
}

impl Cluster {
    /// Fewest quads worth a box of their own (the box's test costs about what one quad's does).
    pub const MIN_QUADS: u32 = 4;
}

/// One quad as eight rays at once test it: its place in the packets' order, its [`QuadForm`], and
/// its numbers, read out of the packets once per scene (the loop over the quads then has nothing to
/// decide but the form).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LaneQuad {
    pub index: u32,
    pub form: QuadForm,
    pub d: f64,
    pub q: [f64; 3],
    pub du: [f64; 3],
    pub dv: [f64; 3],
    pub normal: [f64; 3],
}

/// A small group's quads as eight rays at once test them ([`closest_avx2`], [`closest_avx512`]):
/// those in no [`Cluster`] in the packets' order, then each cluster's behind its box.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LaneQuads {
    pub rest: Vec<LaneQuad>,
    pub clusters: Vec<(Aabb, Vec<LaneQuad>)>,
}

impl LaneQuads {
    /// The quads of `packets` (unused lanes left out), the quads of each of `clusters` apart.
    pub fn new(packets: &[Quad4], clusters: &[Cluster]) -> LaneQuads {
        let mut all = Vec::new();
        for (i, p) in packets.iter().enumerate() {
            for lane in 0..4 {
                let form = QuadForm::of(p, lane);
                if form == QuadForm::Unused {
                    continue;
                }
                let get = |v: &[crate::lanes::F64x4; 3]| [v[0].0[lane], v[1].0[lane], v[2].0[lane]];
                all.push(LaneQuad {
                    index: (4 * i + lane) as u32,
                    form,
                    d: p.d.0[lane],
                    q: get(&p.q),
                    du: get(&p.du),
                    dv: get(&p.dv),
                    normal: get(&p.normal),
                });
            }
        }
        let held = |q: &LaneQuad, c: &Cluster| q.index < 64 && (c.quads >> q.index) & 1 != 0;
        LaneQuads {
            rest: all
                .iter()
                .filter(|q| !clusters.iter().any(|c| held(q, c)))
                .copied()
                .collect(),
            clusters: clusters
                .iter()
                .map(|c| {
                    (
                        c.bounds,
                        all.iter().filter(|q| held(q, c)).copied().collect(),
                    )
                })
                .collect(),
        }
    }
}

#[cfg(target_arch = "x86_64")]
pub use wide::{closest_avx2, closest_avx512};

#[cfg(target_arch = "x86_64")]
mod wide {
    use super::{Closest8, LaneQuad, LaneQuads, NO_HIT, QuadForm, Rays8, SPHERE};
    use crate::aabb::Aabb;
    use crate::ray::Interval;
    use crate::shapes::Sphere;
    use crate::wide8::*;

    /// Each lane's closest hit so far, in registers: [`Closest8`]'s fields (`which` the hit's number
    /// as a float, exact below 2^53).
    #[derive(Clone, Copy)]
    struct Found<W> {
        t: W,
        which: W,
    }

    /// The quads `quads`, one after the other, each lane's closest hit so far in `found`.
    /// `ANY_ORDER`: `found` may hold a quad that comes later in the packets' order (the rest are
    /// taken before the clusters), so an equal `t` goes to whichever comes first.
    #[inline(always)]
    fn quads<W: Lanes, const ANY_ORDER: bool>(
        quads: &[LaneQuad],
        o: V3<W>,
        dir: V3<W>,
        inv: V3<W>,
        range: Interval,
        found: &mut Found<W>,
    ) {
        let (zero, one) = (o[0].zero_like(), o[0].splat_like(1.0));
        let min = o[0].splat_like(range.min);
        let no_hit = o[0].splat_like(NO_HIT as f64);
        // (the axis forms hold for ranges that exclude every zero and negative parameter)
        let axis_forms = range.min >= 0.0;
        for quad in quads {
            let (t, alpha, beta) = match quad.form {
                QuadForm::Unused => continue,
                QuadForm::Axis { k, neg, plane } if axis_forms => {
                    // `(s d - o_k) * (1 / d_k)`, each axis a constant, so that the rays'
                    // coordinates stay in registers
                    let sd = zero.splat_like(if neg { -quad.d } else { quad.d });
                    let t = match k {
                        0 => (sd - o[0]) * inv[0],
                        1 => (sd - o[1]) * inv[1],
                        _ => (sd - o[2]) * inv[2],
                    };
                    let (alpha, beta) = match plane {
                        Some((1, 2)) => in_plane::<W, 1, 2>(quad, o, dir, t),
                        Some((2, 1)) => in_plane::<W, 2, 1>(quad, o, dir, t),
                        Some((0, 2)) => in_plane::<W, 0, 2>(quad, o, dir, t),
                        Some((2, 0)) => in_plane::<W, 2, 0>(quad, o, dir, t),
                        Some((0, 1)) => in_plane::<W, 0, 1>(quad, o, dir, t),
                        Some(_) => in_plane::<W, 1, 0>(quad, o, dir, t),
                        None => coordinates(quad, o, dir, t),
                    };
                    (t, alpha, beta)
                }
                _ => {
                    // As `Quad::hit`: t = (d - n . o) * (1 / (n . dir)).
                    let n = splat3_of(zero, quad.normal);
                    let t = (zero.splat_like(quad.d) - dot(n, o)) * (one / dot(n, dir));
                    let (alpha, beta) = coordinates(quad, o, dir, t);
                    (t, alpha, beta)
                }
            };
            let number = zero.splat_like(quad.index as f64);
            // Inside the range, shrunk to each lane's closest hit so far (on a tie, closer to the
            // front of the packets' order), and the quad.
            let before = if ANY_ORDER {
                t.lt(found.t) | (t.eq(found.t) & number.lt(found.which) & found.which.lt(no_hit))
            } else {
                t.lt(found.t)
            };
            // `0 <= alpha, beta <= 1` in two comparisons: where its own comparison fails, `min`
            // gives `beta` and `max` gives `alpha`, so that a NaN in either fails one of them
            let k = min.lt(t) & before & zero.le(alpha.min(beta)) & beta.max(alpha).le(one);
            found.t = found.t.select(k, t);
            found.which = found.which.select(k, number);
        }
    }

    /// The width of [`closest`]'s lanes, and how it tests an instance's quads where only some of
    /// the lanes enter their box.
    trait Packet: Lanes {
        /// A cluster's quads `quads` ([`quads`], in any order) for the lanes of `entering`.
        fn instance(
            quads: &[LaneQuad],
            o: V3<Self>,
            dir: V3<Self>,
            inv: V3<Self>,
            range: Interval,
            found: &mut Found<Self>,
            entering: Self::Mask,
        );
    }

    impl Packet for Avx512 {
        /// All eight lanes at once (the lanes not entering find no closer hit there: the box
        /// bounds every quad in it).
        #[inline(always)]
        fn instance(
            cluster: &[LaneQuad],
            o: V3<Self>,
            dir: V3<Self>,
            inv: V3<Self>,
            range: Interval,
            found: &mut Found<Self>,
            _entering: Bits8,
        ) {
            quads::<Self, true>(cluster, o, dir, inv, range, found);
        }
    }

    impl Packet for Avx2 {
        /// Each half of the packet whose four lanes hold one that enters, in one register (a ray
        /// in the room meets the box's bounds about one time in six or seven, so that most
        /// packets take one half or none).
        #[inline(always)]
        fn instance(
            cluster: &[LaneQuad],
            o: V3<Self>,
            dir: V3<Self>,
            inv: V3<Self>,
            range: Interval,
            found: &mut Found<Self>,
            entering: Lanes4x2,
        ) {
            let bits = entering.bits();
            let (o2, dir2) = (o.map(Avx2::halves), dir.map(Avx2::halves));
            let inv2 = inv.map(Avx2::halves);
            let (t, which) = (found.t.halves(), found.which.halves());
            let mut out = [t, which];
            for h in 0..2 {
                if (bits >> (4 * h)) & 15 == 0 {
                    continue;
                }
                let o = [o2[0][h], o2[1][h], o2[2][h]];
                let dir = [dir2[0][h], dir2[1][h], dir2[2][h]];
                let inv = [inv2[0][h], inv2[1][h], inv2[2][h]];
                let mut half = Found {
                    t: t[h],
                    which: which[h],
                };
                quads::<Avx2Half, true>(cluster, o, dir, inv, range, &mut half);
                (out[0][h], out[1][h]) = (half.t, half.which);
            }
            *found = Found {
                t: Avx2::from_halves(out[0]),
                which: Avx2::from_halves(out[1]),
            };
        }
    }

    /// [`super::closest_portable`] in the lanes, written once for both instruction sets: the quads
    /// of `quads` in no cluster, in order; then each cluster's, for the lanes that enter its box
    /// before their closest hit so far; then the spheres, each for the lanes that enter its box.
    #[inline(always)]
    fn closest<W: Packet>(
        quads: &LaneQuads,
        spheres: &[(Sphere, Aabb)],
        o: V3<W>,
        dir: V3<W>,
        range: Interval,
    ) -> Found<W> {
        let zero = o[0].zero_like();
        let min = o[0].splat_like(range.min);
        let mut found = Found {
            t: o[0].splat_like(range.max),
            which: o[0].splat_like(NO_HIT as f64),
        };
        // `ray.direction.recip()`, as the one-ray traversal takes it for the boxes, and the
        // reciprocals `Quad::hit` takes of the quads in axis planes
        let one = o[0].splat_like(1.0);
        let inv = [one / dir[0], one / dir[1], one / dir[2]];
        self::quads::<W, false>(&quads.rest, o, dir, inv, range, &mut found);
        if quads.clusters.is_empty() && spheres.is_empty() {
            return found;
        }
        for (bounds, cluster) in &quads.clusters {
            let entering = enters(bounds, o, inv, min, found.t);
            if !entering.is_empty() {
                W::instance(cluster, o, dir, inv, range, &mut found, entering);
            }
        }
        for (i, (s, bounds)) in spheres.iter().enumerate() {
            let k = enters(bounds, o, inv, min, found.t);
            if k.is_empty() {
                continue;
            }
            let (k, t) = sphere_t(s, o, dir, min, found.t, k);
            found.t = found.t.select(k, t);
            found.which = found
                .which
                .select(k, zero.splat_like((SPHERE | i as u32) as f64));
        }
        found
    }

    /// `found` written where the caller reads it (returned, the 224 bytes were copied by `memcpy`).
    #[inline(always)]
    fn store<W: Wide8>(found: Found<W>, out: &mut Closest8) {
        out.t = found.t.store().0;
        out.hit = found.which.store().0.map(|w| w as u32);
    }

    /// `(alpha, beta)` of `o + t dir` in an axis-plane quad whose `du` has its one non-zero
    /// coordinate on axis `A` and `dv` on axis `B` ([`QuadForm::Axis`]).
    #[inline(always)]
    fn in_plane<W: Lanes, const A: usize, const B: usize>(
        quad: &LaneQuad,
        o: V3<W>,
        dir: V3<W>,
        t: W,
    ) -> (W, W) {
        let like = t;
        let pa = (o[A] + t * dir[A]) - like.splat_like(quad.q[A]);
        let pb = (o[B] + t * dir[B]) - like.splat_like(quad.q[B]);
        (
            pa * like.splat_like(quad.du[A]),
            pb * like.splat_like(quad.dv[B]),
        )
    }

    /// As `Quad::hit`: the plane coordinates `(alpha, beta)` of `o + t dir` in `quad` (`planar = o +
    /// t dir - q`, then its dot products with the dual basis).
    #[inline(always)]
    fn coordinates<W: Lanes>(quad: &LaneQuad, o: V3<W>, dir: V3<W>, t: W) -> (W, W) {
        let zero = t.zero_like();
        let planar = sub3(add3(o, scale3(t, dir)), splat3_of(zero, quad.q));
        let alpha = dot(planar, splat3_of(zero, quad.du));
        (alpha, dot(planar, splat3_of(zero, quad.dv)))
    }

    /// `x` in every lane.
    #[inline(always)]
    fn splat3_of<W: Lanes>(like: W, x: [f64; 3]) -> V3<W> {
        [
            like.splat_like(x[0]),
            like.splat_like(x[1]),
            like.splat_like(x[2]),
        ]
    }

    /// The entry and exit of a slab `[lo, hi]` along one axis: glam's `min` and `max` of
    /// `(lo - o) inv` and `(hi - o) inv`.
    #[inline(always)]
    fn slab<W: Lanes>(lo: f64, hi: f64, o: W, inv: W) -> (W, W) {
        let t0 = (o.splat_like(lo) - o) * inv;
        let t1 = (o.splat_like(hi) - o) * inv;
        (t0.min(t1), t0.max(t1))
    }

    /// The lanes whose ray enters `bounds` within `(min, closest)`: [`Aabb::hit`] lane by lane.
    /// glam's `min`, `max` and their `_element` forms are the lanes' `min` and `max`; `f64::min`
    /// and `f64::max` against a number that is never NaN likewise, with the number second.
    #[inline(always)]
    fn enters<W: Lanes>(bounds: &Aabb, o: V3<W>, inv: V3<W>, min: W, closest: W) -> W::Mask {
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
    fn sphere_t<W: Lanes>(
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
        quads: &LaneQuads,
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
        store(closest(quads, spheres, o, dir, range), out)
    }

    /// [`super::closest_portable`] in AVX2 instructions (four lanes to a register), into `out`:
    /// bit-identical results.
    ///
    /// # Safety
    /// Only where the processor has AVX2.
    #[target_feature(enable = "avx2")]
    pub unsafe fn closest_avx2(
        quads: &LaneQuads,
        spheres: &[(Sphere, Aabb)],
        rays: &Rays8,
        range: Interval,
        out: &mut Closest8,
    ) {
        // SAFETY: compiled with AVX2, run where the processor has it.
        let (o, dir) = unsafe { (load3::<Avx2>(&rays.origin), load3::<Avx2>(&rays.direction)) };
        store(closest(quads, spheres, o, dir, range), out)
    }
}
