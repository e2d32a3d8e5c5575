//! How far apart convex solids are, for telling a medium's boundary pieces apart
//! ([`crate::boundary_pieces`]): the distance from a point to a segment, a box and a
//! parallelogram; the least such distance along a path (a golden-section search of a convex
//! function); the separating axis theorem for boxes and parallelograms; and whether a point lies
//! inside a closed surface of parallelograms (the parity of a ray's crossings).
//!
//! Two convex solids are apart exactly where their projections onto some line are (the separating
//! axis theorem). For two convex polyhedra one of finitely many lines will do: the faces' normals
//! of each and the cross products of an edge of each (Gottschalk, Lin and Manocha, "OBBTree",
//! 1996). A box has three of each; a parallelogram, taken as the limit of a thin slab, has its
//! normal and the two in-plane normals of its sides as faces, and its two sides and its normal as
//! edges.

use crate::vec::{Point3, Vec3};
use glam::DMat3;

/// A convex solid the separating axis test takes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Solid {
    /// A box: its centre, its edges' unit directions (the columns of a rotation) and half its size
    /// along each.
    Box {
        center: Point3,
        axes: DMat3,
        half: Vec3,
    },
    /// The parallelogram of corners `q`, `q + u`, `q + v`, `q + u + v`.
    Flat { q: Point3, u: Vec3, v: Vec3 },
}

impl Solid {
    fn center(&self) -> Point3 {
        match *self {
            Solid::Box { center, .. } => center,
            Solid::Flat { q, u, v } => q + (u + v) * 0.5,
        }
    }

    /// Half the length of the solid's projection onto the unit line `n`.
    fn reach(&self, n: Vec3) -> f64 {
        match *self {
            Solid::Box { axes, half, .. } => {
                (0..3).map(|i| half[i] * axes.col(i).dot(n).abs()).sum()
            }
            Solid::Flat { u, v, .. } => 0.5 * (u.dot(n).abs() + v.dot(n).abs()),
        }
    }

    /// The unit normals of its faces and the unit directions of its edges.
    fn faces_and_edges(&self) -> ([Vec3; 3], [Vec3; 3]) {
        match *self {
            Solid::Box { axes, .. } => {
                let a = [axes.col(0), axes.col(1), axes.col(2)];
                (a, a)
            }
            Solid::Flat { u, v, .. } => {
                let n = u.cross(v).normalize_or_zero();
                let faces = [
                    n,
                    u.cross(n).normalize_or_zero(),
                    v.cross(n).normalize_or_zero(),
                ];
                (faces, [u.normalize_or_zero(), v.normalize_or_zero(), n])
            }
        }
    }
}

/// Whether the projections of `a` and `b` onto some line are more than `tol` apart: a face's
/// normal of either or the cross product of an edge of each. Cross products of edges within 1e-6
/// of parallel are skipped: where edges are parallel, the faces' normals already hold every
/// separating direction needed.
pub fn solids_apart(a: &Solid, b: &Solid, tol: f64) -> bool {
    let d = b.center() - a.center();
    let gap = |n: Vec3| d.dot(n).abs() - a.reach(n) - b.reach(n);
    let ((fa, ea), (fb, eb)) = (a.faces_and_edges(), b.faces_and_edges());
    let crossed = (0..9).filter_map(|k| {
        let n = ea[k / 3].cross(eb[k % 3]);
        let len = n.length();
        (len > 1e-6).then(|| n / len)
    });
    fa.into_iter()
        .chain(fb)
        .filter(|n| *n != Vec3::ZERO)
        .chain(crossed)
        .any(|n| gap(n) > tol)
}

/// The Euclidean distance from `p` to the box of centre `c`, unit edge directions `axes` (a
/// rotation's columns) and half sizes `half` (0 inside it): in the box's own frame, the length of
/// how far each coordinate lies beyond the box's half size.
pub fn distance_to_box(p: Point3, c: Point3, axes: DMat3, half: Vec3) -> f64 {
    let local = axes.transpose() * (p - c);
    (local.abs() - half).max(Vec3::ZERO).length()
}

