//! The Lambertian vertex of eight paths in the lanes: where a lane's ray met a quad of constant
//! albedo (most vertices of the Cornell box), everything from the hit to the next ray is computed
//! eight lanes at a time, with nothing built per lane:
//!
//! - the hit point `p = Q + alpha u + beta v` and the normal turned against the ray
//!   ([`crate::shapes::Quad::hit_at`], [`crate::hit::Hit::face`]);
//! - the `mixture` strategy's direction `omega` and weight `s(omega) / p(omega)`
//!   ([`crate::mixture8::Mixture8`]);
//! - the throughput times `albedo * s / p` ([`crate::integrator::OneSamplePath::diffuse`]);
//! - the next ray, from `p` pushed off the surface by four times the quad's error bound to the side
//!   `omega` leaves on ([`crate::hit::Hit::spawn_origin`]).
//!
//! The quads' numbers are kept one row per quad ([`QuadSurfaces`]), and the eight rows the lanes
//! met are transposed into columns in registers ([`crate::wide8::Wide8::columns`]); the hit's
//! coordinates `(alpha, beta)` in its quad are computed there, from the ray and `t`, as
//! [`crate::shapes::Quad::coordinates`] computes them. Each lane computes the same `f64`
//! operations in the same order as the one-path code, so the paths, and the image, are
//! bit-identical to tracing one path at a time (tested in `crates/render/tests/paths8.rs`).
//! Only the bounce's two numbers are drawn lane by lane, each from its own sample's sequence.

use crate::material::{Albedo, Material};
use crate::ray8::HitKinds;
use crate::scene::{GroupId, Object, Scene};

/// A quad's numbers: `Q`, `u`, `v`, the unit outward normal, the error bound of a hit point, the
/// albedo, the dual basis `du`, `dv` its coordinates are taken in, and two unused.
type Row = [f64; 24];

/// The quads of a small group in the order of its packets (quad `k` is lane `k % 4` of packet
/// `k / 4`, the numbering of [`crate::ray8::Closest8::hit`]), for the vertex in the lanes.
pub struct QuadSurfaces {
    rows: Vec<Row>,
    /// Quad `k`'s light, if its material is a light of constant radiance.
    lights: Vec<Option<QuadLight>>,
    /// The quads whose material is Lambertian of a constant albedo, and those in `lights`, as bits
    /// (for eight lanes' hits at once).
    lambertian_kind: HitKinds,
    light_kind: HitKinds,
}

/// A quad that emits a constant radiance: what a path that meets it gathers
/// ([`crate::material::Material::emitted`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QuadLight {
    pub emit: crate::vec::Color,
    pub two_sided: bool,
    /// The quad's unit outward normal (its front is the side the normal points to).
    pub normal: crate::vec::Vec3,
}

impl QuadLight {
    /// The radiance a ray of direction `d` gathers from the light: `emit` from the front (where
    /// `d . n < 0`, [`crate::hit::Hit::face`]) or from either side of a two-sided light, else 0.
    #[inline(always)]
    pub fn emitted(&self, d: crate::vec::Vec3) -> crate::vec::Color {
        if self.two_sided || d.dot(self.normal) < 0.0 {
            self.emit
        } else {
            crate::vec::Color::ZERO
        }
    }
}

