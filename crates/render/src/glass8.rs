//! The glass vertex of eight paths in the lanes: where a lane's ray met a static sphere of a
//! dielectric (the glass ball of book 3's Cornell box, about a third of its vertices), the vertex
//! from the hit to the next ray is computed eight lanes at a time:
//!
//! - the hit point `p = o + t d` and the normal `(p - c) / r` turned against the ray
//!   ([`crate::shapes::Sphere::hit_at`], [`crate::hit::Hit::face`]);
//! - the book's dielectric: the ratio of indices `eta`, `cos theta = min(-d/|d| . n, 1)`, a
//!   reflection where `eta sin theta > 1` (total internal reflection) or where Schlick's
//!   reflectance `R(theta) = r0 + (1 - r0)(1 - cos theta)^5`, `r0 = ((1 - eta)/(1 + eta))^2`, exceeds
//!   the vertex's uniform number, else Snell's refraction ([`crate::material::Material::scatter`],
//!   [`crate::vec::reflect`], [`crate::vec::refract`]);
//! - the next ray, from `p` pushed off the surface by four times the hit's error bound to the side
//!   the new direction leaves on ([`crate::hit::Hit::spawn_origin`]).
//!
//! The throughput is unchanged (glass attenuates by 1). Each lane computes the same `f64`
//! operations in the same order as the one-path code, so the paths, and the image, are
//! bit-identical to tracing one path at a time (tested in `crates/render/tests/paths8.rs`).
//!
//! What stays lane by lane: the uniform number, looked at in each sample's own sequence before the
//! lanes know whether the reflectance will ask for it, and drawn afterwards only where it did
//! ([`crate::sampler::Ctx::peek_1d`], [`crate::sampler::Ctx::take_1d`]), so that each sample's
//! sequence and counts are those of the one-path code; and a hit whose point is too far off the
//! sphere for the unprojected normal ([`GlassSpheres::error`]), which the one-path code takes.

use crate::material::Material;
use crate::ray::Ray;
use crate::ray8::{Rays8, SPHERE};
use crate::scene::{GroupId, Scene};
use crate::shapes::{Sphere, UNIT_NORMAL};

/// A glass sphere's numbers: its centre, `1 / r`, its index of refraction and the index's
/// reciprocal (both as the one-path code computes them), the rest unused.
type Row = [f64; 16];

/// The static spheres of a small group in the order of [`crate::ray8::Closest8::hit`]'s numbers
/// (`SPHERE | i` is sphere `i`), those of a dielectric with their numbers for the lanes.
pub struct GlassSpheres {
    spheres: Vec<Option<(Sphere, Row)>>,
    /// The glass spheres as bits, for eight lanes' hits at once.
    kind: crate::ray8::HitKinds,
}

impl GlassSpheres {
    /// The static spheres of group `g` (if its rays are intersected eight at a time with every
    /// answer in the lanes) whose material is a dielectric; `None` if there is none.
    pub fn new(scene: &Scene, g: GroupId) -> Option<GlassSpheres> {
        let group = &scene.groups[g.0 as usize];
        let spheres: Vec<Option<(Sphere, Row)>> = group
            .accel
            .spheres
            .as_ref()?
            .iter()
            .map(|(s, _)| match scene.materials[s.material.index()] {
                Material::Dielectric { ior } if !s.is_moving() => {
                    let mut row = [0.0; 16];
                    row[..3].copy_from_slice(&s.center.to_array());
                    row[3] = 1.0 / s.radius;
                    row[4] = ior;
                    row[5] = 1.0 / ior;
                    Some((*s, row))
                }
                _ => None,
            })
            .collect();
        if !spheres.iter().any(Option::is_some) {
            return None;
        }
        let quads = 4 * group.accel.packets.len();
        let kind = crate::ray8::HitKinds::new(quads, spheres.len(), |h| {
            h & SPHERE != 0 && spheres[(h & !SPHERE) as usize].is_some()
        })?;
        Some(GlassSpheres { spheres, kind })
    }

    /// The lanes whose hit in `hit` (as [`crate::ray8::Closest8::hit`] numbers it) is on a glass
    /// sphere ([`GlassSpheres::is_glass`] lane by lane).
    #[inline(always)]
    pub fn glass_lanes(&self, hit: &[u32; 8]) -> u8 {
        self.kind.lanes(hit)
    }

    /// The glass sphere a lane's hit `h` is on (as [`crate::ray8::Closest8::hit`] numbers it), if
    /// it is on one: a quad's hit, no hit, or another sphere's is not.
    #[inline(always)]
    pub fn sphere(&self, h: u32) -> Option<&Sphere> {
        if h & SPHERE == 0 {
            return None;
        }
        match self.spheres.get((h & !SPHERE) as usize) {
            Some(Some((s, _))) => Some(s),
            _ => None,
        }
    }

    /// Whether a lane's hit `h` is on a glass sphere.
    #[inline(always)]
    pub fn is_glass(&self, h: u32) -> bool {
        self.sphere(h).is_some()
    }

    /// The error bound of the hit of `ray` at `t` on `s` ([`Sphere::point_error`]), if the lanes
    /// take it: where [`Sphere::hit_at`] keeps the unprojected point (the bound at most
    /// [`UNIT_NORMAL`] `|r|`).
    #[inline(always)]
    pub fn error(s: &Sphere, ray: &Ray, t: f64) -> Option<f64> {
        let err = s.point_error(ray, t);
        (err <= UNIT_NORMAL * s.radius.abs()).then_some(err)
    }
}

