//! Targets: shapes that can be sampled towards ("lights" in the book, chapter 9), and the two the
//! book needs, spheres and quads.
//!
//! This crate knows nothing of the renderer's shapes. A shape that wants to be sampled towards
//! implements [`ShapeSampler`]; [`SphereTarget`] and [`QuadTarget`] hold the geometry and the sampling so that a
//! renderer's sphere or quad can delegate to them.

use crate::pdf::{positive_finite, random_unit_square};
use crate::{DirectionSample, Onb, warp};
use glam::{DVec2, DVec3};
use rand::Rng;

// ANCHOR: target_trait
/// A shape that directions can be sampled towards from a point: the book's `hittable::random` and
/// `hittable::pdf_value` ("lights", chapter 9), with the same contract as [`Pdf`](crate::Pdf): what
/// `sample` draws is distributed with density `pdf`, and a shape with no directions from `origin` (a
/// one-sided light seen from behind) returns `None` there while its `pdf` is 0.
#[doc(alias = "Target")]
pub trait ShapeSampler {
    /// The density per steradian, seen from `origin`, with which [`ShapeSampler::sample`] picks the
    /// unit vector `direction`: 0 when the ray `origin + t direction` misses the shape.
    #[doc(alias = "pdf_value")]
    fn pdf(&self, origin: DVec3, direction: DVec3) -> f64;

    /// A unit direction from `origin` towards the shape for the uniform numbers `u` in `[0, 1)^2`, with
    /// its density; `None` where the shape offers no direction.
    #[doc(alias = "random")]
    fn sample(&self, origin: DVec3, u: DVec2) -> Option<DirectionSample>;

    /// The book's name for [`ShapeSampler::pdf`].
    #[inline]
    fn pdf_value(&self, origin: DVec3, direction: DVec3) -> f64 {
        self.pdf(origin, direction)
    }

    /// The book's `random(origin)`: [`ShapeSampler::sample`] of two numbers from `rng`, the direction
    /// only (the zero vector where `sample` fails).
    #[inline]
    fn random<R: Rng + ?Sized>(&self, origin: DVec3, rng: &mut R) -> DVec3
    where
        Self: Sized,
    {
        self.sample(origin, random_unit_square(rng))
            .map_or(DVec3::ZERO, |s| s.direction)
    }
}
// ANCHOR_END: target_trait

impl<T: ShapeSampler + ?Sized> ShapeSampler for &T {
    #[inline]
    fn pdf(&self, origin: DVec3, direction: DVec3) -> f64 {
        (**self).pdf(origin, direction)
    }
    #[inline]
    fn sample(&self, origin: DVec3, u: DVec2) -> Option<DirectionSample> {
        (**self).sample(origin, u)
    }
}

/// A sphere to sample towards, by the cone of directions it subtends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereTarget {
    center: DVec3,
    radius: f64,
}

/// The narrowest cone a [`SphereTarget`] is sampled in: `sin^2 theta_max = 2^-64`, an angular
/// radius of `2^-32` (2.3e-10 rad). Unit vectors in `f64` lie about 1e-16 apart, so a direction
/// drawn in a cone of angular radius `theta` rounds to one outside it, where `pdf` is 0, about
/// `3.5e-17 / theta` of the time: 1.5e-7 at this floor, 0.29 at 1e-16 rad, and always below about
/// 4e-17 rad. A sphere narrower than this counts as too small to see, as one whose density
/// overflows: no sample and density 0. Its share of the light arriving at a point is at most
/// `pi 2^-64` sr (1.7e-19) times its radiance.
pub const MIN_CONE_SIN2: f64 = 1.0 / (1u128 << 64) as f64;

/// What a sphere looks like from a point: a cone (axis, `1 - cos theta_max`), or all around.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SphereView {
    /// The point is outside: the sphere fills the cone about the unit `axis` with this `1 - cos
    /// theta_max`, which is 0 for a sphere too small to see (below [`MIN_CONE_SIN2`]).
    Cone { axis: DVec3, one_minus_cos_max: f64 },
    /// The point is inside or on the sphere: every direction meets it; sampled uniformly.
    Surrounding,
}

impl SphereTarget {
    /// A sphere of this centre and radius (its absolute value; a negative radius is the book's trick
    /// for hollow glass and means the same surface here).
    pub fn new(center: DVec3, radius: f64) -> SphereTarget {
        SphereTarget {
            center,
            radius: radius.abs(),
        }
    }

    /// The centre.
    pub fn center(&self) -> DVec3 {
        self.center
    }

