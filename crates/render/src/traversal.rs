//! Tracing a ray through a scene: each group's binary BVH ([`crate::bvh`]) collapsed to 4-wide nodes
//! whose leaves hold quads in packets of four ([`Accel`]), and the closest-hit traversal over them,
//! through instances (the ray moved into the group's frame) and constant media.

use crate::aabb::Aabb;
use crate::bvh::{Bvh, Bvh4, EMPTY, LEAF, PACKET};
use crate::hit::{Hit, REL_ERROR};
pub use crate::hit_tier::{HitTier, HitTierError};
use crate::quad8::Quad8;
use crate::ray::{Interval, Ray};
use crate::sampler::Ctx;
use crate::scene::{ConstantMedium, GroupId, Object, Scene, Transform};
use crate::shapes::{Quad, Quad4, Sphere};
use crate::vec::Vec3;
use std::mem::MaybeUninit;

/// The traversal form of a group: [`Bvh4`] nodes whose leaves are [`LeafItems`], or for a small
/// group ([`Accel::small`]) no tree at all.
#[derive(Clone, Debug, Default)]
pub struct Accel {
    pub tree: Bvh4,
    /// Per leaf of `tree`: its quad packets and its other objects.
    pub leaves: Vec<LeafItems>,
    pub packets: Vec<Quad4>,
    /// Indices into the group's objects of the objects that are not quads.
    pub others: Vec<u32>,
    /// A small group's flat form ([`Accel::small`]): every quad in `packets`, tested straight
    /// through, then each of `others`, each behind the box beside it in `other_bounds`, which must be
    /// entered before the closest hit so far. `tree` and `leaves` are then empty.
    pub flat: bool,
    /// For a small group: the bounding box of each of `others`.
    pub other_bounds: Vec<Aabb>,
    /// For a small group: its quads again, in the order of `packets`, eight to a packet (quad `k` in
    /// lane `k % 8` of packet `k / 8`, as in lane `k % 4` of `packets[k / 4]`), for the AVX-512 tier
    /// ([`HitTier::Avx512`]); a rest of at most four is left to the last of `packets`, the tail.
    pub packets8: Vec<Quad8>,
    /// Whether the AVX-512 tier tests the last of `packets` after `packets8` (see [`Quad8::packets`]).
    pub tail4: bool,
    /// For a small group whose `others` are all static spheres: those spheres with their boxes, in
    /// the order of `others`, so that eight rays test them in the lanes too ([`crate::ray8`]).
    pub spheres: Option<Vec<(Sphere, Aabb)>>,
    /// For a small group: its quads as eight rays at once intersect them
    /// ([`crate::ray8::LaneQuads`]: each with its [`crate::ray8::QuadForm`], a flattened
    /// instance's behind its box, [`crate::ray8::Cluster`]).
    pub lane_quads: crate::ray8::LaneQuads,
}

/// The smallest uniform number `u` for which a free path `-ln(1 - u) / sigma` is taken to be at least
/// `u / sigma` in floating point as it is in exact arithmetic, so that a path that cannot end
/// before a limit is known without its logarithm (`Scene::hit_medium`, the `mis` integrator's
/// distance sampling). Then `1 - u` is exact (`u` a multiple of 2^-53), and `-ln(1 - u)` exceeds `u`
/// by `u^2 / 2 >= 2^-41`, far more than the logarithm's rounding; the division or product by the
/// density and the sum with a start are monotonic, so the bound survives them too.
pub(crate) const SURE_PASS_MIN_U: f64 = 1.0 / (1u64 << 20) as f64;

/// Whether the free path `mean * -ln(1 - u)` (computed as `-mean * ln(1 - u)`) is at least `limit`,
/// known from `u` alone: `u >= SURE_PASS_MIN_U` and `u * mean >= limit`. Never says so of a path
/// that, computed, is shorter (test `a_sure_pass_is_a_pass`).
#[inline(always)]
pub(crate) fn free_path_surely_reaches(u: f64, mean: f64, limit: f64) -> bool {
    u >= SURE_PASS_MIN_U && u * mean >= limit
}

/// Whether the point `t0 - ln(1 - u) / density` (computed as such) lies at or beyond `limit`, known
/// from `u` alone: `u >= SURE_PASS_MIN_U` and `t0 + u / density >= limit`.
#[inline(always)]
pub(crate) fn free_point_surely_beyond(u: f64, t0: f64, density: f64, limit: f64) -> bool {
    u >= SURE_PASS_MIN_U && t0 + u / density >= limit
}

/// The largest group traversed in the flat form: its quads in at most three packets (the Cornell
/// room's six walls and its box's six faces, flattened into it by [`crate::flatten`]) and at most two
/// other objects. A tree over so few objects costs more in box tests and stack work than it culls:
/// every ray inside the Cornell room meets the boxes of most of its walls.
pub const SMALL_QUADS: usize = 3 * PACKET;
/// See [`SMALL_QUADS`].
pub const SMALL_OTHERS: usize = 2;

/// A leaf's quads (`packets[packets.0 .. packets.0 + packets.1]`) and other objects (likewise in
/// `others`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LeafItems {
    pub packets: (u32, u32),
    pub others: (u32, u32),
}

