//! The `mis` vertex of eight paths in the lanes (book 3, chapter 12's mixture, with next-event
//! estimation and the power heuristic of Veach's thesis): where a lane's ray met a Lambertian quad
//! of constant albedo (most vertices of the Cornell box), everything from the hit to its two rays
//! is computed eight lanes at a time:
//!
//! - the hit point and the normal turned against the ray, as [`crate::vertex8`] computes them;
//! - the light sample: a direction `omega_l` towards the scene's one emitter, drawn by the
//!   emitter's density `p_l` (solid angle at the point), the cosine density `s(omega_l)` there, the
//!   material sampling's density `p_m(omega_l) = a p_others + (1 - a) s` (`a` =
//!   [`crate::integrator::OTHERS_SHARE`]), and the shadow ray's factor `w_l s / p_l`, `w_l` the
//!   power heuristic `p_l^2 / (p_l^2 + p_m^2)`;
//! - material sampling: a direction `omega` from the mixture `p_m` ([`crate::mixture8`]), the
//!   throughput times `albedo s(omega) / p_m(omega)`, and `p_m(omega)`, which weighs emission the
//!   next vertex meets.
//!
//! The targets' views from the points (the glass ball's cone) are made once for both densities.
//! Each lane computes the same `f64` operations in the same order as `MisPath::vertex` does one
//! path at a time, so the image is bit-identical (tested in `crates/render/tests/paths8.rs`);
//! Russian roulette, which may draw a number, stays lane by lane.

use crate::lanes::F64x8;
use crate::lights::Lights;
use crate::mixture8::{Mixture8, Target8};

/// The most non-emitting targets the vertex in the lanes takes (their views from the eight points
/// are kept on the stack, a few hundred bytes each, and the array is cleared for each batch).
pub const MAX_OTHERS: usize = crate::mixture8::FEW_TARGETS;

/// What the `mis` vertex in the lanes needs of the scene's targets: its one emitter and the
/// non-emitting targets mixed into material sampling. Built once per render.
#[derive(Clone, Debug)]
pub struct MisLanes {
    emitter: Target8,
    others: Mixture8,
    /// The share `a` of material sampling drawn towards the other targets.
    share: f64,
}

impl MisLanes {
    /// The vertex in the lanes for `lights`, where the scene has exactly one emitter (no choice of
    /// emitter to weigh) and one or two ([`MAX_OTHERS`]) non-emitting targets (the Cornell box's
    /// glass ball), none of them a quad sampled by spherical rectangles; else `None` (the vertex is computed one path at a
    /// time).
    pub fn new(lights: &Lights) -> Option<MisLanes> {
        Self::with_share(lights, crate::integrator::OTHERS_SHARE)
    }

    /// [`MisLanes::new`] with another share of the other targets than the integrator's
    /// [`crate::integrator::OTHERS_SHARE`]: for the tests that show a wrong vertex is caught.
    #[doc(hidden)]
    pub fn with_share(lights: &Lights, share: f64) -> Option<MisLanes> {
        let [emitter] = lights.emitters.as_slice() else {
            return None;
        };
        if lights.others.len() > MAX_OTHERS {
            return None;
        }
        Some(MisLanes {
            emitter: Target8::new(emitter)?,
            others: Mixture8::new(&lights.others, share)?,
            share,
        })
    }
}

/// The vertex's answers, lane by lane: where `shadow` is set, the light sample's shadow ray and
/// what its emission counts with (`carried = throughput * albedo`, `weight = w_l s / p_l`); where
/// `next` is set, the path's next ray, its throughput and the density `pdf` it was drawn with
/// from the point `p`.
#[derive(Clone, Copy, Debug, Default)]
pub struct MisOut {
    pub shadow: u8,
    pub shadow_origin: [F64x8; 3],
    pub shadow_direction: [F64x8; 3],
    pub carried: [F64x8; 3],
    pub weight: F64x8,
    pub next: u8,
    pub p: [F64x8; 3],
    pub next_origin: [F64x8; 3],
    pub next_direction: [F64x8; 3],
    pub throughput: [F64x8; 3],
    pub pdf: F64x8,
}

#[cfg(target_arch = "x86_64")]
mod wide {
    use super::{MisLanes, MisOut};
    use crate::lanes::F64x8;
    use crate::mixture8::wide::View8;
    use crate::ray8::{Closest8, Rays8};
    use crate::traversal::HitTier;
    use crate::vertex8::QuadSurfaces;
    use crate::warp8::cosine_hemisphere_pdf;
    use crate::wide8::*;

