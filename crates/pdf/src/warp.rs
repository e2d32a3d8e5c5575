//! Warps: maps from the unit square to directions (or points), each beside its density and its inverse.
//!
//! Each warp takes `u` in `[0, 1)^2` and is a pure function, in the style of pbrt-v4's
//! `util/sampling.h`: `sample_*` warps, `*_pdf` gives the density of what it returns (per steradian for
//! directions, per unit area for points), and `invert_*` maps a result back to the `u` that produced it.
//! Directions are in a local frame whose `+z` axis is the normal (or the cone's axis); an [`Onb`]
//! carries them to the world.
//!
//! ```
//! use glam::DVec2;
//! use rtl_pdf::warp;
//! let u = DVec2::new(0.25, 0.5);
//! let w = warp::sample_cosine_hemisphere(u); // a unit direction with z = cos theta > 0
//! let pdf = warp::cosine_hemisphere_pdf(w.z); // cos theta / pi, per steradian
//! assert!((pdf - w.z / std::f64::consts::PI).abs() < 1e-16);
//! let back = warp::invert_cosine_hemisphere_sample(w);
//! assert!((back - u).abs().max_element() < 1e-15);
//! ```
//!
//! [`Onb`]: crate::Onb

use glam::{DVec2, DVec3};
use std::f64::consts::{FRAC_1_PI, FRAC_PI_2, FRAC_PI_4, PI, TAU};

/// The smallest `cos theta` a hemisphere warp returns, `2^-40` (about `9e-13`): far above the rounding
/// of a frame that carries the direction to the world (about `1e-16`), so the direction stays above
/// the horizon there too, where its density is positive; and far below the `cos theta` of any `u`
/// away from the boundary of the square, so only `u` on that boundary (or within `2^-40` of it) move.
pub const MIN_COS_THETA: f64 = 1.0 / (1u64 << 40) as f64;

/// The largest `2 u - 1` of the concentric map, `1 - 2^-52`: what `u = 1 - 2^-53` gives. `u = 0` is
/// mapped as its neighbour `2^-53` is, so neither end of `[0, 1)` reaches the rim of the disk.
pub const CONCENTRIC_MAX: f64 = 1.0 - f64::EPSILON;

/// The largest `u.x` of the cone warp, `1 - 2^-48`: the rounding of `1 - cos theta` recomputed from the
/// direction (a few ulps) cannot then carry the last `u` outside the cone.
pub const CONE_U_MAX: f64 = 1.0 - 16.0 * f64::EPSILON;

/// The azimuth `phi` of `w` about `+z`, in `[0, 1)` turns (so `phi / 2 pi`).
#[inline]
fn azimuth_turns(w: DVec3) -> f64 {
    let t = w.y.atan2(w.x) / TAU;
    // atan2 is in [-pi, pi]; fold negative angles up. `t + 1` can round to exactly 1 for tiny
    // negative `t`, which is the same direction as 0.
    let t = if t < 0.0 { t + 1.0 } else { t };
    if t >= 1.0 { 0.0 } else { t }
}

/// `(1 - cos theta)` of a unit vector `w` about `+z`, accurate near `+z` where `1 - w.z` cancels.
#[inline]
pub fn one_minus_cos_theta(w: DVec3) -> f64 {
    if w.z > 0.0 {
        (w.x * w.x + w.y * w.y) / (1.0 + w.z)
    } else {
        1.0 - w.z
    }
}

/// `(sin x, cos x)` for `|x| <= pi / 4`, by their Taylor polynomials to degrees 15 and 16: the first
/// omitted terms are below `5e-17` there, so the results are within about an ulp of the exact values,
/// without the general argument reduction of a library `sin_cos`.
#[inline]
fn sin_cos_eighth(x: f64) -> (f64, f64) {
    let x2 = x * x;
    // 1/3!, 1/5!, ... and 1/2!, 1/4!, ...; Horner in x^2 from the smallest term (no `mul_add`:
    // without the `fma` target feature it is a library call).
    let s: f64 = 1.0 / 1_307_674_368_000.0;
    let s = 1.0 / 6_227_020_800.0 - s * x2;
    let s = 1.0 / 39_916_800.0 - s * x2;
    let s = 1.0 / 362_880.0 - s * x2;
    let s = 1.0 / 5_040.0 - s * x2;
    let s = 1.0 / 120.0 - s * x2;
    let s = 1.0 / 6.0 - s * x2;
    let s = 1.0 - s * x2;
    let c: f64 = 1.0 / 20_922_789_888_000.0;
    let c = 1.0 / 87_178_291_200.0 - c * x2;
    let c = 1.0 / 479_001_600.0 - c * x2;
    let c = 1.0 / 3_628_800.0 - c * x2;
    let c = 1.0 / 40_320.0 - c * x2;
    let c = 1.0 / 720.0 - c * x2;
    let c = 1.0 / 24.0 - c * x2;
    let c = 1.0 / 2.0 - c * x2;
    let c = 1.0 - c * x2;
    (x * s, c)
}

