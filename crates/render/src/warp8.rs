//! rtl-pdf's warps for eight points at once, in the lanes of AVX-512 registers: the cosine-weighted
//! hemisphere (by the concentric disk), the cone, the uniform sphere, and the orthonormal basis that
//! carries their directions to the world.
//!
//! Each is the scalar warp of [`rtl_pdf::warp`] (and [`rtl_pdf::Onb`]) operation for operation: the
//! same `f64` operations in the same order, no fused multiply-adds, and the scalar code's branches
//! taken lane by lane as masked moves. The sines and cosines are rtl-pdf's own polynomials, not a
//! library's, so they too are the same in every lane. Every result is bit-identical to the scalar
//! one (tested in `crates/render/tests/paths8.rs` on random and edge inputs).
//!
//! Every function here is compiled for AVX-512F and may be called only where the processor has it.

#![cfg(target_arch = "x86_64")]

use rtl_pdf::warp::{CONCENTRIC_MAX, CONE_U_MAX, MIN_COS_THETA};
use std::arch::x86_64::*;
use std::f64::consts::{FRAC_1_PI, FRAC_PI_4, PI, TAU};

/// Eight `f64` lanes.
pub type F8 = __m512d;
/// One bit per lane.
pub type M8 = __mmask8;

/// A number in every lane.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn splat(x: f64) -> F8 {
    _mm512_set1_pd(x)
}

/// `a + b`, lane by lane.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn add(a: F8, b: F8) -> F8 {
    _mm512_add_pd(a, b)
}

/// `a - b`.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn sub(a: F8, b: F8) -> F8 {
    _mm512_sub_pd(a, b)
}

/// `a * b`.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn mul(a: F8, b: F8) -> F8 {
    _mm512_mul_pd(a, b)
}

/// `a / b`.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn div(a: F8, b: F8) -> F8 {
    _mm512_div_pd(a, b)
}

/// `sqrt(a)`, correctly rounded as the scalar one is.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn sqrt(a: F8) -> F8 {
    _mm512_sqrt_pd(a)
}

/// `-a`: the sign bit flipped (as Rust's `-`, so `-0` from `0`).
#[inline]
#[target_feature(enable = "avx512f")]
pub fn neg(a: F8) -> F8 {
    let bits = _mm512_xor_si512(_mm512_castpd_si512(a), _mm512_set1_epi64(i64::MIN));
    _mm512_castsi512_pd(bits)
}

/// `|a|`: the sign bit cleared.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn abs(a: F8) -> F8 {
    let bits = _mm512_and_si512(_mm512_castpd_si512(a), _mm512_set1_epi64(i64::MAX));
    _mm512_castsi512_pd(bits)
}

/// `magnitude.copysign(sign)`.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn copysign(magnitude: F8, sign: F8) -> F8 {
    let m = _mm512_and_si512(_mm512_castpd_si512(magnitude), _mm512_set1_epi64(i64::MAX));
    let s = _mm512_and_si512(_mm512_castpd_si512(sign), _mm512_set1_epi64(i64::MIN));
    _mm512_castsi512_pd(_mm512_or_si512(m, s))
}

/// glam's `min`: `a < b ? a : b` (NaN in either gives `b`), which is `vminpd a, b`. It is also
/// `f64::min(a, b)` wherever `b` is never NaN.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn min(a: F8, b: F8) -> F8 {
    _mm512_min_pd(a, b)
}

/// glam's `max`: `a > b ? a : b`, which is `vmaxpd a, b`; `f64::max(a, b)` wherever `b` is never NaN.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn max(a: F8, b: F8) -> F8 {
    _mm512_max_pd(a, b)
}

/// `f64::clamp(x, lo, hi)`: `lo` below it, `hi` above, NaN kept.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn clamp(x: F8, lo: f64, hi: f64) -> F8 {
    let (lo, hi) = (splat(lo), splat(hi));
    let x = _mm512_mask_mov_pd(x, lt(x, lo), lo);
    _mm512_mask_mov_pd(x, gt(x, hi), hi)
}

