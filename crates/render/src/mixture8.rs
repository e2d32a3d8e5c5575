//! The book's mixture density for eight Lambertian shading points at once (book 3, chapters 10 and
//! 12): `p = w p_targets + (1 - w) p_cosine`, sampled and evaluated in the lanes of AVX-512 registers
//! for eight paths traced side by side ([`crate::paths8`]).
//!
//! One path at a time, each vertex takes a branch the random numbers decide (the targets or the
//! cosine lobe; which target), and the processor mispredicts about half of them. In the lanes both
//! branches are computed and each lane keeps its own: the work of the branches not taken is what
//! the vector instructions buy back eight times over.
//!
//! Lane by lane, every number is the one [`crate::integrator`]'s `sample_diffuse` computes for the
//! `mixture` strategy from [`rtl_pdf::MixturePdf`], [`rtl_pdf::HittablePdf`] (uniform choice),
//! [`crate::lights::LightTarget`] and [`rtl_pdf::CosinePdf`]: the same operations in the same order
//! ([`crate::warp8`]), each early return a lane's failure. So the image is bit-identical (tested in
//! `crates/render/tests/paths8.rs`).

use crate::lights::LightTarget;
use glam::DVec3;
use rtl_pdf::QuadSampling;

/// One importance target, as the lanes read it.
#[derive(Clone, Copy, Debug)]
enum Target8 {
    /// A quad sampled by area ([`rtl_pdf::QuadTarget`]): corner, edges, unit normal, `1 / area`,
    /// dual basis, edge scale, and whether it is one-sided.
    Quad {
        q: DVec3,
        u: DVec3,
        v: DVec3,
        normal: DVec3,
        inv_area: f64,
        vw: DVec3,
        wu: DVec3,
        edge_scale: f64,
        one_sided: bool,
    },
    /// A sphere ([`rtl_pdf::SphereTarget`]): centre and radius.
    Sphere { center: DVec3, radius: f64 },
}

/// The `mixture` strategy's density at Lambertian points, for eight at once: the targets and the
/// share `w` of directions drawn towards them. Built once per render.
#[derive(Clone, Debug)]
pub struct Mixture8 {
    targets: Vec<Target8>,
    weight: f64,
}

impl Mixture8 {
    /// The mixture of the targets `lights` (the book's list) with share `weight` in `(0, 1)`; `None`
    /// if there are no targets (the strategy then samples the material alone) or a quad samples by
    /// spherical rectangles, which the lanes do not.
    pub fn new(lights: &[LightTarget], weight: f64) -> Option<Mixture8> {
        if lights.is_empty() || lights.len() > wide_limit() || !(weight > 0.0 && weight < 1.0) {
            return None;
        }
        let targets = lights
            .iter()
            .map(|t| match t {
                LightTarget::Quad { quad, one_sided } => (quad.sampling() == QuadSampling::Area)
                    .then(|| {
                        let (vw, wu) = quad.dual_basis();
                        Target8::Quad {
                            q: quad.q(),
                            u: quad.u(),
                            v: quad.v(),
                            normal: quad.normal(),
                            inv_area: quad.inv_area(),
                            vw,
                            wu,
                            edge_scale: quad.edge_scale(),
                            one_sided: *one_sided,
                        }
                    }),
                LightTarget::Sphere(s) => Some(Target8::Sphere {
                    center: s.center(),
                    radius: s.radius(),
                }),
            })
            .collect::<Option<Vec<_>>>()?;
        Some(Mixture8 { targets, weight })
    }
}

/// The most targets the lanes take.
fn wide_limit() -> usize {
    #[cfg(target_arch = "x86_64")]
    return wide::MAX_TARGETS;
    #[cfg(not(target_arch = "x86_64"))]
    0
}

#[cfg(target_arch = "x86_64")]
mod wide {
    use super::{Mixture8, Target8};
    use crate::warp8::*;
    use rtl_pdf::ONE_MINUS_EPSILON;
    use std::arch::x86_64::*;

    /// A direction and its density in each lane, and the lanes where the sampler succeeded.
    struct Sampled {
        direction: V3,
        pdf: F8,
        ok: M8,
    }

