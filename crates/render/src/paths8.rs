//! Thirty-two paths side by side, in four packets of eight ([`PACKETS`]): the book's one-sample
//! estimator ([`OneSamplePath`]) traced for 32 samples at once, each packet's rays intersected together
//! in the lanes of vector registers ([`crate::ray8`]: one AVX-512 register, or two AVX2 ones). For
//! `mixture`, a vertex on a Lambertian quad of constant albedo is then computed whole in the lanes
//! too ([`crate::vertex8`]: the point, the mixture's direction and weight, the throughput, the next
//! ray), in batches of eight gathered from all the packets (about half a packet's rays meet such a
//! quad, so with one packet the batch ran half empty), and so is a vertex on a glass sphere
//! ([`crate::glass8`]: the record, the dielectric, the next ray); a path that meets a light of
//! constant radiance gathers it without building the hit's record; any other vertex (the sky, a
//! texture, metal) is computed on its own as one path at a time would, the directions of its
//! Lambertian bounces drawn and weighted in the lanes again ([`crate::mixture8`]).
//!
//! A scene as small as book 3's Cornell box (twelve quads and a sphere, no tree) spends most of a
//! path's intersection on work that does not depend on the ray: with one ray, the quads fill the
//! lanes and every ray pays for the reduction to its closest quad and for the latency of each step;
//! with eight rays, each quad is broadcast once and tested against all eight.
//!
//! Every sample is still a function of `(seed, pixel, k)` alone, traced with its own numbers (a
//! [`Ctx`] per lane), and each pixel's samples are summed in the order of `k`: samples that end
//! early wait in a ring until those before them are done. So the image is bit-identical to tracing
//! one path at a time (tested in `crates/render/tests/paths8.rs`).

use crate::integrator::{Bounce, OneSamplePath, Strategy, sample_diffuse};
use crate::lanes::F64x8;
use crate::material::ScatterPdf;
use crate::mixture8::Mixture8;
use crate::ray::{Interval, Ray};
use crate::ray8::Rays8;
use crate::render::{Accumulator, Renderer};
use crate::sampler::{Ctx, Dimension, Stats};
use crate::scene::{GroupId, Scene};
use crate::vec::{Color, Point3, Vec3};

/// Lanes of a packet: rays intersected at once.
pub const LANES: usize = 8;

/// Packets of paths in flight per thread: thirty-two paths. Each round of the loop runs its phases
/// (the packets' intersections, the glass batches, the Lambertian batches) one after the other, so
/// that each phase's code, once fetched, serves four packets: the loop's code is larger than a
/// 32 KB instruction cache (about 32-35 KB of it runs every round with AVX2, cachegrind), and with two packets it
/// was fetched again in every phase. Four packets took 0.96-0.97 times the time of two; six and
/// eight cost more in the data they keep (`render-speed.md`, "Issue 16, twenty-second round").
pub const PACKETS: usize = 4;

/// The fewest waiting Lambertian vertices worth a second batch in one round: fewer wait for the
/// next, each leaving its lane of a packet's intersection idle for a round. A batch of the
/// Cornell box's vertex costs about what four idle lanes of its intersection do (1, 2, 4, 8 and 9
/// measured, `rtl render cornell --strategy mixture`, both tiers: none better than 4 beyond noise).
const SECOND_BATCH: u32 = 4;

/// How many samples may be finished but not yet summed into their pixel (waiting for an earlier
/// sample of the row, still in flight, to end). A lane whose next sample would go beyond waits.
const RING: usize = 256;

/// Whether a render of `scene` by `strategy` traces paths side by side in the lanes here: the
/// book's one-sample strategies (`mis` has its own integrator and its own lanes, [`crate::mis8`]),
/// when the scene's rays meet a small group on
/// a processor with AVX2 or AVX-512 ([`Scene::hits_eight_at_once`]).
pub fn applies(scene: &Scene, strategy: Strategy) -> bool {
    !matches!(strategy, Strategy::Mis(_)) && scene.hits_eight_at_once(GroupId(0))
}