/// `(sin 2 pi t, cos 2 pi t)` for `t` in `[0, 1]`: the nearest quarter turn `k / 4` is split off
/// exactly (`t - k / 4` is exact by Sterbenz's lemma), the rest is at most an eighth of a turn.
#[inline]
fn sin_cos_turns(t: f64) -> (f64, f64) {
    let k = (4.0 * t).round();
    let (s, c) = sin_cos_eighth(TAU * (t - 0.25 * k));
    match k as u32 & 3 {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

// ANCHOR: uniform_sphere
/// A direction uniform over the unit sphere, density `1 / (4 pi)` per steradian.
///
/// `cos theta = 1 - 2 u.x` and `phi = 2 pi u.y` (Archimedes: equal bands of height have equal area).
/// `sin theta` is computed as `2 sqrt(u.x (1 - u.x))`, not `sqrt(1 - z^2)`, so the result stays unit
/// length at both poles.
#[inline]
pub fn sample_uniform_sphere(u: DVec2) -> DVec3 {
    let z = 1.0 - 2.0 * u.x;
    let r = 2.0 * (u.x * (1.0 - u.x)).max(0.0).sqrt();
    let (sin_phi, cos_phi) = sin_cos_turns(u.y);
    DVec3::new(r * cos_phi, r * sin_phi, z)
}

/// The density of [`sample_uniform_sphere`]: `1 / (4 pi)` per steradian.
#[inline]
pub const fn uniform_sphere_pdf() -> f64 {
    1.0 / (4.0 * PI)
}
// ANCHOR_END: uniform_sphere

/// The `u` for which [`sample_uniform_sphere`] returns the unit vector `w`. At the poles
/// (`u.x = 0`) every `u.y` gives the same direction, and `u.y` does not come back.
#[inline]
pub fn invert_uniform_sphere_sample(w: DVec3) -> DVec2 {
    DVec2::new(one_minus_cos_theta(w) / 2.0, azimuth_turns(w))
}

// ANCHOR: uniform_hemisphere
/// A direction uniform over the hemisphere `z >= 0`, density `1 / (2 pi)` per steradian.
///
/// `cos theta = u.x`, `phi = 2 pi u.y`; `cos theta` is at least `MIN_COS_THETA` (`2^-40`), so `u.x = 0`
/// gives a direction just above the horizon, not in the tangent plane.
#[inline]
pub fn sample_uniform_hemisphere(u: DVec2) -> DVec3 {
    let z = u.x.max(MIN_COS_THETA);
    let r = ((1.0 - z) * (1.0 + z)).max(0.0).sqrt();
    let (sin_phi, cos_phi) = sin_cos_turns(u.y);
    DVec3::new(r * cos_phi, r * sin_phi, z)
}

/// The density of [`sample_uniform_hemisphere`]: `1 / (2 pi)` per steradian.
#[inline]
pub const fn uniform_hemisphere_pdf() -> f64 {
    1.0 / (2.0 * PI)
}
// ANCHOR_END: uniform_hemisphere

/// The `u` for which [`sample_uniform_hemisphere`] returns `w` (`w.z >= 0`): `(cos theta, phi / 2 pi)`.
/// A `u.x` below `MIN_COS_THETA` comes back as `MIN_COS_THETA`, the `cos theta` it was drawn with.
#[inline]
pub fn invert_uniform_hemisphere_sample(w: DVec3) -> DVec2 {
    DVec2::new(w.z, azimuth_turns(w))
}

// ANCHOR: concentric_disk
/// A point uniform on the unit disk, density `1 / pi` per unit area, by the concentric map of
/// Shirley and Chiu ("A Low Distortion Map Between Disk and Square", 1997): squares around the
/// centre of `[-1, 1]^2` go to circles, so strata stay compact. `2 u - 1` is kept within
/// `±(1 - 2^-52)`, so the point is strictly inside the disk at both ends of `u`.
#[inline]
pub fn sample_uniform_disk_concentric(u: DVec2) -> DVec2 {
    let o =
        (2.0 * u - DVec2::ONE).clamp(DVec2::splat(-CONCENTRIC_MAX), DVec2::splat(CONCENTRIC_MAX));
    if o.x == 0.0 && o.y == 0.0 {
        return DVec2::ZERO;
    }
    // theta = pi/4 (o.y / o.x), or pi/2 - pi/4 (o.x / o.y), whose sine and cosine swap.
    if o.x.abs() > o.y.abs() {
        let (s, c) = sin_cos_eighth(FRAC_PI_4 * (o.y / o.x));
        DVec2::new(o.x * c, o.x * s)
    } else {
        let (s, c) = sin_cos_eighth(FRAC_PI_4 * (o.x / o.y));
        DVec2::new(o.y * s, o.y * c)
    }
}
// ANCHOR_END: concentric_disk

/// The density of [`sample_uniform_disk_concentric`]: `1 / pi` per unit area of the disk.
#[inline]
pub const fn uniform_disk_pdf() -> f64 {
    FRAC_1_PI
}

/// The `u` in `[0, 1)^2` for which [`sample_uniform_disk_concentric`] returns `p` (`|p| <= 1`). A
/// coordinate `u = 0` comes back as `2^-53`, which the warp maps to the same point (see
/// [`CONCENTRIC_MAX`]).
pub fn invert_uniform_disk_concentric_sample(p: DVec2) -> DVec2 {
    let r = p.length();
    if r == 0.0 {
        return DVec2::splat(0.5);
    }
    let mut angle = p.y.atan2(p.x);
    if angle < -FRAC_PI_4 {
        angle += TAU;
    }
    // The four wedges of the forward map, by the sign of the dominant coordinate.
    let o = if angle < FRAC_PI_4 {
        DVec2::new(r, r * angle / FRAC_PI_4)
    } else if angle < 3.0 * FRAC_PI_4 {
        DVec2::new(r * (FRAC_PI_2 - angle) / FRAC_PI_4, r)
    } else if angle < 5.0 * FRAC_PI_4 {
        DVec2::new(-r, -r * (angle - PI) / FRAC_PI_4)
    } else {
        DVec2::new(-r * (1.5 * PI - angle) / FRAC_PI_4, -r)
    };
    ((o + DVec2::ONE) / 2.0).clamp(DVec2::ZERO, DVec2::splat(1.0 - f64::EPSILON / 2.0))
}

// ANCHOR: cosine_hemisphere
/// A direction on the hemisphere `z >= 0` with density `cos theta / pi` per steradian.
///
/// Malley's method: a point uniform on the unit disk (here by the concentric map) lifted straight up
/// to the hemisphere. The projected-area measure `cos theta d omega` is the disk's area measure, so the
/// density per steradian is `(1 / pi) cos theta`. Near the rim, where `1 - |d|^2` rounds towards 0,
/// `cos theta` is kept at least `MIN_COS_THETA` (`2^-40`): the direction stays above the horizon,
/// where its density is positive.
#[inline]
pub fn sample_cosine_hemisphere(u: DVec2) -> DVec3 {
    let d = sample_uniform_disk_concentric(u);
    // (a negative 1 - |d|^2 gives a NaN square root, which `max` replaces)
    let z = (1.0 - d.length_squared()).sqrt().max(MIN_COS_THETA);
    DVec3::new(d.x, d.y, z)
}

/// The density of [`sample_cosine_hemisphere`] for a direction with this `cos theta`:
/// `max(0, cos theta) / pi`, exactly 0 at and below the horizon.
#[inline]
pub fn cosine_hemisphere_pdf(cos_theta: f64) -> f64 {
    if cos_theta > 0.0 {
        cos_theta * FRAC_1_PI
    } else {
        0.0
    }
}
// ANCHOR_END: cosine_hemisphere

/// The `u` for which [`sample_cosine_hemisphere`] returns `w`.
#[inline]
pub fn invert_cosine_hemisphere_sample(w: DVec3) -> DVec2 {
    invert_uniform_disk_concentric_sample(DVec2::new(w.x, w.y))
}

// ANCHOR: uniform_cone
/// `1 - cos theta_max` of the cone that a sphere of radius `r` subtends from distance `d > r`, given
/// `sin^2 theta_max = r^2 / d^2`. Computed as `sin^2 / (1 + cos)`, which does not cancel when the
/// sphere is small or far away (where `1 - sqrt(1 - sin^2)` rounds to 0).
#[inline]
pub fn cone_one_minus_cos(sin2_theta_max: f64) -> f64 {
    let s2 = sin2_theta_max.clamp(0.0, 1.0);
    s2 / (1.0 + (1.0 - s2).sqrt())
}

/// A direction uniform in the cone about `+z` with `1 - cos theta <= one_minus_cos_max`, density
/// `1 / (2 pi (1 - cos theta_max))` per steradian.
///
/// The cone is given by `1 - cos theta_max` (in `(0, 2]`; 2 is the whole sphere) rather than
/// `cos theta_max`, so that very narrow cones keep their size: `1 - cos theta = u.x (1 - cos theta_max)`,
/// `sin theta = sqrt(t (2 - t))` with `t = 1 - cos theta`, `phi = 2 pi u.y`. `u.x` is kept at most
/// `1 - 2^-48`, so the direction is inside the cone even after rounding.
#[inline]
pub fn sample_uniform_cone(u: DVec2, one_minus_cos_max: f64) -> DVec3 {
    let t = u.x.min(CONE_U_MAX) * one_minus_cos_max;
    let cos_theta = 1.0 - t;
    let sin_theta = (t * (2.0 - t)).max(0.0).sqrt();
    let (sin_phi, cos_phi) = sin_cos_turns(u.y);
    DVec3::new(sin_theta * cos_phi, sin_theta * sin_phi, cos_theta)
}

/// The density of [`sample_uniform_cone`]: one over the cone's solid angle `2 pi (1 - cos theta_max)`.
#[inline]
pub fn uniform_cone_pdf(one_minus_cos_max: f64) -> f64 {
    1.0 / (TAU * one_minus_cos_max)
}
// ANCHOR_END: uniform_cone

/// The `u` for which [`sample_uniform_cone`] returns the unit vector `w` (inside the cone):
/// `((1 - cos theta) / (1 - cos theta_max), phi / 2 pi)`. A `u.x` above `CONE_U_MAX` comes back as
/// `CONE_U_MAX`, the `u.x` it was drawn with; at the apex (`u.x = 0`) `u.y` does not come back.
#[inline]
pub fn invert_uniform_cone_sample(w: DVec3, one_minus_cos_max: f64) -> DVec2 {
    DVec2::new(one_minus_cos_theta(w) / one_minus_cos_max, azimuth_turns(w))
}

// ANCHOR: parallelogram
/// A point uniform on the parallelogram `q + s e1 + t e2`, `(s, t) = u`: density `1 / |e1 x e2|` per
/// unit area.
#[inline]
pub fn sample_parallelogram(u: DVec2, q: DVec3, e1: DVec3, e2: DVec3) -> DVec3 {
    q + u.x * e1 + u.y * e2
}

/// The density of [`sample_parallelogram`] per unit area: one over its area `|e1 x e2|`.
#[inline]
pub fn parallelogram_pdf(e1: DVec3, e2: DVec3) -> f64 {
    1.0 / e1.cross(e2).length()
}

/// The `(s, t)` of a point `p` in the plane of the parallelogram `q + s e1 + t e2`.
///
/// With `n = e1 x e2` and `w = n / (n . n)`: `s = w . ((p - q) x e2)`, `t = w . (e1 x (p - q))`
/// (the book's quad hit test, chapter 6 of book 2).
#[inline]
pub fn invert_parallelogram_sample(p: DVec3, q: DVec3, e1: DVec3, e2: DVec3) -> DVec2 {
    let n = e1.cross(e2);
    let w = n / n.length_squared();
    let d = p - q;
    DVec2::new(w.dot(d.cross(e2)), w.dot(e1.cross(d)))
}

/// Converts a density per unit area at `point` (a surface with unit normal `normal`) to a density per
/// steradian of the direction from `origin`: `pdf_area * d^2 / |cos theta_light|`.
///
/// Returns 0 when the surface is seen exactly edge-on (or `point == origin`): such a direction carries
/// no solid angle and is reported as a miss, never as an infinite density.
#[inline]
pub fn area_to_solid_angle(pdf_area: f64, origin: DVec3, point: DVec3, normal: DVec3) -> f64 {
    let to = point - origin;
    let d2 = to.length_squared();
    let cos_light = normal.dot(to).abs() / d2.sqrt();
    if cos_light > 0.0 && d2 > 0.0 {
        let pdf = pdf_area * d2 / cos_light;
        // `|pdf| <= MAX` is `pdf.is_finite()` by a floating-point comparison (see `positive_finite`)
        if pdf.abs() <= f64::MAX { pdf } else { 0.0 }
    } else {
        0.0
    }
}
// ANCHOR_END: parallelogram

// ANCHOR: spherical_rectangle
/// The spherical rectangle that a rectangle `q + s ex + t ey` (`ex . ey = 0`) subtends from `origin`,
/// sampled uniformly in solid angle by the area-preserving map of Urena, Fajardo and King, "An
/// Area-Preserving Parametrization for Spherical Rectangles" (EGSR 2013).
///
/// `u.x` picks the sub-rectangle `[x0, x_u]` whose solid angle is `u.x S`, found in closed form;
/// `u.y` then places the point on the segment at `x_u` uniformly in the height `h = y / sqrt(d^2 + y^2)`
/// of its projection onto the sphere. Density: `1 / S` per steradian, `S` the solid angle.
#[derive(Clone, Copy, Debug)]
pub struct SphericalRectangle {
    origin: DVec3,
    /// Local frame: `x` along `ex`, `y` along `ey`, `z` normal, flipped so the rectangle is at `z0 < 0`.
    x: DVec3,
    y: DVec3,
    z: DVec3,
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    z0: f64,
    /// z components of the normals of the bottom and top edges' great circles.
    b0: f64,
    b1: f64,
    /// `2 pi - gamma_2 - gamma_3`: the part of the angle sum that does not depend on `u.x`.
    k: f64,
    solid_angle: f64,
}

/// Solid angle (and the terms the sampler needs) of the rectangle `[x0, x1] x [y0, y1]` at height
/// `z0 < 0` seen from the origin: the angle excess `gamma_0 + gamma_1 + gamma_2 + gamma_3 - 2 pi` of
/// the spherical quadrilateral. Returns `(S, k, b0, b1)`.
///
/// The normals of the edges' great circles are the corners' cross products, which in this frame
/// have a zero and two coordinates each: `n0 = (0, z0, -y0) / l(y0)`, `n1 = (-z0, 0, x1) / l(x1)`,
/// `n2 = (0, -z0, y1) / l(y1)`, `n3 = (z0, 0, -x0) / l(x0)` with `l(a) = sqrt(z0^2 + a^2)`, so the
/// cosines `-n_i . n_(i+1)` of the interior angles are `+-x y / (l(x) l(y))`: four square roots
/// where four cross products and normalisations would take twelve products more each.
#[inline]
fn rectangle_angles(x0: f64, x1: f64, y0: f64, y1: f64, z0: f64) -> (f64, f64, f64, f64) {
    let z2 = z0 * z0;
    let l = |a: f64| (z2 + a * a).sqrt();
    let (lx0, lx1, ly0, ly1) = (l(x0), l(x1), l(y0), l(y1));
    let angle = |c: f64| c.clamp(-1.0, 1.0).acos();
    let g0 = angle(x1 * y0 / (lx1 * ly0));
    let g1 = angle(-(x1 * y1) / (lx1 * ly1));
    let g2 = angle(x0 * y1 / (lx0 * ly1));
    let g3 = angle(-(x0 * y0) / (lx0 * ly0));
    let k = TAU - g2 - g3;
    ((g0 + g1 - k).max(0.0), k, -y0 / ly0, y1 / ly1)
}

/// What a rectangle `q + s ex + t ey` contributes to its [`SphericalRectangle`]s whatever the origin:
/// its corner, unit edge directions `x`, `y`, normal `z = x x y` and edge lengths. Made once per
/// rectangle (a light), so that each shading point only does the part that depends on it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RectangleFrame {
    q: DVec3,
    x: DVec3,
    y: DVec3,
    z: DVec3,
    exl: f64,
    eyl: f64,
}

impl RectangleFrame {
    /// The frame of `q + s ex + t ey`; `None` when an edge has zero length. `ex` and `ey` must be
    /// orthogonal.
    pub fn new(q: DVec3, ex: DVec3, ey: DVec3) -> Option<RectangleFrame> {
        let (exl, eyl) = (ex.length(), ey.length());
        if !(exl > 0.0 && eyl > 0.0) {
            return None;
        }
        let x = ex / exl;
        let y = ey / eyl;
        Some(RectangleFrame {
            q,
            x,
            y,
            z: x.cross(y),
            exl,
            eyl,
        })
    }
}

impl SphericalRectangle {
    /// The spherical rectangle of `q + s ex + t ey` seen from `origin`. `None` when `origin` lies in the
    /// rectangle's plane or an edge has zero length (no solid angle); `ex` and `ey` must be
    /// orthogonal.
    pub fn new(origin: DVec3, q: DVec3, ex: DVec3, ey: DVec3) -> Option<SphericalRectangle> {
        SphericalRectangle::from_frame(origin, &RectangleFrame::new(q, ex, ey)?)
    }

    /// [`SphericalRectangle::new`] of a rectangle whose frame is made already: the same numbers.
    #[inline]
    pub fn from_frame(origin: DVec3, frame: &RectangleFrame) -> Option<SphericalRectangle> {
        let RectangleFrame {
            q,
            x,
            y,
            z,
            exl,
            eyl,
        } = *frame;
        let mut z = z;
        let d = q - origin;
        let mut z0 = d.dot(z);
        if z0 > 0.0 {
            z = -z;
            z0 = -z0;
        }
        if z0 >= 0.0 || !z0.is_finite() {
            return None;
        }
        let x0 = d.dot(x);
        let y0 = d.dot(y);
        let (x1, y1) = (x0 + exl, y0 + eyl);
        let (solid_angle, k, b0, b1) = rectangle_angles(x0, x1, y0, y1, z0);
        Some(SphericalRectangle {
            origin,
            x,
            y,
            z,
            x0,
            x1,
            y0,
            y1,
            z0,
            b0,
            b1,
            k,
            solid_angle,
        })
    }

    /// The solid angle `S` of the rectangle seen from the origin, in steradians.
    #[inline]
    pub fn solid_angle(&self) -> f64 {
        self.solid_angle
    }

    /// The density of [`SphericalRectangle::sample`]'s direction: `1 / S` per steradian.
    #[inline]
    pub fn pdf(&self) -> f64 {
        1.0 / self.solid_angle
    }

    /// A point on the rectangle for `u` in `[0, 1)^2`, whose direction from the origin is uniform in
    /// solid angle: density [`SphericalRectangle::pdf`] per steradian.
    pub fn sample(&self, u: DVec2) -> DVec3 {
        // 1. The x of the sub-rectangle [x0, xu] with solid angle u.x S.
        let au = u.x * self.solid_angle + self.k;
        let (sin_au, cos_au) = au.sin_cos();
        let fu = (cos_au * self.b0 - self.b1) / sin_au;
        let cu = (1.0 / (fu * fu + self.b0 * self.b0).sqrt())
            .copysign(fu)
            .clamp(-1.0, 1.0);
        let xu = (-(cu * self.z0) / (1.0 - cu * cu).max(0.0).sqrt()).clamp(self.x0, self.x1);
        // 2. The y on the segment at xu, uniform in the height of its projection on the sphere.
        let d = (xu * xu + self.z0 * self.z0).sqrt();
        let h0 = self.y0 / (d * d + self.y0 * self.y0).sqrt();
        let h1 = self.y1 / (d * d + self.y1 * self.y1).sqrt();
        let hv = h0 + u.y * (h1 - h0);
        let hv2 = hv * hv;
        let yv = if hv2 < 1.0 - 1e-12 {
            (hv * d / (1.0 - hv2).sqrt()).clamp(self.y0, self.y1)
        } else {
            self.y1
        };
        self.origin + xu * self.x + yv * self.y + self.z0 * self.z
    }

    /// The unit direction from the origin towards [`SphericalRectangle::sample`]`(u)`.
    #[inline]
    pub fn sample_direction(&self, u: DVec2) -> DVec3 {
        (self.sample(u) - self.origin).normalize()
    }

    /// The `u` for which [`SphericalRectangle::sample`] returns `point` (a point of the rectangle):
    /// `u.x` is the solid angle of the sub-rectangle `[x0, x_p]` over `S`, `u.y` the relative height;
    /// both clamped into `[0, 1]`.
    pub fn invert(&self, point: DVec3) -> DVec2 {
        let p = point - self.origin;
        let xu = p.dot(self.x).clamp(self.x0, self.x1);
        let yv = p.dot(self.y).clamp(self.y0, self.y1);
        let ux = if xu <= self.x0 {
            0.0
        } else {
            rectangle_angles(self.x0, xu, self.y0, self.y1, self.z0).0 / self.solid_angle
        };
        let d = (xu * xu + self.z0 * self.z0).sqrt();
        let h0 = self.y0 / (d * d + self.y0 * self.y0).sqrt();
        let h1 = self.y1 / (d * d + self.y1 * self.y1).sqrt();
        let hv = yv / (d * d + yv * yv).sqrt();
        let uy = if h1 > h0 { (hv - h0) / (h1 - h0) } else { 0.0 };
        DVec2::new(ux.clamp(0.0, 1.0), uy.clamp(0.0, 1.0))
    }
}
// ANCHOR_END: spherical_rectangle

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_xoshiro::Xoshiro256PlusPlus;

    const U_MAX: f64 = 1.0 - f64::EPSILON / 2.0; // 1 - 2^-53, the largest f64 below 1

    fn corners() -> Vec<DVec2> {
        let vals = [0.0, 1e-300, 1e-17, 0.5, U_MAX];
        let mut v = Vec::new();
        for &a in &vals {
            for &b in &vals {
                v.push(DVec2::new(a, b));
            }
        }
        v
    }

    #[test]
    fn sphere_and_cosine_directions_are_unit_at_extreme_u() {
        for u in corners() {
            for (name, w) in [
                ("sphere", sample_uniform_sphere(u)),
                ("hemisphere", sample_uniform_hemisphere(u)),
                ("cosine", sample_cosine_hemisphere(u)),
                ("cone", sample_uniform_cone(u, 0.3)),
                ("cone tiny", sample_uniform_cone(u, 5e-19)),
                ("cone whole sphere", sample_uniform_cone(u, 2.0)),
            ] {
                assert!(w.is_finite(), "{name} at {u}: {w}");
                assert!(
                    (w.length() - 1.0).abs() < 1e-12,
                    "{name} at {u}: |w| = {}",
                    w.length()
                );
                if name == "hemisphere" || name == "cosine" {
                    assert!(w.z >= 0.0, "{name} at {u}: z = {}", w.z);
                }
            }
        }
    }

    #[test]
    fn inverses_undo_the_warps() {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(7);
        for _ in 0..2000 {
            let u = DVec2::new(rng.random(), rng.random());
            let close = |a: DVec2, b: DVec2, tol: f64, what: &str| {
                // azimuth wraps around: 0 and 1 are the same
                let dy = (a.y - b.y).abs();
                assert!(
                    (a.x - b.x).abs() < tol && dy.min(1.0 - dy) < tol,
                    "{what}: {a} vs {b}"
                );
            };
            close(
                invert_uniform_sphere_sample(sample_uniform_sphere(u)),
                u,
                1e-12,
                "sphere",
            );
            close(
                invert_uniform_hemisphere_sample(sample_uniform_hemisphere(u)),
                u,
                1e-12,
                "hemisphere",
            );
            let c = invert_cosine_hemisphere_sample(sample_cosine_hemisphere(u));
            assert!((c - u).abs().max_element() < 1e-9, "cosine: {c} vs {u}");
            close(
                invert_uniform_cone_sample(sample_uniform_cone(u, 0.2), 0.2),
                u,
                1e-9,
                "cone",
            );
            let (q, e1, e2) = (
                DVec3::new(1.0, 2.0, 3.0),
                DVec3::new(0.5, 0.1, 0.0),
                DVec3::new(0.2, -1.0, 0.3),
            );
            let p = invert_parallelogram_sample(sample_parallelogram(u, q, e1, e2), q, e1, e2);
            assert!(
                (p - u).abs().max_element() < 1e-12,
                "parallelogram: {p} vs {u}"
            );
        }
    }

    #[test]
    fn spherical_rectangle_of_a_cube_face_is_a_sixth_of_the_sphere() {
        // the face z = -1 of the cube [-1, 1]^3, seen from its centre
        let r = SphericalRectangle::new(
            DVec3::ZERO,
            DVec3::new(-1.0, -1.0, -1.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(0.0, 2.0, 0.0),
        )
        .unwrap();
        assert!((r.solid_angle() - 4.0 * PI / 6.0).abs() < 1e-12);
        // the centre of the unit square goes to the centre of the face
        assert!((r.sample(DVec2::splat(0.5)) - DVec3::new(0.0, 0.0, -1.0)).length() < 1e-12);
    }

    #[test]
    fn spherical_rectangle_inverse_undoes_the_sample() {
        let mut rng = Xoshiro256PlusPlus::seed_from_u64(8);
        let r = SphericalRectangle::new(
            DVec3::new(0.3, 0.2, 1.5),
            DVec3::new(-1.0, -0.5, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(0.0, 1.5, 0.0),
        )
        .unwrap();
        for _ in 0..2000 {
            let u = DVec2::new(rng.random(), rng.random());
            let p = r.sample(u);
            assert!(p.z.abs() < 1e-12, "point off the plane: {p}");
            let back = r.invert(p);
            assert!((back - u).abs().max_element() < 1e-9, "{back} vs {u}");
        }
        assert!(
            SphericalRectangle::new(DVec3::new(5.0, 5.0, 0.0), DVec3::ZERO, DVec3::X, DVec3::Y)
                .is_none()
        );
    }

    #[test]
    fn cone_solid_angle_has_no_cancellation() {
        for d in [1e2f64, 1e4, 1e6, 1e9] {
            let s2 = 1.0 / (d * d);
            // 1 - sqrt(1 - x) = x/2 + x^2/8 + x^3/16 + ...
            let exact = s2 / 2.0 + s2 * s2 / 8.0 + s2 * s2 * s2 / 16.0;
            let got = cone_one_minus_cos(s2);
            assert!(
                ((got - exact) / exact).abs() < 1e-12,
                "d = {d}: {got} vs {exact}"
            );
        }
    }

    #[test]
    fn cosine_pdf_is_exactly_zero_at_and_below_the_horizon() {
        assert_eq!(cosine_hemisphere_pdf(0.0), 0.0);
        assert_eq!(cosine_hemisphere_pdf(-0.0), 0.0);
        assert_eq!(cosine_hemisphere_pdf(-1e-300), 0.0);
        assert_eq!(cosine_hemisphere_pdf(-1.0), 0.0);
        assert!(cosine_hemisphere_pdf(1e-300) > 0.0);
    }

    #[test]
    fn polynomial_sin_cos_agrees_with_the_library() {
        // The library's own argument `2 pi t` is rounded by up to half an ulp of 2 pi (4.4e-16), so
        // the two agree to a few ulps of 1, not to an ulp of the result.
        let close = |a: f64, b: f64| (a - b).abs() <= 4.0 * f64::EPSILON;
        for i in 0..=100_000 {
            let t = i as f64 / 100_000.0;
            let (s, c) = sin_cos_turns(t);
            let (s0, c0) = (TAU * t).sin_cos();
            assert!(
                close(s, s0) && close(c, c0),
                "t = {t}: ({s}, {c}) vs ({s0}, {c0})"
            );
            let x = (t - 0.5) * FRAC_PI_2;
            let (s, c) = sin_cos_eighth(x);
            let (s0, c0) = x.sin_cos();
            assert!(
                close(s, s0) && close(c, c0),
                "x = {x}: ({s}, {c}) vs ({s0}, {c0})"
            );
        }
    }
}