    /// The numbers a batch of the vertex reads: the lanes' hits and rays, their throughputs, the
    /// light sample's and the bounce's uniform pairs.
    pub struct MisIn<'a> {
        pub surfaces: &'a QuadSurfaces,
        pub found: &'a Closest8,
        pub rays: &'a Rays8,
        pub throughput: &'a [F64x8; 3],
        pub u_light: &'a [F64x8; 2],
        pub u_material: &'a [F64x8; 2],
    }

    /// rtl-pdf's `power_heuristic(1, a, 1, b)`: `a^2 / (a^2 + b^2)` through the ratio of the
    /// smaller to the larger; 0 where `a` is not positive (or NaN), else 1 where `b` is not, 1/2
    /// where they are equal.
    #[inline(always)]
    fn power_heuristic<W: Wide8>(a: W, b: W) -> W {
        heuristic::<W, true>(a, b)
    }

    /// `h(x)`: `x^2` (`POWER`) or `x`.
    #[inline(always)]
    fn h<W: Wide8, const POWER: bool>(x: W) -> W {
        if POWER { x * x } else { x }
    }

    /// rtl-pdf's `h(a) / (h(a) + h(b))` in the lanes, for `h(x) = x^2` (`POWER`) or `h(x) = x`
    /// (the balance heuristic). (No closure for `h`: a closure does not take its caller's target
    /// features, and its arithmetic would be calls.)
    #[inline(always)]
    pub(super) fn heuristic<W: Wide8, const POWER: bool>(a: W, b: W) -> W {
        let (zero, one) = (a.zero_like(), a.splat_like(1.0));
        let larger = one / (one + h::<W, POWER>(b / a));
        let r = h::<W, POWER>(a / b);
        let smaller = r / (one + r);
        let w = smaller.select(a.gt(b), larger);
        let w = w.select(a.eq(b), a.splat_like(0.5));
        let w = w.select(b.is_nan() | b.le(zero), one);
        w.select(a.is_nan() | a.le(zero), zero)
    }

    impl MisLanes {
        /// The `mis` vertex of the lanes of `lanes`, whose rays met Lambertian quads of constant
        /// albedo, the lanes of `light_lanes` taking a light sample, written to `out`.
        ///
        /// # Safety
        /// Only where the processor runs `tier`, which is AVX2 or AVX-512.
        pub unsafe fn vertex(
            &self,
            tier: HitTier,
            input: &MisIn<'_>,
            lanes: u8,
            light_lanes: u8,
            out: &mut MisOut,
        ) {
            if lanes == 0 {
                return;
            }
            // SAFETY: as this function's.
            unsafe {
                match tier {
                    HitTier::Avx512 => self.avx512(input, lanes, light_lanes, out),
                    _ => self.avx2(input, lanes, light_lanes, out),
                }
            }
        }

        #[target_feature(enable = "avx512f")]
        unsafe fn avx512(&self, input: &MisIn<'_>, lanes: u8, light: u8, out: &mut MisOut) {
            // SAFETY: compiled with AVX-512F, run where the processor has it.
            unsafe { self.vertex_in::<Avx512>(input, lanes, light, out) }
        }

        #[target_feature(enable = "avx2")]
        unsafe fn avx2(&self, input: &MisIn<'_>, lanes: u8, light: u8, out: &mut MisOut) {
            // SAFETY: compiled with AVX2, run where the processor has it.
            unsafe { self.vertex_in::<Avx2>(input, lanes, light, out) }
        }

        /// [`MisLanes::vertex`] in the instructions of `W`.
        ///
        /// # Safety
        /// As [`Wide8::splat`]; `lanes` is not empty and names only lanes whose hit is a
        /// Lambertian quad of `input.surfaces`.
        #[inline(always)]
        unsafe fn vertex_in<W: Wide8>(
            &self,
            input: &MisIn<'_>,
            lanes: u8,
            light_lanes: u8,
            out: &mut MisOut,
        ) {
            // SAFETY: as this function's.
            let (at, tp, ul, um) = unsafe {
                let o = load3::<W>(&input.rays.origin);
                let dir = load3::<W>(&input.rays.direction);
                (
                    input.surfaces.surface_in(input.found, o, dir, lanes),
                    load3::<W>(input.throughput),
                    [W::load(&input.u_light[0]), W::load(&input.u_light[1])],
                    [W::load(&input.u_material[0]), W::load(&input.u_material[1])],
                )
            };
            let (p, normal, albedo) = (at.p, at.normal, at.albedo);
            let zero = p[0].zero_like();
            // (each target's view built in its place: an array of them cleared first cost a
            // memset of a few hundred bytes a batch)
            let (one, two);
            let views: &[View8<W>] = match self.others.target_list() {
                [a] => {
                    one = [a.view(p)];
                    &one
                }
                [a, b] => {
                    two = [a.view(p), b.view(p)];
                    &two
                }
                _ => unreachable!("one or two targets besides the emitter ([`MAX_OTHERS`])"),
            };
            let (wa, rest) = (
                zero.splat_like(self.share),
                zero.splat_like(1.0 - self.share),
            );

            // `light_sample`: the emitter's direction and density, the cosine density there,
            // the mixture's (`pdf_given_b`), the power heuristic, `w_l s / p_l`
            if light_lanes != 0 {
                let view = self.emitter.view(p);
                let ls = self.emitter.sample(&view, p, ul);
                let s_l = cosine_hemisphere_pdf(dot(ls.direction, normal));
                let ratio = s_l / ls.pdf;
                let ok = zero.mask(light_lanes)
                    & ls.ok
                    & ls.pdf.gt(zero)
                    & s_l.gt(zero)
                    & ratio.le(zero.splat_like(f64::MAX));
                let p_material = wa * self.others.targets_pdf(views, p, ls.direction) + rest * s_l;
                let w = power_heuristic(ls.pdf, p_material);
                out.shadow = ok.bits();
                out.shadow_origin = store3(at.spawn(ls.direction));
                out.shadow_direction = store3(ls.direction);
                out.carried = store3([tp[0] * albedo[0], tp[1] * albedo[1], tp[2] * albedo[2]]);
                out.weight = (w * ratio).store();
            } else {
                out.shadow = 0;
            }

            // material sampling mixed with the other targets: the next ray
            let (d, r, mix, ok) = self.others.sample_seen(views, p, normal, um, lanes);
            let times = [
                tp[0] * (albedo[0] * r),
                tp[1] * (albedo[1] * r),
                tp[2] * (albedo[2] * r),
            ];
            out.next = (zero.mask(lanes) & ok).bits();
            out.p = store3(p);
            out.next_origin = store3(at.spawn(d));
            out.next_direction = store3(d);
            out.throughput = store3(times);
            out.pdf = mix.store();
        }
    }
}