    /// The radius (never negative).
    pub fn radius(&self) -> f64 {
        self.radius
    }

    // ANCHOR: sphere_view
    /// The cone the sphere subtends from `origin`: `sin^2 theta_max = r^2 / d^2`, and
    /// `1 - cos theta_max = sin^2 / (1 + cos)` (no cancellation for far or small spheres).
    #[inline]
    pub fn view(&self, origin: DVec3) -> SphereView {
        let (to_center, d2, r2) = self.relative(origin);
        if d2 <= r2 || d2 == 0.0 || d2.is_nan() {
            return SphereView::Surrounding;
        }
        SphereView::Cone {
            axis: to_center / d2.sqrt(),
            one_minus_cos_max: Self::cone(r2 / d2),
        }
    }

    /// `1 - cos theta_max` for `sin^2 theta_max`, or 0 (too small to see) below the directions'
    /// resolution, [`MIN_CONE_SIN2`].
    #[inline]
    fn cone(sin2_theta_max: f64) -> f64 {
        if sin2_theta_max >= MIN_CONE_SIN2 {
            warp::cone_one_minus_cos(sin2_theta_max)
        } else {
            0.0
        }
    }

    /// `(c - o, |c - o|^2, r^2)` for the centre `c` seen from `o`, in a unit in which the squares
    /// neither overflow nor underflow. Everything the cone needs is homogeneous in that unit (the
    /// ratio `r^2 / d^2`, the axis, the sign of a dot product, `|(c - o) x d|^2` against `r^2`), so
    /// the usual case is the plain computation, and only where `d^2` overflows (a sphere more than
    /// 1.3e154 away, whose axis would be the zero vector) or `r^2` leaves the normal range (a radius
    /// below 1.5e-154, whose `r^2 / d^2` would lose its digits or vanish) are both divided by the
    /// largest coordinate of `c - o` first.
    #[inline]
    fn relative(&self, origin: DVec3) -> (DVec3, f64, f64) {
        let to_center = self.center - origin;
        let d2 = to_center.length_squared();
        let r2 = self.radius * self.radius;
        if d2 <= f64::MAX && r2 >= f64::MIN_POSITIVE {
            return (to_center, d2, r2);
        }
        let m = to_center.abs().max_element();
        if !positive_finite(m) {
            return (to_center, d2, r2); // the origin at the centre, or not finite
        }
        // (a radius far beyond |c - o| may overflow to r^2 = inf here: the origin is inside)
        let (to_center, r) = (to_center / m, self.radius / m);
        (to_center, to_center.length_squared(), r * r)
    }
    // ANCHOR_END: sphere_view
}

// ANCHOR: sphere_target
impl ShapeSampler for SphereTarget {
    /// Uniform in the cone: `1 / (2 pi (1 - cos theta_max))` inside it, 0 outside (and 0 for a
    /// sphere too small to see, which `sample` never draws: narrower than [`MIN_CONE_SIN2`], or so
    /// small that the density is not a finite number).
    /// "Inside the cone" is the same as "the ray hits the sphere": the ray points towards the centre
    /// `c` and passes within `r` of it, `|(c - o) x d|^2 <= r^2` (a cross product, so no cancellation
    /// near the axis, and no square root or division before a hit). From inside the sphere:
    /// `1 / (4 pi)`.
    #[inline]
    fn pdf(&self, origin: DVec3, direction: DVec3) -> f64 {
        let (to_center, d2, r2) = self.relative(origin);
        if d2 <= r2 || d2 == 0.0 || d2.is_nan() {
            return warp::uniform_sphere_pdf();
        }
        if to_center.dot(direction) <= 0.0 || to_center.cross(direction).length_squared() > r2 {
            return 0.0;
        }
        let pdf = warp::uniform_cone_pdf(Self::cone(r2 / d2));
        // a sphere too small to see (narrower than the directions' resolution, or so small that
        // its density overflows) is never sampled, so never hit: `sample` gives `None` there
        if positive_finite(pdf) { pdf } else { 0.0 }
    }

    /// Uniform in the cone the sphere subtends (`None` for a sphere too small to see from `origin`),
    /// uniform over the sphere of directions from inside.
    #[inline]
    fn sample(&self, origin: DVec3, u: DVec2) -> Option<DirectionSample> {
        match self.view(origin) {
            SphereView::Cone {
                axis,
                one_minus_cos_max,
            } => DirectionSample::new(
                Onb::new(axis).transform(warp::sample_uniform_cone(u, one_minus_cos_max)),
                warp::uniform_cone_pdf(one_minus_cos_max),
            ),
            SphereView::Surrounding => Some(DirectionSample {
                direction: warp::sample_uniform_sphere(u),
                pdf: warp::uniform_sphere_pdf(),
            }),
        }
    }
}
// ANCHOR_END: sphere_target