impl Accel {
    /// The traversal form of `objects` (in leaf order of `bvh`, `bounds[i]` the box of `objects[i]`):
    /// the flat form if the group is small, the 4-wide tree otherwise. `draws` says whether a hit in
    /// the group may draw random numbers (it holds a medium, directly or nested): such a group keeps
    /// the tree, whose order of tests the random stream, and so the image, depends on.
    /// `instance[i]` is the flattened instance `objects[i]` came from, if any
    /// ([`crate::flatten::flatten_instances_marked`]).
    pub fn new(
        objects: &[Object],
        bounds: &[Aabb],
        instance: &[Option<u32>],
        bvh: &Bvh,
        draws: bool,
    ) -> Accel {
        assert_eq!(objects.len(), bounds.len());
        let quads = objects
            .iter()
            .filter(|o| matches!(o, Object::Quad(_)))
            .count();
        if !draws && quads <= SMALL_QUADS && objects.len() - quads <= SMALL_OTHERS {
            Self::small(objects, bounds).with_clusters(objects, bounds, instance)
        } else {
            Self::tree(objects, bvh)
        }
    }

    /// The flat form of a small group (see [`Accel::flat`]), its quads packed in the objects' order.
    pub fn small(objects: &[Object], bounds: &[Aabb]) -> Accel {
        let quads: Vec<(Quad, u32)> = objects
            .iter()
            .enumerate()
            .filter_map(|(i, o)| match o {
                Object::Quad(q) => Some((*q, i as u32)),
                _ => None,
            })
            .collect();
        let (others, other_bounds) = objects
            .iter()
            .enumerate()
            .filter(|(_, o)| !matches!(o, Object::Quad(_)))
            .map(|(i, _)| (i as u32, bounds[i]))
            .unzip();
        let plain: Vec<Quad> = quads.iter().map(|(q, _)| *q).collect();
        let (packets8, held) = Quad8::packets(&plain);
        let spheres = objects
            .iter()
            .zip(bounds)
            .filter(|(o, _)| !matches!(o, Object::Quad(_)))
            .map(|(o, b)| match o {
                Object::Sphere(s) if !s.is_moving() => Some((*s, *b)),
                _ => None,
            })
            .collect();
        let packets: Vec<Quad4> = quads.chunks(PACKET).map(Quad4::new).collect();
        Accel {
            lane_quads: crate::ray8::LaneQuads::new(&packets, &[]),
            packets,
            packets8,
            tail4: held < plain.len(),
            spheres,
            others,
            other_bounds,
            flat: true,
            ..Accel::default()
        }
    }

    /// A small group's [`crate::ray8::Cluster`]s: the quads of each flattened instance (`instance[i]`
    /// for `objects[i]`) that has at least [`crate::ray8::Cluster::MIN_QUADS`], behind the box of
    /// their bounds (`bounds[i]`, each a quad's padded box).
    pub fn with_clusters(
        mut self,
        objects: &[Object],
        bounds: &[Aabb],
        instance: &[Option<u32>],
    ) -> Accel {
        use crate::ray8::Cluster;
        let mut clusters: Vec<(u32, Cluster)> = Vec::new();
        // the quads' places in the packets' order: the objects' order, quads alone
        let quads = objects
            .iter()
            .zip(bounds)
            .zip(instance)
            .filter(|((o, _), _)| matches!(o, Object::Quad(_)));
        for (k, ((_, b), from)) in quads.enumerate() {
            let Some(from) = *from else { continue };
            if k >= 64 {
                return self;
            }
            match clusters.iter_mut().find(|(f, _)| *f == from) {
                Some((_, c)) => {
                    c.quads |= 1 << k;
                    c.bounds = c.bounds.union(b);
                }
                None => clusters.push((
                    from,
                    Cluster {
                        quads: 1 << k,
                        bounds: *b,
                    },
                )),
            }
        }
        let clusters: Vec<Cluster> = clusters
            .into_iter()
            .map(|(_, c)| c)
            .filter(|c| c.quads.count_ones() >= Cluster::MIN_QUADS)
            .collect();
        self.lane_quads = crate::ray8::LaneQuads::new(&self.packets, &clusters);
        self
    }

    /// The 4-wide tree form of `objects` (in leaf order of `bvh`).
    pub fn tree(objects: &[Object], bvh: &Bvh) -> Accel {
        let tree = Bvh4::from_binary(bvh);
        let mut accel = Accel::default();
        for leaf in &tree.leaves {
            let range = leaf.first as usize..(leaf.first + leaf.count) as usize;
            let quads: Vec<(Quad, u32)> = range
                .clone()
                .filter_map(|i| match objects[i] {
                    Object::Quad(q) => Some((q, i as u32)),
                    _ => None,
                })
                .collect();
            let p0 = accel.packets.len() as u32;
            accel.packets.extend(quads.chunks(PACKET).map(Quad4::new));
            let o0 = accel.others.len() as u32;
            accel.others.extend(
                range
                    .filter(|&i| !matches!(objects[i], Object::Quad(_)))
                    .map(|i| i as u32),
            );
            accel.leaves.push(LeafItems {
                packets: (p0, accel.packets.len() as u32 - p0),
                others: (o0, accel.others.len() as u32 - o0),
            });
        }
        accel.tree = tree;
        accel
    }

    /// Is this a small group's flat form?
    pub fn is_small(&self) -> bool {
        self.flat
    }
}

