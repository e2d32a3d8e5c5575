//! Whether quads close a surface, as a medium's boundary must: every edge of each quad an edge of
//! exactly one other, corners equal to within a rounding error ([`CLOSE`]), no two quads at one
//! place. [`SceneBuilder::open_quad`](crate::builder::SceneBuilder::open_quad) gathers a boundary's quads where its
//! instances put them (boxes and groups that close by themselves left out) and asks `first_open`.

use crate::ids::GroupId;
use crate::shapes::Quad;
use crate::transform::Transform;
use crate::vec::Point3;
use std::collections::HashMap;

/// How close two quads' corners must be to be the same corner of a closed surface
/// ([`SceneBuilder::open_quad`](crate::builder::SceneBuilder::open_quad)): this fraction of the largest coordinate, edge or translation of
/// either quad. Rounding (0.1 + 0.7 is not 0.8; a rotation by 15 degrees) moves a corner by a few
/// parts in 1e16; corners written a part in 1e9 apart are apart.
pub const CLOSE: f64 = 1e-9;

/// A quad that keeps a medium's boundary from enclosing a volume ([`SceneBuilder::open_quad`](crate::builder::SceneBuilder::open_quad)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OpenQuad {
    /// The group holding it, and its index among that group's objects ([`SceneBuilder::objects`](crate::builder::SceneBuilder::objects)).
    pub group: GroupId,
    pub index: usize,
    pub problem: OpenSurface,
}

/// Why a quad keeps a surface from closing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum OpenSurface {
    /// Its edge from `from` to `to` (in the coordinates of the group looked at) is an edge of
    /// `others` other quads, not of exactly one: the surface is open there (0), or more than two
    /// quads meet there.
    Edge {
        from: Point3,
        to: Point3,
        others: usize,
    },
    /// It lies where another quad does: the two enclose no volume.
    Coincident,
    /// Two of its own corners are one corner (within [`CLOSE`]): it is a sliver that encloses
    /// nothing, and its edges, paired with each other, would pass for shared.
    Sliver,
}

/// A quad placed in the space of the group looked at ([`SceneBuilder::open_quad`](crate::builder::SceneBuilder::open_quad)).
pub(crate) struct LooseQuad {
    /// `q`, `q + u`, `q + v`, `q + u + v`.
    corners: [Point3; 4],
    /// The largest coordinate of its corners, edges and translation, before and after placing.
    scale: f64,
    pub(crate) group: GroupId,
    pub(crate) index: usize,
}

impl LooseQuad {
    pub(crate) fn new(q: &Quad, to: Transform, group: GroupId, index: usize) -> Self {
        let local = [q.q, q.q + q.u, q.q + q.v, q.q + q.u + q.v];
        let corners = local.map(|c| to.point(c));
        let scale = local
            .iter()
            .chain(&corners)
            .chain(&[q.u, q.v, to.translation])
            .map(|p| p.abs().max_element())
            .fold(0.0, f64::max);
        LooseQuad {
            corners,
            scale,
            group,
            index,
        }
    }
}

/// The first of `quads` (and why) whose edges are not each an edge of exactly one other quad, or
/// that lies where another does; `None` if they close a surface.
pub(crate) fn first_open(quads: &[LooseQuad]) -> Option<(usize, OpenSurface)> {
    // Corners within CLOSE of each other are one vertex, found among the vertices already kept in a
    // grid of cells 16 times the largest such distance (`reach`): in a corner's own cell, and in a
    // neighbouring one only if the corner lies within twice `reach` of the side they share (twice:
    // its place in the cell is rounded).
    let corner = |i: usize| quads[i / 4].corners[i % 4];
    let largest = quads.iter().map(|q| q.scale).fold(0.0, f64::max);
    let reach = CLOSE * largest;
    let cell = (16.0 * reach).max(f64::MIN_POSITIVE);
    let n = 4 * quads.len();
    let mut vertex: Vec<usize> = (0..n).collect();
    // per cell the last vertex kept in it, and per vertex the one kept there before it
    let mut grid: HashMap<[i64; 3], usize> = HashMap::new();
    let mut before: Vec<usize> = vec![usize::MAX; n];
    for i in 0..n {
        let p = corner(i);
        let at = p / cell;
        let k = at.floor().as_i64vec3().to_array();
        // per axis, the neighbouring cells the corner is near (-1, 0 or 1 besides its own)
        let side = |a: usize| {
            let f = (at[a] - at[a].floor()) * cell;
            if f < 2.0 * reach {
                -1
            } else if cell - f < 2.0 * reach {
                1
            } else {
                0
            }
        };
        let sides = [side(0), side(1), side(2)];
        let steps = |a: usize| {
            if sides[a] == 0 {
                0..=0
            } else {
                sides[a].min(0)..=sides[a].max(0)
            }
        };
        let mut found = None;
        'cells: for dx in steps(0) {
            for dy in steps(1) {
                for dz in steps(2) {
                    let near = [
                        k[0].saturating_add(dx),
                        k[1].saturating_add(dy),
                        k[2].saturating_add(dz),
                    ];
                    let mut j = grid.get(&near).copied().unwrap_or(usize::MAX);
                    while j != usize::MAX {
                        let tol = CLOSE * quads[i / 4].scale.max(quads[j / 4].scale);
                        if (p - corner(j)).abs().max_element() <= tol {
                            found = Some(j);
                            break 'cells;
                        }
                        j = before[j];
                    }
                }
            }
        }
        match found {
            Some(j) => vertex[i] = j,
            None => before[i] = grid.insert(k, i).unwrap_or(usize::MAX),
        }
    }
    const EDGES: [(usize, usize); 4] = [(0, 1), (1, 3), (3, 2), (2, 0)];
    let edge = |q: usize, (a, b): (usize, usize)| {
        let (a, b) = (vertex[4 * q + a], vertex[4 * q + b]);
        (a.min(b), a.max(b))
    };
    let mut edges: HashMap<(usize, usize), usize> = HashMap::new();
    let mut places: HashMap<[usize; 4], usize> = HashMap::new();
    for q in 0..quads.len() {
        for e in EDGES {
            *edges.entry(edge(q, e)).or_default() += 1;
        }
    }
    for (q, quad) in quads.iter().enumerate() {
        let mut place: [usize; 4] = std::array::from_fn(|c| vertex[4 * q + c]);
        place.sort_unstable();
        if place.windows(2).any(|w| w[0] == w[1]) {
            return Some((q, OpenSurface::Sliver));
        }
        for e in EDGES {
            let others = edges[&edge(q, e)] - 1;
            if others != 1 {
                let (from, to) = (quad.corners[e.0], quad.corners[e.1]);
                return Some((q, OpenSurface::Edge { from, to, others }));
            }
        }
        if *places.entry(place).or_insert(q) != q {
            return Some((q, OpenSurface::Coincident));
        }
    }
    None
}
