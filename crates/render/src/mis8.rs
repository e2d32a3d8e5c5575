//! Thirty-two `mis` paths side by side, in four packets of eight (as [`crate::paths8`]'s, for the
//! same reason): next-event estimation with multiple importance sampling (the integrator's
//! `MisPath`: `radiance_mis`'s loop a vertex at a time) traced for 32 samples at once, each
//! packet's rays intersected together in the lanes of
//! vector registers ([`crate::ray8`]), as [`crate::paths8`] does for the book's one-sample
//! strategies.
//!
//! A `mis` vertex asks for two rays: its light sample's shadow ray and the path's next ray. A
//! lane traces them one after the other: the shadow ray in one round, its emission added when it
//! comes back, then the next ray in the following round (so every packet's lanes hold one kind of
//! ray or the other, mixed as the paths happen to be). A vertex on a Lambertian quad of constant
//! albedo (where the scene has one emitter and other targets: the Cornell box) is computed in the
//! lanes, such vertices of all the packets gathered eight at a time ([`crate::mis_vertex8`]): its
//! light sample, its material sample, their weights and the numbers they draw; a shadow ray that
//! meets a light of constant radiance, a Lambertian quad or nothing is read without building its
//! hit's record. Every other vertex is computed on its own, as one path at a time computes it,
//! with the lane's own numbers ([`crate::sampler::Ctx`]); the rays'
//! hits are the ones [`Scene::hit`] finds, bit for bit ([`Scene::hit8_small`]). Only scenes
//! without media take this form (a shadow ray through a medium records what it crosses, a ray
//! through one may scatter in it: both one ray at a time), and each pixel's samples are summed in
//! the order of `k` (`paths8`'s `RowSamples`): the image is bit-identical to tracing one path at a time
//! (tested in `crates/render/tests/paths8.rs`).

use crate::integrator::Strategy;
use crate::scene::{GroupId, Scene};
#[cfg(target_arch = "x86_64")]
use crate::{
    integrator::{MisPath, MisStep, MisVariant, MisVertex},
    lanes::F64x8,
    material::Material,
    mis_vertex8::{MisIn, MisOut},
    paths8::{LANES, RowSamples},
    ray::{Interval, Ray},
    ray8::NO_HIT,
    ray8::Rays8,
    render::Renderer,
    sampler::{Ctx, Dimension, PaddedIndex, Stats, points_2d_avx2},
    vec::{Color, Point3, Vec3},
};

use crate::paths8::PACKETS;

/// Whether a render of `scene` by `strategy` traces `mis` paths side by side in the lanes: for
/// `mis`, in a scene without media whose rays meet a small group, on a processor with AVX2 or
/// AVX-512 ([`Scene::hits_eight_at_once`]).
pub fn applies(scene: &Scene, strategy: Strategy) -> bool {
    matches!(strategy, Strategy::Mis(_))
        && scene.features.media == 0
        && scene.hits_eight_at_once(GroupId(0))
}

/// A batch of up to eight Lambertian vertices gathered from the packets for the lanes: their
/// quads' hits, their rays, their throughputs, their numbers, and the lanes that take a light
/// sample.
#[cfg(target_arch = "x86_64")]
#[derive(Clone, Copy, Default)]
struct MisBatch {
    found: crate::ray8::Closest8,
    rays: Rays8,
    throughput: [F64x8; 3],
    u_light: [F64x8; 2],
    u_material: [F64x8; 2],
    light: u8,
    /// Low-discrepancy numbers: each lane's sample and pairs, computed for the batch at once.
    light_index: [PaddedIndex; LANES],
    light_pair: [u32; LANES],
    material_index: [PaddedIndex; LANES],
    material_pair: [u32; LANES],
}

