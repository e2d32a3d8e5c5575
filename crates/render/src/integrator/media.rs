//! Paths and shadow rays through participating media of constant density: a shadow ray's exact
//! transmittance, distance sampling per medium, the light scattered along a whole path segment
//! estimated at one equiangular point, and forced scattering on camera rays that would leave the
//! scene through a medium.

use super::ROULETTE_AFTER;
use super::equiangular::Equiangular;
use super::mis::{MisVariant, VertexPdf, emitter_seen, light_sample};
use crate::hit::Hit;
use crate::lights::{LightTarget, Lights};
use crate::material::Scatter;
use crate::media_crossed::{MediaCrossed, MediumMode};
use crate::ray::{Interval, Ray};
use crate::sampler::{Ctx, Dimension};
use crate::scene::{GroupId, Scene};
use crate::traversal::free_point_surely_beyond;
use crate::vec::{Color, Point3, Vec3};
use rtl_pdf::HittablePdf;

// ANCHOR: shadow_ray
/// What a shadow ray meets: the first surface along `ray`, and the transmittance of the media before
/// it, `exp(-sum_i sigma_i l_i)` for constant media of density `sigma_i` crossed over length `l_i`.
///
/// The transmittance is computed exactly, not estimated: a constant medium's is known in closed form,
/// so a shadow ray needs no random number and adds no variance (a delta-tracking or track-length
/// estimate would be 0 or 1 at random, with variance `T (1 - T)`; ratio tracking is for media whose
/// density varies). One traversal: media let the ray through and record where it was inside them
/// (the BVH never skips a medium that starts before the closest surface), and the stretches are
/// clipped at the surface found. Only if more media were crossed than can be recorded without
/// allocating is the traversal repeated up to the surface.
#[inline]
pub(crate) fn trace_shadow(scene: &Scene, ray: &Ray, ctx: &mut Ctx) -> Option<(Hit, f64)> {
    ctx.stats.rays += 1;
    if scene.features.media == 0 {
        return scene.hit(ray, ctx).map(|h| (h, 1.0));
    }
    ctx.media = MediumMode::Record;
    ctx.crossed.clear();
    let hit = scene.hit(ray, ctx);
    let depth = match &hit {
        Some(h) if ctx.crossed.overflow => {
            ctx.crossed.clear();
            // every medium before the surface, and nothing else, up to the surface
            let _ = scene.hit_group(GroupId(0), ray, Interval::new(0.0, h.t), ctx);
            ctx.crossed.optical_depth(h.t)
        }
        Some(h) => ctx.crossed.optical_depth(h.t),
        None => 0.0,
    };
    ctx.media = MediumMode::Scatter;
    hit.map(|h| (h, (-depth).exp()))
}
// ANCHOR_END: shadow_ray

/// `min(1, SEGMENT_SAMPLE_RATE tau)` for a segment of optical depth `tau` (the survivors reweighted by
/// the inverse), about as often as the path scatters there (`1 - exp(-tau) ~ tau`). On book2-final
/// (400 x 400, 16 spp; its fog has `tau` about 0.5 along a camera ray) rates 1, 2 and 4 give noise
/// constants 0.222, 0.212, 0.211 at 734-760k, 655-662k, 622-654k samples/s per core: 1 is soonest
/// to a given noise, by a little.
pub const SEGMENT_SAMPLE_RATE: f64 = 1.0;
/// [`SEGMENT_SAMPLE_RATE`] for the camera ray's segment: every camera ray through book2-final's fog
/// alone (`tau` about 0.5) takes its light sample, the ones to a surface (shorter) 2 `tau` of the
/// time. On book2-final (400 x 400, 16 spp) rate 2 on the camera ray lowers the noise constant from
/// 0.2231 to 0.2141 for 3-5% of the rate; 100 (every camera segment) gives 0.2137 for 20%.
pub const CAMERA_SEGMENT_SAMPLE_RATE: f64 = 2.0;
/// The largest optical depth of a segment that takes its light sample at an equiangular point. The
/// equiangular density ignores the transmittance: in a medium much denser than the segment is long
/// the light is scattered from a skin of depth `1 / sigma` where the segment enters, which it almost
/// never draws a point in (and at density 1e30 cannot: the ulp of `t` is wider than the skin). Such a
/// segment's scattering point takes its own light sample instead, as before segment sampling. At
/// `tau` 8 the transmittance ends at 3e-4: the equiangular points are still where the light is.
pub const SEGMENT_MAX_OPTICAL_DEPTH: f64 = 8.0;
/// The emitters whose centres the equiangular density of a segment is mixed from (the first ones
/// of the scene; any density that covers the segment is unbiased, these make it a good one).
const EQUIANGULAR_CENTRES: usize = 4;