/// How a [`QuadTarget`] picks directions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum QuadSampling {
    /// A point uniform on the quad's area, its density converted to solid angle (the book's way).
    Area,
    /// Uniform in the solid angle of the rectangle (Urena et al. 2013), where it is worth it.
    SphericalRectangle,
}

/// Below this solid angle (steradians) the spherical-rectangle terms lose precision and area sampling
/// is as good; above the upper limit the rectangle is nearly a hemisphere. The values are those pbrt-v4
/// gives its spherical triangles (its rectangles switch to area sampling below 1e-4 sr only).
pub const MIN_SPHERICAL_RECTANGLE_SOLID_ANGLE: f64 = 3e-4;
/// See [`MIN_SPHERICAL_RECTANGLE_SOLID_ANGLE`].
pub const MAX_SPHERICAL_RECTANGLE_SOLID_ANGLE: f64 = 6.22;

/// How far [`QuadTarget::hit`] lets a point lie outside the parameter square `[0, 1]^2`, per unit
/// of `|dual| t (reach + |o| + |q| + |u| + |v| + t) / |h|` ([`QuadTarget::edge_slack`]): a few
/// roundings of each magnitude, with room. Measured on points drawn on the edges and corners of
/// four quads (small, large, slanted, far from the coordinates' origin, by area and by spherical
/// rectangles) from 160,000 origins near, far and grazing, the largest excursion was 2.6% of the
/// slack this allows.
pub const EDGE_ROUNDING: f64 = 16.0 * f64::EPSILON;

/// The most [`QuadTarget::hit`] lets a point lie outside the parameter square by, however badly
/// the intersection is conditioned (an origin barely above the plane): `2^-24`, well inside the
/// millionth of its size that a hierarchy over the targets widens a quad's box by.
pub const MAX_EDGE_SLACK: f64 = 1.0 / 16_777_216.0;

/// A parallelogram `q + s u + t v`, `(s, t)` in `[0, 1]^2`, to sample towards; two-sided.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct QuadTarget {
    q: DVec3,
    u: DVec3,
    v: DVec3,
    /// unit normal `u x v / |u x v|`
    normal: DVec3,
    area: f64,
    /// `1 / area`, the density per unit area of a uniform point (infinite for a degenerate quad, which
    /// nothing hits)
    inv_area: f64,
    /// `v x w` and `w x u` with `w = n / (n . n)`, `n = u x v`: the plane coordinates of a hit `q + p`
    /// are `(p . (v x w), p . (w x u))`
    vw: DVec3,
    wu: DVec3,
    /// `max |u_i| + max |v_i|`, the quad's part of the in-plane tolerance of [`QuadTarget::height`]
    edge_scale: f64,
    /// `max |q_i| + edge_scale`: the quad's part of the magnitude of the coordinates an intersection
    /// with it rounds
    coord_scale: f64,
    /// `EDGE_ROUNDING max(|v x w|, |w x u|)`: how far out of the parameter square one unit of the
    /// intersection's rounding error can move a point
    slack_unit: f64,
    sampling: QuadSampling,
    /// The rectangle's frame when it samples by spherical rectangles (made once, not per origin).
    frame: Option<warp::RectangleFrame>,
}

impl QuadTarget {
    /// The parallelogram with corner `q` and edges `u`, `v`, sampled by area.
    pub fn new(q: DVec3, u: DVec3, v: DVec3) -> QuadTarget {
        let n = u.cross(v);
        let area = n.length();
        let (normal, w) = if area > 0.0 && area.is_finite() {
            (n / area, n / (area * area))
        } else {
            (DVec3::ZERO, DVec3::ZERO) // degenerate: every pdf_value is 0
        };
        let (vw, wu) = (v.cross(w), w.cross(u));
        let edge_scale = u.abs().max_element() + v.abs().max_element();
        QuadTarget {
            q,
            u,
            v,
            normal,
            area,
            inv_area: 1.0 / area,
            vw,
            wu,
            edge_scale,
            coord_scale: q.abs().max_element() + edge_scale,
            slack_unit: EDGE_ROUNDING * vw.length().max(wu.length()),
            sampling: QuadSampling::Area,
            frame: None,
        }
    }