impl QuadSurfaces {
    /// The quads of group `g` if its rays are intersected eight at a time with every answer in the
    /// lanes (its objects other than quads are all static spheres) and some quad is Lambertian of
    /// a constant albedo; else `None`.
    pub fn new(scene: &Scene, g: GroupId) -> Option<QuadSurfaces> {
        let group = &scene.groups[g.0 as usize];
        group.accel.spheres.as_ref()?;
        let mut rows = Vec::new();
        let mut lambertian = Vec::new();
        let mut lights = Vec::new();
        for packet in &group.accel.packets {
            for &index in &packet.index {
                let quad = match group.objects.get(index as usize) {
                    Some(Object::Quad(q)) => Some(q),
                    _ => None,
                };
                let albedo = quad.and_then(|q| match scene.materials[q.material.index()] {
                    Material::Lambertian {
                        albedo: Albedo::Constant(c),
                    } => Some(c),
                    _ => None,
                });
                let mut row = [0.0; 24];
                if let (Some(q), Some(a)) = (quad, albedo) {
                    let parts = [q.q, q.u, q.v, q.normal];
                    for (k, v) in parts.iter().enumerate() {
                        row[3 * k..3 * k + 3].copy_from_slice(&v.to_array());
                    }
                    row[12] = q.err;
                    row[13..16].copy_from_slice(&a.to_array());
                    row[16..19].copy_from_slice(&q.du.to_array());
                    row[19..22].copy_from_slice(&q.dv.to_array());
                }
                rows.push(row);
                lambertian.push(albedo.is_some());
                lights.push(
                    quad.and_then(|q| match scene.materials[q.material.index()] {
                        Material::DiffuseLight {
                            emit: Albedo::Constant(emit),
                            two_sided,
                        } => Some(QuadLight {
                            emit,
                            two_sided,
                            normal: q.normal,
                        }),
                        _ => None,
                    }),
                );
            }
        }
        if !lambertian.contains(&true) {
            return None;
        }
        let spheres = group.accel.spheres.as_ref().map_or(0, Vec::len);
        let kind = |is: &dyn Fn(usize) -> bool| {
            HitKinds::new(rows.len(), spheres, |h| {
                (h as usize) < rows.len() && is(h as usize)
            })
        };
        Some(QuadSurfaces {
            lambertian_kind: kind(&|k| lambertian[k])?,
            light_kind: kind(&|k| lights[k].is_some())?,
            rows,
            lights,
        })
    }

    /// The lanes whose hit in `hit` (as [`crate::ray8::Closest8::hit`] numbers it) is on a
    /// Lambertian quad of constant albedo ([`QuadSurfaces::lambertian`] lane by lane).
    #[inline(always)]
    pub fn lambertian_lanes(&self, hit: &[u32; 8]) -> u8 {
        self.lambertian_kind.lanes(hit)
    }

    /// The lanes whose hit in `hit` is on a light of constant radiance.
    #[inline(always)]
    pub fn light_lanes(&self, hit: &[u32; 8]) -> u8 {
        self.light_kind.lanes(hit)
    }

    /// Whether a lane's hit `h` (as [`crate::ray8::Closest8::hit`] numbers it) is on a Lambertian
    /// quad of constant albedo: a sphere's, or no hit, is not.
    #[inline(always)]
    pub fn lambertian(&self, h: u32) -> bool {
        self.lambertian_kind.has(h)
    }

    /// The light of constant radiance a lane's hit `h` is on, if it is on one.
    #[inline(always)]
    pub fn light(&self, h: u32) -> Option<&QuadLight> {
        self.lights.get(h as usize).and_then(Option::as_ref)
    }
}

#[cfg(target_arch = "x86_64")]
pub use wide::{coordinates, lambertian};

#[cfg(target_arch = "x86_64")]
mod wide {
    use super::{QuadSurfaces, Row};
    use crate::lanes::F64x8;
    use crate::mixture8::Mixture8;
    use crate::ray8::{Closest8, Rays8};
    use crate::traversal::HitTier;
    use crate::wide8::*;

    /// What the lanes' quads are where their rays met them: the hit point, the unit normal turned
    /// against the ray, the point's error bound, the albedo; and the point pushed off the surface
    /// for a ray leaving it either way.
    pub(crate) struct Surface8<W: Lanes> {
        /// The hit's coordinates in its quad, as `Quad::coordinates` computes them.
        pub alpha: W,
        pub beta: W,
        pub p: V3<W>,
        pub normal: V3<W>,
        pub albedo: V3<W>,
        /// `p` pushed off by four times the error bound against the normal, and along it.
        below: V3<W>,
        above: V3<W>,
    }

    impl<W: Lanes> Surface8<W> {
        /// `Hit::spawn_origin` of a ray leaving in direction `d`: `above` where
        /// `d . normal >= 0`, else `below`. (A function, not a closure: a closure does not take its
        /// caller's target features, and its intrinsics would be calls.)
        #[inline(always)]
        pub fn spawn(&self, d: V3<W>) -> V3<W> {
            select3(
                self.below,
                dot(d, self.normal).ge(d[0].zero_like()),
                self.above,
            )
        }
    }