/// Samples finished out of order, summed into their pixels in order.
struct Ring {
    value: [Color; RING],
    done: [bool; RING],
    /// The first sample (in the row's order) not yet summed.
    commit: u64,
    /// Its pixel, and how many of that pixel's samples are still to be summed (counted down, not
    /// divided out of `commit`: a 64-bit division per sample costs tens of cycles on some
    /// processors).
    pixel: usize,
    left: u64,
}

impl Ring {
    /// An empty ring for a row of pixels with `spp` samples each.
    fn new(spp: u64) -> Ring {
        Ring {
            value: [Color::ZERO; RING],
            done: [false; RING],
            commit: 0,
            pixel: 0,
            left: spp,
        }
    }

    /// Keep sample `seq`'s value (sample `seq` of the row is one of pixel `seq / spp`), then sum
    /// every finished sample from `commit` on, in order, into its pixel.
    #[inline]
    pub(crate) fn finish(
        &mut self,
        seq: u64,
        value: Color,
        spp: u64,
        row: &mut Row<'_>,
        stats: &mut Stats,
    ) {
        let slot = (seq % RING as u64) as usize;
        self.value[slot] = value;
        self.done[slot] = true;
        loop {
            let slot = (self.commit % RING as u64) as usize;
            if !self.done[slot] {
                break;
            }
            self.done[slot] = false;
            let i = self.pixel;
            let v = self.value[slot];
            if !Accumulator::add(&mut row.sum[i], &mut row.count[i], &mut row.dropped[i], v) {
                stats.non_finite += 1;
            }
            self.commit += 1;
            self.left -= 1;
            if self.left == 0 {
                (self.pixel, self.left) = (i + 1, spp);
            }
        }
    }
}

/// A row of the accumulation buffer.
struct Row<'a> {
    sum: &'a mut [Color],
    count: &'a mut [u64],
    dropped: &'a mut [u64],
}

/// A row's samples for paths traced side by side (here and in [`crate::mis8`]): started in the
/// order of `(pixel, k)`, one on each idle lane, and summed into their pixels in that order
/// whenever they end ([`Ring`]).
pub(crate) struct RowSamples<'a> {
    row: Row<'a>,
    ring: Ring,
    stats: Stats,
    j: usize,
    k0: u64,
    k1: u64,
    spp: u64,
    total: u64,
    /// The next sample to start, in the row's order; its pixel and sample, `(next / spp, k0 +
    /// next % spp)`, counted rather than divided out.
    next: u64,
    next_i: usize,
    next_k: u64,
    /// The scramble key of the pixel whose samples are being started, made at its first.
    key: u64,
}

impl<'a> RowSamples<'a> {
    /// Samples `k0..k1` of each pixel of row `j`, summed into `sum`, `count` and `dropped`.
    pub(crate) fn new(
        j: usize,
        k0: u64,
        k1: u64,
        sum: &'a mut [Color],
        count: &'a mut [u64],
        dropped: &'a mut [u64],
    ) -> Self {
        let spp = k1.saturating_sub(k0);
        RowSamples {
            total: sum.len() as u64 * spp,
            row: Row {
                sum,
                count,
                dropped,
            },
            ring: Ring::new(spp),
            stats: Stats::default(),
            j,
            k0,
            k1,
            spp,
            next: 0,
            next_i: 0,
            next_k: k0,
            key: 0,
        }
    }