/// Camera rays (bounce 0; bounces `0..FORCED_SCATTER_BOUNCES`) that would otherwise leave the scene
/// through a medium scatter in it on every path (the forced scattering of `trace_through_media`). On
/// book2-final a camera ray that meets only the fog (optical depth about 0.5) scatters 39% of the time
/// by distance sampling, so the light such a pixel gets from beyond its segment is a Bernoulli draw.
/// Forcing the later bounces too costs more than it saves (book/src/figures/render-speed.md, fog5).
pub const FORCED_SCATTER_BOUNCES: u32 = 1;
// (forced scattering takes the roulette's dimension: the two never meet at one bounce)
const _: () = assert!(FORCED_SCATTER_BOUNCES <= ROULETTE_AFTER);
/// The share of the equiangular density in the density a forced scattering point is drawn from (the
/// rest is the exponential of distance sampling, truncated to the stretch): near the emitters, where
/// the light is, and never less than `1 - FORCED_EQUIANGULAR_SHARE` times the exponential's density
/// anywhere, so the weight `sigma T / p` stays below `(1 - exp(-tau)) / (1 - share)`.
pub const FORCED_EQUIANGULAR_SHARE: f64 = 0.8;

/// What a path segment through media gives the path: its next vertex, whether that vertex takes a
/// light sample itself, the light scattered along the segment towards the ray's origin, and, when
/// the path was forced to scatter, how the throughput is split between the vertex and the background.
pub(crate) struct Segment {
    pub vertex: Option<Hit>,
    pub samples_lights: bool,
    pub in_scattered: Color,
    /// `Some((w, T))` when the path was forced to scatter before leaving the scene: the vertex carries
    /// `w = sigma T(t) / p(t)` of the throughput, the background is seen with `T = exp(-tau)`.
    pub forced: Option<(f64, f64)>,
}