#[cfg(target_arch = "x86_64")]
impl MisBatch {
    /// Lane `l` of a packet (what it met, `found`, its ray in `rays`, its `throughput`) into
    /// batch lane `i`.
    #[inline(always)]
    fn take(
        &mut self,
        i: usize,
        found: &crate::ray8::Closest8,
        rays: &Rays8,
        l: usize,
        throughput: Color,
    ) {
        self.found.hit[i] = found.hit[l];
        self.found.t[i] = found.t[l];
        for a in 0..3 {
            self.rays.origin[a].0[i] = rays.origin[a].0[l];
            self.rays.direction[a].0[i] = rays.direction[a].0[l];
            self.throughput[a].0[i] = throughput[a];
        }
    }
}

/// [`Renderer::render_pass_until`]'s work on row `j` for `mis`: samples `k0..k1` of each of its
/// pixels, [`PACKETS`] times eight paths at a time; `None` if `stop()` (asked before each pixel's
/// first sample) said to stop. Called only where [`applies`] said so (an AVX tier runs).
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
    let (scene, lights) = (r.scene, &r.lights);
    let options = r
        .settings
        .strategy
        .mis_options()
        .expect("mis8 renders only `mis`");
    let max_depth = r.settings.max_depth;
    // crossing connections through a glass ball at the lanes' vertices (the one-path vertex makes
    // its own)
    let crossing = options.manifold && !lights.manifold.crossable.is_empty();
    let mut samples = RowSamples::new(j, k0, k1, sum, count, dropped);
    // Everything per path is indexed `[g][l]`: packet `g`, lane `l`.
    let mut ctxs: [[Ctx; LANES]; PACKETS] =
        std::array::from_fn(|_| std::array::from_fn(|_| Ctx::new()));
    let placeholder = Ray::new(Point3::ZERO, Vec3::X, 0.0);
    let mut paths = [[MisPath::default(); LANES]; PACKETS];
    // the bounce of the vertex each path's ray (or the shadow ray of whose vertex) is traced for
    let mut depths = [[0u32; LANES]; PACKETS];
    let mut seqs = [[0u64; LANES]; PACKETS];
    let mut rays = [[placeholder; LANES]; PACKETS];
    // a lane tracing a shadow ray keeps its path's next ray here (`None`: the path ends after it)
    let mut after_shadow = [[None::<Ray>; LANES]; PACKETS];
    let mut shadows = [0u8; PACKETS];
    let mut lanes = [Rays8::default(); PACKETS];
    let tier = crate::traversal::HitTier::current();
    let mut per_lane = [[crate::traversal::Found::NOTHING; LANES]; PACKETS];
    let mut closest = [crate::ray8::Closest8::default(); PACKETS];
    let mut active = [0u8; PACKETS];
    // The Lambertian vertex in the lanes ([`crate::mis_vertex8`]), in batches of eight gathered
    // from all the packets: the batches' hits, rays, throughputs and numbers, their answers, each
    // path's place in them (`slot[g][l] = n`: lane `n % 8` of batch `n / 8`) and which paths of
    // each packet are in one.
    let in_lanes = r.mis_vertex_in_lanes();
    // (every sample of a render draws its numbers the same way)
    let lds = r.low_discrepancy();
    let mut batch = [MisBatch::default(); PACKETS];
    let mut out = [MisOut::default(); PACKETS];
    let mut slot = [[0u8; LANES]; PACKETS];
    let mut in_batch = [0u8; PACKETS];
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
                paths[g][l] = MisPath::default();
                depths[g][l] = 0;
                seqs[g][l] = seq;
                rays[g][l] = ray;
                lanes[g].set(l, &ray);
                active[g] |= 1 << l;
            }
        }
        if active == [0; PACKETS] {
            break;
        }
        // Every packet's rays intersected.
        let mut found: [Option<_>; PACKETS] = std::array::from_fn(|_| None);
        for g in 0..PACKETS {
            if active[g] == 0 {
                continue;
            }
            // SAFETY: `applies` chose this form only where the processor runs an AVX tier.
            found[g] = Some(unsafe {
                scene.hit8_small(
                    tier,
                    GroupId(0),
                    &rays[g],
                    &lanes[g],
                    active[g],
                    Interval::FORWARD,
                    &mut ctxs[g],
                    &mut closest[g],
                    &mut per_lane[g],
                )
            });
        }
        // The paths whose ray met a Lambertian quad of constant albedo, outside any dielectric,
        // gathered into batches for their vertex in the lanes, with the numbers one path at a
        // time would draw there (the light sample's pair, the bounce's): low-discrepancy pairs
        // computed for the whole batch, else drawn lane by lane in that order.
        if let Some((surfaces, mis)) = in_lanes {
            let mut n = 0usize;
            for g in 0..PACKETS {
                let mut lambertian =
                    surfaces.lambertian_lanes(&closest[g].hit) & active[g] & !shadows[g];
                let mut bits = lambertian;
                while bits != 0 {
                    let l = bits.trailing_zeros() as usize;
                    bits &= bits - 1;
                    let path = &paths[g][l];
                    if !path.takes_light_samples() {
                        lambertian &= !(1 << l);
                        continue;
                    }
                    let (b, i) = (n / LANES, n % LANES);
                    let (into, ctx, depth) = (&mut batch[b], &mut ctxs[g][l], depths[g][l]);
                    into.take(i, &closest[g], &lanes[g], l, path.throughput);
                    let (light, material) = (Dimension::Light(depth), Dimension::Material(depth));
                    if lds {
                        // (computed for the whole batch below)
                        if depth + 1 < max_depth {
                            (into.light_index[i], into.light_pair[i]) = ctx.defer_2d(light);
                            into.light |= 1 << i;
                        }
                        (into.material_index[i], into.material_pair[i]) = ctx.defer_2d(material);
                    } else {
                        if depth + 1 < max_depth {
                            let u = ctx.sample_2d(light);
                            (into.u_light[0].0[i], into.u_light[1].0[i]) = (u.x, u.y);
                            into.light |= 1 << i;
                        }
                        let u = ctx.sample_2d(material);
                        (into.u_material[0].0[i], into.u_material[1].0[i]) = (u.x, u.y);
                    }
                    slot[g][l] = n as u8;
                    n += 1;
                }
                in_batch[g] = lambertian;
            }
            for (b, (batch, out)) in batch.iter_mut().zip(&mut out).enumerate() {
                let count = n.saturating_sub(b * LANES).min(LANES);
                if count == 0 {
                    break;
                }
                if lds {
                    // SAFETY: `applies` chose this form only where the processor runs an AVX tier.
                    unsafe {
                        let (x, y) = points_2d_avx2(&batch.light_index, &batch.light_pair);
                        batch.u_light = [x, y];
                        let (x, y) = points_2d_avx2(&batch.material_index, &batch.material_pair);
                        batch.u_material = [x, y];
                    }
                }
                let input = MisIn {
                    surfaces,
                    found: &batch.found,
                    rays: &batch.rays,
                    throughput: &batch.throughput,
                    u_light: &batch.u_light,
                    u_material: &batch.u_material,
                };
                let all = ((1u16 << count) - 1) as u8;
                // SAFETY: `applies` chose this form only where the processor runs an AVX tier.
                unsafe { mis.vertex(tier, &input, all, batch.light, out) };
                batch.light = 0;
            }
        }
        let at = |v: &[F64x8; 3], i: usize| Vec3::new(v[0].0[i], v[1].0[i], v[2].0[i]);
        for g in 0..PACKETS {
            let traced = active[g];
            let Some(found) = found[g].as_ref() else {
                continue;
            };
            let (ctxs, paths, rays, lanes) =
                (&mut ctxs[g], &mut paths[g], &mut rays[g], &mut lanes[g]);
            let (depths, after_shadow, shadows) =
                (&mut depths[g], &mut after_shadow[g], &mut shadows[g]);
            let (active, seqs) = (&mut active[g], &seqs[g]);
            let (in_batch, slot) = (in_batch[g], &slot[g]);
            let mut bits = traced;
            while bits != 0 {
                let l = bits.trailing_zeros() as usize;
                bits &= bits - 1;
                let ctx = &mut ctxs[l];
                let next = if *shadows & (1 << l) != 0 {
                    *shadows &= !(1 << l);
                    let h = closest[g].hit[l];
                    match in_lanes {
                        // a light of constant radiance, a Lambertian quad, nothing: no record
                        Some((s, _)) if s.light(h).is_some() || s.lambertian(h) || h == NO_HIT => {
                            let light = s.light(h);
                            paths[l].shadow_met(light.map(|q| q.emitted(rays[l].direction)));
                        }
                        _ => {
                            let hit = found.record(&closest[g], &per_lane[g], l, &rays[l]);
                            // (no media: nothing is crossed, the transmittance is 1)
                            paths[l].shadow_arrived(scene, hit.as_ref().map(|h| (h, 1.0)), ctx);
                        }
                    }
                    after_shadow[l]
                } else {
                    let step = if in_batch & (1 << l) != 0 {
                        let n = slot[l] as usize;
                        let (out, i) = (&out[n / LANES], n % LANES);
                        let waiting = (out.shadow & (1 << i) != 0)
                            .then(|| (at(&out.carried, i), out.weight.0[i]));
                        let bounce = (out.next & (1 << i) != 0)
                            .then(|| (at(&out.throughput, i), at(&out.p, i), out.pdf.0[i]));
                        let time = rays[l].time;
                        // The crossing connection, where glass can focus light here: one path at a
                        // time, from the vertex's record.
                        let crossed = if crossing
                            && depths[l] + 3 < max_depth
                            && lights.manifold.reaches_any(at(&out.p, i))
                        {
                            found
                                .record(&closest[g], &per_lane[g], l, &rays[l])
                                .and_then(|hit| {
                                    let albedo = match &scene.materials[hit.material.index()] {
                                        Material::Lambertian { albedo } => {
                                            albedo.value(&hit, &scene.textures, ctx)
                                        }
                                        _ => unreachable!("the lanes' vertices are Lambertian"),
                                    };
                                    let at = MisVertex {
                                        depth: depths[l],
                                        max_depth,
                                        samples_lights: true,
                                        options,
                                        variant: MisVariant::Book,
                                    };
                                    paths[l].crossing_from_lanes(
                                        scene, lights, &hit, albedo, time, &at, ctx,
                                    )
                                })
                        } else {
                            None
                        };
                        let goes_on = paths[l].lambertian_from_lanes(
                            waiting, bounce, crossed, depths[l], options, ctx,
                        );
                        MisStep {
                            shadow: waiting.map(|_| {
                                Ray::new(
                                    at(&out.shadow_origin, i),
                                    at(&out.shadow_direction, i),
                                    time,
                                )
                            }),
                            next: goes_on.then(|| {
                                Ray::new(at(&out.next_origin, i), at(&out.next_direction, i), time)
                            }),
                        }
                    } else {
                        let hit = found.record(&closest[g], &per_lane[g], l, &rays[l]);
                        let vertex = MisVertex {
                            depth: depths[l],
                            max_depth,
                            samples_lights: true,
                            options,
                            variant: MisVariant::Book,
                        };
                        paths[l].vertex(scene, lights, &rays[l], hit.as_ref(), vertex, ctx)
                    };
                    if let Some(shadow) = step.shadow {
                        ctx.stats.rays += 1;
                        rays[l] = shadow;
                        lanes.set(l, &shadow);
                        after_shadow[l] = step.next;
                        *shadows |= 1 << l;
                        continue;
                    }
                    step.next
                };
                // The path goes on with its next ray, within its depth, or is summed into its pixel.
                match next {
                    Some(ray) if depths[l] + 1 < max_depth => {
                        depths[l] += 1;
                        ctx.stats.rays += 1;
                        ctx.bounce = depths[l];
                        rays[l] = ray;
                        lanes.set(l, &ray);
                    }
                    _ => {
                        *active &= !(1 << l);
                        samples.finish(seqs[l], paths[l].l, ctx);
                    }
                }
            }
        }
    }
    Some(samples.stats(ctxs.iter().flatten()))
}