/// The distance from `p` to the segment from `a` to `b`.
pub fn segment_distance(p: Point3, a: Point3, b: Point3) -> f64 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let t = if len2 > 0.0 && len2.is_finite() {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p - (a + ab * t)).length()
}

/// The distance from `p` to the parallelogram of corners `q`, `q + u`, `q + v`, `q + u + v`: to
/// the point of its plane below `p` where that lies inside it (its coordinates `(alpha, beta)` in
/// `u`, `v` from the normal equations), else to the nearest of its four sides.
pub fn parallelogram_distance(p: Point3, q: Point3, u: Vec3, v: Vec3) -> f64 {
    let w = p - q;
    let (uu, uv, vv) = (u.dot(u), u.dot(v), v.dot(v));
    let (wu, wv) = (w.dot(u), w.dot(v));
    let det = uu * vv - uv * uv;
    let (alpha, beta) = ((wu * vv - wv * uv) / det, (wv * uu - wu * uv) / det);
    if (0.0..=1.0).contains(&alpha) && (0.0..=1.0).contains(&beta) {
        return (w - u * alpha - v * beta).length();
    }
    let (a, b, c) = (q + u, q + u + v, q + v);
    segment_distance(p, q, a)
        .min(segment_distance(p, a, b))
        .min(segment_distance(p, b, c))
        .min(segment_distance(p, c, q))
}

/// The least value over `t` in [0, 1] of `f(a + t (b - a))`, for `f` convex (a distance to a convex
/// set, which is convex along any line): a golden-section search, whose 80 steps narrow the
/// segment by 0.618^80 = 2e-17, and the two ends.
pub fn least_along(a: Point3, b: Point3, f: impl Fn(Point3) -> f64) -> f64 {
    let at = |t: f64| f(a + (b - a) * t);
    let g = (5f64.sqrt() - 1.0) / 2.0;
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..80 {
        let (x, y) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if at(x) <= at(y) {
            hi = y;
        } else {
            lo = x;
        }
    }
    at(0.5 * (lo + hi)).min(at(0.0)).min(at(1.0))
}

/// Directions for [`inside`]'s rays, none along an axis or a diagonal of one.
const RAYS: [Vec3; 3] = [
    Vec3::new(0.524_437_4, 0.612_092_1, 0.591_818_2),
    Vec3::new(-0.715_307_9, 0.301_612_4, 0.630_349_2),
    Vec3::new(0.208_514_3, -0.806_270_5, 0.553_521_7),
];

