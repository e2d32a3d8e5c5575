//! rtl-pdf's warps for eight points at once ([`crate::wide8`]): the cosine-weighted hemisphere (by
//! the concentric disk), the cone, the uniform sphere, and the orthonormal basis that carries their
//! directions to the world.
//!
//! Each is the scalar warp of [`rtl_pdf::warp`] (and [`rtl_pdf::Onb`]) operation for operation: the
//! same `f64` operations in the same order, no fused multiply-adds, and the scalar code's branches
//! taken lane by lane as selections. The sines and cosines are rtl-pdf's own polynomials, not a
//! library's, so they too are the same in every lane. Every result is bit-identical to the scalar
//! one (tested in `crates/render/tests/paths8.rs` on random and edge inputs).

#![cfg(target_arch = "x86_64")]

use crate::wide8::{V3, Wide8, add3, scale3};
use rtl_pdf::warp::{CONCENTRIC_MAX, CONE_U_MAX, MIN_COS_THETA};
use std::f64::consts::{FRAC_1_PI, FRAC_PI_4, TAU};

/// `(sin x, cos x)` for `|x| <= pi / 4`: rtl-pdf's Taylor polynomials, Horner from the smallest term.
#[inline(always)]
pub fn sin_cos_eighth<W: Wide8>(x: W) -> (W, W) {
    let x2 = x * x;
    let s = x.splat_like(1.0 / 1_307_674_368_000.0);
    let s = horner(x2, 1.0 / 6_227_020_800.0, s);
    let s = horner(x2, 1.0 / 39_916_800.0, s);
    let s = horner(x2, 1.0 / 362_880.0, s);
    let s = horner(x2, 1.0 / 5_040.0, s);
    let s = horner(x2, 1.0 / 120.0, s);
    let s = horner(x2, 1.0 / 6.0, s);
    let s = horner(x2, 1.0, s);
    let c = x.splat_like(1.0 / 20_922_789_888_000.0);
    let c = horner(x2, 1.0 / 87_178_291_200.0, c);
    let c = horner(x2, 1.0 / 479_001_600.0, c);
    let c = horner(x2, 1.0 / 3_628_800.0, c);
    let c = horner(x2, 1.0 / 40_320.0, c);
    let c = horner(x2, 1.0 / 720.0, c);
    let c = horner(x2, 1.0 / 24.0, c);
    let c = horner(x2, 1.0 / 2.0, c);
    let c = horner(x2, 1.0, c);
    (x * s, c)
}

/// One step of Horner's rule from the top: `k - acc x2`.
#[inline(always)]
fn horner<W: Wide8>(x2: W, k: f64, acc: W) -> W {
    x2.splat_like(k) - acc * x2
}

/// `(sin 2 pi t, cos 2 pi t)` for `t` in `[0, 1]`: the nearest quarter turn split off, as rtl-pdf's.
#[inline(always)]
pub fn sin_cos_turns<W: Wide8>(t: W) -> (W, W) {
    let k = (t.splat_like(4.0) * t).round();
    let (s, c) = sin_cos_eighth(t.splat_like(TAU) * (t - t.splat_like(0.25) * k));
    // quarter `k & 3` (`k` in 0..=4 here; `k as u32` takes a NaN to 0, as `max` does):
    // (s, c), (c, -s), (-s, -c), (-c, s)
    let k = k.max(t.zero_like());
    let q = k - t.splat_like(4.0) * (k * t.splat_like(0.25)).trunc();
    let (q1, q2, q3) = (
        q.eq(t.splat_like(1.0)),
        q.eq(t.splat_like(2.0)),
        q.eq(t.splat_like(3.0)),
    );
    let (odd, half) = (q1 | q3, q2 | q3);
    let (sin, cos) = (s.select(odd, c), c.select(odd, s));
    // sin is negated in quarters 2 and 3, cos in quarters 1 and 2
    (sin.select(half, -sin), cos.select(odd ^ half, -cos))
}

/// `2 u - 1`, kept within `±CONCENTRIC_MAX` by glam's `clamp` (`max`, then `min`).
#[inline(always)]
fn concentric_offset<W: Wide8>(u: W) -> W {
    let o = u.splat_like(2.0) * u - u.splat_like(1.0);
    o.max(u.splat_like(-CONCENTRIC_MAX))
        .min(u.splat_like(CONCENTRIC_MAX))
}