    /// The next sample begun in `ctx`, counted as its path's first ray: its number in the row's
    /// order and its camera ray. `Some(None)` if no sample is left or the ring has no room for
    /// one; `None` if `stop()` (asked before each pixel's first sample) said to stop. A sample
    /// allowed no intersection at all (`max_depth` 0) is black, and summed at once.
    #[inline]
    pub(crate) fn start(
        &mut self,
        r: &Renderer,
        ctx: &mut Ctx,
        stop: &(dyn Fn() -> bool + Sync),
    ) -> Option<Option<(u64, Ray)>> {
        while self.next < self.total && self.next - self.ring.commit < RING as u64 {
            let (i, k) = (self.next_i, self.next_k);
            (self.next_i, self.next_k) = if k + 1 == self.k1 {
                (i + 1, self.k0)
            } else {
                (i, k + 1)
            };
            if k == self.k0 {
                if stop() {
                    return None;
                }
                self.key = r.pixel_key_of(i, self.j);
            }
            let ray = r.start_sample_keyed(i, self.j, k, self.key, ctx);
            let seq = self.next;
            self.next += 1;
            if r.settings.max_depth > 0 {
                ctx.stats.rays += 1;
                ctx.bounce = 0;
                return Some(Some((seq, ray)));
            }
            self.finish(seq, Color::ZERO, ctx);
        }
        Some(None)
    }

    /// Sample `seq`, traced in `ctx`, ends with `value`.
    #[inline]
    pub(crate) fn finish(&mut self, seq: u64, value: Color, ctx: &mut Ctx) {
        Renderer::finish_sample(ctx);
        let (spp, row, stats) = (self.spp, &mut self.row, &mut self.stats);
        self.ring.finish(seq, value, spp, row, stats);
    }

    /// The counters of the row: those of its samples' `ctxs` and the non-finite samples dropped.
    pub(crate) fn stats<'c>(self, ctxs: impl Iterator<Item = &'c Ctx>) -> Stats {
        ctxs.fold(self.stats, |s, c| s + c.stats)
    }
}

