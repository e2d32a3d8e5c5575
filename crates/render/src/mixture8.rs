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
pub(crate) enum Target8 {
    /// A quad sampled by area ([`rtl_pdf::QuadTarget`]): corner, edges, unit normal, `1 / area`,
    /// dual basis, edge scale, the terms of its edges' slack, and whether it is one-sided.
    Quad {
        q: DVec3,
        u: DVec3,
        v: DVec3,
        normal: DVec3,
        inv_area: f64,
        vw: DVec3,
        wu: DVec3,
        edge_scale: f64,
        coord_scale: f64,
        slack_unit: f64,
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
    /// How many targets.
    pub fn targets(&self) -> usize {
        self.targets.len()
    }

    /// The targets, in the lanes' form.
    pub(crate) fn target_list(&self) -> &[Target8] {
        &self.targets
    }

    /// The mixture of the targets `lights` (the book's list) with share `weight` in `(0, 1)`; `None`
    /// if there are no targets (the strategy then samples the material alone) or a quad samples by
    /// spherical rectangles, which the lanes do not.
    pub fn new(lights: &[LightTarget], weight: f64) -> Option<Mixture8> {
        if lights.is_empty()
            || lights.len() > MAX_TARGETS
            || crate::render::check_mixture_weight(weight).is_err()
        {
            return None;
        }
        let targets = lights
            .iter()
            .map(Target8::new)
            .collect::<Option<Vec<_>>>()?;
        Some(Mixture8 { targets, weight })
    }
}

impl Target8 {
    /// `t` as the lanes read it; `None` for a quad that samples by spherical rectangles, which the
    /// lanes do not.
    pub(crate) fn new(t: &LightTarget) -> Option<Target8> {
        match t {
            LightTarget::Quad { quad, one_sided } => {
                (quad.sampling() == QuadSampling::Area).then(|| {
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
                        coord_scale: quad.coord_scale(),
                        slack_unit: quad.slack_unit(),
                        one_sided: *one_sided,
                    }
                })
            }
            LightTarget::Sphere(s) => Some(Target8::Sphere {
                center: s.center(),
                radius: s.radius(),
            }),
        }
    }
}

/// The most targets the lanes take (their views are kept on the stack).
pub const MAX_TARGETS: usize = 8;

/// The targets of the book's scenes (the Cornell box's light and glass ball): up to this many,
/// the lanes build each target's view in its place on the stack, rather than in an array of
/// [`MAX_TARGETS`] cleared first.
pub const FEW_TARGETS: usize = 2;

#[cfg(target_arch = "x86_64")]
pub(crate) mod wide {
    use super::{MAX_TARGETS, Mixture8, Target8};
    use crate::lanes::F64x8;
    use crate::warp8::*;
    use crate::wide8::*;
    use rtl_pdf::ONE_MINUS_EPSILON;

    /// The directions, the weights and the lanes where the path goes on, stored.
    pub type Stored = ([F64x8; 3], F64x8, u8);

    /// A direction and its density in each lane, and the lanes where the sampler succeeded.
    pub(crate) struct Sampled<W: Wide8> {
        pub direction: V3<W>,
        pub pdf: W,
        pub ok: W::Mask,
    }

    /// rtl-pdf's `remap(u, lo, p)`: `((u - lo) / p).clamp(0, 1 - 2^-53)`, `lo` and `p` lane by lane.
    #[inline(always)]
    fn remap<W: Wide8>(u: W, lo: W, p: W) -> W {
        ((u - lo) / p).clamp(0.0, ONE_MINUS_EPSILON)
    }

    /// `x / n` for a count `n`: a multiplication by `1 / n` where `n` is a power of two (both are
    /// exact scalings by a power of two, so the same number), else the division.
    #[inline(always)]
    fn over<W: Wide8>(x: W, n: usize) -> W {
        if n.is_power_of_two() {
            x * x.splat_like(1.0 / n as f64)
        } else {
            x / x.splat_like(n as f64)
        }
    }