/// rtl-pdf's `sample_uniform_disk_concentric`.
#[inline(always)]
pub fn sample_uniform_disk_concentric<W: Wide8>(u: [W; 2]) -> [W; 2] {
    // glam's `clamp` of a `DVec2`: `max` then `min`
    let o = [concentric_offset(u[0]), concentric_offset(u[1])];
    let zero = o[0].zero_like();
    let centre = o[0].eq(zero) & o[1].eq(zero);
    let wide = o[0].abs().gt(o[1].abs());
    // |o.x| > |o.y|: theta = pi/4 (o.y / o.x); else from o.x / o.y, sine and cosine swapped
    let (num, den) = (o[0].select(wide, o[1]), o[1].select(wide, o[0]));
    let (s, c) = sin_cos_eighth(o[0].splat_like(FRAC_PI_4) * (num / den));
    let x = (o[1] * s).select(wide, o[0] * c);
    let y = (o[1] * c).select(wide, o[0] * s);
    [x.select(centre, zero), y.select(centre, zero)]
}

/// rtl-pdf's `sample_cosine_hemisphere`: the local direction about `+z`.
#[inline(always)]
pub fn sample_cosine_hemisphere<W: Wide8>(u: [W; 2]) -> V3<W> {
    let d = sample_uniform_disk_concentric(u);
    let r2 = d[0] * d[0] + d[1] * d[1];
    // `f64::max` against a number: a NaN root gives the number
    let z = (u[0].splat_like(1.0) - r2)
        .sqrt()
        .max(u[0].splat_like(MIN_COS_THETA));
    [d[0], d[1], z]
}

/// rtl-pdf's `cosine_hemisphere_pdf`: `cos theta / pi` above the horizon, 0 elsewhere.
#[inline(always)]
pub fn cosine_hemisphere_pdf<W: Wide8>(cos_theta: W) -> W {
    let above = cos_theta.gt(cos_theta.zero_like());
    (cos_theta * cos_theta.splat_like(FRAC_1_PI)).zero_unless(above)
}

/// rtl-pdf's `cone_one_minus_cos`: `1 - cos theta_max` from `sin^2 theta_max`.
#[inline(always)]
pub fn cone_one_minus_cos<W: Wide8>(sin2_theta_max: W) -> W {
    let s2 = sin2_theta_max.clamp(0.0, 1.0);
    let one = s2.splat_like(1.0);
    s2 / (one + (one - s2).sqrt())
}

/// rtl-pdf's `sample_uniform_cone` about `+z`.
#[inline(always)]
pub fn sample_uniform_cone<W: Wide8>(u: [W; 2], one_minus_cos_max: W) -> V3<W> {
    let t = u[0].min(u[0].splat_like(CONE_U_MAX)) * one_minus_cos_max;
    let cos_theta = t.splat_like(1.0) - t;
    let sin_theta = (t * (t.splat_like(2.0) - t)).max(t.zero_like()).sqrt();
    let (sin_phi, cos_phi) = sin_cos_turns(u[1]);
    [sin_theta * cos_phi, sin_theta * sin_phi, cos_theta]
}

/// rtl-pdf's `uniform_cone_pdf`: `1 / (2 pi (1 - cos theta_max))`.
#[inline(always)]
pub fn uniform_cone_pdf<W: Wide8>(one_minus_cos_max: W) -> W {
    let x = one_minus_cos_max;
    x.splat_like(1.0) / (x.splat_like(TAU) * x)
}

/// rtl-pdf's `sample_uniform_sphere`.
#[inline(always)]
pub fn sample_uniform_sphere<W: Wide8>(u: [W; 2]) -> V3<W> {
    let one = u[0].splat_like(1.0);
    let z = one - u[0].splat_like(2.0) * u[0];
    let r = u[0].splat_like(2.0) * (u[0] * (one - u[0])).max(u[0].zero_like()).sqrt();
    let (sin_phi, cos_phi) = sin_cos_turns(u[1]);
    [r * cos_phi, r * sin_phi, z]
}

/// [`rtl_pdf::Onb`] in the lanes: the basis `(u, v, w)` of Duff et al. from the unit `w`.
#[derive(Clone, Copy)]
pub struct Onb8<W: Wide8> {
    u: V3<W>,
    v: V3<W>,
    w: V3<W>,
}

impl<W: Wide8> Onb8<W> {
    /// The basis whose third axis is `w`.
    #[inline(always)]
    pub fn new(w: V3<W>) -> Onb8<W> {
        let [x, y, z] = w;
        let one = z.splat_like(1.0);
        let sign = one.copysign(z);
        let a = -one / (sign + z);
        let b = x * y * a;
        let u = [one + sign * x * x * a, sign * b, -sign * x];
        let v = [b, sign + y * y * a, -y];
        Onb8 { u, v, w }
    }

    /// `local.x u + local.y v + local.z w`.
    #[inline(always)]
    pub fn transform(&self, local: V3<W>) -> V3<W> {
        add3(
            add3(scale3(local[0], self.u), scale3(local[1], self.v)),
            scale3(local[2], self.w),
        )
    }
}
