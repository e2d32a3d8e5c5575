//! The pieces of a medium's boundary: the closed shapes it is made of (balls, moving spheres,
//! boxes, closed surfaces of quads), and whether they lie apart.
//!
//! A constant medium takes the stretches of a ray between its crossings of the boundary, in
//! pairs: in at the first, out at the next, in again at the one after, and so on
//! ([`crate::scene::Scene`]'s `hit_medium`). That is the inside of the boundary only where every
//! crossing changes sides, which holds for any number of closed pieces as long as they neither
//! overlap nor touch. Through two overlapping balls the crossings go in, in, out, out, and the
//! pairs would put the medium where the balls do not overlap and miss it where they do; through
//! two boxes face to face the shared face is crossed twice at one place. So a boundary whose
//! pieces come within a rounding error of each other is refused when the scene is read
//! ([`Pieces::first_touching`]); each piece can be a medium of its own instead (where media overlap,
//! their densities add).
//!
//! Pieces are compared exactly ([`crate::separation`]): two balls by their centres' distance
//! (`|c1 - c2| > r1 + r2`), a ball and a box by the distance from the centre to the box, a moving
//! sphere by the least such distance over its shutter's times (against a ball, the distance from a
//! point to a segment; against another moving sphere, the least distance of the two centres at one
//! time), two boxes by the separating axis theorem. A surface of quads is apart from another piece
//! where none of its quads comes near it and neither lies inside the other (a point of each tested
//! against the other). Past [`MAX_QUAD_TESTS`] tests of quads a surface is compared by its
//! bounding box, which may refuse pieces that are apart but close: the message says so.

use crate::aabb::Aabb;
use crate::separation::{
    Solid, distance_to_box, inside, least_along, parallelogram_distance, segment_distance,
    solids_apart,
};
use crate::vec::{Point3, Vec3};
use glam::DMat3;

/// How close two pieces may come, relative to their coordinates' magnitude, and still be apart:
/// far above the rounding of a crossing (a few ulps), far below any gap a scene means.
pub const TOUCH: f64 = 1e-9;

/// At most this many pairs of pieces are compared (sorted along x, only pairs whose x ranges
/// meet): a boundary of more pieces that close together is accepted unchecked past it.
pub const MAX_PAIRS: usize = 10_000_000;

/// At most this many tests of a quad against another piece or quad, over a whole boundary; past
/// them surfaces of quads are compared by their bounding boxes.
pub const MAX_QUAD_TESTS: usize = 10_000_000;

/// What a piece of a boundary is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PieceKind {
    /// A sphere (static).
    Ball { center: Point3, radius: f64 },
    /// A moving sphere: its centre at times 0 and 1 (it moves along the segment between them at
    /// a steady speed) and its radius.
    MovingSphere {
        from: Point3,
        to: Point3,
        radius: f64,
    },
    /// A box (six quads) as it is placed: its centre, its edges' unit directions (the columns of
    /// `axes`, a rotation) and half its size along each.
    Box {
        center: Point3,
        axes: DMat3,
        half: Vec3,
    },
    /// A closed surface of quads: `count` of [`Pieces::quads`] from `first`.
    Quads { first: usize, count: usize },
}

/// One closed piece of a boundary, in the boundary's coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Piece {
    pub kind: PieceKind,
    pub bounds: Aabb,
}

/// A quad as placed in the boundary: corners `q`, `q + u`, `q + v`, `q + u + v`.
pub type Parallelogram = (Point3, Vec3, Vec3);

/// A boundary's pieces, and the quads its surfaces of quads are made of.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Pieces {
    pub pieces: Vec<Piece>,
    pub quads: Vec<Parallelogram>,
}

impl Piece {
    /// A static sphere.
    pub fn ball(center: Point3, radius: f64) -> Piece {
        let r = Point3::splat(radius.abs());
        Piece {
            kind: PieceKind::Ball {
                center,
                radius: radius.abs(),
            },
            bounds: Aabb::EMPTY.include(center - r).include(center + r),
        }
    }