    /// What a target looks like from the eight origins: all that its density and its sampler
    /// compute from the origin alone, computed once for both.
    #[derive(Clone, Copy)]
    pub(crate) enum View8<W: Wide8> {
        /// A quad: the origin's height `h` above its plane, the lanes behind it (one-sided) and
        /// those out of its plane, and the part of the magnitude of the coordinates in its edges'
        /// slack that depends on the origin alone (`reach + |o| + coord_scale`).
        Quad {
            h: W,
            behind: W::Mask,
            off: W::Mask,
            magnitude: W,
        },
        /// A sphere: the offset to its centre, its square and the radius squared (both divided
        /// by the largest coordinate of the offset squared where `SphereTarget::relative` divides
        /// them), the lanes inside it, and the cone's `1 - cos theta_max` and density.
        Sphere {
            to_center: V3<W>,
            d2: W,
            r2: W,
            surrounding: W::Mask,
            omc: W,
            cone_pdf: W,
        },
        /// Not made (an entry past the targets).
        Nothing,
    }

    impl<W: Wide8> View8<W> {
        /// A placeholder for a view not yet made.
        pub(crate) const NONE: View8<W> = View8::Nothing;
    }

    impl Target8 {
        /// [`View8`] of this target from `origin`: `LightTarget::behind` and `QuadTarget::height`
        /// for a quad; `SphereTarget::view`'s terms for a sphere.
        #[inline(always)]
        pub(crate) fn view<W: Wide8>(&self, origin: V3<W>) -> View8<W> {
            let o = origin[0];
            let zero = o.zero_like();
            match *self {
                Target8::Quad {
                    q,
                    normal,
                    edge_scale,
                    coord_scale,
                    one_sided,
                    ..
                } => {
                    let rel = sub3(origin, splat3_like(o, q));
                    let h = dot(splat3_like(o, normal), rel);
                    let behind = if one_sided { h.le(zero) } else { o.mask(0) };
                    let reach = max_element([rel[0].abs(), rel[1].abs(), rel[2].abs()]);
                    let scale = reach + o.splat_like(edge_scale);
                    let off = h.abs().gt(o.splat_like(8.0 * f64::EPSILON) * scale);
                    let o_max = max_element([origin[0].abs(), origin[1].abs(), origin[2].abs()]);
                    let magnitude = reach + o_max + o.splat_like(coord_scale);
                    View8::Quad {
                        h,
                        behind,
                        off,
                        magnitude,
                    }
                }
                Target8::Sphere { center, radius } => {
                    let mut to_center = sub3(splat3_like(o, center), origin);
                    let mut d2 = dot(to_center, to_center);
                    let mut r2 = o.splat_like(radius * radius);
                    // SphereTarget::relative: where d^2 overflows (a sphere more than 1.3e154
                    // away) or r^2 leaves the normal range, both in the unit of the largest
                    // coordinate of c - o (lanes where that is 0 or not finite keep the plain
                    // squares)
                    let plain =
                        d2.le(o.splat_like(f64::MAX)) & r2.ge(o.splat_like(f64::MIN_POSITIVE));
                    let m =
                        max_element([to_center[0].abs(), to_center[1].abs(), to_center[2].abs()]);
                    let scaled = !plain & m.positive_finite();
                    if !scaled.is_empty() {
                        let unit = [to_center[0] / m, to_center[1] / m, to_center[2] / m];
                        let r = o.splat_like(radius) / m;
                        to_center = select3(to_center, scaled, unit);
                        d2 = d2.select(scaled, dot(unit, unit));
                        r2 = r2.select(scaled, r * r);
                    }
                    let surrounding = d2.le(r2) | d2.eq(zero) | d2.is_nan();
                    // (0 below the directions' resolution, as SphereTarget::view)
                    let s2 = r2 / d2;
                    let omc = cone_one_minus_cos(s2)
                        .zero_unless(s2.ge(o.splat_like(rtl_pdf::MIN_CONE_SIN2)));
                    View8::Sphere {
                        to_center,
                        d2,
                        r2,
                        surrounding,
                        omc,
                        cone_pdf: uniform_cone_pdf(omc),
                    }
                }
            }
        }

