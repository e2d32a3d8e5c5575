//! `mis`'s manifold connections ([`crate::manifold`]): the estimators that connect a vertex to an
//! emitter through a glass ball, the path's memory that a connection was made, and the weight of the
//! emission that material sampling meets along the same kind of path.
//!
//! A connection from a vertex inside an interface *leaves* it (one refraction); one from a vertex
//! outside *crosses* it (two). Either draws a point `y` on an emitter by area and, through every
//! path the solver finds, estimates
//!
//! `s(omega) G (prod (1 - F)) T L_e(y) / p_A(y)`,
//!
//! weighted by the power heuristic against material sampling's density of the same point,
//! `p_m(omega) G` (area measure at `y`). The legs outside are shadow rays, which must meet what the
//! solver says they meet (the sphere at the refraction point, the emitter at `y`) and carry the
//! transmittance of the media they cross. A leg inside a clear interface (one that holds nothing
//! but media filling it whole) meets nothing: its transmittance is `exp(-sigma length)`.

use crate::hit::{Hit, REL_ERROR, UvSource};
use crate::integrator::{MisVariant, VertexPdf, trace_shadow, with_others};
use crate::lights::{LightTarget, Lights};
use crate::manifold::{EmitterPoint, Interface, Manifold};
use crate::ray::Ray;
use crate::sampler::Ctx;
use crate::scene::Scene;
use crate::vec::{Color, Point3, Vec3};
use rtl_pdf::{HittablePdf, Pdf, power_heuristic};

/// Which way a connection goes through its interface.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    /// From inside, out (one refraction).
    Leaving,
    /// From outside, in and out (two).
    Crossing,
}

/// A vertex that made a manifold connection, remembered while the path follows the same kind of
/// path: its point, the density its material sampling drew the path's next direction with, the
/// interface, the kind, the first refraction point the path went through, and whether it is out
/// of the interface (then the emission it meets next is weighed against the connection).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Through {
    p: Point3,
    pdf: f64,
    interface: u16,
    kind: Kind,
    first: Option<Point3>,
    out: bool,
}

impl Through {
    pub fn new(p: Point3, pdf: f64, interface: u16, kind: Kind) -> Through {
        Through {
            p,
            pdf,
            interface,
            kind,
            first: None,
            out: false,
        }
    }

    /// After the path refracted through a dielectric at `hit` (in if `hit.front_face`), leaving it
    /// in `inside` dielectrics: the state, if the path still follows the connection's kind (out of
    /// the interface for a leaving one; in, then out, for a crossing one).
    pub fn refracted(self, manifold: &Manifold, hit: &Hit, inside: u32) -> Option<Through> {
        let iface = &manifold.interfaces[self.interface as usize];
        let on = hit.material == iface.material && iface.on_surface(hit.p, hit.err);
        match (self.kind, self.first, hit.front_face) {
            (Kind::Leaving, None, false) if on && inside == 0 => Some(Through {
                first: Some(hit.p),
                out: true,
                ..self
            }),
            (Kind::Crossing, None, true) if on && inside == 1 => Some(Through {
                first: Some(hit.p),
                ..self
            }),
            (Kind::Crossing, Some(_), false) if on && inside == 0 && !self.out => {
                Some(Through { out: true, ..self })
            }
            _ => None,
        }
    }

    /// The weight of emission met at `hit` by the path in this state: the power heuristic against
    /// the connection if the path is out of the interface and solving from the vertex towards the
    /// point met finds the path's first refraction point (the connection could have made this
    /// path); 1 otherwise.
    pub fn material_weight(&self, lights: &Lights, hit: &Hit) -> f64 {
        let (Some(first), true) = (self.first, self.out) else {
            return 1.0;
        };
        let manifold = &lights.manifold;
        let Some(e) = manifold.emitter_point(hit) else {
            return 1.0;
        };
        let iface = &manifold.interfaces[self.interface as usize];
        let same = |x: Point3| (x - first).length() <= 1e-6 * iface.radius;
        let geometry = match self.kind {
            Kind::Leaving => iface
                .leaving(self.p, e.y)
                .as_slice()
                .iter()
                .find(|r| same(r.x))
                .map(|r| r.geometry * e.normal.dot(r.dir_out).abs()),
            Kind::Crossing => iface
                .crossings(self.p, e.y)
                .as_slice()
                .iter()
                .find(|k| same(k.entry))
                .map(|k| k.geometry * e.normal.dot(k.dir_out).abs()),
        };
        let density = match self.kind {
            Kind::Leaving => e.density,
            Kind::Crossing => {
                if !manifold.reaches(self.interface, e.emitter, self.p) {
                    return 1.0;
                }
                e.density / manifold.crossable.len() as f64
            }
        };
        geometry.map_or(1.0, |g| power_heuristic(1.0, self.pdf * g, 1.0, density))
    }
}