    /// rtl-pdf's `remap(u, lo, p)`: `((u - lo) / p).clamp(0, 1 - 2^-53)`, `lo` and `p` lane by lane.
    #[inline]
    #[target_feature(enable = "avx512f")]
    fn remap(u: F8, lo: F8, p: F8) -> F8 {
        clamp(div(sub(u, lo), p), 0.0, ONE_MINUS_EPSILON)
    }

    /// What a target looks like from the eight origins: all that its density and its sampler
    /// compute from the origin alone, computed once for both.
    #[derive(Clone, Copy)]
    enum View8 {
        /// A quad: the lanes behind it (one-sided) and those out of its plane.
        Quad { behind: M8, off: M8 },
        /// A sphere: the offset to its centre, its square, the lanes inside it, and the cone's
        /// `1 - cos theta_max` and density.
        Sphere {
            to_center: V3,
            d2: F8,
            surrounding: M8,
            omc: F8,
            cone_pdf: F8,
        },
    }

    impl Target8 {
        /// [`View8`] of this target from `origin`: `LightTarget::behind` and `QuadTarget::height`
        /// for a quad; `SphereTarget::view`'s terms for a sphere.
        #[inline(always)]
        unsafe fn view(&self, origin: V3) -> View8 {
            // SAFETY: called only from functions compiled with AVX-512F, into which it is inlined.
            unsafe {
                let zero = _mm512_setzero_pd();
                match *self {
                    Target8::Quad {
                        q,
                        normal,
                        edge_scale,
                        one_sided,
                        ..
                    } => {
                        let rel = sub3(origin, splat3(q));
                        let h = dot3(splat3(normal), rel);
                        let behind = if one_sided { le(h, zero) } else { 0 };
                        let magnitude = max_element3([abs(rel[0]), abs(rel[1]), abs(rel[2])]);
                        let scale = add(magnitude, splat(edge_scale));
                        let off = gt(abs(h), mul(splat(8.0 * f64::EPSILON), scale));
                        View8::Quad { behind, off }
                    }
                    Target8::Sphere { center, radius } => {
                        let to_center = sub3(splat3(center), origin);
                        let d2 = dot3(to_center, to_center);
                        let r2 = splat(radius * radius);
                        let surrounding =
                            le(d2, r2) | eq(d2, zero) | _mm512_cmp_pd_mask::<_CMP_UNORD_Q>(d2, d2);
                        let omc = cone_one_minus_cos(div(r2, d2));
                        View8::Sphere {
                            to_center,
                            d2,
                            surrounding,
                            omc,
                            cone_pdf: uniform_cone_pdf(omc),
                        }
                    }
                }
            }
        }

        /// rtl-pdf's `area_to_solid_angle(inv_area, origin, point, normal)`.
        #[inline(always)]
        unsafe fn area_to_solid_angle(
            inv_area: f64,
            origin: V3,
            point: V3,
            normal: glam::DVec3,
        ) -> F8 {
            // SAFETY: called only from functions compiled with AVX-512F, into which it is inlined.
            unsafe {
                let to = sub3(point, origin);
                let d2 = dot3(to, to);
                let cos_light = div(abs(dot3(splat3(normal), to)), sqrt(d2));
                let zero = _mm512_setzero_pd();
                let ok = gt(cos_light, zero) & gt(d2, zero);
                let pdf = div(mul(splat(inv_area), d2), cos_light);
                let ok = ok & le(abs(pdf), splat(f64::MAX));
                _mm512_maskz_mov_pd(ok, pdf)
            }
        }