impl Scene {
    /// The closest hit along `ray` at `t > 0`.
    #[inline]
    pub fn hit(&self, ray: &Ray, ctx: &mut Ctx) -> Option<Hit> {
        self.hit_group(GroupId(0), ray, Interval::FORWARD, ctx)
    }

    /// The closest hit in group `g` with `t` in the open interval `range`: iterative traversal of the
    /// 4-wide BVH, nearest child first, skipping any child whose box the ray enters beyond the closest
    /// hit so far. Quads are tested four at a time, and only the closest hit's record is built if it
    /// is a quad's or a sphere's.
    ///
    /// On x86-64 processors with AVX2 (detected at run time) the same code is compiled for 4-wide
    /// vectors and the quad packets use [`Quad4::hit_avx`]; with AVX-512F as well, a small group's
    /// quads are tested eight at a time ([`HitTier::Avx512`]). Rounding is identical (no fused
    /// multiply-adds are formed), so the hits are too.
    ///
    /// Never inlined: inlined into the integrator's loop, the same code was 5-7% slower on the
    /// Cornell box's `mixture` in both tiers (user time, interleaved; fewer instructions, but the loop's
    /// registers and code layout suffer).
    #[inline(never)]
    pub fn hit_group(&self, g: GroupId, ray: &Ray, range: Interval, ctx: &mut Ctx) -> Option<Hit> {
        #[cfg(target_arch = "x86_64")]
        match HitTier::cached() {
            // Only the small groups take the AVX-512 form: the trees keep the AVX2 code (compiled
            // with AVX-512 they were up to 5% slower on book 2's final scene in one measurement).
            HitTier::Avx512 if self.groups[g.0 as usize].accel.flat => {
                // SAFETY: the processor runs the tier: AVX-512F, VL and AVX2.
                return unsafe { self.hit_group_avx512(g, ray, range, ctx) };
            }
            HitTier::Avx2 | HitTier::Avx512 => {
                // SAFETY: the processor runs the tier: AVX2.
                return unsafe { self.hit_group_avx2(g, ray, range, ctx) };
            }
            HitTier::Portable => {}
        }
        self.hit_group_portable(g, ray, range, ctx)
    }