    /// A sphere of `radius` whose centre moves from `from` at time 0 to `to` at time 1.
    pub fn moving_ball(from: Point3, to: Point3, radius: f64) -> Piece {
        let r = Point3::splat(radius.abs());
        Piece {
            kind: PieceKind::MovingSphere {
                from,
                to,
                radius: radius.abs(),
            },
            bounds: Aabb::EMPTY
                .include(from.min(to) - r)
                .include(from.max(to) + r),
        }
    }

    /// The box from `lo` to `hi` (its own coordinates) placed by `rotation` then `translation`.
    pub fn placed_box(lo: Point3, hi: Point3, rotation: DMat3, translation: Vec3) -> Piece {
        let (center, half) = ((lo + hi) * 0.5, (hi - lo).abs() * 0.5);
        let mut bounds = Aabb::EMPTY;
        for i in 0..8 {
            let c = Vec3::new(
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
            );
            bounds = bounds.include(rotation * c + translation);
        }
        Piece {
            kind: PieceKind::Box {
                center: rotation * center + translation,
                axes: rotation,
                half,
            },
            bounds,
        }
    }

    /// Its bounding box as a piece: what a surface of quads is compared as without its quads.
    fn bounding_box(&self) -> Piece {
        Piece {
            kind: PieceKind::Box {
                center: (self.bounds.min + self.bounds.max) * 0.5,
                axes: DMat3::IDENTITY,
                half: (self.bounds.max - self.bounds.min) * 0.5,
            },
            bounds: self.bounds,
        }
    }

    /// The largest magnitude of the piece's coordinates (the scale of [`TOUCH`]).
    fn magnitude(&self) -> f64 {
        self.bounds
            .min
            .abs()
            .max(self.bounds.max.abs())
            .max_element()
    }

    /// Whether the two pieces lie more than [`TOUCH`] of their magnitude apart, a surface of quads
    /// taken by its bounding box (as [`Pieces`] takes it past its budget).
    pub fn apart(&self, other: &Piece) -> bool {
        self.apart_in(other, &[], &mut 0)
    }

    /// [`Piece::apart`], surfaces of quads by their quads in `quads` while `budget` lasts.
    fn apart_in(&self, other: &Piece, quads: &[Parallelogram], budget: &mut usize) -> bool {
        let tol = TOUCH * self.magnitude().max(other.magnitude());
        let (a, b) = (&self.bounds, &other.bounds);
        if (0..3).any(|k| a.max[k] + tol < b.min[k] || b.max[k] + tol < a.min[k]) {
            return true; // (their bounding boxes are apart)
        }
        let of =
            |first: usize, count: usize| quads.get(first..first + count).filter(|a| !a.is_empty());
        match (self.kind, other.kind) {
            (PieceKind::Quads { first, count }, _) => {
                if let Some(a) = of(first, count) {
                    match surface_apart(a, other, quads, tol, budget) {
                        Some(apart) => return apart,
                        None => *budget = 0, // (spent: by bounding boxes from here on)
                    }
                }
                self.bounding_box().apart_in(other, quads, budget)
            }
            (_, PieceKind::Quads { .. }) => other.apart_in(self, quads, budget),
            (
                PieceKind::Ball {
                    center: a,
                    radius: ra,
                },
                PieceKind::Ball {
                    center: b,
                    radius: rb,
                },
            ) => (a - b).length() > ra + rb + tol,
            // a ball and a moving one: the distance from the ball's centre to the path of the
            // other's; two moving ones: the least distance between their centres at one time,
            // which is that of the origin from the path of their difference
            (
                PieceKind::Ball { center, radius: r },
                PieceKind::MovingSphere { from, to, radius },
            )
            | (
                PieceKind::MovingSphere { from, to, radius },
                PieceKind::Ball { center, radius: r },
            ) => segment_distance(center, from, to) > r + radius + tol,
            (
                PieceKind::MovingSphere {
                    from: fa,
                    to: ta,
                    radius: ra,
                },
                PieceKind::MovingSphere {
                    from: fb,
                    to: tb,
                    radius: rb,
                },
            ) => segment_distance(Point3::ZERO, fa - fb, ta - tb) > ra + rb + tol,
            (PieceKind::Ball { center: p, radius }, PieceKind::Box { center, axes, half })
            | (PieceKind::Box { center, axes, half }, PieceKind::Ball { center: p, radius }) => {
                distance_to_box(p, center, axes, half) > radius + tol
            }
            (
                PieceKind::MovingSphere { from, to, radius },
                PieceKind::Box { center, axes, half },
            )
            | (
                PieceKind::Box { center, axes, half },
                PieceKind::MovingSphere { from, to, radius },
            ) => least_along(from, to, |p| distance_to_box(p, center, axes, half)) > radius + tol,
            (
                PieceKind::Box { center, axes, half },
                PieceKind::Box {
                    center: c,
                    axes: r,
                    half: h,
                },
            ) => {
                let (a, b) = (
                    Solid::Box { center, axes, half },
                    Solid::Box {
                        center: c,
                        axes: r,
                        half: h,
                    },
                );
                solids_apart(&a, &b, tol)
            }
        }
    }
}