/// The path's next vertex along `ray` when the scene has media, and the light the segment scatters
/// towards the ray's origin (to be multiplied by the path's throughput).
///
/// One traversal records the media the ray crosses up to the first surface (as a shadow ray does);
/// the path then scatters in medium `i` at the exponentially distributed distance of its density
/// `sigma_i` (the first such point before the surface wins: book 2's distance sampling, per medium).
/// The light scattered along the segment, `sum_i int sigma_i T(t) L_s,i(t) dt` (`T` the transmittance
/// from the origin, `L_s` what a light sample at `ray(t)` estimates), is estimated at one point drawn
/// from an equiangular density about the emitters' centres, over the stretches in media, not at the
/// scattering point: a thin fog lit by a nearby light varies along the ray as the inverse square of
/// the distance to the light, which the distance sampling ignores (and it scatters on few rays).
/// The point scattered at then takes no light sample of its own; the emission its material-sampled
/// direction meets keeps its power-heuristic weight, which with the segment's weight sums to 1 at
/// every point and direction, so the two estimate complementary parts of the same integral.
///
/// With `force` set, a ray that meets no surface and crosses one medium always scatters in it
/// ([`forced_scatter`]); that point takes the light sample itself.
///
/// Returns the vertex, whether it takes a light sample itself (a surface; a forced point; a medium
/// point when more media were crossed than can be recorded and the ray was traced again with book 2's
/// scattering, or when the segment is deeper than [`SEGMENT_MAX_OPTICAL_DEPTH`]), the segment's
/// in-scattered light and the forced split.
#[inline]
#[allow(clippy::too_many_arguments)] // the segment's parts, each used once
pub(super) fn trace_through_media(
    scene: &Scene,
    lights: &Lights,
    ray: &Ray,
    sample_segment: bool,
    segment_rate: f64,
    force: bool,
    variant: MisVariant,
    ctx: &mut Ctx,
) -> Segment {
    ctx.media = MediumMode::Record;
    ctx.crossed.clear();
    let surface = scene.hit(ray, ctx);
    ctx.media = MediumMode::Scatter;
    if ctx.crossed.overflow {
        ctx.stats.rays += 1;
        return Segment {
            vertex: scene.hit(ray, ctx),
            samples_lights: true,
            in_scattered: Color::ZERO,
            forced: None,
        };
    }
    let crossed = ctx.crossed;
    let t_surface = surface.as_ref().map_or(f64::INFINITY, |h| h.t);
    let tau = crossed.optical_depth(t_surface);
    if force
        && surface.is_none()
        && crossed.len() == 1
        && tau > 0.0
        && let Some(segment) = forced_scatter(lights, ray, &crossed, tau, variant, ctx)
    {
        return segment;
    }
    // (NaN counts as dense: the point then samples the lights itself)
    let dense = (tau > SEGMENT_MAX_OPTICAL_DEPTH || tau.is_nan())
        && variant != MisVariant::SegmentsAtAnyDepth;
    let in_scattered = if sample_segment && !dense {
        segment_light(
            scene,
            lights,
            ray,
            &crossed,
            t_surface,
            tau,
            segment_rate,
            variant,
            ctx,
        )
    } else {
        Color::ZERO
    };
    // Distance sampling, medium by medium.
    let mut closest = t_surface;
    let mut phase = None;
    for ((t0, t1, density), m) in crossed.stretches() {
        let t1 = t1.min(t_surface);
        if t0 < t1 {
            let u = ctx.uniform();
            // `-ln(1 - u) >= u`: a `u` that reaches past the stretch or the closest point so far
            // decides without the logarithm, exactly as it would with it.
            if free_point_surely_beyond(u, t0, density, t1.min(closest)) {
                continue;
            }
            // 1 - u lies in (0, 1], so the logarithm is finite.
            let t = t0 - (1.0 - u).ln() / density;
            if t < t1 && t < closest {
                closest = t;
                phase = Some(m);
            }
        }
    }
    match phase {
        None => Segment {
            vertex: surface,
            samples_lights: true,
            in_scattered,
            forced: None,
        },
        Some(m) => Segment {
            vertex: Some(medium_point(ray, closest, m)),
            samples_lights: dense,
            in_scattered,
            forced: None,
        },
    }
}

/// A point of the medium (phase function `material`) at `ray(t)`.
#[inline]
fn medium_point(ray: &Ray, t: f64, material: u32) -> Hit {
    Hit {
        t,
        p: ray.at(t),
        normal: Vec3::X,
        front_face: true,
        err: 0.0,
        material: crate::ids::MaterialId(material),
        uv_source: crate::hit::UvSource::Uv(0.0, 0.0),
    }
}