/// Whether `p` lies inside the closed surface of the parallelograms `(q, u, v)`: whether a ray from
/// it crosses them an odd number of times. A ray that passes within `margin` (of the coordinates'
/// unit) of a parallelogram's side, or along its plane, is not counted on: another direction is
/// tried. `None` if every direction was such (or the surface is empty).
pub fn inside(p: Point3, quads: &[(Point3, Vec3, Vec3)], margin: f64) -> Option<bool> {
    if quads.is_empty() {
        return None;
    }
    'rays: for d in RAYS {
        let d = d.normalize();
        let mut crossings = 0u64;
        for &(q, u, v) in quads {
            let n = u.cross(v);
            let (num, den) = ((q - p).dot(n), d.dot(n));
            if den.abs() <= 1e-12 * n.length() {
                if num.abs() <= margin * n.length() {
                    continue 'rays; // (along its plane)
                }
                continue;
            }
            let t = num / den;
            if t <= 0.0 {
                continue;
            }
            let w = p + d * t - q;
            let (uu, uv, vv) = (u.dot(u), u.dot(v), v.dot(v));
            let (wu, wv) = (w.dot(u), w.dot(v));
            let det = uu * vv - uv * uv;
            let (alpha, beta) = ((wu * vv - wv * uv) / det, (wv * uu - wu * uv) / det);
            // the margin in each coordinate: `margin` over the side's length across it
            let (ea, eb) = (
                margin / u.length().max(1e-300),
                margin / v.length().max(1e-300),
            );
            let near = |x: f64, e: f64| x.abs() <= e || (x - 1.0).abs() <= e;
            let within = |x: f64, e: f64| x > -e && x < 1.0 + e;
            if within(alpha, ea) && within(beta, eb) {
                if near(alpha, ea) || near(beta, eb) {
                    continue 'rays; // (through a side)
                }
                crossings += 1;
            }
        }
        return Some(crossings % 2 == 1);
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_and_a_parallelogram() {
        let (q, u, v) = (Point3::ZERO, Vec3::X * 2.0, Vec3::new(1.0, 1.0, 0.0));
        // above its inside, beside a side, beyond a corner
        assert!((parallelogram_distance(Point3::new(1.5, 0.5, 3.0), q, u, v) - 3.0).abs() < 1e-15);
        assert!((parallelogram_distance(Point3::new(1.0, -2.0, 0.0), q, u, v) - 2.0).abs() < 1e-15);
        let corner = parallelogram_distance(Point3::new(4.0, 1.0, 0.0), q, u, v);
        assert!((corner - 1.0).abs() < 1e-15, "{corner}");
    }

    /// The unit cube's six faces as parallelograms; points inside and out, one on the ray's
    /// way through an edge (another direction is taken).
    #[test]
    fn inside_a_cube_of_parallelograms() {
        let (x, y, z) = (Vec3::X, Vec3::Y, Vec3::Z);
        let o = Point3::ZERO;
        let cube = [
            (o, y, x),
            (z, x, y),
            (o, x, z),
            (y, z, x),
            (o, z, y),
            (x, y, z),
        ];
        assert_eq!(inside(Point3::splat(0.5), &cube, 1e-9), Some(true));
        assert_eq!(inside(Point3::splat(1.5), &cube, 1e-9), Some(false));
        assert_eq!(
            inside(Point3::new(0.5, 0.5, -0.1), &cube, 1e-9),
            Some(false)
        );
        // a point from which the first direction's ray passes through the edge x = 1, z = 1
        let d = RAYS[0].normalize();
        let p = Point3::new(1.0, 0.6, 1.0) - d * 0.5;
        assert!(p.x > 0.0 && p.x < 1.0 && p.z > 0.0 && p.z < 1.0 && p.y > 0.0 && p.y < 1.0);
        assert_eq!(inside(p, &cube, 1e-9), Some(true));
        assert_eq!(inside(p, &[], 1e-9), None);
    }

    #[test]
    fn parallelograms_apart_by_a_side_s_normal_in_their_plane() {
        // two squares in one plane, 0.01 apart along a diagonal direction: only an in-plane normal
        // of a side separates them
        let a = Solid::Flat {
            q: Point3::ZERO,
            u: Vec3::X,
            v: Vec3::Y,
        };
        let b = |gap: f64| Solid::Flat {
            q: Point3::new(1.0 + gap, 0.5, 0.0),
            u: Vec3::X,
            v: Vec3::Y,
        };
        assert!(solids_apart(&a, &b(0.01), 1e-9));
        assert!(!solids_apart(&a, &b(0.0), 1e-9));
        assert!(!solids_apart(&a, &b(-0.01), 1e-9));
        // a square across another's middle, and one above it
        let across = Solid::Flat {
            q: Point3::new(0.5, -1.0, -1.0),
            u: Vec3::Y * 3.0,
            v: Vec3::Z * 2.0,
        };
        assert!(!solids_apart(&a, &across, 1e-9));
        let above = Solid::Flat {
            q: Point3::new(0.5, -1.0, 0.01),
            u: Vec3::Y * 3.0,
            v: Vec3::Z * 2.0,
        };
        assert!(solids_apart(&a, &above, 1e-9));
    }
}