    impl QuadSurfaces {
        /// The surfaces the rays of direction `dir` met in the lanes of `lanes`, Lambertian quads
        /// of constant albedo (`found`, numbered as these) from the origins `o`: their rows
        /// transposed into columns, the coordinates `(alpha, beta)` of `o + t dir` in each lane's
        /// quad (`Quad::coordinates`), `Quad::hit_at`'s point `p = Q + alpha u + beta v` and
        /// `Hit::face`'s normal.
        ///
        /// # Safety
        /// As [`Wide8::splat`]; `lanes` is not empty.
        #[inline(always)]
        pub(crate) unsafe fn surface_in<W: Wide8>(
            &self,
            found: &Closest8,
            o: V3<W>,
            dir: V3<W>,
            lanes: u8,
        ) -> Surface8<W> {
            // each lane's quad (the first lane's where a lane takes no part)
            let first = &self.rows[found.hit[lanes.trailing_zeros() as usize] as usize];
            let mut rows: [&Row; 8] = [first; 8];
            for (i, row) in rows.iter_mut().enumerate() {
                if lanes & (1 << i) != 0 {
                    *row = &self.rows[found.hit[i] as usize];
                }
            }
            // SAFETY: as this function's.
            let (c, t) = unsafe { (W::columns(&rows), W::load_unaligned(&found.t)) };
            let zero = t.zero_like();
            let (q, e1, e2) = ([c[0], c[1], c[2]], [c[3], c[4], c[5]], [c[6], c[7], c[8]]);
            let (outward, err, albedo) = ([c[9], c[10], c[11]], c[12], [c[13], c[14], c[15]]);
            let (du, dv) = ([c[16], c[17], c[18]], [c[19], c[20], c[21]]);
            let planar = sub3(add3(o, scale3(t, dir)), q);
            let (alpha, beta) = (dot(planar, du), dot(planar, dv));
            let p = add3(add3(q, scale3(alpha, e1)), scale3(beta, e2));
            let front = dot(dir, outward).lt(zero);
            let normal = select3(neg3(outward), front, outward);
            // `Hit::spawn_origin`: p pushed off by 4 err along the normal
            let push = zero.splat_like(4.0) * err;
            let offset = [normal[0] * push, normal[1] * push, normal[2] * push];
            Surface8 {
                alpha,
                beta,
                p,
                normal,
                albedo,
                below: sub3(p, offset),
                above: add3(p, offset),
            }
        }
    }

    /// The Lambertian vertex of the lanes of `lanes`, whose rays (`rays`) met Lambertian quads of
    /// constant albedo (`found`, numbered as `surfaces`), with the bounce's numbers `u` and the
    /// `mixture` strategy's density `m`: each of these lanes' `throughput` takes `albedo * s / p`
    /// and its ray in `rays` becomes the next one. Returns the lanes whose path goes on (the
    /// others' paths end here: no usable direction, or a throughput of zero).
    ///
    /// # Safety
    /// Only where the processor runs `tier`, which is AVX2 or AVX-512.
    #[allow(clippy::too_many_arguments)]
    pub unsafe fn lambertian(
        tier: HitTier,
        surfaces: &QuadSurfaces,
        m: &Mixture8,
        found: &Closest8,
        rays: &mut Rays8,
        throughput: &mut [F64x8; 3],
        u: &[F64x8; 2],
        lanes: u8,
    ) -> u8 {
        if lanes == 0 {
            return 0;
        }
        // SAFETY: as this function's.
        unsafe {
            match tier {
                HitTier::Avx512 => avx512(surfaces, m, found, rays, throughput, u, lanes),
                _ => avx2(surfaces, m, found, rays, throughput, u, lanes),
            }
        }
    }