/// [`Renderer::render_pass_until`]'s work on row `j`: samples `k0..k1` of each of its pixels,
/// [`PACKETS`] times eight paths at a time; `None` if `stop()` (asked before each pixel's first
/// sample) said to stop.
/// Called only where [`applies`] said so (an AVX tier runs).
#[cfg(target_arch = "x86_64")]
#[allow(clippy::too_many_arguments)]
pub(crate) fn render_row(
    r: &Renderer,
    j: usize,
    k0: u64,
    k1: u64,
    sum: &mut [Color],
    count: &mut [u64],
    dropped: &mut [u64],
    stop: &(dyn Fn() -> bool + Sync),
) -> Option<Stats> {
    let scene = r.scene;
    let (strategy, weight) = (r.settings.strategy, r.settings.mixture_weight);
    let max_depth = r.settings.max_depth;
    let mut samples = RowSamples::new(j, k0, k1, sum, count, dropped);
    // Everything per path is indexed `[g][l]`: packet `g`, lane `l`.
    let mut ctxs: [[Ctx; LANES]; PACKETS] =
        std::array::from_fn(|_| std::array::from_fn(|_| Ctx::new()));
    let placeholder = Ray::new(Point3::ZERO, Vec3::X, 0.0);
    let mut paths = [[OneSamplePath::default(); LANES]; PACKETS];
    let mut seqs = [[0u64; LANES]; PACKETS];
    let mut rays = [[placeholder; LANES]; PACKETS];
    let mut lanes = [Rays8::default(); PACKETS];
    let mixture = r.mixture_in_lanes();
    let tier = crate::traversal::HitTier::current();
    let mut shading = Shading8::default();
    let mut hits: [Option<crate::hit::Hit>; LANES] = [None; LANES];
    let mut attenuations = [Color::ZERO; LANES];
    let mut per_lane = [[crate::traversal::Found::NOTHING; LANES]; PACKETS];
    let mut closest = [crate::ray8::Closest8::default(); PACKETS];
    // The Lambertian vertex in the lanes ([`crate::vertex8`]): the paths' throughputs kept
    // there too (lane by lane in `paths` only around a vertex computed one path at a time), and the
    // lanes' rays in `lanes` (`rays` keeps each ray's time, and its origin and direction are
    // brought up to date before a vertex is computed one path at a time).
    let surfaces = r.lambertian_vertex_in_lanes();
    let mut throughput = [[F64x8::ZERO; 3]; PACKETS];
    let mut active = [0u8; PACKETS];
    // The paths whose ray met a Lambertian quad, waiting for the vertex in the lanes (their
    // quads' numbers and `t` kept in `met`), and the batch of up to eight of them gathered for it.
    let mut pending = [0u8; PACKETS];
    let mut met = [crate::ray8::Closest8::default(); PACKETS];
    let mut batch = Batch::default();
    // The glass vertex in the lanes ([`crate::glass8`]): the paths whose ray met a glass sphere,
    // gathered from all the packets (`glass_from[i]` is batch lane `i % 8` of `glass_batch[i / 8]`).
    let glass = r.glass_vertex_in_lanes();
    let mut glass_batch = [crate::glass8::Glass8::default(); PACKETS];
    let mut glass_from = [(0usize, 0usize); PACKETS * LANES];
    let mut glass_n = 0;
    loop {
        // Each idle path takes the row's next sample, if the ring has room for it.
        for g in 0..PACKETS {
            let mut idle = !active[g];
            while idle != 0 {
                let l = idle.trailing_zeros() as usize;
                idle &= idle - 1;
                let Some((seq, ray)) = samples.start(r, &mut ctxs[g][l], stop)? else {
                    break;
                };
                // (field by field: a whole new path written at once was read back across its
                // stores, which cannot forward to the load)
                let path = &mut paths[g][l];
                path.throughput = Color::ONE;
                path.l = Color::ZERO;
                path.depth = 0;
                for t in &mut throughput[g] {
                    t.0[l] = 1.0;
                }
                seqs[g][l] = seq;
                rays[g][l] = ray;
                lanes[g].set(l, &ray);
                active[g] |= 1 << l;
            }
        }
        if active == [0; PACKETS] {
            break;
        }
        // the paths left waiting by the last batch, which go first in this one
        let waited = pending;
        for g in 0..PACKETS {
            // (a path waiting for its Lambertian vertex has no new ray to trace)
            let traced = active[g] & !pending[g];
            if traced == 0 {
                continue;
            }
            // SAFETY: `applies` chose this form only where the processor runs an AVX tier.
            let found = unsafe {
                scene.hit8_small(
                    tier,
                    GroupId(0),
                    &rays[g],
                    &lanes[g],
                    traced,
                    Interval::FORWARD,
                    &mut ctxs[g],
                    &mut closest[g],
                    &mut per_lane[g],
                )
            };
            let (lanes, throughput) = (&mut lanes[g], &mut throughput[g]);
            let (ctxs, paths, rays) = (&mut ctxs[g], &mut paths[g], &mut rays[g]);
            let (closest, active, seqs) = (&closest[g], &mut active[g], &seqs[g]);
            // A path that goes on takes its next ray; one that ends is summed into its pixel.
            macro_rules! advance {
                ($l:expr, $next:expr) => {{
                    let l = $l;
                    let (path, ctx) = (&paths[l], &mut ctxs[l]);
                    match $next {
                        Some(next) if path.depth < max_depth => {
                            ctx.stats.rays += 1;
                            ctx.bounce = path.depth;
                            rays[l] = next;
                            lanes.set(l, &next);
                            for (a, t) in throughput.iter_mut().enumerate() {
                                t.0[l] = path.throughput[a];
                            }
                        }
                        _ => {
                            *active &= !(1 << l);
                            samples.finish(seqs[l], path.l, ctx);
                        }
                    }
                }};
            }
            // The paths whose vertex is Lambertian on a quad of constant albedo wait for the
            // batch, with their quads' numbers.
            let mut lambertian = 0u8;
            if let Some(s) = surfaces {
                // (the set made without a branch per lane: which kind a lane met is a coin toss)
                lambertian = s.lambertian_lanes(&closest.hit) & traced;
                let met = &mut met[g];
                let mut bits = lambertian;
                while bits != 0 {
                    let l = bits.trailing_zeros() as usize;
                    bits &= bits - 1;
                    met.hit[l] = closest.hit[l];
                    met.t[l] = closest.t[l];
                }
                pending[g] |= lambertian;
            }
            // The paths whose ray met a glass sphere go to the glass batch, with the uniform
            // numbers of their vertex (drawn after the batch, where the vertex asked for them),
            // where the lanes take them (`GlassSpheres::error`).
            let mut glassy = 0u8;
            if let Some(gs) = glass {
                glassy = gs.glass_lanes(&closest.hit) & traced & !lambertian;
                let mut bits = glassy;
                while bits != 0 {
                    let l = bits.trailing_zeros() as usize;
                    bits &= bits - 1;
                    let h = closest.hit[l];
                    let sphere = gs.sphere(h).expect("a glass lane's sphere");
                    let (ray, t) = (lanes.ray(l, rays[l].time), closest.t[l]);
                    let Some(err) = crate::glass8::GlassSpheres::error(sphere, &ray, t) else {
                        glassy &= !(1 << l);
                        continue;
                    };
                    let u = ctxs[l].peek_1d(Dimension::Material(ctxs[l].bounce));
                    // (`OneSamplePath::scatter` counts the depth first)
                    paths[l].depth += 1;
                    let (b, i) = (glass_n / LANES, glass_n % LANES);
                    let batch = &mut glass_batch[b];
                    (batch.sphere[i], batch.t[i]) = (h & !crate::ray8::SPHERE, t);
                    (batch.err[i], batch.u[i]) = (err, u);
                    batch.rays.set(i, &ray);
                    glass_from[glass_n] = (g, l);
                    glass_n += 1;
                }
            }
            // The paths whose ray met a light of constant radiance gather it and end there
            // (`OneSamplePath::scatter` without the hit's record).
            let mut lit = 0u8;
            if let Some(s) = surfaces {
                lit = s.light_lanes(&closest.hit) & traced & !lambertian & !glassy;
                let mut bits = lit;
                while bits != 0 {
                    let l = bits.trailing_zeros() as usize;
                    bits &= bits - 1;
                    if let Some(light) = s.light(closest.hit[l]) {
                        let at = |v: &[F64x8; 3]| Vec3::new(v[0].0[l], v[1].0[l], v[2].0[l]);
                        let emitted = light.emitted(at(&lanes.direction));
                        paths[l].l += at(throughput) * emitted;
                        advance!(l, Option::<Ray>::None);
                    }
                }
            }
            // Every other path's vertex up to its diffuse direction; Lambertian bounces of
            // `mixture` wait for the lanes.
            let mut waiting = 0u8;
            let mut bits = traced & !lambertian & !glassy & !lit;
            while bits != 0 {
                let l = bits.trailing_zeros() as usize;
                bits &= bits - 1;
                let ray = if surfaces.is_some() {
                    // the lanes hold the ray and the throughput (`rays[l]` the ray's time)
                    paths[l].throughput =
                        Color::new(throughput[0].0[l], throughput[1].0[l], throughput[2].0[l]);
                    lanes.ray(l, rays[l].time)
                } else {
                    rays[l]
                };
                let hit = found.record(closest, &per_lane[g], l, &ray);
                let next = match paths[l].scatter(scene, &ray, hit.as_ref(), &mut ctxs[l]) {
                    None => None,
                    Some(Bounce::Along(next)) => Some(next),
                    Some(Bounce::Diffuse {
                        attenuation,
                        pdf: ScatterPdf::Cosine(_),
                        u,
                    }) if mixture.is_some() => {
                        let hit = hit.expect("a diffuse bounce has a hit");
                        shading.set(l, hit.p, hit.normal, u);
                        (hits[l], attenuations[l]) = (Some(hit), attenuation);
                        waiting |= 1 << l;
                        continue;
                    }
                    Some(Bounce::Diffuse {
                        attenuation,
                        pdf,
                        u,
                    }) => {
                        let hit = hit.expect("a diffuse bounce has a hit");
                        let lights = &r.lights;
                        sample_diffuse(strategy, weight, &pdf, hit.p, hit.normal, lights, u)
                            .and_then(|(direction, w)| {
                                paths[l].diffuse(&hit, &ray, attenuation, direction, w)
                            })
                    }
                };
                advance!(l, next);
            }
            if let (Some(m), true) = (mixture, waiting != 0) {
                // SAFETY: `applies` chose this form only where the processor runs an AVX tier.
                let (direction, w) = unsafe { shading.mixture(tier, m, waiting) };
                let mut bits = waiting;
                while bits != 0 {
                    let l = bits.trailing_zeros() as usize;
                    bits &= bits - 1;
                    let next = match (w[l], &hits[l]) {
                        (Some(w), Some(hit)) => {
                            paths[l].diffuse(hit, &rays[l], attenuations[l], direction[l], w)
                        }
                        _ => None,
                    };
                    advance!(l, next);
                }
            }
        }
        // The glass batches: each path goes on with its next ray (its throughput unchanged).
        if let Some(gs) = glass {
            for (b, batch) in glass_batch.iter_mut().enumerate() {
                let n = glass_n.saturating_sub(b * LANES).min(LANES);
                if n == 0 {
                    break;
                }
                // SAFETY: `applies` chose this form only where the processor runs an AVX tier.
                let asked =
                    unsafe { crate::glass8::dielectric(tier, gs, batch, ((1u16 << n) - 1) as u8) };
                for (i, &(g, l)) in glass_from[b * LANES..b * LANES + n].iter().enumerate() {
                    let (path, ctx) = (&paths[g][l], &mut ctxs[g][l]);
                    if asked & (1 << i) != 0 {
                        ctx.take_1d(Dimension::Material(ctx.bounce));
                    }
                    if path.depth < max_depth {
                        ctx.stats.rays += 1;
                        ctx.bounce = path.depth;
                        let lanes = &mut lanes[g];
                        for a in 0..3 {
                            lanes.origin[a].0[l] = batch.rays.origin[a].0[i];
                            lanes.direction[a].0[l] = batch.rays.direction[a].0[i];
                        }
                    } else {
                        active[g] &= !(1 << l);
                        samples.finish(seqs[g][l], path.l, ctx);
                    }
                }
            }
            glass_n = 0;
        }
        let (Some(s), Some(m)) = (surfaces, mixture) else {
            continue;
        };
        // Batches of up to eight waiting paths (those that waited already first), their bounce's
        // numbers drawn (as `OneSamplePath::scatter` draws them, after the depth is counted),
        // until fewer than `DEFER` are left: those wait for the next round.
        let mut waited = waited;
        let mut least = 1;
        loop {
            let left: u32 = pending.iter().map(|p| p.count_ones()).sum();
            if left < least {
                break;
            }
            least = SECOND_BATCH;
            let mut n = 0;
            for from in [waited, pending] {
                for g in 0..PACKETS {
                    let mut bits = from[g] & pending[g];
                    while bits != 0 && n < LANES {
                        let l = bits.trailing_zeros() as usize;
                        bits &= bits - 1;
                        pending[g] &= !(1 << l);
                        let depth = paths[g][l].depth;
                        paths[g][l].depth += 1;
                        let u = ctxs[g][l].sample_2d(Dimension::Material(depth));
                        batch.gather(n, (g, l), u, &met[g], &lanes[g], &throughput[g]);
                        n += 1;
                    }
                }
            }
            waited = [0; PACKETS];
            // SAFETY: `applies` chose this form only where the processor runs an AVX tier.
            let go = unsafe {
                crate::vertex8::lambertian(
                    tier,
                    s,
                    m,
                    &batch.met,
                    &mut batch.rays,
                    &mut batch.throughput,
                    &batch.u,
                    ((1u16 << n) - 1) as u8,
                )
            };
            for (b, &(g, l)) in batch.from.iter().enumerate().take(n) {
                let (path, ctx) = (&paths[g][l], &mut ctxs[g][l]);
                if go & (1 << b) != 0 && path.depth < max_depth {
                    ctx.stats.rays += 1;
                    ctx.bounce = path.depth;
                    batch.scatter(b, &mut lanes[g], &mut throughput[g], l);
                } else {
                    active[g] &= !(1 << l);
                    samples.finish(seqs[g][l], path.l, ctx);
                }
            }
        }
    }
    Some(samples.stats(ctxs.iter().flatten()))
}