/// `b` where `m` is set, `a` elsewhere.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn select(m: M8, b: F8, a: F8) -> F8 {
    _mm512_mask_mov_pd(a, m, b)
}

/// `a < b` (false if either is NaN).
#[inline]
#[target_feature(enable = "avx512f")]
pub fn lt(a: F8, b: F8) -> M8 {
    _mm512_cmp_pd_mask::<_CMP_LT_OQ>(a, b)
}

/// `a <= b`.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn le(a: F8, b: F8) -> M8 {
    _mm512_cmp_pd_mask::<_CMP_LE_OQ>(a, b)
}

/// `a > b`.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn gt(a: F8, b: F8) -> M8 {
    _mm512_cmp_pd_mask::<_CMP_GT_OQ>(a, b)
}

/// `a == b` (so `-0 == 0`).
#[inline]
#[target_feature(enable = "avx512f")]
pub fn eq(a: F8, b: F8) -> M8 {
    _mm512_cmp_pd_mask::<_CMP_EQ_OQ>(a, b)
}

/// `x > 0 && x <= f64::MAX`: rtl-pdf's `positive_finite`.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn positive_finite(x: F8) -> M8 {
    gt(x, _mm512_setzero_pd()) & le(x, splat(f64::MAX))
}

/// `x` rounded towards zero to an integer (exact).
#[inline]
#[target_feature(enable = "avx512f")]
pub fn trunc(x: F8) -> F8 {
    _mm512_roundscale_pd::<{ _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC }>(x)
}

/// `f64::round`: to the nearest integer, halves away from zero. (The vector instruction's nearest
/// rounds halves to even, so the half is decided from the exact fraction `|x| - trunc |x|`.)
#[inline]
#[target_feature(enable = "avx512f")]
pub fn round(x: F8) -> F8 {
    let a = abs(x);
    let t = trunc(a);
    let up = _mm512_cmp_pd_mask::<_CMP_GE_OQ>(sub(a, t), splat(0.5));
    copysign(_mm512_mask_add_pd(t, up, t, splat(1.0)), x)
}

/// Three coordinates, each in the lanes of one register.
pub type V3 = [F8; 3];

/// `a + b`, coordinate by coordinate.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn add3(a: V3, b: V3) -> V3 {
    [add(a[0], b[0]), add(a[1], b[1]), add(a[2], b[2])]
}

/// `a - b`.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn sub3(a: V3, b: V3) -> V3 {
    [sub(a[0], b[0]), sub(a[1], b[1]), sub(a[2], b[2])]
}

/// `s * a` (glam's `f64 * DVec3`).
#[inline]
#[target_feature(enable = "avx512f")]
pub fn scale3(s: F8, a: V3) -> V3 {
    [mul(s, a[0]), mul(s, a[1]), mul(s, a[2])]
}

/// glam's `dot`: `(a.x b.x + a.y b.y) + a.z b.z`.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn dot3(a: V3, b: V3) -> F8 {
    add(add(mul(a[0], b[0]), mul(a[1], b[1])), mul(a[2], b[2]))
}

/// glam's `cross`.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn cross3(a: V3, b: V3) -> V3 {
    [
        sub(mul(a[1], b[2]), mul(b[1], a[2])),
        sub(mul(a[2], b[0]), mul(b[2], a[0])),
        sub(mul(a[0], b[1]), mul(b[0], a[1])),
    ]
}

/// glam's `max_element`: `max(x, max(y, z))`, `a > b ? a : b` each.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn max_element3(a: V3) -> F8 {
    max(a[0], max(a[1], a[2]))
}

/// `b` where `m` is set, `a` elsewhere, coordinate by coordinate.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn select3(m: M8, b: V3, a: V3) -> V3 {
    [
        select(m, b[0], a[0]),
        select(m, b[1], a[1]),
        select(m, b[2], a[2]),
    ]
}