// ANCHOR: forced_scatter
/// Forced scattering on a ray that leaves the scene through one medium's stretch `t0..t1` (density
/// `sigma`, optical depth `tau`): what reaches the ray's origin is
/// `int_t0^t1 sigma T(t) L_s(t) dt + T(t1) L_background`. Distance sampling estimates the integral by
/// scattering with probability `1 - exp(-tau)` and shows the background otherwise; here the background
/// term is added as it is (times `T = exp(-tau)`) and the integral by a point drawn on every path from
/// `p(t) = a q(t) + (1 - a) sigma T(t) / (1 - exp(-tau))` (`a` = [`FORCED_EQUIANGULAR_SHARE`], `q`
/// the equiangular density about the emitters' centres over the stretch, the second term the
/// exponential truncated to the stretch), weighted `sigma T(t) / p(t)`: with `a = 0` exactly
/// `1 - exp(-tau)`. The point takes its own light sample (weighted by the power heuristic against the
/// phase function's direction, as at a surface): the segment's equiangular sample would be a second
/// shadow ray for the same light.
///
/// `None` (and book 2's distance sampling) if the point comes out non-finite (an unbounded stretch).
#[inline]
fn forced_scatter(
    lights: &Lights,
    ray: &Ray,
    crossed: &MediaCrossed,
    tau: f64,
    variant: MisVariant,
    ctx: &mut Ctx,
) -> Option<Segment> {
    let ((t0, t1, density), m) = crossed.stretches().next()?;
    // 1 - exp(-tau), exact for a thin medium
    let scatters = -(-tau).exp_m1();
    let n = lights.emitters.len().min(EQUIANGULAR_CENTRES);
    let mut centres = [Equiangular::default(); EQUIANGULAR_CENTRES];
    let mut equiangular = n > 0 && t1.is_finite();
    if equiangular {
        for (e, target) in centres.iter_mut().zip(&lights.emitters) {
            *e = Equiangular::about(ray, emitter_centre(target));
            e.mass = e.angle(t0, t1);
            equiangular &= e.mass > 0.0 && e.mass.is_finite();
        }
    }
    let a = if equiangular {
        FORCED_EQUIANGULAR_SHARE
    } else {
        0.0
    };
    let centres = &centres[..n];
    // One stratified number picks the density, the centre and the point: `[0, a)` the equiangular
    // densities (`n` equal parts, one a centre), `[a, 1)` the exponential, each part rescaled to
    // `[0, 1)`, so the pixel's samples are spread along the ray.
    let u = ctx.sample_1d(Dimension::Scatter(ctx.bounce));
    let t = if u < a {
        let v = u / a * n as f64;
        let i = (v as usize).min(n - 1);
        let e = centres[i];
        e.at_angle(t0, t1, (v - i as f64).clamp(0.0, 1.0) * e.mass)
    } else {
        let v = ((u - a) / (1.0 - a)).clamp(0.0, 1.0);
        // the inverse of the truncated exponential's distribution; ln_1p's argument is in [-1, 0]
        (t0 - (v * (-tau).exp_m1()).ln_1p() / density).clamp(t0, t1)
    };
    if !t.is_finite() {
        return None;
    }
    let weight = if a > 0.0 {
        // sigma T(t), T from the stretch's start (the ray meets nothing else)
        let sigma_t = density * (-density * (t - t0)).exp();
        let q = centres.iter().map(|e| e.q(t)).sum::<f64>() / n as f64;
        sigma_t / (a * q + (1.0 - a) * sigma_t / scatters)
    } else {
        scatters
    };
    let weight = match variant {
        MisVariant::WrongForcedScatterWeight => weight / scatters,
        _ => weight,
    };
    let through = match variant {
        MisVariant::WrongForcedBackground => 0.0,
        _ => (-tau).exp(),
    };
    Some(Segment {
        vertex: Some(medium_point(ray, t, m)),
        samples_lights: true,
        in_scattered: Color::ZERO,
        forced: Some((weight, through)),
    })
}
// ANCHOR_END: forced_scatter

/// The point an emitter's equiangular density is centred on.
#[inline]
fn emitter_centre(target: &LightTarget) -> Point3 {
    match target {
        LightTarget::Quad { quad, .. } => quad.q() + 0.5 * (quad.u() + quad.v()),
        LightTarget::Sphere(s) => s.center(),
    }
}