/// A batch of Lambertian vertices for [`crate::vertex8`], gathered lane by lane from the paths
/// that wait for one: batch lane `b` is the path `from[b]` (packet, lane), with its quad's number
/// and `t`, its ray, its throughput and its bounce's two numbers.
struct Batch {
    from: [(usize, usize); LANES],
    met: crate::ray8::Closest8,
    rays: Rays8,
    throughput: [F64x8; 3],
    u: [F64x8; 2],
}

impl Default for Batch {
    fn default() -> Self {
        Batch {
            from: [(0, 0); LANES],
            met: crate::ray8::Closest8::default(),
            rays: Rays8::default(),
            throughput: [F64x8::ZERO; 3],
            u: [F64x8::ZERO; 2],
        }
    }
}

impl Batch {
    /// Batch lane `b` takes path `(g, l)`: its quad's number and `t` from `met`, its ray from
    /// `rays`, its throughput, and the bounce's numbers `u`.
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // (three arrays, one coordinate at a time)
    fn gather(
        &mut self,
        b: usize,
        (g, l): (usize, usize),
        u: glam::DVec2,
        met: &crate::ray8::Closest8,
        rays: &Rays8,
        throughput: &[F64x8; 3],
    ) {
        self.from[b] = (g, l);
        self.met.hit[b] = met.hit[l];
        self.met.t[b] = met.t[l];
        for a in 0..3 {
            self.rays.origin[a].0[b] = rays.origin[a].0[l];
            self.rays.direction[a].0[b] = rays.direction[a].0[l];
            self.throughput[a].0[b] = throughput[a].0[l];
        }
        (self.u[0].0[b], self.u[1].0[b]) = (u.x, u.y);
    }