/// What a connection's vertex brings: where it is (`hit`), its material density `pdf` (drawn
/// from mixed with `towards_others`), and the time of its path.
pub(crate) struct Vertex<'a> {
    pub hit: &'a Hit,
    pub pdf: &'a VertexPdf,
    pub towards_others: Option<&'a HittablePdf<'a, LightTarget>>,
    pub time: f64,
}

impl Vertex<'_> {
    /// The material's density `s` of leaving in `direction`, and the density material sampling
    /// draws it with (`s` mixed with the other targets); `None` where `s` is 0.
    fn densities(&self, direction: Vec3) -> Option<(f64, f64)> {
        let s = self.pdf.pdf(direction);
        if s.is_nan() || s <= 0.0 {
            return None;
        }
        let drawn = match self.towards_others {
            Some(t) => with_others(*t, *self.pdf).pdf_given_b(direction, s),
            None => s,
        };
        Some((s, drawn))
    }
}

// ANCHOR: manifold_connection
/// The connection of a vertex inside interface `k` out towards an emitter, for the numbers `u`:
/// the point `y`, then every refraction point `x` found, each by `s G (1 - F) T_in T_out L_e / p_A`
/// with the power heuristic's weight. The connection's roulette ([`Interface::roulette`]) plays on
/// `u.x` first. The vertex's attenuation and the path's throughput are the caller's.
#[inline(never)]
pub(crate) fn leaving(
    scene: &Scene,
    lights: &Lights,
    vertex: &Vertex<'_>,
    k: u16,
    u: glam::DVec2,
    variant: MisVariant,
    ctx: &mut Ctx,
) -> Color {
    let manifold = &lights.manifold;
    let iface = &manifold.interfaces[k as usize];
    let p = vertex.hit.p;
    let q = iface.roulette(p);
    if u.x >= q {
        return Color::ZERO;
    }
    let u = glam::DVec2::new((u.x / q).min(1.0 - f64::EPSILON / 2.0), u.y);
    ctx.stats.manifold_connections += 1;
    let Some(e) = manifold.sample_emitter(u) else {
        return Color::ZERO;
    };
    let mut sum = Color::ZERO;
    for r in iface.leaving(p, e.y).as_slice() {
        let Some((s, drawn)) = vertex.densities(r.dir_in) else {
            continue;
        };
        let mut geometry = r.geometry * e.normal.dot(r.dir_out).abs();
        if variant == MisVariant::WrongManifoldGeometry {
            geometry /= r.across;
        }
        let w = power_heuristic(1.0, e.density, 1.0, drawn * geometry);
        let factor = s * geometry / (e.density * q) * iface.transmission(r.cos_in) * w;
        if !(factor > 0.0 && factor.is_finite()) {
            continue;
        }
        // Inside, from the vertex to x.
        let (at_x, t_in) = if iface.clear {
            (surface(iface, r.x), (-iface.filled * r.len_in).exp())
        } else {
            let ray = vertex.hit.spawn(r.dir_in, vertex.time);
            match leg_to_sphere(scene, &ray, iface, r.x, false, ctx) {
                Some(leg) => leg,
                None => continue,
            }
        };
        // Outside, from x to the emitter.
        let ray = at_x.spawn(e.y - at_x.p, vertex.time);
        if let Some((emitted, t_out)) = leg_to_emitter(scene, &ray, &e, r.len_out, ctx) {
            sum += emitted * (factor * t_in * t_out);
        }
    }
    sum
}