    /// [`Scene::hit_group`] in the given tier for group `g` itself (groups nested in it go through
    /// [`Scene::hit_group`]), for tests and benchmarks that compare the tiers; `None` (no answer) if
    /// the processor does not run it.
    pub fn hit_group_in(
        &self,
        tier: HitTier,
        g: GroupId,
        ray: &Ray,
        range: Interval,
        ctx: &mut Ctx,
    ) -> Option<Option<Hit>> {
        if !tier.available() {
            return None;
        }
        Some(match tier {
            HitTier::Portable => self.hit_group_portable(g, ray, range, ctx),
            #[cfg(target_arch = "x86_64")]
            // SAFETY: the processor runs the tier, checked just above.
            HitTier::Avx2 => unsafe { self.hit_group_avx2(g, ray, range, ctx) },
            #[cfg(target_arch = "x86_64")]
            // SAFETY: as above.
            HitTier::Avx512 => unsafe { self.hit_group_avx512(g, ray, range, ctx) },
            #[cfg(not(target_arch = "x86_64"))]
            _ => unreachable!("only the portable tier runs off x86-64"),
        })
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx512f,avx512vl,avx2")]
    unsafe fn hit_group_avx512(
        &self,
        g: GroupId,
        ray: &Ray,
        range: Interval,
        ctx: &mut Ctx,
    ) -> Option<Hit> {
        self.hit_group_with::<true, true>(g, ray, range, ctx)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn hit_group_avx2(
        &self,
        g: GroupId,
        ray: &Ray,
        range: Interval,
        ctx: &mut Ctx,
    ) -> Option<Hit> {
        self.hit_group_with::<true, false>(g, ray, range, ctx)
    }

    /// [`Scene::hit_group`] as processors without AVX2 run it (the quad packets lane by lane), on any
    /// processor, for group `g` itself (groups nested in it go through [`Scene::hit_group`]): the tests
    /// check that both paths find the same hits.
    pub fn hit_group_portable(
        &self,
        g: GroupId,
        ray: &Ray,
        range: Interval,
        ctx: &mut Ctx,
    ) -> Option<Hit> {
        self.hit_group_with::<false, false>(g, ray, range, ctx)
    }

    /// The traversal, its quad packets tested with AVX instructions if `AVX` (only ever set where the
    /// processor has them) and lane by lane otherwise; a small group's eight at a time in AVX-512
    /// instructions if `WIDE` (likewise).
    #[inline(always)]
    fn hit_group_with<const AVX: bool, const WIDE: bool>(
        &self,
        g: GroupId,
        ray: &Ray,
        range: Interval,
        ctx: &mut Ctx,
    ) -> Option<Hit> {
        let group = &self.groups[g.0 as usize];
        if let [only] = &group.objects[..] {
            // A medium's boundary, say: its box would cost as much as the object.
            return self.hit_object(only, ray, range, ctx);
        }
        let accel = &group.accel;
        if accel.flat {
            return self.hit_small_with::<AVX, WIDE>(g, ray, range, ctx);
        }
        let nodes = &accel.tree.nodes;
        if nodes.is_empty() {
            return None;
        }
        let inv = ray.direction.recip();
        let origin = ray.origin.to_array();
        let inv = inv.to_array();
        // From the reciprocal, so that a direction component of -0 counts as negative.
        let neg = [inv[0] < 0.0, inv[1] < 0.0, inv[2] < 0.0];
        let mut closest = range.max;
        let mut best = Closest::Nothing;
        // Stacked children and their entry parameters. Left uninitialised (clearing them costs as much
        // as a box test): only the entries below `sp` are ever read, and each was written when pushed.
        let mut stack = [MaybeUninit::<u32>::uninit(); 64];
        let mut stack_near = [MaybeUninit::<f64>::uninit(); 64];
        let mut sp = 0usize;
        let mut next = 0u32;
        let mut next_near = range.min;
        loop {
            if next_near <= closest {
                if next & LEAF == 0 {
                    let n = &nodes[next as usize];
                    let (near, mask) = Bvh4::hit_children(n, origin, inv, neg, range.min, closest);
                    // Push the children hit, farthest first, so the nearest is visited next.
                    let base = sp;
                    let mut m = mask;
                    while m != 0 {
                        let i = m.trailing_zeros() as usize;
                        m &= m - 1;
                        let (child, t) = (n.child[i], near[i]);
                        // Insertion into the pushed run, kept sorted by decreasing entry.
                        let mut j = sp;
                        while j > base {
                            // SAFETY: base <= j - 1 < sp, and every entry below sp was written.
                            let (below, below_near) = unsafe {
                                (stack[j - 1].assume_init(), stack_near[j - 1].assume_init())
                            };
                            if below_near >= t {
                                break;
                            }
                            stack[j].write(below);
                            stack_near[j].write(below_near);
                            j -= 1;
                        }
                        stack[j].write(child);
                        stack_near[j].write(t);
                        sp += 1;
                    }
                } else {
                    let leaf = &accel.leaves[(next & !LEAF) as usize];
                    let (p0, np) = leaf.packets;
                    for pi in p0..p0 + np {
                        let packet = &accel.packets[pi as usize];
                        let h =
                            hit_packet_splat::<AVX>(packet, ray, Interval::new(range.min, closest));
                        if let Some(h) = h {
                            closest = h.t;
                            best = Closest::quad(pi, &h);
                        }
                    }
                    let (o0, no) = leaf.others;
                    for &oi in &accel.others[o0 as usize..(o0 + no) as usize] {
                        let o = &group.objects[oi as usize];
                        let within = Interval::new(range.min, closest);
                        if let Some((t, c)) = self.hit_other(o, ray, within, ctx) {
                            closest = t;
                            best = c;
                        }
                    }
                }
            }
            if sp == 0 {
                break;
            }
            sp -= 1;
            // SAFETY: sp < the number of entries pushed, each written when pushed.
            (next, next_near) = unsafe { (stack[sp].assume_init(), stack_near[sp].assume_init()) };
            debug_assert!(next != EMPTY);
        }
        best.record(group, ray, closest)
    }

    /// The closest hit in the small group `g` ([`Accel::small`]): its quad packets one after the
    /// other, so that the nearest wall bounds the rest, then its other objects, each culled by its box
    /// against the closest hit so far. (A sphere too: its own test rejects only the rays whose line
    /// misses it, not those that meet a wall first, and a third of the Cornell box's rays are aimed
    /// at its glass sphere.) As for quads, a sphere's record is built only if its hit is the closest.
    ///
    /// If `WIDE`, the quads are tested in [`Accel::packets8`], all at once, and the closest lane is
    /// the one testing the 4-lane packets in turn finds.
    #[inline(always)]
    fn hit_small_with<const AVX: bool, const WIDE: bool>(
        &self,
        g: GroupId,
        ray: &Ray,
        range: Interval,
        ctx: &mut Ctx,
    ) -> Option<Hit> {
        let group = &self.groups[g.0 as usize];
        let accel = &group.accel;
        let mut closest = range.max;
        let mut best = Closest::Nothing;
        #[cfg(target_arch = "x86_64")]
        if WIDE {
            // SAFETY: `WIDE` is set only by `hit_group_avx512`, compiled with AVX-512F and run where
            // it is.
            let h = unsafe {
                let lanes = crate::quad8::RayLanes8::new(ray);
                let tail = if accel.tail4 {
                    accel.packets.last()
                } else {
                    None
                };
                Quad8::closest_avx512(&accel.packets8, tail, &lanes, range)
            };
            if let Some(h) = h {
                closest = h.t;
                best = Closest::Quad {
                    packet: (h.index / PACKET) as u32,
                    lane: h.index % PACKET,
                    alpha: h.alpha,
                    beta: h.beta,
                };
            }
        }
        if !WIDE {
            let lanes = ray_lanes::<AVX>(ray);
            for (pi, packet) in accel.packets.iter().enumerate() {
                if let Some(h) =
                    hit_packet::<AVX>(packet, ray, &lanes, Interval::new(range.min, closest))
                {
                    closest = h.t;
                    best = Closest::quad(pi as u32, &h);
                }
            }
        }
        if accel.others.is_empty() {
            return best.record(group, ray, closest);
        }
        let (closest, best) = self.others_in_turn(group, ray, range.min, (closest, best), ctx);
        best.record(group, ray, closest)
    }

    /// A small group's other objects after its quads: each, in order, if the ray enters its box
    /// before the closest hit so far (`so_far`, its parameter and what it is), and the closest hit
    /// after them.
    #[inline(always)]
    fn others_in_turn<'a>(
        &self,
        group: &'a crate::scene::Group,
        ray: &Ray,
        min: f64,
        so_far: (f64, Closest<'a>),
        ctx: &mut Ctx,
    ) -> (f64, Closest<'a>) {
        let (mut closest, mut best) = so_far;
        let accel = &group.accel;
        let inv = ray.direction.recip();
        for (&oi, bounds) in accel.others.iter().zip(&accel.other_bounds) {
            if bounds.hit(ray.origin, inv, min, closest).is_none() {
                continue;
            }
            let o = &group.objects[oi as usize];
            if let Some((t, c)) = self.hit_other(o, ray, Interval::new(min, closest), ctx) {
                closest = t;
                best = c;
            }
        }
        (closest, best)
    }

    /// Whether eight rays can be intersected with group `g` at once ([`Scene::hit8_small`]): a
    /// small group (no tree), on a processor whose tier is AVX2 or AVX-512.
    pub fn hits_eight_at_once(&self, g: GroupId) -> bool {
        let group = &self.groups[g.0 as usize];
        cfg!(target_arch = "x86_64")
            && HitTier::cached() != HitTier::Portable
            && group.accel.flat
            && group.objects.len() > 1
    }

    /// The closest hit in the small group `g` ([`Accel::small`], [`Scene::hits_eight_at_once`]) of
    /// each ray `rays[i]` whose bit `i` is set in `active`, with `t` in the open interval `range`;
    /// `lanes` holds the same rays by coordinate ([`crate::ray8::Rays8`]); `found` receives the
    /// quads' and static spheres' hits, and `per_lane` the hits of other objects. The quads and the static spheres are tested for all eight rays
    /// at once ([`crate::ray8`], in the instructions of
    /// `tier`), other objects lane by lane with the lane's own `ctxs[i]`, exactly as
    /// [`Scene::hit_group`] tests them for one ray: every lane's record ([`Hits8::record`]) is the
    /// one [`Scene::hit_group`] returns, bit for bit.
    ///
    /// # Safety
    /// Only where the processor runs `tier`, which is AVX2 or AVX-512.
    #[cfg(target_arch = "x86_64")]
    #[allow(clippy::too_many_arguments)]
    pub unsafe fn hit8_small<'s>(
        &'s self,
        tier: HitTier,
        g: GroupId,
        rays: &[Ray; 8],
        lanes: &crate::ray8::Rays8,
        active: u8,
        range: Interval,
        ctxs: &mut [Ctx; 8],
        found: &mut crate::ray8::Closest8,
        per_lane: &mut [Found<'s>; 8],
    ) -> Hits8<'s> {
        let group = &self.groups[g.0 as usize];
        let accel = &group.accel;
        debug_assert!(accel.flat);
        let spheres = accel.spheres.as_deref();
        let spheres8 = spheres.unwrap_or(&[]);
        let lane_quads = &accel.lane_quads;
        // SAFETY: the caller runs this where the processor runs `tier`.
        unsafe {
            match tier {
                HitTier::Avx512 => {
                    crate::ray8::closest_avx512(lane_quads, spheres8, lanes, range, found)
                }
                _ => crate::ray8::closest_avx2(lane_quads, spheres8, lanes, range, found),
            }
        };
        let hits = Hits8 {
            group,
            per_lane: spheres.is_none(),
        };
        if !hits.per_lane {
            return hits;
        }
        // Others that are not all static spheres: one lane at a time, as for one ray (the
        // records in `per_lane`, which the caller keeps: returned, they were copied each time).
        let mut bits = active;
        while bits != 0 {
            let i = bits.trailing_zeros() as usize;
            bits &= bits - 1;
            let so_far = (found.t[i], hits.closest(found, i, &rays[i]));
            let (closest, best) =
                self.others_in_turn(group, &rays[i], range.min, so_far, &mut ctxs[i]);
            per_lane[i] = Found {
                closest: best,
                t: closest,
            };
        }
        hits
    }

    /// A hit on `o`, an object of a leaf or small group that is not in a quad packet, as the closest
    /// candidate so far: a sphere's only as its parameter (its record is built if it stays the
    /// closest), any other object's with its record.
    #[inline(always)]
    fn hit_other<'a>(
        &self,
        o: &'a Object,
        ray: &Ray,
        within: Interval,
        ctx: &mut Ctx,
    ) -> Option<(f64, Closest<'a>)> {
        match o {
            Object::Sphere(s) => s.hit_t(ray, within).map(|t| (t, Closest::Sphere(s))),
            o => self
                .hit_object(o, ray, within, ctx)
                .map(|h| (h.t, Closest::Other(h))),
        }
    }