        /// rtl-pdf's `area_to_solid_angle(inv_area, origin, point, normal)`.
        #[inline(always)]
        fn area_to_solid_angle<W: Wide8>(
            inv_area: f64,
            origin: V3<W>,
            point: V3<W>,
            normal: V3<W>,
        ) -> W {
            let to = sub3(point, origin);
            let d2 = dot(to, to);
            let cos_light = dot(normal, to).abs() / d2.sqrt();
            let zero = d2.zero_like();
            let ok = cos_light.gt(zero) & d2.gt(zero);
            let pdf = d2.splat_like(inv_area) * d2 / cos_light;
            let ok = ok & pdf.abs().le(d2.splat_like(f64::MAX));
            pdf.zero_unless(ok)
        }

        /// `LightTarget::pdf(origin, direction)` in each lane, `view` this target's from `origin`.
        #[inline(always)]
        pub(crate) fn pdf<W: Wide8>(&self, view: &View8<W>, origin: V3<W>, direction: V3<W>) -> W {
            let o = origin[0];
            let zero = origin[0].zero_like();
            match (*self, *view) {
                (
                    Target8::Quad {
                        q,
                        normal,
                        inv_area,
                        vw,
                        wu,
                        slack_unit,
                        ..
                    },
                    View8::Quad {
                        h,
                        behind,
                        off,
                        magnitude,
                    },
                ) => {
                    // QuadTarget::hit: t = -h / (n . d), then the point's plane coordinates, in
                    // [0, 1] to within QuadTarget::edge_slack (which the scalar code computes only
                    // outside [0, 1]^2: the slack is never negative, so the lanes' one test is the
                    // same)
                    let normal = splat3_like(o, normal);
                    let t = -h / dot(normal, direction);
                    let point = add3(origin, scale3(t, direction));
                    let on = sub3(point, splat3_like(o, q));
                    let (a, b) = (dot(on, splat3_like(o, vw)), dot(on, splat3_like(o, wu)));
                    let slack = (zero.splat_like(slack_unit) * t * (magnitude + t) / h.abs())
                        .min(zero.splat_like(rtl_pdf::MAX_EDGE_SLACK));
                    let (lo, hi) = (zero - slack, zero.splat_like(1.0) + slack);
                    let inside = lo.le(a) & a.le(hi) & lo.le(b) & b.le(hi);
                    let hit = !behind & off & t.positive_finite() & inside;
                    if hit.is_empty() {
                        return zero;
                    }
                    Self::area_to_solid_angle(inv_area, origin, point, normal).zero_unless(hit)
                }
                (
                    Target8::Sphere { .. },
                    View8::Sphere {
                        to_center,
                        r2,
                        surrounding,
                        cone_pdf,
                        ..
                    },
                ) => {
                    let c = cross(to_center, direction);
                    let missed = dot(to_center, direction).le(zero) | dot(c, c).gt(r2);
                    // (0 where the cone's density is not a finite number, as SphereTarget::pdf:
                    // where 1 - cos theta_max is 0, below the directions' resolution or by
                    // underflow, and where it is so small the density overflows)
                    let cone = cone_pdf.zero_unless(cone_pdf.positive_finite() & !missed);
                    cone.select(
                        surrounding,
                        zero.splat_like(rtl_pdf::warp::uniform_sphere_pdf()),
                    )
                }
                _ => unreachable!("a target's view is of its own kind"),
            }
        }