/// One equiangular point on the media stretches of `ray` before `t_surface` (of optical depth `tau`)
/// and its light sample, weighted `sigma T(t) / (P q(t))` (`P = min(1, rate tau)` the probability the
/// segment is sampled at all).
#[inline]
#[allow(clippy::too_many_arguments)] // the segment's parts, each used once
fn segment_light(
    scene: &Scene,
    lights: &Lights,
    ray: &Ray,
    crossed: &MediaCrossed,
    t_surface: f64,
    tau: f64,
    rate: f64,
    variant: MisVariant,
    ctx: &mut Ctx,
) -> Color {
    if lights.emitters.is_empty() || tau.is_nan() || tau <= 0.0 {
        return Color::ZERO;
    }
    let chance = (rate * tau).min(1.0);
    if ctx.uniform() >= chance {
        return Color::ZERO;
    }
    let mut centres = [Equiangular::default(); EQUIANGULAR_CENTRES];
    let n = lights.emitters.len().min(EQUIANGULAR_CENTRES);
    for (e, target) in centres.iter_mut().zip(&lights.emitters) {
        *e = Equiangular::about(ray, emitter_centre(target));
        e.mass = crossed
            .stretches()
            .map(|((t0, t1, _), _)| {
                let t1 = t1.min(t_surface);
                if t1 > t0 { e.angle(t0, t1) } else { 0.0 }
            })
            .sum();
    }
    let centres = &centres[..n];
    if centres.iter().any(|e| e.mass.is_nan() || e.mass <= 0.0) {
        return Color::ZERO; // no stretch of positive length before the surface
    }
    // A centre, then a stretch by its share of the centre's angle, then the angle within it.
    let e = centres[((ctx.uniform() * n as f64) as usize).min(n - 1)];
    let mut pick = ctx.uniform() * e.mass;
    let mut chosen = None;
    let one = crossed.len() == 1;
    for ((t0, t1, density), m) in crossed.stretches() {
        let t1 = t1.min(t_surface);
        // one stretch: its angle is the mass, already taken (the same arctangent)
        let range = if one {
            e.mass
        } else if t1 > t0 {
            e.angle(t0, t1)
        } else {
            0.0
        };
        if range > 0.0 {
            chosen = Some((range, t0, t1, density, m));
            if pick < range {
                break;
            }
            pick -= range;
        }
    }
    let Some((range, t0, t1, density, m)) = chosen else {
        return Color::ZERO;
    };
    let t = e.at_angle(t0, t1, pick.clamp(0.0, range));
    let q = centres.iter().map(|e| e.q(t)).sum::<f64>() / n as f64;
    let hit = Hit {
        t,
        p: ray.at(t),
        normal: Vec3::X,
        front_face: true,
        err: 0.0,
        material: crate::ids::MaterialId(m),
        uv_source: crate::hit::UvSource::Uv(0.0, 0.0),
    };
    let material = &scene.materials[hit.material.index()];
    let Some(Scatter::Diffuse { attenuation, pdf }) =
        material.scatter(ray, &hit, &scene.textures, ctx)
    else {
        return Color::ZERO;
    };
    if attenuation == Color::ZERO {
        return Color::ZERO; // a black medium (book 2's smoke): its shadow ray would add nothing
    }
    let towards_others = HittablePdf::new(hit.p, &lights.others);
    let u = glam::DVec2::new(ctx.uniform(), ctx.uniform());
    let Some((to_light, weight)) = light_sample(
        lights,
        &hit,
        ray.time,
        &VertexPdf::Material(pdf),
        towards_others.as_ref(),
        u,
    ) else {
        return Color::ZERO;
    };
    let seen = trace_shadow(scene, &to_light, ctx);
    let Some((emitted, weight)) =
        emitter_seen(scene, seen.as_ref().map(|(h, t)| (h, *t)), weight, ctx)
    else {
        return Color::ZERO;
    };
    let transmittance = match variant {
        MisVariant::WrongSegmentTransmittance => 1.0,
        _ => (-crossed.optical_depth(t)).exp(),
    };
    let f = density * transmittance / (chance * q);
    if !f.is_finite() {
        return Color::ZERO;
    }
    attenuation * emitted * (weight * f)
}