/// A vector in every lane.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn splat3(v: glam::DVec3) -> V3 {
    [splat(v.x), splat(v.y), splat(v.z)]
}

/// `(sin x, cos x)` for `|x| <= pi / 4`: rtl-pdf's Taylor polynomials, Horner from the smallest term.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn sin_cos_eighth(x: F8) -> (F8, F8) {
    let x2 = mul(x, x);
    let step = |k: f64, acc: F8| sub(splat(k), mul(acc, x2));
    let s = splat(1.0 / 1_307_674_368_000.0);
    let s = step(1.0 / 6_227_020_800.0, s);
    let s = step(1.0 / 39_916_800.0, s);
    let s = step(1.0 / 362_880.0, s);
    let s = step(1.0 / 5_040.0, s);
    let s = step(1.0 / 120.0, s);
    let s = step(1.0 / 6.0, s);
    let s = step(1.0, s);
    let c = splat(1.0 / 20_922_789_888_000.0);
    let c = step(1.0 / 87_178_291_200.0, c);
    let c = step(1.0 / 479_001_600.0, c);
    let c = step(1.0 / 3_628_800.0, c);
    let c = step(1.0 / 40_320.0, c);
    let c = step(1.0 / 720.0, c);
    let c = step(1.0 / 24.0, c);
    let c = step(1.0 / 2.0, c);
    let c = step(1.0, c);
    (mul(x, s), c)
}

/// `(sin 2 pi t, cos 2 pi t)` for `t` in `[0, 1]`: the nearest quarter turn split off, as rtl-pdf's.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn sin_cos_turns(t: F8) -> (F8, F8) {
    let k = round(mul(splat(4.0), t));
    let (s, c) = sin_cos_eighth(mul(splat(TAU), sub(t, mul(splat(0.25), k))));
    // quarter `k & 3`: (s, c), (c, -s), (-s, -c), (-c, s); `k as u32` saturates, so a NaN is 0
    let q = _mm512_cvtepu32_epi64(_mm512_cvttpd_epu32(max(k, _mm512_setzero_pd())));
    let bit = |b: i64| _mm512_test_epi64_mask(q, _mm512_set1_epi64(b));
    let (odd, half) = (bit(1), bit(2));
    let (sin, cos) = (select(odd, c, s), select(odd, s, c));
    // sin is negated in quarters 2 and 3, cos in quarters 1 and 2
    (
        select(half, neg(sin), sin),
        select(odd ^ half, neg(cos), cos),
    )
}

/// rtl-pdf's `sample_uniform_disk_concentric`.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn sample_uniform_disk_concentric(u: [F8; 2]) -> [F8; 2] {
    // glam's `clamp` of a `DVec2`: `max` then `min`, as `vmaxpd`, `vminpd`
    let o = u.map(|x| {
        let o = sub(mul(splat(2.0), x), splat(1.0));
        min(max(o, splat(-CONCENTRIC_MAX)), splat(CONCENTRIC_MAX))
    });
    let zero = _mm512_setzero_pd();
    let centre = eq(o[0], zero) & eq(o[1], zero);
    let wide = gt(abs(o[0]), abs(o[1]));
    // |o.x| > |o.y|: theta = pi/4 (o.y / o.x), else from o.x / o.y with sine and cosine swapped
    let (num, den) = (select(wide, o[1], o[0]), select(wide, o[0], o[1]));
    let (s, c) = sin_cos_eighth(mul(splat(FRAC_PI_4), div(num, den)));
    let x = select(wide, mul(o[0], c), mul(o[1], s));
    let y = select(wide, mul(o[0], s), mul(o[1], c));
    [select(centre, zero, x), select(centre, zero, y)]
}