/// Eight glass vertices, lane by lane: the sphere each lane's ray met (its place among the group's
/// spheres), the ray's parameter `t` there and the hit point's error bound, the vertex's uniform
/// number, and the rays (replaced by the next ones).
#[derive(Clone, Copy, Debug, Default)]
pub struct Glass8 {
    pub sphere: [u32; 8],
    pub t: [f64; 8],
    pub err: [f64; 8],
    pub u: [f64; 8],
    pub rays: Rays8,
}

#[cfg(target_arch = "x86_64")]
pub use wide::dielectric;

#[cfg(target_arch = "x86_64")]
mod wide {
    use super::{Glass8, GlassSpheres, Row};
    use crate::traversal::HitTier;
    use crate::wide8::*;

    /// The glass vertex of the lanes of `lanes` (not empty; each lane's sphere a glass one of
    /// `spheres`): each of these lanes' ray in `g.rays` becomes the next one (the other lanes'
    /// rays are overwritten with numbers of no meaning). Returns the lanes whose vertex asked for
    /// its uniform number (those without total internal reflection).
    ///
    /// # Safety
    /// Only where the processor runs `tier`, which is AVX2 or AVX-512.
    pub unsafe fn dielectric(
        tier: HitTier,
        spheres: &GlassSpheres,
        g: &mut Glass8,
        lanes: u8,
    ) -> u8 {
        // SAFETY: as this function's.
        unsafe {
            match tier {
                HitTier::Avx512 => avx512(spheres, g, lanes),
                _ => avx2(spheres, g, lanes),
            }
        }
    }

    #[target_feature(enable = "avx512f")]
    unsafe fn avx512(spheres: &GlassSpheres, g: &mut Glass8, lanes: u8) -> u8 {
        // SAFETY: compiled with AVX-512F, run where the processor has it.
        unsafe { vertex::<Avx512>(spheres, g, lanes) }
    }

    #[target_feature(enable = "avx2")]
    unsafe fn avx2(spheres: &GlassSpheres, g: &mut Glass8, lanes: u8) -> u8 {
        // SAFETY: compiled with AVX2, run where the processor has it.
        unsafe { vertex::<Avx2>(spheres, g, lanes) }
    }

    /// [`dielectric`] in the instructions of `W`.
    ///
    /// # Safety
    /// As [`Wide8::splat`]; `lanes` is not empty and names only lanes whose sphere is a glass one.
    #[inline(always)]
    unsafe fn vertex<W: Wide8>(spheres: &GlassSpheres, g: &mut Glass8, lanes: u8) -> u8 {
        let row = |i: usize| -> &Row {
            match &spheres.spheres[g.sphere[i] as usize] {
                Some((_, row)) => row,
                None => unreachable!("a lane of the batch met a glass sphere"),
            }
        };
        // each lane's sphere (the first lane's where a lane takes no part)
        let first = row(lanes.trailing_zeros() as usize);
        let mut rows: [&Row; 8] = [first; 8];
        for (i, r) in rows.iter_mut().enumerate() {
            if lanes & (1 << i) != 0 {
                *r = row(i);
            }
        }
        // SAFETY: as this function's.
        let (c, t, err, u, o, d) = unsafe {
            (
                W::columns(&rows),
                W::load_unaligned(&g.t),
                W::load_unaligned(&g.err),
                W::load_unaligned(&g.u),
                load3::<W>(&g.rays.origin),
                load3::<W>(&g.rays.direction),
            )
        };
        let (center, inv_r, ior, inv_ior) = ([c[0], c[1], c[2]], c[3], c[4], c[5]);
        let zero = t.zero_like();
        let one = zero.splat_like(1.0);
        // (glam's `v * s` as `s * v`: a product rounds the same either way)
        // `Sphere::hit_at`: p = o + t d, the normal (p - c) / r against the ray
        let p = add3(o, scale3(t, d));
        let outward = scale3(inv_r, sub3(p, center));
        let front = dot(d, outward).lt(zero);
        let normal = select3(neg3(outward), front, outward);
        // `Material::scatter` for a dielectric
        let eta = ior.select(front, inv_ior);
        let unit = scale3(one / dot(d, d).sqrt(), d);
        let cos = dot(neg3(unit), normal).min(one);
        let sin = (one - cos * cos).max(zero).sqrt();
        let total = (eta * sin).gt(one);
        // `schlick`: x^5 as (x (x x)(x x)), the one-path code's order
        let r0 = (one - eta) / (one + eta);
        let r0 = r0 * r0;
        let x = one - cos;
        let x2 = x * x;
        let reflectance = r0 + (one - r0) * (x2 * x2 * x);
        let reflects = total | reflectance.gt(u);
        // `reflect(unit, n)` and `refract(unit, n, eta)`
        let reflected = sub3(
            unit,
            scale3(zero.splat_like(2.0) * dot(unit, normal), normal),
        );
        let perp = scale3(eta, add3(unit, scale3(cos, normal)));
        let parallel = scale3(-(one - dot(perp, perp)).abs().sqrt(), normal);
        let direction = select3(add3(perp, parallel), reflects, reflected);
        // `Hit::spawn_origin`: p pushed off by 4 err along the normal, to the side it leaves on
        let offset = scale3(zero.splat_like(4.0) * err, normal);
        let out = dot(direction, normal).ge(zero);
        let origin = select3(sub3(p, offset), out, add3(p, offset));
        // Every lane's ray is stored whole: those outside `lanes` took no part and their rays are
        // of no use to anyone (a blend with the old rays would become masked stores, which AMD
        // processors before Zen 4 run slowly).
        g.rays.origin = store3(origin);
        g.rays.direction = store3(direction);
        (zero.mask(lanes) & !total).bits()
    }
}