    /// The coordinates `(alpha, beta)` in their quads of the hits `found` of the rays `rays`, in
    /// the lanes of `lanes` (Lambertian quads of `surfaces`, not empty), as [`lambertian`]
    /// computes them in the instructions of `tier`: what the tests hold to
    /// [`crate::shapes::Quad::coordinates`], bit for bit.
    ///
    /// # Safety
    /// Only where the processor runs `tier`, which is AVX2 or AVX-512.
    pub unsafe fn coordinates(
        tier: HitTier,
        surfaces: &QuadSurfaces,
        found: &Closest8,
        rays: &Rays8,
        lanes: u8,
    ) -> [F64x8; 2] {
        #[target_feature(enable = "avx512f")]
        unsafe fn avx512(
            s: &QuadSurfaces,
            found: &Closest8,
            rays: &Rays8,
            lanes: u8,
        ) -> [F64x8; 2] {
            // SAFETY: compiled with AVX-512F, run where the processor has it.
            unsafe { coordinates_in::<Avx512>(s, found, rays, lanes) }
        }
        #[target_feature(enable = "avx2")]
        unsafe fn avx2(s: &QuadSurfaces, found: &Closest8, rays: &Rays8, lanes: u8) -> [F64x8; 2] {
            // SAFETY: compiled with AVX2, run where the processor has it.
            unsafe { coordinates_in::<Avx2>(s, found, rays, lanes) }
        }
        // SAFETY: as this function's.
        unsafe {
            match tier {
                HitTier::Avx512 => avx512(surfaces, found, rays, lanes),
                _ => avx2(surfaces, found, rays, lanes),
            }
        }
    }

    /// [`coordinates`] in the instructions of `W`.
    ///
    /// # Safety
    /// As [`Wide8::splat`]; as [`coordinates`].
    #[inline(always)]
    unsafe fn coordinates_in<W: Wide8>(
        s: &QuadSurfaces,
        found: &Closest8,
        rays: &Rays8,
        lanes: u8,
    ) -> [F64x8; 2] {
        // SAFETY: as this function's.
        let at = unsafe {
            let (o, dir) = (load3::<W>(&rays.origin), load3::<W>(&rays.direction));
            s.surface_in(found, o, dir, lanes)
        };
        [at.alpha.store(), at.beta.store()]
    }

    #[target_feature(enable = "avx512f")]
    unsafe fn avx512(
        s: &QuadSurfaces,
        m: &Mixture8,
        found: &Closest8,
        rays: &mut Rays8,
        throughput: &mut [F64x8; 3],
        u: &[F64x8; 2],
        lanes: u8,
    ) -> u8 {
        // SAFETY: compiled with AVX-512F, run where the processor has it.
        unsafe { vertex::<Avx512>(s, m, found, rays, throughput, u, lanes) }
    }

    #[target_feature(enable = "avx2")]
    unsafe fn avx2(
        s: &QuadSurfaces,
        m: &Mixture8,
        found: &Closest8,
        rays: &mut Rays8,
        throughput: &mut [F64x8; 3],
        u: &[F64x8; 2],
        lanes: u8,
    ) -> u8 {
        // SAFETY: compiled with AVX2, run where the processor has it.
        unsafe { vertex::<Avx2>(s, m, found, rays, throughput, u, lanes) }
    }

    /// [`lambertian`] in the instructions of `W`.
    ///
    /// # Safety
    /// As [`Wide8::splat`]; `lanes` is not empty and names only lanes whose hit is a Lambertian
    /// quad of `s`.
    #[inline(always)]
    unsafe fn vertex<W: Wide8>(
        s: &QuadSurfaces,
        m: &Mixture8,
        found: &Closest8,
        rays: &mut Rays8,
        throughput: &mut [F64x8; 3],
        u: &[F64x8; 2],
        lanes: u8,
    ) -> u8 {
        // SAFETY: as this function's.
        let (at, o, dir, tp, u) = unsafe {
            let (o, dir) = (load3::<W>(&rays.origin), load3::<W>(&rays.direction));
            (
                s.surface_in(found, o, dir, lanes),
                o,
                dir,
                load3::<W>(throughput),
                [W::load(&u[0]), W::load(&u[1])],
            )
        };
        let Surface8 {
            p, normal, albedo, ..
        } = at;
        let zero = p[0].zero_like();
        // the mixture's direction and `s / p`
        let (d, w, ok) = m.sample_in(p, normal, u, lanes);
        // `OneSamplePath::diffuse`: the throughput times `albedo * (s / p)`
        let times = [
            tp[0] * (albedo[0] * w),
            tp[1] * (albedo[1] * w),
            tp[2] * (albedo[2] * w),
        ];
        let go = zero.mask(lanes) & ok;
        let tp = select3(tp, go, times);
        let black = times[0].eq(zero) & times[1].eq(zero) & times[2].eq(zero);
        let go = go & !black;
        let origin = at.spawn(d);
        *throughput = store3(tp);
        rays.origin = store3(select3(o, go, origin));
        rays.direction = store3(select3(dir, go, d));
        go.bits()
    }
}