/// Whether the closed surface of the quads `a` lies more than `tol` from `other` (whose own quads,
/// if it is a surface of them, are in `all`): none of `a`'s quads within `tol` of it, and neither
/// inside the other (a point of each tested against the other). `None` once `budget` tests of a
/// quad are spent.
fn surface_apart(
    a: &[Parallelogram],
    other: &Piece,
    all: &[Parallelogram],
    tol: f64,
    budget: &mut usize,
) -> Option<bool> {
    let near = |b: &Aabb, c: &Aabb| {
        (0..3).all(|k| b.min[k] <= c.max[k] + tol && c.min[k] <= b.max[k] + tol)
    };
    let bounds = |&(q, u, v): &Parallelogram| {
        [q + u, q + v, q + u + v]
            .into_iter()
            .fold(Aabb::EMPTY.include(q), |b, c| b.include(c))
    };
    let others = match other.kind {
        PieceKind::Quads { first, count } => all.get(first..first + count)?,
        _ => &[],
    };
    for quad @ &(q, u, v) in a {
        let qb = bounds(quad);
        if !near(&qb, &other.bounds) {
            continue;
        }
        *budget = budget.checked_sub(1)?;
        let flat = Solid::Flat { q, u, v };
        let touches = match other.kind {
            PieceKind::Ball { center, radius } => {
                parallelogram_distance(center, q, u, v) <= radius + tol
            }
            PieceKind::MovingSphere { from, to, radius } => {
                least_along(from, to, |p| parallelogram_distance(p, q, u, v)) <= radius + tol
            }
            PieceKind::Box { center, axes, half } => {
                !solids_apart(&flat, &Solid::Box { center, axes, half }, tol)
            }
            PieceKind::Quads { .. } => {
                let mut touches = false;
                for other_quad @ &(q2, u2, v2) in others {
                    if !near(&qb, &bounds(other_quad)) {
                        continue;
                    }
                    *budget = budget.checked_sub(1)?;
                    if !solids_apart(
                        &flat,
                        &Solid::Flat {
                            q: q2,
                            u: u2,
                            v: v2,
                        },
                        tol,
                    ) {
                        touches = true;
                        break;
                    }
                }
                touches
            }
        };
        if touches {
            return Some(false);
        }
    }
    // No quad comes near: `other` lies wholly inside the surface, wholly outside, or (a surface
    // itself) around it. (A solid around it would hold its quads, which the tests above meet.)
    *budget = budget.checked_sub(a.len() + others.len())?;
    let point = match other.kind {
        PieceKind::Ball { center, .. } | PieceKind::Box { center, .. } => center,
        PieceKind::MovingSphere { from, .. } => from,
        PieceKind::Quads { .. } => others.first()?.0,
    };
    let margin = tol.max(f64::MIN_POSITIVE);
    let within = inside(point, a, margin).unwrap_or(true);
    let around = !others.is_empty() && inside(a.first()?.0, others, margin).unwrap_or(true);
    Some(!within && !around)
}

