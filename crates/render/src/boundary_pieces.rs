//! The pieces of a medium's boundary: the closed shapes it is made of (balls, boxes, closed
//! surfaces of quads), and whether they lie apart.
//!
//! A constant medium takes the stretches of a ray between its crossings of the boundary, in
//! pairs: in at the first, out at the next, in again at the one after, and so on
//! ([`crate::scene::Scene`]'s `hit_medium`). That is the inside of the boundary only where every
//! crossing changes sides, which holds for any number of closed pieces as long as they neither
//! overlap nor touch. Through two overlapping balls the crossings go in, in, out, out, and the
//! pairs would put the medium where the balls do not overlap and miss it where they do; through
//! two boxes face to face the shared face is crossed twice at one place. So a boundary whose
//! pieces come within a rounding error of each other is refused when the scene is read
//! ([`first_touching`]); each piece can be a medium of its own instead (where media overlap,
//! their densities add).
//!
//! Balls are compared exactly (`|c1 - c2| > r1 + r2`); a box (turned, it is compared by its
//! bounding box), a moving sphere (the box it sweeps) and a surface of quads are compared by
//! their bounding boxes, which may refuse pieces that are apart but close: the message says so.

use crate::aabb::Aabb;
use crate::vec::Point3;

/// How close two pieces may come, relative to their coordinates' magnitude, and still be apart:
/// far above the rounding of a crossing (a few ulps), far below any gap a scene means.
pub const TOUCH: f64 = 1e-9;

/// At most this many pairs of pieces are compared (sorted along x, only pairs whose x ranges
/// meet): a boundary of more pieces that close together is accepted unchecked past it.
pub const MAX_PAIRS: usize = 10_000_000;

/// What a piece of a boundary is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PieceKind {
    /// A sphere (static): compared exactly.
    Ball { center: Point3, radius: f64 },
    /// A moving sphere, by the box it sweeps.
    MovingSphere,
    /// A box (six quads), by its bounding box.
    Box,
    /// A closed surface of loose quads, by its bounding box.
    Quads,
}

/// One closed piece of a boundary, in the boundary's coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Piece {
    pub kind: PieceKind,
    pub bounds: Aabb,
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

    /// The largest magnitude of the piece's coordinates (the scale of [`TOUCH`]).
    fn magnitude(&self) -> f64 {
        self.bounds
            .min
            .abs()
            .max(self.bounds.max.abs())
            .max_element()
    }

    /// Whether the two pieces lie more than [`TOUCH`] of their magnitude apart: balls by their
    /// centres' distance, a ball and a box by the distance from the centre to the box, boxes by a
    /// gap along some axis.
    pub fn apart(&self, other: &Piece) -> bool {
        let tol = TOUCH * self.magnitude().max(other.magnitude());
        match (self.kind, other.kind) {
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
            (PieceKind::Ball { center, radius }, _) => {
                distance_to_box(center, &other.bounds) > radius + tol
            }
            (_, PieceKind::Ball { center, radius }) => {
                distance_to_box(center, &self.bounds) > radius + tol
            }
            _ => {
                let (a, b) = (&self.bounds, &other.bounds);
                (0..3).any(|k| a.max[k] + tol < b.min[k] || b.max[k] + tol < a.min[k])
            }
        }
    }
}

/// The Euclidean distance from `p` to the box `b` (0 inside it).
fn distance_to_box(p: Point3, b: &Aabb) -> f64 {
    (b.min - p).max(p - b.max).max(Point3::ZERO).length()
}

/// The first pair of `pieces` (by their order along x) that overlap or touch ([`Piece::apart`]),
/// comparing only pairs whose x ranges meet, at most [`MAX_PAIRS`] of them.
pub fn first_touching(pieces: &[Piece]) -> Option<(usize, usize)> {
    let mut order: Vec<usize> = (0..pieces.len()).collect();
    order.sort_by(|&i, &j| pieces[i].bounds.min.x.total_cmp(&pieces[j].bounds.min.x));
    let mut pairs = 0;
    for (k, &i) in order.iter().enumerate() {
        let a = &pieces[i];
        for &j in &order[k + 1..] {
            let b = &pieces[j];
            if b.bounds.min.x > a.bounds.max.x + TOUCH * a.magnitude().max(b.magnitude()) {
                break; // (nor do the rest, further along x)
            }
            if !a.apart(b) {
                return Some((i.min(j), i.max(j)));
            }
            pairs += 1;
            if pairs >= MAX_PAIRS {
                return None;
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn solid(kind: PieceKind, a: [f64; 3], b: [f64; 3]) -> Piece {
        Piece {
            kind,
            bounds: Aabb::EMPTY
                .include(Point3::from(a))
                .include(Point3::from(b)),
        }
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
        let corner = solid(PieceKind::Box, [0.6, 0.6, 0.6], [2.0, 2.0, 2.0]);
        // the box's corner lies 0.6 sqrt 3 = 1.04 from the centre: apart, though the boxes meet
        assert!(a.apart(&corner) && corner.apart(&a));
        let face = solid(PieceKind::Box, [0.99, -5.0, -5.0], [2.0, 5.0, 5.0]);
        assert!(!a.apart(&face) && !face.apart(&a));
        let around = solid(PieceKind::Quads, [-3.0; 3], [3.0; 3]);
        assert!(!a.apart(&around));
    }

    #[test]
    fn boxes_by_a_gap_along_some_axis() {
        let a = solid(PieceKind::Box, [0.0; 3], [1.0; 3]);
        assert!(a.apart(&solid(PieceKind::Box, [0.0, 1.001, 0.0], [1.0, 2.0, 1.0])));
        // face to face: the shared face would be crossed twice at one place
        assert!(!a.apart(&solid(PieceKind::Box, [0.0, 1.0, 0.0], [1.0, 2.0, 1.0])));
        assert!(!a.apart(&solid(PieceKind::MovingSphere, [0.5; 3], [4.0; 3])));
    }

    #[test]
    fn the_sweep_finds_the_pair_that_touches_among_many_apart() {
        // a row of 1000 balls 2.5 apart, then one that reaches into its neighbour
        let mut pieces: Vec<Piece> = (0..1000)
            .map(|i| Piece::ball(Point3::new(2.5 * i as f64, 0.0, 0.0), 1.0))
            .collect();
        assert_eq!(first_touching(&pieces), None);
        pieces[700] = Piece::ball(Point3::new(2.5 * 700.0 - 0.6, 0.0, 0.0), 1.0);
        assert_eq!(first_touching(&pieces), Some((699, 700)));
        // a checker that compared nothing would say apart: one far ball inside a large one
        let pieces = [
            Piece::ball(Point3::ZERO, 100.0),
            Piece::ball(Point3::new(50.0, 0.0, 0.0), 1.0),
        ];
        assert_eq!(first_touching(&pieces), Some((0, 1)));
    }
}