    /// Whether to sample by spherical rectangles. Only a rectangle (`u . v = 0`, to 1e-12 relative) can;
    /// for other parallelograms this keeps area sampling. Even for a rectangle, the per-origin choice
    /// falls back to area sampling where the solid angle is outside
    /// [[`MIN_SPHERICAL_RECTANGLE_SOLID_ANGLE`], [`MAX_SPHERICAL_RECTANGLE_SOLID_ANGLE`]]; `pdf_value`
    /// always makes the same choice as `random`.
    pub fn with_spherical_rectangles(mut self, on: bool) -> QuadTarget {
        self.frame = if on && self.is_rectangle() {
            warp::RectangleFrame::new(self.q, self.u, self.v)
        } else {
            None
        };
        self.sampling = if self.frame.is_some() {
            QuadSampling::SphericalRectangle
        } else {
            QuadSampling::Area
        };
        self
    }

    /// `u . v = 0` to 1e-12 relative.
    pub fn is_rectangle(&self) -> bool {
        self.area > 0.0 && self.u.dot(self.v).abs() <= 1e-12 * self.u.length() * self.v.length()
    }

    /// How directions are picked: by area, or by spherical rectangles where they are worth it.
    pub fn sampling(&self) -> QuadSampling {
        self.sampling
    }
    /// The corner `q`.
    pub fn q(&self) -> DVec3 {
        self.q
    }
    /// The first edge `u`.
    pub fn u(&self) -> DVec3 {
        self.u
    }
    /// The second edge `v`.
    pub fn v(&self) -> DVec3 {
        self.v
    }
    /// The area `|u x v|`.
    pub fn area(&self) -> f64 {
        self.area
    }
    /// The unit normal `u x v / |u x v|` (zero for a degenerate quad).
    pub fn normal(&self) -> DVec3 {
        self.normal
    }
    /// `1 / area`: the density per unit area of a point uniform on the quad.
    pub fn inv_area(&self) -> f64 {
        self.inv_area
    }
    /// The dual basis `(v x w, w x u)` of the quad's plane (`w = n / (n . n)`, `n = u x v`): a point
    /// `q + p` of the plane has coordinates `(p . (v x w), p . (w x u))`.
    pub fn dual_basis(&self) -> (DVec3, DVec3) {
        (self.vw, self.wu)
    }
    /// `max |u_i| + max |v_i|`: the quad's part of the tolerance below which an origin counts as in
    /// its plane.
    pub fn edge_scale(&self) -> f64 {
        self.edge_scale
    }

    /// `max |q_i| + max |u_i| + max |v_i|`: the quad's part of the magnitude of the coordinates an
    /// intersection rounds ([`QuadTarget::edge_slack`]).
    pub fn coord_scale(&self) -> f64 {
        self.coord_scale
    }
    /// `EDGE_ROUNDING max(|v x w|, |w x u|)` ([`QuadTarget::edge_slack`]).
    pub fn slack_unit(&self) -> f64 {
        self.slack_unit
    }

    /// The signed height of `origin` above the quad's plane, or `None` when `origin` lies in the plane
    /// (to rounding: within 8 ulps of the distances involved), where the quad has no solid angle.
    #[inline]
    fn height(&self, origin: DVec3) -> Option<f64> {
        self.height_and_reach(origin).map(|(h, _)| h)
    }

    /// [`QuadTarget::height`] and `max |origin_i - q_i|`.
    #[inline]
    fn height_and_reach(&self, origin: DVec3) -> Option<(f64, f64)> {
        let rel = origin - self.q;
        let h = self.normal.dot(rel);
        let reach = rel.abs().max_element();
        let scale = reach + self.edge_scale;
        (h.abs() > 8.0 * f64::EPSILON * scale).then_some((h, reach))
    }