impl Pieces {
    /// The first pair of pieces (by their order along x) that overlap or touch
    /// ([`Piece::apart`], surfaces of quads by their quads for the first [`MAX_QUAD_TESTS`] tests),
    /// comparing only pairs whose x ranges meet, at most [`MAX_PAIRS`] of them; and whether the
    /// pair was compared exactly (not by a surface of quads' bounding box).
    pub fn first_touching(&self) -> Option<(usize, usize, bool)> {
        let pieces = &self.pieces;
        let mut order: Vec<usize> = (0..pieces.len()).collect();
        order.sort_by(|&i, &j| pieces[i].bounds.min.x.total_cmp(&pieces[j].bounds.min.x));
        let mut pairs = 0;
        let mut budget = MAX_QUAD_TESTS;
        for (k, &i) in order.iter().enumerate() {
            let a = &pieces[i];
            for &j in &order[k + 1..] {
                let b = &pieces[j];
                if b.bounds.min.x > a.bounds.max.x + TOUCH * a.magnitude().max(b.magnitude()) {
                    break; // (nor do the rest, further along x)
                }
                if !a.apart_in(b, &self.quads, &mut budget) {
                    let quads = |p: &Piece| matches!(p.kind, PieceKind::Quads { .. });
                    let exact = !(quads(a) || quads(b)) || budget > 0;
                    return Some((i.min(j), i.max(j), exact));
                }
                pairs += 1;
                if pairs >= MAX_PAIRS {
                    return None;
                }
            }
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// Uniform numbers in [0, 1) from SplitMix64 seeded with `seed`.
    fn uniforms(seed: u64) -> impl FnMut() -> f64 {
        let mut state = seed;
        move || {
            state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
            let mut z = state;
            z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// A rotation from four of `next`'s numbers (a normalised quaternion).
    fn rotation(next: &mut dyn FnMut() -> f64) -> DMat3 {
        let q = glam::DQuat::from_xyzw(next() - 0.5, next() - 0.5, next() - 0.5, next() - 0.5);
        DMat3::from_quat(q.normalize())
    }

    /// A surface of quads without its quads (compared by its bounding box).
    const QUADS: PieceKind = PieceKind::Quads { first: 0, count: 0 };

    fn solid(kind: PieceKind, a: [f64; 3], b: [f64; 3]) -> Piece {
        Piece {
            kind,
            bounds: Aabb::EMPTY
                .include(Point3::from(a))
                .include(Point3::from(b)),
        }
    }

    /// The box from `a` to `b`, not turned.
    fn cube(a: [f64; 3], b: [f64; 3]) -> Piece {
        Piece::placed_box(a.into(), b.into(), DMat3::IDENTITY, Vec3::ZERO)
    }

    /// The box of half sizes `half` turned by `r` and centred at `c`.
    fn turned(half: [f64; 3], r: DMat3, c: Vec3) -> Piece {
        let h = Vec3::from(half);
        Piece::placed_box(-h, h, r, c)
    }

    #[test]
    fn balls_apart_by_their_centres_and_radii() {
        let a = Piece::ball(Point3::ZERO, 1.0);
        // apart by 1e-6: apart; touching, overlapping, nested: not
        assert!(a.apart(&Piece::ball(Point3::new(3.0 + 1e-6, 0.0, 0.0), 2.0)));
        assert!(!a.apart(&Piece::ball(Point3::new(3.0, 0.0, 0.0), 2.0)));
        assert!(!a.apart(&Piece::ball(Point3::new(2.5, 0.0, 0.0), 2.0)));
        assert!(!a.apart(&Piece::ball(Point3::new(0.1, 0.0, 0.0), 0.2)));
        // diagonal neighbours whose bounding boxes overlap are apart
        let d = 2.0 / 3f64.sqrt() + 1e-3;
        assert!(a.apart(&Piece::ball(Point3::splat(d), 1.0 - 1e-9)));
        assert!(a.bounds.max.x > d - 1.0);
    }

    #[test]
    fn a_ball_and_a_box_by_the_distance_to_the_box() {
        let a = Piece::ball(Point3::ZERO, 1.0);
        let corner = cube([0.6, 0.6, 0.6], [2.0, 2.0, 2.0]);
        // the box's corner lies 0.6 sqrt 3 = 1.04 from the centre: apart, though the boxes meet
        assert!(a.apart(&corner) && corner.apart(&a));
        let face = cube([0.99, -5.0, -5.0], [2.0, 5.0, 5.0]);
        assert!(!a.apart(&face) && !face.apart(&a));
        let around = solid(QUADS, [-3.0; 3], [3.0; 3]);
        assert!(!a.apart(&around));
        // a unit cube turned 45 degrees about y, a face towards the ball along the diagonal of x
        // and z: the face lies 2.1 - 0.5 = 1.6 from the centre, the corner of its bounding box
        // 2.1 - 1 = 1.1
        let diagonal = Vec3::new(1.0, 0.0, 1.0).normalize();
        let diamond = turned([0.5; 3], DMat3::from_rotation_y(0.25 * PI), diagonal * 2.1);
        let ball = |r: f64| Piece::ball(Point3::ZERO, r);
        assert!(!ball(1.5).apart(&solid(
            QUADS,
            diamond.bounds.min.into(),
            diamond.bounds.max.into()
        )));
        assert!(ball(1.5).apart(&diamond) && diamond.apart(&ball(1.5)));
        assert!(!ball(1.65).apart(&diamond) && !diamond.apart(&ball(1.65)));
    }

    #[test]
    fn boxes_by_a_gap_along_some_axis() {
        let a = cube([0.0; 3], [1.0; 3]);
        assert!(a.apart(&cube([0.0, 1.001, 0.0], [1.0, 2.0, 1.0])));
        // face to face: the shared face would be crossed twice at one place
        assert!(!a.apart(&cube([0.0, 1.0, 0.0], [1.0, 2.0, 1.0])));
        // a moving sphere starting sqrt 3 from the cube's corner
        let moving = |r: f64| Piece::moving_ball(Point3::splat(2.0), Point3::splat(4.0), r);
        assert!(a.apart(&moving(1.7)) && !a.apart(&moving(1.8)));
        // a box turned 45 degrees about z off the cube's edge at x = y = 1, a face towards it,
        // `t` from the edge to the box's centre: 0.01 apart at t = 0.51, though their bounding
        // boxes overlap; touching at 0.5; overlapping at 0.49
        let diagonal = Vec3::new(1.0, 1.0, 0.0).normalize();
        for (t, apart) in [(0.51, true), (0.5, false), (0.49, false)] {
            let c = Vec3::new(1.0, 1.0, 0.5) + diagonal * t;
            let diamond = turned([0.5; 3], DMat3::from_rotation_z(0.25 * PI), c);
            assert!(diamond.bounds.min.x < 1.0 && diamond.bounds.min.y < 1.0);
            assert_eq!(a.apart(&diamond), apart, "t {t}");
            assert_eq!(diamond.apart(&a), apart, "t {t}");
        }
    }

    /// Moving spheres are apart where their centres, at each time, are: two whose paths cross at
    /// different times (the first passes the origin at time 1/2, the second reaches it at time 1:
    /// their centres come within sqrt 2 of each other, at time 3/4), a ball beside a diagonal
    /// path, a path passing a box's edge 0.354 away (0.5 - 2 + 2 over sqrt 2) at time 3/4. Each
    /// apart at a radius just below, touching just above, though their bounding boxes overlap.
    #[test]
    fn moving_spheres_by_their_centres_at_each_time() {
        let p = |x: f64, y: f64| Point3::new(x, y, 0.0);
        let across = |r: f64| Piece::moving_ball(p(-2.0, 0.0), p(2.0, 0.0), r);
        let up = |r: f64| Piece::moving_ball(p(0.0, -4.0), p(0.0, 0.0), r);
        let h = 0.5 * 2f64.sqrt();
        assert!(across(h - 1e-6).apart(&up(h - 1e-6)));
        assert!(!across(h + 1e-6).apart(&up(h + 1e-6)));
        let (a, b) = (across(0.5).bounds, up(0.5).bounds);
        assert!((0..3).all(|k| a.min[k] <= b.max[k] && b.min[k] <= a.max[k]));
        let diagonal = |r: f64| Piece::moving_ball(p(-5.0, -5.0), p(5.0, 5.0), r);
        let ball = Piece::ball(p(2.0, -2.0), 1.0);
        let gap = 2.0 * 2f64.sqrt() - 1.0;
        assert!(diagonal(gap - 1e-6).apart(&ball) && ball.apart(&diagonal(gap - 1e-6)));
        assert!(!diagonal(gap + 1e-6).apart(&ball));
        let cube = Piece::placed_box(
            Point3::new(0.5, 0.5, -1.0),
            Point3::new(2.0, 2.0, 1.0),
            DMat3::IDENTITY,
            Vec3::ZERO,
        );
        let past = |r: f64| Piece::moving_ball(p(-2.0, 0.0), p(1.0, 3.0), r);
        let d = 0.5 / 2f64.sqrt();
        assert!(past(d - 1e-6).apart(&cube) && cube.apart(&past(d - 1e-6)));
        assert!(!past(d + 1e-6).apart(&cube) && !cube.apart(&past(d + 1e-6)));
        assert!(past(0.3).bounds.min.x < 0.5 && past(0.3).bounds.max.y > 0.5);
    }

    /// Two boxes, one with an edge along z turned towards +x, the other with an edge along y
    /// turned towards -x: only the cross product of the two edges (the x axis) separates them; a
    /// test of the six faces' normals alone would call them touching.
    #[test]
    fn boxes_apart_by_the_cross_product_of_two_edges() {
        let s = 2f64.sqrt();
        let a = turned([1.0; 3], DMat3::from_rotation_z(0.25 * PI), Vec3::ZERO);
        let b = |x: f64| turned([1.0; 3], DMat3::from_rotation_y(0.25 * PI), Vec3::X * x);
        assert!(a.apart(&b(2.0 * s + 0.01)));
        assert!(!a.apart(&b(2.0 * s - 0.01)));
        let parts = |p: &Piece| match p.kind {
            PieceKind::Box { center, axes, half } => (center, axes, half),
            _ => unreachable!(),
        };
        let (ca, ra, ha) = parts(&a);
        let (cb, rb, hb) = parts(&b(2.0 * s + 0.01));
        let d = cb - ca;
        let faces_only = (0..3).flat_map(|i| [ra.col(i), rb.col(i)]).any(|n| {
            let reach =
                |r: DMat3, h: Vec3| (0..3).map(|i| h[i] * r.col(i).dot(n).abs()).sum::<f64>();
            d.dot(n).abs() - reach(ra, ha) - reach(rb, hb) > 0.0
        });
        assert!(
            !faces_only,
            "the faces' normals alone separate them: not the case this tests"
        );
    }

    /// Random turned boxes placed against each other with a corner of one on a face of the
    /// other: touching (not apart), and 1e-6 beyond the face along its normal, with the corner
    /// that reaches furthest against it: apart. A test that took turned boxes for their bounding
    /// boxes fails the second half; one that skipped an axis or took a box's half size for its
    /// whole the first.
    #[test]
    fn random_boxes_touching_and_just_apart() {
        let mut next = uniforms(0x5eed);
        for _ in 0..2000 {
            let ha = Vec3::new(0.1 + next(), 0.1 + next(), 0.1 + next());
            let hb = Vec3::new(0.1 + next(), 0.1 + next(), 0.1 + next());
            let (ra, rb) = (rotation(&mut next), rotation(&mut next));
            let ca = Vec3::new(next(), next(), next()) * 4.0 - 2.0;
            let a = turned(ha.into(), ra, ca);
            // a point on one of a's faces (axis k, side s) and that face's outward normal
            let (k, s) = (
                (next() * 3.0) as usize % 3,
                if next() < 0.5 { -1.0 } else { 1.0 },
            );
            let mut local = Vec3::new(next(), next(), next()) * 2.0 - 1.0;
            local[k] = s;
            let p = ca + ra * (local * ha);
            let n = ra.col(k) * s;
            // b's corner furthest along -n, put at p and then 1e-6 beyond it
            let sign = |x: f64| if x < 0.0 { 1.0 } else { -1.0 };
            let corner = Vec3::new(
                sign(rb.col(0).dot(n)),
                sign(rb.col(1).dot(n)),
                sign(rb.col(2).dot(n)),
            ) * hb;
            let at = |q: Vec3| turned(hb.into(), rb, q - rb * corner);
            assert!(!a.apart(&at(p)) && !at(p).apart(&a), "a corner on a face");
            let beyond = at(p + n * 1e-6);
            assert!(
                a.apart(&beyond) && beyond.apart(&a),
                "a corner 1e-6 beyond a face"
            );
        }
    }

    /// A box and the same box written as six quads must be told apart from anything alike: 3000
    /// random turned boxes, each against a random ball, moving sphere and turned box (inside it,
    /// around it, touching it or apart), compared once as a box and once as a surface of quads.
    /// A surface test that missed a quad, took a point inside for outside or skipped an axis of the
    /// separating axis test would disagree somewhere.
    #[test]
    fn a_box_written_as_quads_is_apart_where_the_box_is() {
        let mut next = uniforms(0xb0c5);
        let point = |next: &mut dyn FnMut() -> f64, scale: f64| {
            Vec3::new(next() - 0.5, next() - 0.5, next() - 0.5) * scale
        };
        let (mut agreed, mut apart) = (0, 0);
        for _ in 0..3000 {
            let h = Vec3::new(0.2 + next(), 0.2 + next(), 0.2 + next());
            let (r, c) = (rotation(&mut next), point(&mut next, 1.0));
            let as_box = turned(h.into(), r, c);
            // its six faces, each corner placed as the box's
            let corner = |s: Vec3| r * (s * h) + c;
            let faces: Vec<Parallelogram> = (0..3)
                .flat_map(|k| {
                    let (i, j) = ((k + 1) % 3, (k + 2) % 3);
                    [-1.0, 1.0].map(|side| {
                        let mut s = Vec3::splat(-1.0);
                        s[k] = side;
                        let q = corner(s);
                        let (mut a, mut b) = (s, s);
                        (a[i], b[j]) = (1.0, 1.0);
                        (q, corner(a) - q, corner(b) - q)
                    })
                })
                .collect();
            let bounds = faces.iter().fold(Aabb::EMPTY, |b, &(q, u, v)| {
                b.include(q)
                    .include(q + u)
                    .include(q + v)
                    .include(q + u + v)
            });
            let surface = Piece {
                kind: PieceKind::Quads { first: 0, count: 6 },
                bounds,
            };
            let others = [
                Piece::ball(point(&mut next, 4.0), 0.05 + 1.5 * next()),
                Piece::moving_ball(point(&mut next, 4.0), point(&mut next, 4.0), 0.05 + next()),
                turned(
                    [0.05 + next(), 0.05 + next(), 0.05 + next()],
                    rotation(&mut next),
                    point(&mut next, 4.0),
                ),
            ];
            for other in others {
                let all = Pieces {
                    pieces: vec![surface, other],
                    quads: faces.clone(),
                };
                let by_quads = all.first_touching().is_none();
                assert_eq!(
                    by_quads,
                    as_box.apart(&other),
                    "{other:?} and the box {as_box:?}"
                );
                agreed += 1;
                apart += by_quads as usize;
            }
        }
        // both verdicts were asked often
        assert!(
            apart > 1500 && agreed - apart > 1500,
            "{apart} apart of {agreed}"
        );
    }

    /// A surface of quads inside another, apart from it, is not apart: a point of the inner one
    /// lies inside the outer. Nor is a ball inside a surface, or a surface inside a ball.
    #[test]
    fn a_piece_inside_a_surface_of_quads_or_around_it_touches_it() {
        let cube = |lo: f64, size: f64| -> Vec<Parallelogram> {
            let (x, y, z) = (Vec3::X * size, Vec3::Y * size, Vec3::Z * size);
            let o = Point3::splat(lo);
            vec![
                (o, y, x),
                (o + z, x, y),
                (o, x, z),
                (o + y, z, x),
                (o, z, y),
                (o + x, y, z),
            ]
        };
        let surface = |first: usize, lo: f64, size: f64| Piece {
            kind: PieceKind::Quads { first, count: 6 },
            bounds: Aabb::EMPTY
                .include(Point3::splat(lo))
                .include(Point3::splat(lo + size)),
        };
        let mut quads = cube(0.0, 4.0);
        quads.extend(cube(1.0, 1.0));
        let nested = Pieces {
            pieces: vec![surface(0, 0.0, 4.0), surface(6, 1.0, 1.0)],
            quads: quads.clone(),
        };
        assert_eq!(nested.first_touching(), Some((0, 1, true)));
        // either way round: the inner surface's quads against the outer, and the other way
        let (outer_surface, inner_surface) = (surface(0, 0.0, 4.0), surface(6, 1.0, 1.0));
        for (a, b) in [
            (outer_surface, inner_surface),
            (inner_surface, outer_surface),
        ] {
            assert!(
                !a.apart_in(&b, &quads, &mut MAX_QUAD_TESTS.clone()),
                "{a:?} {b:?}"
            );
        }
        let outer = |piece: Piece| Pieces {
            pieces: vec![surface(0, 0.0, 4.0), piece],
            quads: quads[..6].to_vec(),
        };
        // inside, around, apart, and beside the cube's corner within its bounding box's reach
        for (c, r, touches) in [
            (2.0, 1.0, true),
            (2.0, 5.0, true),
            (6.0, 1.0, false),
            (4.5, 0.8, false),
        ] {
            let ball = Piece::ball(Point3::splat(c), r);
            assert_eq!(outer(ball).first_touching().is_some(), touches, "{ball:?}");
        }
        // without its quads a surface is its bounding box: a ball by its distance to that box
        // (0.5 sqrt 3 = 0.866 from the corner here)
        for (r, apart) in [(0.85, true), (0.9, false)] {
            let ball = Piece::ball(Point3::splat(4.5), r);
            assert_eq!(surface(0, 0.0, 4.0).apart(&ball), apart, "radius {r}");
        }
    }

    #[test]
    fn the_sweep_finds_the_pair_that_touches_among_many_apart() {
        // a row of 1000 balls 2.5 apart, then one that reaches into its neighbour
        let mut pieces: Vec<Piece> = (0..1000)
            .map(|i| Piece::ball(Point3::new(2.5 * i as f64, 0.0, 0.0), 1.0))
            .collect();
        let first = |pieces: &[Piece]| {
            let all = Pieces {
                pieces: pieces.to_vec(),
                quads: Vec::new(),
            };
            all.first_touching().map(|(i, j, _)| (i, j))
        };
        assert_eq!(first(&pieces), None);
        pieces[700] = Piece::ball(Point3::new(2.5 * 700.0 - 0.6, 0.0, 0.0), 1.0);
        assert_eq!(first(&pieces), Some((699, 700)));
        // a checker that compared nothing would say apart: one far ball inside a large one
        let pieces = [
            Piece::ball(Point3::ZERO, 100.0),
            Piece::ball(Point3::new(50.0, 0.0, 0.0), 1.0),
        ];
        assert_eq!(first(&pieces), Some((0, 1)));
    }
}