/// The connection of a vertex outside the interfaces through one of those it can cross (chosen
/// uniformly by a number of the sample's generator), towards an emitter: the point `y` (from two
/// more), then every crossing found, each by `s G (1 - F_in) (1 - F_out) T L_e / p_A` with the power
/// heuristic's weight. Returns the contribution and the interface, or `None` where no connection
/// is made from the vertex (no interface and emitter pass [`Manifold::reaches`] from it, and
/// nothing is drawn; or it lies inside the chosen interface).
#[inline(never)]
pub(crate) fn crossing(
    scene: &Scene,
    lights: &Lights,
    vertex: &Vertex<'_>,
    variant: MisVariant,
    ctx: &mut Ctx,
) -> Option<(Color, u16)> {
    let manifold = &lights.manifold;
    let n = manifold.crossable.len();
    let p = vertex.hit.p;
    if !manifold.reaches_any(p) {
        return None;
    }
    let pick = ctx.uniform() * n as f64;
    let i = (pick as usize).min(n.checked_sub(1)?);
    let k = manifold.crossable[i];
    let iface = &manifold.interfaces[k as usize];
    if !iface.crossed_from(p) {
        return None;
    }
    let u = glam::DVec2::new(
        (pick - i as f64).clamp(0.0, 1.0 - f64::EPSILON / 2.0),
        ctx.uniform(),
    );
    let Some(e) = manifold.sample_emitter(u) else {
        return Some((Color::ZERO, k));
    };
    if !manifold.reaches(k, e.emitter, p) {
        return Some((Color::ZERO, k));
    }
    ctx.stats.manifold_connections += 1;
    let density = e.density / n as f64;
    let mut sum = Color::ZERO;
    for c in iface.crossings(p, e.y).as_slice() {
        let Some((s, drawn)) = vertex.densities(c.dir_in) else {
            continue;
        };
        let mut geometry = c.geometry * e.normal.dot(c.dir_out).abs();
        if variant == MisVariant::WrongManifoldGeometry {
            geometry /= c.across;
        }
        let w = power_heuristic(1.0, density, 1.0, drawn * geometry);
        let factor =
            s * geometry / density * iface.transmission_through(c.cos_outside, c.cos_inside) * w;
        if !(factor > 0.0 && factor.is_finite()) {
            continue;
        }
        // Outside, from the vertex to the entry; inside (clear), across; outside, to the emitter.
        let ray = vertex.hit.spawn(c.dir_in, vertex.time);
        let Some((_, t_in)) = leg_to_sphere(scene, &ray, iface, c.entry, true, ctx) else {
            continue;
        };
        let t_inside = (-iface.filled * c.len_inside).exp();
        let exit = surface(iface, c.exit);
        let ray = exit.spawn(e.y - exit.p, vertex.time);
        if let Some((emitted, t_out)) = leg_to_emitter(scene, &ray, &e, c.len_out, ctx) {
            sum += emitted * (factor * t_in * t_inside * t_out);
        }
    }
    Some((sum, k))
}
// ANCHOR_END: manifold_connection

/// A point `x` of the interface's sphere as a hit to spawn rays from (its error bound that of a
/// computed point of the sphere).
fn surface(iface: &Interface, x: Point3) -> Hit {
    Hit {
        t: 0.0,
        p: x,
        normal: (x - iface.centre) / iface.radius,
        front_face: true,
        err: REL_ERROR * (iface.centre.abs().max_element() + iface.radius),
        material: iface.material,
        uv_source: UvSource::Uv(0.0, 0.0),
    }
}

/// The shadow ray `ray` towards the interface's point `x`: its hit and transmittance, if the first
/// surface it meets is the interface there, from outside if `from_outside`, else from inside.
fn leg_to_sphere(
    scene: &Scene,
    ray: &Ray,
    iface: &Interface,
    x: Point3,
    from_outside: bool,
    ctx: &mut Ctx,
) -> Option<(Hit, f64)> {
    let (h, t) = trace_shadow(scene, ray, ctx)?;
    (h.material == iface.material
        && h.front_face == from_outside
        && (h.p - x).length() <= 1e-6 * iface.radius + 8.0 * h.err)
        .then_some((h, t))
}

/// The shadow ray `ray` towards the emitter point `e`, `len` away: the emission there and the
/// transmittance, if the first surface it meets is an emitter at `e.y`.
fn leg_to_emitter(
    scene: &Scene,
    ray: &Ray,
    e: &EmitterPoint,
    len: f64,
    ctx: &mut Ctx,
) -> Option<(Color, f64)> {
    let (h, t) = trace_shadow(scene, ray, ctx)?;
    let m = &scene.materials[h.material.index()];
    (m.is_emitter() && (h.p - e.y).length() <= 1e-6 * len + 8.0 * h.err)
        .then(|| (m.emitted(&h, &scene.textures, ctx), t))
}