/// rtl-pdf's `sample_cosine_hemisphere`: the local direction about `+z`.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn sample_cosine_hemisphere(u: [F8; 2]) -> V3 {
    let d = sample_uniform_disk_concentric(u);
    let r2 = add(mul(d[0], d[0]), mul(d[1], d[1]));
    // `f64::max` against a number: `vmaxpd` with the number second (a NaN root gives the number)
    let z = max(sqrt(sub(splat(1.0), r2)), splat(MIN_COS_THETA));
    [d[0], d[1], z]
}

/// rtl-pdf's `cosine_hemisphere_pdf`: `cos theta / pi` above the horizon, 0 elsewhere.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn cosine_hemisphere_pdf(cos_theta: F8) -> F8 {
    let above = gt(cos_theta, _mm512_setzero_pd());
    _mm512_maskz_mov_pd(above, mul(cos_theta, splat(FRAC_1_PI)))
}

/// rtl-pdf's `cone_one_minus_cos`: `1 - cos theta_max` from `sin^2 theta_max`.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn cone_one_minus_cos(sin2_theta_max: F8) -> F8 {
    let s2 = clamp(sin2_theta_max, 0.0, 1.0);
    div(s2, add(splat(1.0), sqrt(sub(splat(1.0), s2))))
}

/// rtl-pdf's `sample_uniform_cone` about `+z`.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn sample_uniform_cone(u: [F8; 2], one_minus_cos_max: F8) -> V3 {
    let t = mul(min(u[0], splat(CONE_U_MAX)), one_minus_cos_max);
    let cos_theta = sub(splat(1.0), t);
    let sin_theta = sqrt(max(mul(t, sub(splat(2.0), t)), _mm512_setzero_pd()));
    let (sin_phi, cos_phi) = sin_cos_turns(u[1]);
    [mul(sin_theta, cos_phi), mul(sin_theta, sin_phi), cos_theta]
}

/// rtl-pdf's `uniform_cone_pdf`: `1 / (2 pi (1 - cos theta_max))`.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn uniform_cone_pdf(one_minus_cos_max: F8) -> F8 {
    div(splat(1.0), mul(splat(TAU), one_minus_cos_max))
}

/// rtl-pdf's `sample_uniform_sphere`.
#[inline]
#[target_feature(enable = "avx512f")]
pub fn sample_uniform_sphere(u: [F8; 2]) -> V3 {
    let z = sub(splat(1.0), mul(splat(2.0), u[0]));
    let r = mul(
        splat(2.0),
        sqrt(max(mul(u[0], sub(splat(1.0), u[0])), _mm512_setzero_pd())),
    );
    let (sin_phi, cos_phi) = sin_cos_turns(u[1]);
    [mul(r, cos_phi), mul(r, sin_phi), z]
}

/// rtl-pdf's `uniform_sphere_pdf`, `1 / (4 pi)`.
pub const UNIFORM_SPHERE_PDF: f64 = 1.0 / (4.0 * PI);

/// [`rtl_pdf::Onb`] in the lanes: the basis `(u, v, w)` of Duff et al. from the unit `w`.
#[derive(Clone, Copy)]
pub struct Onb8 {
    u: V3,
    v: V3,
    w: V3,
}

impl Onb8 {
    /// The basis whose third axis is `w`.
    #[inline]
    #[target_feature(enable = "avx512f")]
    pub fn new(w: V3) -> Onb8 {
        let [x, y, z] = w;
        let sign = copysign(splat(1.0), z);
        let a = div(splat(-1.0), add(sign, z));
        let b = mul(mul(x, y), a);
        let u = [
            add(splat(1.0), mul(mul(mul(sign, x), x), a)),
            mul(sign, b),
            mul(neg(sign), x),
        ];
        let v = [b, add(sign, mul(mul(y, y), a)), neg(y)];
        Onb8 { u, v, w }
    }

    /// `local.x u + local.y v + local.z w`.
    #[inline]
    #[target_feature(enable = "avx512f")]
    pub fn transform(&self, local: V3) -> V3 {
        add3(
            add3(scale3(local[0], self.u), scale3(local[1], self.v)),
            scale3(local[2], self.w),
        )
    }
}