        /// `LightTarget::pdf(origin, direction)` in each lane, `view` this target's from `origin`.
        #[inline(always)]
        unsafe fn pdf(&self, view: &View8, origin: V3, direction: V3) -> F8 {
            // SAFETY: called only from functions compiled with AVX-512F, into which it is inlined.
            unsafe {
                let zero = _mm512_setzero_pd();
                match (*self, *view) {
                    (
                        Target8::Quad {
                            q,
                            normal,
                            inv_area,
                            vw,
                            wu,
                            ..
                        },
                        View8::Quad { behind, off },
                    ) => {
                        // QuadTarget::hit: t = -h / (n . d), then the point's plane coordinates
                        let rel = sub3(origin, splat3(q));
                        let h = dot3(splat3(normal), rel);
                        let t = div(neg(h), dot3(splat3(normal), direction));
                        let point = add3(origin, scale3(t, direction));
                        let on = sub3(point, splat3(q));
                        let (a, b) = (dot3(on, splat3(vw)), dot3(on, splat3(wu)));
                        let one = splat(1.0);
                        let inside = le(zero, a) & le(a, one) & le(zero, b) & le(b, one);
                        let hit = !behind & off & positive_finite(t) & inside;
                        if hit == 0 {
                            return zero;
                        }
                        let pdf = Self::area_to_solid_angle(inv_area, origin, point, normal);
                        _mm512_maskz_mov_pd(hit, pdf)
                    }
                    (
                        Target8::Sphere { radius, .. },
                        View8::Sphere {
                            to_center,
                            surrounding,
                            omc,
                            cone_pdf,
                            ..
                        },
                    ) => {
                        let cross = cross3(to_center, direction);
                        let r2 = splat(radius * radius);
                        let missed =
                            le(dot3(to_center, direction), zero) | gt(dot3(cross, cross), r2);
                        let cone = _mm512_maskz_mov_pd(gt(omc, zero) & !missed, cone_pdf);
                        select(surrounding, splat(UNIFORM_SPHERE_PDF), cone)
                    }
                    _ => unreachable!("a target's view is of its own kind"),
                }
            }
        }

        /// `LightTarget::sample(origin, u)` in each lane, `view` this target's from `origin`.
        #[inline(always)]
        unsafe fn sample(&self, view: &View8, origin: V3, u: [F8; 2]) -> Sampled {
            // SAFETY: called only from functions compiled with AVX-512F, into which it is inlined.
            unsafe {
                match (*self, *view) {
                    (
                        Target8::Quad {
                            q,
                            u: e1,
                            v: e2,
                            normal,
                            inv_area,
                            ..
                        },
                        View8::Quad { behind, off },
                    ) => {
                        // q + u.x e1 + u.y e2
                        let p = add3(
                            add3(splat3(q), scale3(u[0], splat3(e1))),
                            scale3(u[1], splat3(e2)),
                        );
                        let to = sub3(p, origin);
                        let rcp = div(splat(1.0), sqrt(dot3(to, to)));
                        let direction = [mul(to[0], rcp), mul(to[1], rcp), mul(to[2], rcp)];
                        let pdf = Self::area_to_solid_angle(inv_area, origin, p, normal);
                        let ok = !behind & off & positive_finite(rcp) & positive_finite(pdf);
                        Sampled { direction, pdf, ok }
                    }
                    (
                        Target8::Sphere { .. },
                        View8::Sphere {
                            to_center,
                            d2,
                            surrounding,
                            omc,
                            cone_pdf,
                        },
                    ) => {
                        // the cone about the axis towards the centre
                        let root = sqrt(d2);
                        let axis = [
                            div(to_center[0], root),
                            div(to_center[1], root),
                            div(to_center[2], root),
                        ];
                        let local = sample_uniform_cone(u, omc);
                        let mut s = Sampled {
                            direction: Onb8::new(axis).transform(local),
                            pdf: cone_pdf,
                            ok: positive_finite(cone_pdf),
                        };
                        // or all around, from inside
                        if surrounding != 0 {
                            let around = sample_uniform_sphere(u);
                            s.direction = select3(surrounding, around, s.direction);
                            s.pdf = select(surrounding, splat(UNIFORM_SPHERE_PDF), s.pdf);
                            s.ok |= surrounding;
                        }
                        s
                    }
                    _ => unreachable!("a target's view is of its own kind"),
                }
            }
        }
    }

    /// The most targets the lanes take (their views are kept on the stack).
    pub const MAX_TARGETS: usize = 8;

    /// `x / n` for a count `n`: a multiplication by `1 / n` where `n` is a power of two (both are
    /// exact scalings by a power of two, so the same number), else the division.
    #[inline]
    #[target_feature(enable = "avx512f")]
    fn over(x: F8, n: usize) -> F8 {
        if n.is_power_of_two() {
            mul(x, splat(1.0 / n as f64))
        } else {
            div(x, splat(n as f64))
        }
    }