#[cfg(target_arch = "x86_64")]
pub use wide::MisIn;

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use super::wide::heuristic;
    use crate::lanes::F64x8;
    use crate::wide8::{Avx2, Avx512, Wide8};

    /// Densities where the heuristic's cases meet: zeros of both signs, NaN, negative, subnormal,
    /// huge, infinite, equal.
    const EDGES: [f64; 12] = [
        0.0,
        -0.0,
        f64::NAN,
        -1.0,
        5e-324,
        1e-300,
        0.5,
        1.0,
        2.0,
        1e300,
        f64::MAX,
        f64::INFINITY,
    ];

    /// How many pairs `(a, b)` of [`EDGES`] (and of random densities) the lanes' heuristic with
    /// `h` (`POWER`: the square, else the identity) gives other bits for than rtl-pdf's power heuristic.
    unsafe fn mismatches<W: Wide8, const POWER: bool>() -> usize {
        let mut pairs: Vec<(f64, f64)> = EDGES
            .iter()
            .flat_map(|&a| EDGES.iter().map(move |&b| (a, b)))
            .collect();
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        for _ in 0..400 {
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let a = (x >> 11) as f64 / (1u64 << 53) as f64 * 8.0;
            x = x
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            pairs.push((a, (x >> 11) as f64 / (1u64 << 53) as f64 * 8.0));
        }
        let mut bad = 0;
        for chunk in pairs.chunks(8) {
            let (mut a, mut b) = (F64x8::ZERO, F64x8::ZERO);
            for (i, &(x, y)) in chunk.iter().enumerate() {
                (a.0[i], b.0[i]) = (x, y);
            }
            // SAFETY: the callers run this where the processor has `W`'s instructions.
            let w = unsafe { heuristic::<W, POWER>(W::load(&a), W::load(&b)) }.store();
            for (i, &(x, y)) in chunk.iter().enumerate() {
                bad += (w.0[i].to_bits() != rtl_pdf::power_heuristic(1.0, x, 1.0, y).to_bits())
                    as usize;
            }
        }
        bad
    }

    #[target_feature(enable = "avx2")]
    unsafe fn avx2<const POWER: bool>() -> usize {
        // SAFETY: compiled with AVX2, run where the processor has it.
        unsafe { mismatches::<Avx2, POWER>() }
    }

    #[target_feature(enable = "avx512f")]
    unsafe fn avx512<const POWER: bool>() -> usize {
        // SAFETY: compiled with AVX-512F, run where the processor has it.
        unsafe { mismatches::<Avx512, POWER>() }
    }

    /// The lanes' power heuristic is rtl-pdf's bit for bit, and the check sees the balance
    /// heuristic (`h(x) = x`) as wrong.
    #[test]
    fn the_lanes_power_heuristic_is_rtl_pdfs_bit_for_bit() {
        if std::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor has AVX2.
            unsafe {
                assert_eq!(avx2::<true>(), 0);
                assert!(avx2::<false>() > 100);
            }
        }
        if std::is_x86_feature_detected!("avx512f") {
            // SAFETY: the processor has AVX-512F.
            unsafe {
                assert_eq!(avx512::<true>(), 0);
                assert!(avx512::<false>() > 100);
            }
        }
    }
}