        /// `LightTarget::sample(origin, u)` in each lane, `view` this target's from `origin`.
        #[inline(always)]
        pub(crate) fn sample<W: Wide8>(
            &self,
            view: &View8<W>,
            origin: V3<W>,
            u: [W; 2],
        ) -> Sampled<W> {
            let o = origin[0];
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
                    View8::Quad { behind, off, .. },
                ) => {
                    // q + u.x e1 + u.y e2
                    let p = add3(
                        add3(splat3_like(o, q), scale3(u[0], splat3_like(o, e1))),
                        scale3(u[1], splat3_like(o, e2)),
                    );
                    let to = sub3(p, origin);
                    let rcp = u[0].splat_like(1.0) / dot(to, to).sqrt();
                    let direction = [to[0] * rcp, to[1] * rcp, to[2] * rcp];
                    let pdf =
                        Self::area_to_solid_angle(inv_area, origin, p, splat3_like(o, normal));
                    let ok = !behind & off & rcp.positive_finite() & pdf.positive_finite();
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
                        ..
                    },
                ) => {
                    // the cone about the axis towards the centre
                    let root = d2.sqrt();
                    let axis = [
                        to_center[0] / root,
                        to_center[1] / root,
                        to_center[2] / root,
                    ];
                    let local = sample_uniform_cone(u, omc);
                    let mut s = Sampled {
                        direction: Onb8::new(axis).transform(local),
                        pdf: cone_pdf,
                        ok: cone_pdf.positive_finite(),
                    };
                    // or all around, from inside
                    if !surrounding.is_empty() {
                        s.direction = select3(s.direction, surrounding, sample_uniform_sphere(u));
                        s.pdf = s.pdf.select(
                            surrounding,
                            d2.splat_like(rtl_pdf::warp::uniform_sphere_pdf()),
                        );
                        s.ok = s.ok | surrounding;
                    }
                    s
                }
                _ => unreachable!("a target's view is of its own kind"),
            }
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
        #[inline(always)]
        pub(crate) fn sample_in<W: Wide8>(
            &self,
            p: V3<W>,
            normal: V3<W>,
            u: [W; 2],
            lanes: u8,
        ) -> (V3<W>, W, W::Mask) {
            // (the views on the stack, a few hundred bytes each: for the book's scenes' one or
            // two targets each built in its place, for more an array cleared first)
            let (d, r, _, ok) = match self.targets.as_slice() {
                [a] => self.sample_seen(&[a.view(p)], p, normal, u, lanes),
                [a, b] => self.sample_seen(&[a.view(p), b.view(p)], p, normal, u, lanes),
                _ => {
                    let mut views = [View8::NONE; MAX_TARGETS];
                    self.see_from(p, &mut views);
                    self.sample_seen(&views, p, normal, u, lanes)
                }
            };
            (d, r, ok)
        }

        /// Each target's [`View8`] from the points `p`, one a target from the first entry of
        /// `views` on, which has room for them all (in place: the views are large, and returned
        /// they would be copied).
        #[inline(always)]
        pub(crate) fn see_from<W: Wide8>(&self, p: V3<W>, views: &mut [View8<W>]) {
            for (view, t) in views.iter_mut().zip(&self.targets) {
                *view = t.view(p);
            }
        }

        /// The targets' density `(1 / n) sum_j p_j(direction)` from the points their `views` are
        /// of (one a target), in order (`HittablePdf::pdf`, uniform choice).
        #[inline(always)]
        pub(crate) fn targets_pdf<W: Wide8>(
            &self,
            views: &[View8<W>],
            p: V3<W>,
            direction: V3<W>,
        ) -> W {
            let mut all = p[0].zero_like();
            for (j, t) in self.targets.iter().enumerate() {
                let pj = t.pdf(&views[j], p, direction);
                all = if j == 0 { pj } else { all + pj };
            }
            if self.targets.len() == 1 {
                all
            } else {
                over(all, self.targets.len())
            }
        }

        /// [`Mixture8::sample_in`] with the targets' `views` from `p` made by the caller: the
        /// direction, the weight `s / p`, the mixture's density `p` of the direction, and the
        /// lanes where they are usable.
        #[inline(always)]
        pub(crate) fn sample_seen<W: Wide8>(
            &self,
            views: &[View8<W>],
            p: V3<W>,
            normal: V3<W>,
            u: [W; 2],
            lanes: u8,
        ) -> (V3<W>, W, W, W::Mask) {
            let (wa, n) = (self.weight, self.targets.len());
            let zero = u[0].zero_like();
            let lanes = zero.mask(lanes);
            let towards = lanes & u[0].lt(zero.splat_like(wa));
            let material = lanes & !towards;
            // u.x's rest: remap(u.x, 0, w) towards the targets, remap(u.x, w, 1 - w) else
            let (w, rest_w) = (zero.splat_like(wa), zero.splat_like(1.0 - wa));
            let rest = remap(u[0], w.select(towards, zero), rest_w.select(towards, w));
            // the targets' sample: target i = min(floor(n u), n - 1) (a float cast saturates, NaN
            // and below 0 giving 0) with the rest of n u (rtl-pdf's choose_uniform)
            let (mut direction, mut own, mut chosen, mut ok) =
                ([zero; 3], zero, zero, zero.mask(0));
            if !towards.is_empty() {
                let ut = if n == 1 {
                    [rest, u[1]]
                } else {
                    let scaled = rest * zero.splat_like(n as f64);
                    chosen = scaled
                        .max(zero)
                        .trunc()
                        .min(zero.splat_like((n - 1) as f64));
                    [(scaled - chosen).clamp(0.0, ONE_MINUS_EPSILON), u[1]]
                };
                for (j, t) in self.targets.iter().enumerate() {
                    let these = towards & chosen.eq(zero.splat_like(j as f64));
                    if these.is_empty() {
                        continue;
                    }
                    let s = t.sample(&views[j], p, ut);
                    direction = select3(direction, these, s.direction);
                    own = own.select(these, s.pdf);
                    ok = ok | (these & s.ok);
                }
            }
            // the cosine lobe's
            let mut lobe = zero;
            if !material.is_empty() {
                let local = sample_cosine_hemisphere([rest, u[1]]);
                lobe = cosine_hemisphere_pdf(local[2]);
                direction = select3(direction, material, Onb8::new(normal).transform(local));
                ok = ok | (material & lobe.positive_finite());
            }
            // the targets' densities at the chosen direction, in order
            let (mut with_own, mut all) = (own, zero);
            for (j, t) in self.targets.iter().enumerate() {
                let pj = t.pdf(&views[j], p, direction);
                let other = !chosen.eq(zero.splat_like(j as f64));
                with_own = with_own.select(other, with_own + pj);
                all = if j == 0 { pj } else { all + pj };
            }
            let (with_own, all) = if n == 1 {
                (own, all)
            } else {
                (over(with_own, n), over(all, n))
            };
            let cos = cosine_hemisphere_pdf(dot(direction, normal));
            // towards: w s.pdf + (1 - w) p_cosine; the lobe: w p_targets + (1 - w) s.pdf
            let mix = (w * all + rest_w * lobe).select(towards, w * with_own + rest_w * cos);
            // ratio(s, p): s / p where p > 0, s > 0 and the quotient is finite
            let r = cos / mix;
            let ok = ok & mix.gt(zero) & cos.gt(zero) & r.le(zero.splat_like(f64::MAX));
            (direction, r, mix, ok)
        }

        /// [`Mixture8::sample_in`] with the lanes stored: the directions, the weights, and the
        /// lanes where they are usable.
        #[inline(always)]
        unsafe fn sample_stored<W: Wide8>(
            &self,
            p: &[F64x8; 3],
            normal: &[F64x8; 3],
            u: &[F64x8; 2],
            lanes: u8,
        ) -> Stored {
            // SAFETY: as the caller's.
            let (p, normal, u) = unsafe {
                (
                    load3::<W>(p),
                    load3::<W>(normal),
                    [W::load(&u[0]), W::load(&u[1])],
                )
            };
            let (d, w, ok) = self.sample_in(p, normal, u, lanes);
            (
                [d[0].store(), d[1].store(), d[2].store()],
                w.store(),
                ok.bits(),
            )
        }

        /// `sample_diffuse` of `mixture` for the Lambertian points `p` (unit normals `normal`,
        /// numbers `u`) in the lanes of `lanes`, in the instructions of `tier` (AVX-512, else
        /// AVX2): the directions, their weights `s / p`, and the lanes where the path goes on.
        ///
        /// # Safety
        /// Only where the processor runs `tier`, which is AVX2 or AVX-512.
        pub unsafe fn sample(
            &self,
            tier: crate::traversal::HitTier,
            p: &[F64x8; 3],
            normal: &[F64x8; 3],
            u: &[F64x8; 2],
            lanes: u8,
        ) -> Stored {
            // SAFETY: as this function's.
            unsafe {
                match tier {
                    crate::traversal::HitTier::Avx512 => self.avx512(p, normal, u, lanes),
                    _ => self.avx2(p, normal, u, lanes),
                }
            }
        }

        #[target_feature(enable = "avx512f")]
        unsafe fn avx512(&self, p: &[F64x8; 3], n: &[F64x8; 3], u: &[F64x8; 2], l: u8) -> Stored {
            // SAFETY: compiled with AVX-512F, run where the processor has it.
            unsafe { self.sample_stored::<Avx512>(p, n, u, l) }
        }

        #[target_feature(enable = "avx2")]
        unsafe fn avx2(&self, p: &[F64x8; 3], n: &[F64x8; 3], u: &[F64x8; 2], l: u8) -> Stored {
            // SAFETY: compiled with AVX2, run where the processor has it.
            unsafe { self.sample_stored::<Avx2>(p, n, u, l) }
        }
    }

    #[cfg(test)]
    mod tests {
        use super::{Target8, View8};
        use crate::lanes::F64x8;
        use crate::lights::LightTarget;
        use crate::wide8::*;
        use glam::{DVec2, DVec3};
        use rtl_pdf::{QuadTarget, ShapeSampler, SphereTarget};

        /// Per lane: the density of `d` from `o`, and the sample for `u` (its direction's and
        /// density's bits where it succeeded).
        type Answers = [(u64, Option<([u64; 3], u64)>); 8];

        #[inline(always)]
        unsafe fn answers<W: Wide8>(
            t: &Target8,
            o: &[DVec3; 8],
            d: &[DVec3; 8],
            u: &[DVec2; 8],
        ) -> Answers {
            let three = |v: &[DVec3; 8]| -> [F64x8; 3] {
                std::array::from_fn(|a| F64x8(std::array::from_fn(|i| v[i][a])))
            };
            // SAFETY: as the caller's.
            let (o, d, u) = unsafe {
                (
                    load3::<W>(&three(o)),
                    load3::<W>(&three(d)),
                    [
                        W::load(&F64x8(std::array::from_fn(|i| u[i].x))),
                        W::load(&F64x8(std::array::from_fn(|i| u[i].y))),
                    ],
                )
            };
            let view: View8<W> = t.view(o);
            let pdf = t.pdf(&view, o, d).store();
            let s = t.sample(&view, o, u);
            let (dir, sp, ok) = (store3(s.direction), s.pdf.store(), s.ok.bits());
            std::array::from_fn(|i| {
                let got = (ok & (1 << i) != 0).then(|| {
                    (
                        [dir[0].0[i], dir[1].0[i], dir[2].0[i]].map(f64::to_bits),
                        sp.0[i].to_bits(),
                    )
                });
                (pdf.0[i].to_bits(), got)
            })
        }

        #[target_feature(enable = "avx2")]
        unsafe fn avx2(t: &Target8, o: &[DVec3; 8], d: &[DVec3; 8], u: &[DVec2; 8]) -> Answers {
            // SAFETY: compiled with AVX2, run where the processor has it.
            unsafe { answers::<Avx2>(t, o, d, u) }
        }

        #[target_feature(enable = "avx512f")]
        unsafe fn avx512(t: &Target8, o: &[DVec3; 8], d: &[DVec3; 8], u: &[DVec2; 8]) -> Answers {
            // SAFETY: compiled with AVX-512F, run where the processor has it.
            unsafe { answers::<Avx512>(t, o, d, u) }
        }

        /// How many lanes of `target`'s density and sample in the lanes (in every tier this
        /// processor runs) differ from `LightTarget::pdf` and `LightTarget::sample`, bit for bit,
        /// for the origins `o`, directions `d` and numbers `u`; and how many lanes were compared.
        fn mismatches(
            target: &LightTarget,
            o: &[DVec3; 8],
            d: &[DVec3; 8],
            u: &[DVec2; 8],
        ) -> (usize, usize) {
            let t = Target8::new(target).expect("the lanes take this target");
            let want: Answers = std::array::from_fn(|i| {
                let s = target
                    .sample(o[i], u[i])
                    .map(|s| (s.direction.to_array().map(f64::to_bits), s.pdf.to_bits()));
                (target.pdf(o[i], d[i]).to_bits(), s)
            });
            let (mut bad, mut compared) = (0, 0);
            let mut tiers: Vec<Answers> = Vec::new();
            if std::arch::is_x86_feature_detected!("avx2") {
                // SAFETY: the processor runs AVX2.
                tiers.push(unsafe { avx2(&t, o, d, u) });
            }
            if std::arch::is_x86_feature_detected!("avx512f") {
                // SAFETY: the processor runs AVX-512F.
                tiers.push(unsafe { avx512(&t, o, d, u) });
            }
            for got in tiers {
                for i in 0..8 {
                    compared += 1;
                    bad += (got[i] != want[i]) as usize;
                }
            }
            (bad, compared)
        }

        /// The numbers at the edges of the unit square: a point drawn with one of them lies on an
        /// edge of the quad (`2^-60` rounds onto it).
        const EDGE_US: [f64; 4] = [0.0, 8.673617379884035e-19, 0.5, 1.0 - f64::EPSILON / 2.0];

        /// Towards points on a quad's edges, from near, far and grazing origins, the lanes'
        /// density is the scalar one to the bit (including where its intersection lies outside the
        /// parameter square by a rounding error, inside `QuadTarget::edge_slack`), and positive.
        #[test]
        fn a_quads_edges_in_the_lanes_are_the_scalar_ones_bit_for_bit() {
            let quads = [
                QuadTarget::new(
                    DVec3::new(343.0, 554.0, 332.0),
                    DVec3::new(-130.0, 0.0, 0.0),
                    DVec3::new(0.0, 0.0, -105.0),
                ),
                QuadTarget::new(
                    DVec3::new(0.3, 1.7, -2.1),
                    DVec3::new(1.3, 0.2, 0.1),
                    DVec3::new(0.1, -0.7, 0.9),
                ),
            ];
            let (mut compared, mut outside_then_in, mut positive) = (0, 0, 0);
            for (k, quad) in quads.iter().enumerate() {
                let target = LightTarget::Quad {
                    quad: *quad,
                    one_sided: k == 1,
                };
                let (q, e1, e2, n) = (quad.q(), quad.u(), quad.v(), quad.normal());
                let size = e1.length();
                let centre = q + 0.5 * (e1 + e2);
                let origins = [
                    centre + 0.5 * size * n,
                    centre - 0.3 * size * n + 0.2 * e1,
                    q + 1e-3 * size * n,
                    centre + 1e3 * size * n + 200.0 * e2,
                    q + 3.0 * e1 + 0.4 * e2 + 3e-3 * size * n,
                    q - 2.0 * e2 + 0.5 * e1 + 2e-6 * size * n,
                    q + 1e3 * (e1 + e2) + size * n,
                    centre + 1e6 * size * n,
                ];
                for ux in EDGE_US {
                    for uy in EDGE_US {
                        let u = [DVec2::new(ux, uy); 8];
                        // each lane its own origin, towards the point u names on the quad
                        let d: [DVec3; 8] = std::array::from_fn(|i| {
                            (q + ux * e1 + uy * e2 - origins[i]).normalize()
                        });
                        let (bad, n) = mismatches(&target, &origins, &d, &u);
                        assert_eq!(bad, 0, "quad {k} at ({ux}, {uy})");
                        compared += n;
                        for i in 0..8 {
                            let b = d[i];
                            let p = target.pdf(origins[i], b);
                            if p > 0.0 {
                                positive += 1;
                                // the strict test alone: the intersection in [0, 1]^2
                                let h = quad.normal().dot(origins[i] - quad.q());
                                let t = -h / quad.normal().dot(b);
                                let at = origins[i] + t * b - quad.q();
                                let (vw, wu) = quad.dual_basis();
                                let (aa, bb) = (at.dot(vw), at.dot(wu));
                                let strict = (0.0..=1.0).contains(&aa) && (0.0..=1.0).contains(&bb);
                                outside_then_in += !strict as usize;
                            }
                        }
                    }
                }
            }
            assert!(compared >= 2 * 16 * 8, "{compared}");
            // (one-sided from behind: 0; every other one positive)
            assert!(positive >= 3 * 16 * 8 / 2, "{positive}");
            assert!(
                outside_then_in > 10,
                "the slack was needed {outside_then_in} times"
            );
        }

        /// A sphere beyond the squares of f64 (1e200 away: `d^2` overflows) and one too small
        /// for `r^2` to be a normal number: the lanes rescale as `SphereTarget` does, and give its
        /// density and samples to the bit, finite and positive towards a sphere wide enough to see
        /// (`seen`: above `MIN_CONE_SIN2`), none and 0 towards one too narrow.
        #[test]
        fn a_sphere_beyond_the_squares_in_the_lanes_is_the_scalar_one_bit_for_bit() {
            let spheres = [
                (DVec3::new(1e200, 3e199, -2e199), 1e198, true),
                (DVec3::new(-4e180, 1e160, 7e175), 5e171, true),
                (DVec3::new(0.5, -0.25, 2.0), 1e-160, false),
                (DVec3::new(1e200, 0.0, 0.0), 1e191, true),
                (DVec3::new(1e200, 0.0, 0.0), 1e150, false),
            ];
            let origins: [DVec3; 8] = std::array::from_fn(|i| {
                DVec3::new(i as f64 - 3.0, 0.5 * i as f64, -1.0) * [1.0, 1e3, 1e-3, 1e100][i % 4]
            });
            let us: [DVec2; 8] =
                std::array::from_fn(|i| DVec2::new(EDGE_US[i % 4], EDGE_US[(i / 2) % 4]));
            for (centre, radius, seen) in spheres {
                let target = LightTarget::Sphere(SphereTarget::new(centre, radius));
                // (c - o scaled before it is normalised: its length overflows)
                let towards: [DVec3; 8] = std::array::from_fn(|i| {
                    let c = centre - origins[i];
                    (c / c.abs().max_element()).normalize()
                });
                let (bad, _) = mismatches(&target, &origins, &towards, &us);
                assert_eq!(bad, 0, "sphere at {centre}, radius {radius}");
                // and the scalar numbers are usable ones (what the lanes gave before: no sample,
                // density 0, where the axis was the zero vector)
                for i in 0..8 {
                    let p = target.pdf(origins[i], towards[i]);
                    let s = target.sample(origins[i], us[i]);
                    if !seen {
                        assert!(p == 0.0 && s.is_none(), "{centre}, radius {radius}");
                        continue;
                    }
                    assert!(
                        p > 0.0 && p.is_finite(),
                        "{centre} from {}: {p}",
                        origins[i]
                    );
                    let s = s.expect("a sample");
                    assert!(s.pdf > 0.0 && s.pdf.is_finite() && s.direction.is_finite());
                }
                // directions the samples drew
                let drawn: [DVec3; 8] = std::array::from_fn(|i| {
                    target
                        .sample(origins[i], us[i])
                        .map_or(DVec3::X, |s| s.direction)
                });
                let (bad, _) = mismatches(&target, &origins, &drawn, &us);
                assert_eq!(
                    bad, 0,
                    "sphere at {centre}, radius {radius}, drawn directions"
                );
            }
        }
    }
}