    #[inline]
    fn hit_object(&self, o: &Object, ray: &Ray, range: Interval, ctx: &mut Ctx) -> Option<Hit> {
        match o {
            Object::Sphere(s) => s.hit(ray, range),
            Object::Quad(q) => q.hit(ray, range),
            Object::Instance { transform, group } => {
                self.hit_instance(transform, *group, ray, range, ctx)
            }
            Object::Group(group) => self.hit_group(*group, ray, range, ctx),
            Object::Medium(m) => self.hit_medium(m, ray, range, ctx),
        }
    }

    /// Intersect a placed group: move the ray into the group's frame, hit, move the hit back. The
    /// error bound grows by the rounding of the transform.
    fn hit_instance(
        &self,
        tr: &Transform,
        group: GroupId,
        ray: &Ray,
        range: Interval,
        ctx: &mut Ctx,
    ) -> Option<Hit> {
        let local = Ray::new(
            tr.inverse_point(ray.origin),
            tr.inverse_vector(ray.direction),
            ray.time,
        );
        let mut h = self.hit_group(group, &local, range, ctx)?;
        h.p = tr.point(h.p);
        h.normal = tr.vector(h.normal);
        h.err = h.err * 2.0
            + REL_ERROR * (h.p.abs().max_element() + tr.translation.abs().max_element());
        Some(h)
    }