    // ANCHOR: edge_slack
    /// How far outside the parameter square `[0, 1]^2` the coordinates `(a, b)` that
    /// [`QuadTarget::hit`] computes may lie for a ray that meets the quad (a direction the sampler
    /// drew towards a point on an edge, `u = 0` or `1 - 2^-53`): the rounding error of the
    /// intersection, `O(epsilon)` of the magnitudes involved, with the error in the height `h`
    /// (about `epsilon` of the distance `|o - q|`, the `reach`) moving the point along the ray by its
    /// relative error times `t` (so the bound grows as `t / |h|` for a grazing origin):
    ///
    /// `slack = EDGE_ROUNDING |dual| t (reach + |o| + |q| + |u| + |v| + t) / |h|`,
    ///
    /// `|dual|` the larger of `|v x w|`, `|w x u|` (one unit of length is `|dual|` of the square),
    /// and at most [`MAX_EDGE_SLACK`]. A point within it counts as on the quad: its density is
    /// positive wherever its sampler may draw it, and positive besides only on a band of that width
    /// (for the Cornell box's light `7e-14` of the square seen from the middle of the floor, `2e-11`
    /// from the ceiling a unit above its plane), where the computation cannot tell.
    #[inline]
    pub fn edge_slack(&self, origin: DVec3, reach: f64, h: f64, t: f64) -> f64 {
        let magnitude = reach + origin.abs().max_element() + self.coord_scale + t;
        (self.slack_unit * t * magnitude / h.abs()).min(MAX_EDGE_SLACK)
    }
    // ANCHOR_END: edge_slack

    /// The spherical rectangle seen from `origin`, if this quad samples by them from there.
    #[inline]
    fn spherical_rectangle(&self, origin: DVec3) -> Option<warp::SphericalRectangle> {
        let sr = warp::SphericalRectangle::from_frame(origin, self.frame.as_ref()?)?;
        let s = sr.solid_angle();
        (MIN_SPHERICAL_RECTANGLE_SOLID_ANGLE..=MAX_SPHERICAL_RECTANGLE_SOLID_ANGLE)
            .contains(&s)
            .then_some(sr)
    }

    /// The distance `t` at which the ray `origin + t direction` (unit `direction`) meets the quad, or
    /// `None` on a miss (and from an origin in the plane). The point's coordinates `(a, b)` count as
    /// in `[0, 1]^2` to within their rounding error ([`QuadTarget::edge_slack`]): a direction drawn
    /// towards a point on an edge is not a miss (but from an origin so near the plane that the
    /// error exceeds [`MAX_EDGE_SLACK`], where neither the sample's density nor this one means much).
    #[inline]
    pub fn hit(&self, origin: DVec3, direction: DVec3) -> Option<f64> {
        let (h, reach) = self.height_and_reach(origin)?;
        let denom = self.normal.dot(direction);
        let t = -h / denom;
        if !positive_finite(t) {
            return None;
        }
        let p = origin + t * direction - self.q;
        let a = p.dot(self.vw);
        let b = p.dot(self.wu);
        let within =
            |slack: f64| (-slack..=1.0 + slack).contains(&a) && (-slack..=1.0 + slack).contains(&b);
        if within(0.0) {
            return Some(t);
        }
        // (the slack only for a point near the square: most misses are far from it)
        (within(MAX_EDGE_SLACK) && within(self.edge_slack(origin, reach, h, t))).then_some(t)
    }
}

// ANCHOR: quad_target
impl ShapeSampler for QuadTarget {
    /// Area sampling: `d^2 / (|cos theta_light| A)` where the ray hits; spherical rectangles: `1 / S`
    /// where it hits; 0 on a miss and from an origin in the quad's plane.
    #[inline]
    fn pdf(&self, origin: DVec3, direction: DVec3) -> f64 {
        let Some(t) = self.hit(origin, direction) else {
            return 0.0;
        };
        if let Some(sr) = self.spherical_rectangle(origin) {
            return sr.pdf();
        }
        // the hit point at distance t along the unit direction
        warp::area_to_solid_angle(self.inv_area, origin, origin + t * direction, self.normal)
    }

    /// A point uniform on the quad (or a direction uniform in its spherical rectangle); the density is
    /// made where the point is: `d^2 / (|cos theta_light| A)` of that point, or `1 / S`. `None` from an
    /// origin in the quad's plane, where it has no solid angle.
    #[inline]
    fn sample(&self, origin: DVec3, u: DVec2) -> Option<DirectionSample> {
        self.height(origin)?;
        if let Some(sr) = self.spherical_rectangle(origin) {
            return DirectionSample::new(sr.sample_direction(u), sr.pdf());
        }
        let p = warp::sample_parallelogram(u, self.q, self.u, self.v);
        // glam's `try_normalize`, with the finiteness test kept to two comparisons
        let to = p - origin;
        let rcp = to.length_recip();
        let direction = positive_finite(rcp).then(|| to * rcp)?;
        DirectionSample::new(
            direction,
            warp::area_to_solid_angle(self.inv_area, origin, p, self.normal),
        )
    }
}
// ANCHOR_END: quad_target