    impl Mixture8 {
        /// `sample_diffuse` of the `mixture` strategy at Lambertian points `p` with unit normals
        /// `normal`, from the numbers `u` (the bounce's material pair), in the lanes of `lanes`: the
        /// direction, the weight `s / p` (the cosine density over the mixture's), and the lanes
        /// where both are usable (elsewhere the path ends, as `None` ends it).
        ///
        /// Both branches are drawn where some lane takes them and the direction is chosen lane by
        /// lane; each target is seen from the origins once and its density evaluated once, at the
        /// chosen direction: a lane that sampled the targets adds the others' densities to its
        /// own, one that sampled the cosine lobe takes them all, in the targets' order, as the
        /// scalar code adds them.
        ///
        /// # Safety
        /// Only where the processor has AVX-512F.
        #[target_feature(enable = "avx512f")]
        pub unsafe fn sample(&self, p: V3, normal: V3, u: [F8; 2], lanes: M8) -> (V3, F8, M8) {
            // SAFETY: this function is compiled with AVX-512F and runs where the processor has it.
            unsafe {
                let (wa, n) = (self.weight, self.targets.len());
                let zero = _mm512_setzero_pd();
                let towards = lanes & lt(u[0], splat(wa));
                let material = lanes & !towards;
                let mut views = [View8::Quad { behind: 0, off: 0 }; MAX_TARGETS];
                for (view, t) in views.iter_mut().zip(&self.targets) {
                    *view = t.view(p);
                }
                // u.x's rest: remap(u.x, 0, w) towards the targets, remap(u.x, w, 1 - w) else
                let rest = remap(
                    u[0],
                    select(towards, zero, splat(wa)),
                    select(towards, splat(wa), splat(1.0 - wa)),
                );
                // the targets' sample: target i = min(floor(n u), n - 1) (a float cast saturates,
                // NaN and below 0 giving 0) with the rest of n u (choose_uniform)
                let (mut direction, mut own, mut chosen, mut ok) = ([zero; 3], zero, zero, 0);
                if towards != 0 {
                    let ut = if n == 1 {
                        [rest, u[1]]
                    } else {
                        let scaled = mul(rest, splat(n as f64));
                        chosen = min(trunc(max(scaled, zero)), splat((n - 1) as f64));
                        [clamp(sub(scaled, chosen), 0.0, ONE_MINUS_EPSILON), u[1]]
                    };
                    for (j, t) in self.targets.iter().enumerate() {
                        let these = towards & eq(chosen, splat(j as f64));
                        if these == 0 {
                            continue;
                        }
                        let s = t.sample(&views[j], p, ut);
                        direction = select3(these, s.direction, direction);
                        own = select(these, s.pdf, own);
                        ok |= these & s.ok;
                    }
                }
                // the cosine lobe's
                let mut lobe = zero;
                if material != 0 {
                    let local = sample_cosine_hemisphere([rest, u[1]]);
                    lobe = cosine_hemisphere_pdf(local[2]);
                    direction = select3(material, Onb8::new(normal).transform(local), direction);
                    ok |= material & positive_finite(lobe);
                }
                // the targets' densities at the chosen direction, in order
                let (mut with_own, mut all) = (own, zero);
                for (j, t) in self.targets.iter().enumerate() {
                    let pj = t.pdf(&views[j], p, direction);
                    let other = !eq(chosen, splat(j as f64));
                    with_own = _mm512_mask_add_pd(with_own, other, with_own, pj);
                    all = if j == 0 { pj } else { add(all, pj) };
                }
                let (with_own, all) = if n == 1 {
                    (own, all)
                } else {
                    (over(with_own, n), over(all, n))
                };
                let cos = cosine_hemisphere_pdf(dot3(direction, normal));
                // towards: w s.pdf + (1 - w) p_cosine; the lobe: w p_targets + (1 - w) s.pdf
                let (w, rest) = (splat(wa), splat(1.0 - wa));
                let mix = select(
                    towards,
                    add(mul(w, with_own), mul(rest, cos)),
                    add(mul(w, all), mul(rest, lobe)),
                );
                // ratio(s, p): s / p where p > 0, s > 0 and the quotient is finite
                let r = div(cos, mix);
                let ok = ok & gt(mix, zero) & gt(cos, zero) & le(r, splat(f64::MAX));
                (direction, r, ok)
            }
        }
    }
}