    /// Book 2's constant medium, made robust: find where the ray enters and leaves the boundary (the
    /// first hit on the whole line, then the next hit beyond it by more than the hit's error bound),
    /// clip that stretch to `range`, and scatter at an exponentially distributed distance if it
    /// falls inside. A ray that starts inside the medium (its entry lies behind it) travels from its
    /// origin. The boundary must be closed; a grazing ray whose entry and exit coincide passes
    /// through. A boundary that is not one convex piece (several balls, an L of quads) may be
    /// crossed again: past each stretch the ray looks for the next entry, and so on, each stretch
    /// drawing its own distance (the exponential distribution has no memory, so stretch after
    /// stretch is the same as one draw over their sum). The pieces must lie apart
    /// ([`crate::boundary_pieces`]), so that the crossings alternate in and out.
    fn hit_medium(
        &self,
        m: &ConstantMedium,
        ray: &Ray,
        range: Interval,
        ctx: &mut Ctx,
    ) -> Option<Hit> {
        ctx.stats.medium_evaluations += 1;
        let len = ray.direction.length();
        if let [Object::Sphere(s)] = &self.groups[m.boundary.0 as usize].objects[..] {
            // A sphere's boundary (book 2's fog and subsurface sphere): both crossings from one
            // solution of the quadratic, chosen exactly as the two queries below would choose them.
            let roots = s.roots(ray)?;
            let enter = Sphere::first_root_in(roots, Interval::UNIVERSE)?;
            let gap = 8.0 * s.hit_error(ray.time) / len;
            let exit = Sphere::first_root_in(roots, Interval::new(enter + gap, f64::INFINITY))?;
            return self.medium_stretch(m, ray, range, (enter, exit), ctx);
        }
        let mut from = f64::NEG_INFINITY;
        loop {
            let enter = self.hit_group(m.boundary, ray, Interval::new(from, f64::INFINITY), ctx)?;
            if enter.t >= range.max {
                return None;
            }
            let gap = 8.0 * enter.err / len;
            let exit = self.hit_group(
                m.boundary,
                ray,
                Interval::new(enter.t + gap, f64::INFINITY),
                ctx,
            )?;
            if let Some(h) = self.medium_stretch(m, ray, range, (enter.t, exit.t), ctx) {
                return Some(h);
            }
            if m.convex || exit.t >= range.max {
                return None;
            }
            let next = exit.t + 8.0 * exit.err / len;
            if next.is_nan() || next <= from {
                return None; // (not a number, or no progress: nothing more to find)
            }
            from = next;
        }
    }

    /// The medium `m` over the stretch `enter..exit` of `ray` (parameters) clipped to `range` and
    /// to `t >= 0`: a point where the ray scatters, or `None` if it passes (a shadow ray records the
    /// stretch for its transmittance instead).
    #[inline]
    fn medium_stretch(
        &self,
        m: &ConstantMedium,
        ray: &Ray,
        range: Interval,
        (enter, exit): (f64, f64),
        ctx: &mut Ctx,
    ) -> Option<Hit> {
        let len = ray.direction.length();
        let t0 = enter.max(range.min).max(0.0);
        let t1 = exit.min(range.max);
        if t0 >= t1 || t0.is_nan() || t1.is_nan() {
            return None;
        }
        let inside = (t1 - t0) * len;
        if ctx.media == crate::media_crossed::MediumMode::Record {
            // a shadow ray passes through; its transmittance is taken from the stretches inside
            ctx.crossed
                .push_medium(t0, t1, len / -m.neg_inv_density, m.phase.0);
            return None;
        }
        // The distance is `-ln(1 - u) / sigma >= u / sigma`: a `u` at least as large as the
        // stretch's optical depth passes without its logarithm (most rays through thin fog), the
        // same decision, bit for bit ([`SURE_PASS_MIN_U`]).
        let u = ctx.uniform();
        if free_path_surely_reaches(u, -m.neg_inv_density, inside) {
            return None;
        }
        // 1 - u lies in (0, 1], so the logarithm is finite.
        let distance = m.neg_inv_density * (1.0 - u).ln();
        if distance >= inside {
            return None;
        }
        let t = t0 + distance / len;
        let p = ray.at(t);
        Some(Hit {
            t,
            p,
            normal: Vec3::X,
            front_face: true,
            err: 0.0,
            material: m.phase,
            uv_source: crate::hit::UvSource::Uv(0.0, 0.0),
        })
    }