    /// Batch lane `b`'s next ray and throughput back to lane `l` of its packet.
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // (three arrays, one coordinate at a time)
    fn scatter(&self, b: usize, rays: &mut Rays8, throughput: &mut [F64x8; 3], l: usize) {
        for a in 0..3 {
            rays.origin[a].0[l] = self.rays.origin[a].0[b];
            rays.direction[a].0[l] = self.rays.direction[a].0[b];
            throughput[a].0[l] = self.throughput[a].0[b];
        }
    }
}

/// The Lambertian points waiting for the mixture's directions, by coordinate: point, unit normal,
/// and the bounce's two numbers.
#[derive(Default)]
struct Shading8 {
    p: [F64x8; 3],
    normal: [F64x8; 3],
    u: [F64x8; 2],
}

impl Shading8 {
    /// Lane `l`'s point `p`, normal and numbers `u`.
    #[inline(always)]
    fn set(&mut self, l: usize, p: Vec3, normal: Vec3, u: glam::DVec2) {
        for a in 0..3 {
            self.p[a].0[l] = p[a];
            self.normal[a].0[l] = normal[a];
        }
        self.u[0].0[l] = u.x;
        self.u[1].0[l] = u.y;
    }

    /// The mixture's direction and weight `s / p` in each lane of `lanes` ([`Mixture8`]), in the
    /// instructions of `tier`; `None` where the path ends.
    ///
    /// # Safety
    /// Only where the processor runs `tier`, which is AVX2 or AVX-512.
    #[cfg(target_arch = "x86_64")]
    unsafe fn mixture(
        &self,
        tier: crate::traversal::HitTier,
        m: &Mixture8,
        lanes: u8,
    ) -> ([Vec3; LANES], [Option<f64>; LANES]) {
        // SAFETY: as this function's.
        let (d, weight, ok) = unsafe { m.sample(tier, &self.p, &self.normal, &self.u, lanes) };
        (
            std::array::from_fn(|l| Vec3::new(d[0].0[l], d[1].0[l], d[2].0[l])),
            std::array::from_fn(|l| (ok & (1 << l) != 0).then_some(weight.0[l])),
        )
    }
}