    /// The closest hit by testing every object of group `g` in turn (no BVH): the reference the BVH is
    /// tested against.
    pub fn hit_brute_force(
        &self,
        g: GroupId,
        ray: &Ray,
        range: Interval,
        ctx: &mut Ctx,
    ) -> Option<Hit> {
        let mut closest = range.max;
        let mut best = None;
        for o in &self.groups[g.0 as usize].objects {
            if let Some(h) = self.hit_object(o, ray, Interval::new(range.min, closest), ctx) {
                closest = h.t;
                best = Some(h);
            }
        }
        best
    }
}

/// The ray broadcast to the lanes of the AVX packet test, if `AVX` (only ever set where the processor
/// has it); a placeholder otherwise.
#[cfg(target_arch = "x86_64")]
type Lanes = crate::lanes::avx::RayLanes;
#[cfg(not(target_arch = "x86_64"))]
type Lanes = ();

/// The ray broadcast if `AVX`. (In the small groups' form only: held across the tree's loop, the six
/// registers it takes are spilled and cost more than broadcasting per packet, +2% in book 2's final
/// scene.)
#[inline(always)]
fn ray_lanes<const AVX: bool>(ray: &Ray) -> Lanes {
    #[cfg(target_arch = "x86_64")]
    {
        if AVX {
            // SAFETY: `AVX` is set only by the AVX2 paths, compiled with AVX2 and run where it is.
            return unsafe { Lanes::new(ray.origin.to_array(), ray.direction.to_array()) };
        }
        Lanes::unused()
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = ray;
}

/// [`hit_packet`], broadcasting the ray itself.
#[inline(always)]
fn hit_packet_splat<const AVX: bool>(
    packet: &Quad4,
    ray: &Ray,
    range: Interval,
) -> Option<crate::shapes::Quad4Hit> {
    #[cfg(target_arch = "x86_64")]
    if AVX {
        // SAFETY: `AVX` is set only by `hit_group_avx2`, compiled with AVX2 and run where it is.
        return unsafe { packet.hit_avx_inline(ray, range) };
    }
    packet.hit(ray, range)
}

/// The closest hit in a packet with `t` in `range`, in AVX instructions if `AVX` (only ever set where
/// the processor has them; `lanes` is then `ray` broadcast), lane by lane otherwise.
#[inline(always)]
fn hit_packet<const AVX: bool>(
    packet: &Quad4,
    ray: &Ray,
    lanes: &Lanes,
    range: Interval,
) -> Option<crate::shapes::Quad4Hit> {
    #[cfg(target_arch = "x86_64")]
    if AVX {
        // SAFETY: `AVX` is set only by `hit_group_avx2`, compiled with AVX2 and run where it is.
        return unsafe { packet.hit_avx_lanes(lanes, range) };
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = lanes;
    packet.hit(ray, range)
}

/// What eight rays met in a small group ([`Scene::hit8_small`]), their records not yet built: each
/// built by the path that reads it ([`Hits8::record`]), in place, rather than copied out of the
/// traversal.
pub struct Hits8<'a> {
    group: &'a crate::scene::Group,
    /// Whether the group's other objects were tested one lane at a time: each lane's closest hit
    /// is then in the caller's [`Found`]s.
    per_lane: bool,
}

impl<'a> Hits8<'a> {
    /// Lane `i`'s closest quad or static sphere, of those in `found`, met by `ray` (a quad's
    /// coordinates computed here, as [`Quad::hit`] computes them).
    #[inline(always)]
    fn closest(&self, found: &crate::ray8::Closest8, i: usize, ray: &Ray) -> Closest<'a> {
        let group = self.group;
        match found.hit[i] {
            crate::ray8::NO_HIT => Closest::Nothing,
            h if h & crate::ray8::SPHERE != 0 => {
                let oi = group.accel.others[(h & !crate::ray8::SPHERE) as usize];
                let Object::Sphere(s) = &group.objects[oi as usize] else {
                    unreachable!("the group's spheres are its others")
                };
                Closest::Sphere(s)
            }
            q => {
                let (packet, lane) = (q / PACKET as u32, q as usize % PACKET);
                let index = group.accel.packets[packet as usize].index[lane];
                let Object::Quad(quad) = &group.objects[index as usize] else {
                    unreachable!("a packet lane names a quad")
                };
                let (alpha, beta) = quad.coordinates(ray, found.t[i]);
                Closest::Quad {
                    packet,
                    lane,
                    alpha,
                    beta,
                }
            }
        }
    }

    /// Lane `i`'s record (`None` if its ray met nothing); `ray` is the lane's ray, `found` and
    /// `per_lane` what [`Scene::hit8_small`] filled. Built inline (a sphere's too, unlike
    /// [`Scene::hit_group`]'s), where the path reads it.
    #[inline(always)]
    pub fn record(
        &self,
        found: &crate::ray8::Closest8,
        per_lane: &[Found<'a>; 8],
        i: usize,
        ray: &Ray,
    ) -> Option<Hit> {
        let (closest, t) = if self.per_lane {
            (per_lane[i].closest, per_lane[i].t)
        } else {
            (self.closest(found, i, ray), found.t[i])
        };
        match closest {
            Closest::Sphere(s) => Some(s.hit_at(ray, t)),
            c => c.record(self.group, ray, t),
        }
    }
}

/// What one ray met in a small group, its record not yet built ([`Hits8::record`] builds it).
#[derive(Clone, Copy)]
pub struct Found<'a> {
    closest: Closest<'a>,
    t: f64,
}

impl Found<'_> {
    /// Nothing met.
    pub const NOTHING: Found<'static> = Found {
        closest: Closest::Nothing,
        t: f64::INFINITY,
    };
}

/// The closest hit found so far in a group, its record built only at the end where it can be
/// ([`Closest::record`]).
#[derive(Clone, Copy)]
enum Closest<'a> {
    Nothing,
    /// Lane `lane` of packet `packet`, at plane coordinates `(alpha, beta)`.
    Quad {
        packet: u32,
        lane: usize,
        alpha: f64,
        beta: f64,
    },
    Sphere(&'a Sphere),
    /// Any other object, with its record.
    Other(Hit),
}

impl Closest<'_> {
    #[inline(always)]
    fn quad(packet: u32, h: &crate::shapes::Quad4Hit) -> Self {
        Closest::Quad {
            packet,
            lane: h.lane,
            alpha: h.alpha,
            beta: h.beta,
        }
    }

    /// The record of this hit of `group` at parameter `t` along `ray`.
    #[inline(always)]
    fn record(self, group: &crate::scene::Group, ray: &Ray, t: f64) -> Option<Hit> {
        match self {
            Closest::Nothing => None,
            Closest::Quad {
                packet,
                lane,
                alpha,
                beta,
            } => {
                let index = group.accel.packets[packet as usize].index[lane];
                let Object::Quad(q) = &group.objects[index as usize] else {
                    unreachable!("a packet lane names a quad")
                };
                Some(q.hit_at(ray, t, alpha, beta))
            }
            Closest::Sphere(s) => sphere_record(s, ray, t),
            Closest::Other(h) => Some(h),
        }
    }
}

/// A sphere's record as the traversal's answer, built in place. With `Some(s.hit_at(..))` in
/// [`Closest::record`] the record was built in a temporary by 8-byte stores and copied out by two
/// 64-byte loads, which store-to-load forwarding cannot serve (3-4% of the AVX-512 traversal's
/// samples); returned as `Option<Hit>` from a call of its own, it is written where the traversal's
/// caller reads it (mixture 2-3% faster).
#[inline(never)]
fn sphere_record(s: &Sphere, ray: &Ray, t: f64) -> Option<Hit> {
    Some(s.hit_at(ray, t))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// The uniform numbers to try: the extremes, the bound and its neighbours, random ones as the
    /// sampler draws them (multiples of 2^-53), and small ones that are not (so `1 - u` rounds: a
    /// harder case than the sampler's).
    fn us() -> Vec<f64> {
        let e = f64::EPSILON / 2.0; // 2^-53
        let mut v = vec![
            SURE_PASS_MIN_U,
            SURE_PASS_MIN_U + e,
            SURE_PASS_MIN_U - e,
            e,
            2.0 * e,
            1e-10,
            0.5,
            1.0 - e,
            1.0 - 2.0 * e,
        ];
        let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(7);
        v.extend((0..20_000).map(|_| rng.random::<f64>()));
        v.extend((0..20_000).map(|_| rng.random::<f64>() * 1e-4));
        v
    }

    /// How often a sure-pass test says a free path reaches a limit that, computed with its
    /// logarithm, it falls short of: `path(u, mean, limit)` in [`free_path_surely_reaches`]'s form,
    /// `point(u, t0, density, limit)` in [`free_point_surely_beyond`]'s. Each limit is the next number
    /// above the computed path or point, the nearest one it does not reach.
    fn false_passes(
        path: impl Fn(f64, f64, f64) -> bool,
        point: impl Fn(f64, f64, f64, f64) -> bool,
    ) -> usize {
        let mut bad = 0;
        for u in us() {
            for mean in [1e-30, 1e-3, 0.7, 1.0, 3.0, 1e4, 1e30] {
                let computed = -mean * (1.0 - u).ln();
                bad += usize::from(path(u, mean, computed.next_up()));
                let density = 1.0 / mean;
                for t0 in [0.0, 1e-3, 1.0, 250.0, 1e6] {
                    let t = t0 - (1.0 - u).ln() / density;
                    bad += usize::from(point(u, t0, density, t.next_up()));
                }
            }
        }
        bad
    }

    #[test]
    fn a_sure_pass_is_a_pass() {
        assert_eq!(
            false_passes(free_path_surely_reaches, free_point_surely_beyond),
            0
        );
    }

    /// The checker catches a bound that does not hold: `-ln(1 - u) >= 1.5 u` is false for small `u`.
    #[test]
    fn a_wrong_bound_is_caught() {
        let path = |u: f64, mean: f64, limit: f64| u >= SURE_PASS_MIN_U && 1.5 * u * mean >= limit;
        let point = |u: f64, t0: f64, density: f64, limit: f64| {
            u >= SURE_PASS_MIN_U && t0 + 1.5 * u / density >= limit
        };
        assert!(false_passes(path, |_, _, _, _| false) > 0);
        assert!(false_passes(|_, _, _| false, point) > 0);
    }
}
