//! Whether quads close a surface, as a medium's boundary must: every edge of each quad an edge of
//! exactly one other, corners equal to within a rounding error ([`CLOSE`]), no two quads at one
//! place. An edge may also be shared stretch by stretch with several quads whose corners lie along
//! it (T-junctions: a face split in two beside a whole one), each stretch with exactly one.
//! [`SceneBuilder::open_quad`](crate::builder::SceneBuilder::open_quad) gathers a boundary's
//! quads where its instances put them (boxes and groups that close by themselves left out) and asks
//! `first_open`.

use crate::aabb::Aabb;
use crate::ids::GroupId;
use crate::shapes::Quad;
use crate::transform::Transform;
use crate::vec::Point3;
use std::collections::HashMap;

/// How close two quads' corners must be to be the same corner of a closed surface
/// ([`SceneBuilder::open_quad`](crate::builder::SceneBuilder::open_quad)): this fraction of the
/// largest coordinate, edge or translation of either quad. Rounding (0.1 + 0.7 is not 0.8; a
/// rotation by 15 degrees) moves a corner by a few parts in 1e16; corners written a part in 1e9
/// apart are apart.
pub const CLOSE: f64 = 1e-9;

/// A quad that keeps a medium's boundary from enclosing a volume
/// ([`SceneBuilder::open_quad`](crate::builder::SceneBuilder::open_quad)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OpenQuad {
    /// The group holding it, and its index among that group's objects
    /// ([`SceneBuilder::objects`](crate::builder::SceneBuilder::objects)).
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
    /// Its edge (or the stretch of it) from `from` to `to` is an edge of no other quad, and runs
    /// along part of an edge of the quad `other` (its group and index), yet the edges along that
    /// line do not pair up stretch by stretch: the surface is open there or overlaps itself. (Edges
    /// that meet at T-junctions, a face split in two beside a whole one, do pair up.)
    Junction {
        from: Point3,
        to: Point3,
        other: (GroupId, usize),
    },
    /// It lies where another quad does: the two enclose no volume.
    Coincident,
    /// Two of its own corners are one corner (within [`CLOSE`]): it is a sliver that encloses
    /// nothing, and its edges, paired with each other, would pass for shared.
    Sliver,
    /// The check gave up at this quad: its corner was the one that took the search for shared
    /// corners past [`MAX_LOOKUPS`] (quads of `levels` different scales, each corner looked for in
    /// every level at and above its own). Not known to be open; refused because it could not be
    /// shown closed in reasonable time.
    Unchecked { levels: usize },
    /// The check gave up at this quad: looking whether `edges` edges that are edges of no other
    /// quad run along each other's (T-junctions) took more than [`MAX_LOOKUPS`] comparisons. Not
    /// known to be open; refused because it could not be shown closed in reasonable time.
    UncheckedJunctions { edges: usize },
}

/// The most looks at a level's grid ([`OpenSurface::Unchecked`] beyond): a boundary of 2^20 quads
/// whose scales span four powers of two takes at most 2^24. Only a boundary made to span hundreds of
/// scales with a million quads comes near, where the search would take minutes.
pub const MAX_LOOKUPS: usize = 1 << 26;

/// A quad placed in the space of the group looked at
/// ([`SceneBuilder::open_quad`](crate::builder::SceneBuilder::open_quad)).
#[derive(Clone)]
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

    /// Its placed corner `q` and edges `u`, `v` (the corners `q + u` and `q + v` less `q`).
    pub(crate) fn parallelogram(&self) -> crate::boundary_pieces::Parallelogram {
        let [q, a, b, _] = self.corners;
        (q, a - q, b - q)
    }

    /// The box of its placed corners (unpadded).
    pub(crate) fn bounds(&self) -> Aabb {
        self.corners.iter().fold(Aabb::EMPTY, |b, &c| b.include(c))
    }
}

/// The first of `quads` (and why) whose edges are not each an edge of exactly one other quad, or
/// that lies where another does; `None` if they close a surface.
pub(crate) fn first_open(quads: &[LooseQuad]) -> Option<(usize, OpenSurface)> {
    first_open_counted(quads, MAX_LOOKUPS).0
}

/// The power of two `2^e` at or above a quad's `scale`, by `e` (`i32::MIN` for 0, `i32::MAX` for a
/// scale that is not a finite number).
fn level(scale: f64) -> i32 {
    if !scale.is_finite() {
        return i32::MAX;
    }
    if scale <= 0.0 {
        return i32::MIN;
    }
    let mut e = scale.log2().ceil() as i32;
    while level_size(e) < scale {
        e += 1;
    }
    e
}

/// `2^e` for a [`level`] `e`.
fn level_size(e: i32) -> f64 {
    match e {
        i32::MIN => 0.0,
        i32::MAX => f64::INFINITY,
        e => (e as f64).exp2(),
    }
}

/// [`first_open`] giving up after `max_lookups` looks at a level's grid, and how many pairs of
/// corners it compared (the tests hold that to the number of corners, not its square).
pub(crate) fn first_open_counted(
    quads: &[LooseQuad],
    max_lookups: usize,
) -> (Option<(usize, OpenSurface)>, usize) {
    let (open, compared, _, _) = surface(quads, max_lookups);
    (open, compared)
}

/// For quads that close a surface, which closed surface each is part of: the same number for two
/// quads joined by a chain of shared edges (numbered from 0 in order of first appearance); `None`
/// if they do not close a surface ([`first_open`]).
pub(crate) fn closed_components(quads: &[LooseQuad]) -> Option<Vec<usize>> {
    let (open, _, vertex, split) = surface(quads, MAX_LOOKUPS);
    if open.is_some() {
        return None;
    }
    // union-find over the quads, joined at each edge they share
    let mut parent: Vec<usize> = (0..quads.len()).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    let mut first_at: HashMap<(usize, usize), usize> = HashMap::new();
    for q in 0..quads.len() {
        for (k, (a, b)) in EDGES.into_iter().enumerate() {
            let whole = [vertex[4 * q + a], vertex[4 * q + b]];
            let path = split.get(&(q, k)).map_or(&whole[..], |p| &p[..]);
            for w in path.windows(2) {
                let other = *first_at.entry(pair(w[0], w[1])).or_insert(q);
                let (r, s) = (root(&mut parent, q), root(&mut parent, other));
                parent[r] = s;
            }
        }
    }
    let mut number: HashMap<usize, usize> = HashMap::new();
    Some(
        (0..quads.len())
            .map(|q| {
                let r = root(&mut parent, q);
                let next = number.len();
                *number.entry(r).or_insert(next)
            })
            .collect(),
    )
}

/// The corners at the same edge of a quad, by their index among its four.
const EDGES: [(usize, usize); 4] = [(0, 1), (1, 3), (3, 2), (2, 0)];

/// The key of the edge between vertices `a` and `b`, either way round.
fn pair(a: usize, b: usize) -> (usize, usize) {
    (a.min(b), a.max(b))
}

/// The key of quad `q`'s edge between its corners `(a, b)` (by their index among its four).
fn edge_of(vertex: &[usize], q: usize, (a, b): (usize, usize)) -> (usize, usize) {
    pair(vertex[4 * q + a], vertex[4 * q + b])
}

/// The edges split at T-junctions: `(quad, edge)` to the vertices along it, its ends included.
type Splits = HashMap<(usize, usize), Vec<usize>>;

/// [`first_open_counted`], each corner's vertex (the first corner found at its place), and the
/// edges split at T-junctions.
fn surface(
    quads: &[LooseQuad],
    max_lookups: usize,
) -> (Option<(usize, OpenSurface)>, usize, Vec<usize>, Splits) {
    // Corners within CLOSE of each other (of the larger scale of their two quads) are one vertex.
    // Quads are taken by their scale's level (the power of two at or above it), largest first; a
    // corner is looked for among the vertices already kept, which are all of its level or a larger
    // one. Each level has a grid of cells 16 times the largest distance two corners of that level
    // may be apart and still be one (`reach`, CLOSE times the level's power of two), and a corner
    // looks in each level's grid at and above its own: in its own cell, and in a neighbouring one
    // only if it lies within twice `reach` of the side they share (twice: its place in the cell is
    // rounded). One grid for all (cells sized by the largest quad) put every corner of many small
    // quads into one cell beside a large one, and compared each with all before it.
    let corner = |i: usize| quads[i / 4].corners[i % 4];
    let levels: Vec<i32> = quads.iter().map(|q| level(q.scale)).collect();
    let mut order: Vec<usize> = (0..quads.len()).collect();
    order.sort_by_key(|&q| std::cmp::Reverse(levels[q]));
    let mut present: Vec<i32> = levels.clone();
    present.sort_unstable_by_key(|&l| std::cmp::Reverse(l));
    present.dedup();
    let n = 4 * quads.len();
    let mut vertex: Vec<usize> = (0..n).collect();
    // per level and cell the last vertex kept in it, and per vertex the one kept there before it
    let mut grid: HashMap<(i32, [i64; 3]), usize> = HashMap::new();
    let mut before: Vec<usize> = vec![usize::MAX; n];
    let mut compared = 0;
    let mut looked = 0;
    // a level's `reach`, and a corner's place in that level's grid: its cell, and where in it
    let place_in = |l: i32, p: Point3| {
        let reach = CLOSE * level_size(l);
        let cell = (16.0 * reach).max(f64::MIN_POSITIVE);
        let at = p / cell;
        (reach, cell, at, at.floor().as_i64vec3().to_array())
    };
    for i in order.iter().flat_map(|&q| 4 * q..4 * q + 4) {
        let p = corner(i);
        let own = levels[i / 4];
        let mut found = None;
        'levels: for &l in present.iter().take_while(|&&l| l >= own) {
            looked += 1;
            if looked > max_lookups {
                let levels = present.len();
                return (
                    Some((i / 4, OpenSurface::Unchecked { levels })),
                    compared,
                    vertex,
                    HashMap::new(),
                );
            }
            let (reach, cell, at, k) = place_in(l, p);
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
            for dx in steps(0) {
                for dy in steps(1) {
                    for dz in steps(2) {
                        let near = [
                            k[0].saturating_add(dx),
                            k[1].saturating_add(dy),
                            k[2].saturating_add(dz),
                        ];
                        let mut j = grid.get(&(l, near)).copied().unwrap_or(usize::MAX);
                        while j != usize::MAX {
                            compared += 1;
                            let tol = CLOSE * quads[i / 4].scale.max(quads[j / 4].scale);
                            if (p - corner(j)).abs().max_element() <= tol {
                                found = Some(j);
                                break 'levels;
                            }
                            j = before[j];
                        }
                    }
                }
            }
        }
        match found {
            Some(j) => vertex[i] = j,
            None => {
                let key = (own, place_in(own, p).3);
                before[i] = grid.insert(key, i).unwrap_or(usize::MAX);
            }
        }
    }
    let mut edges: HashMap<(usize, usize), usize> = HashMap::new();
    let mut places: HashMap<[usize; 4], usize> = HashMap::new();
    for q in 0..quads.len() {
        for e in EDGES {
            *edges.entry(edge_of(&vertex, q, e)).or_default() += 1;
        }
    }
    let budget = max_lookups.saturating_sub(looked);
    let split = match split_at_junctions(quads, &vertex, &mut edges, budget) {
        Ok(split) => split,
        Err(open) => return (Some(open), compared, vertex, HashMap::new()),
    };
    for (q, quad) in quads.iter().enumerate() {
        let mut place: [usize; 4] = std::array::from_fn(|c| vertex[4 * q + c]);
        place.sort_unstable();
        if place.windows(2).any(|w| w[0] == w[1]) {
            return (Some((q, OpenSurface::Sliver)), compared, vertex, split);
        }
        for (k, e) in EDGES.into_iter().enumerate() {
            let whole = [vertex[4 * q + e.0], vertex[4 * q + e.1]];
            let path = split.get(&(q, k)).map_or(&whole[..], |p| &p[..]);
            // the ends of piece `i` of the edge: the quad's own corners at the edge's ends
            let end = |i: usize| match i {
                0 => quad.corners[e.0],
                i if i + 1 == path.len() => quad.corners[e.1],
                i => corner(path[i]),
            };
            for (i, w) in path.windows(2).enumerate() {
                let others = edges[&pair(w[0], w[1])] - 1;
                if others != 1 {
                    let (from, to) = (end(i), end(i + 1));
                    let problem = match (others, along(quads, q, from, to)) {
                        (0, Some(r)) => OpenSurface::Junction {
                            from,
                            to,
                            other: (quads[r].group, quads[r].index),
                        },
                        _ => OpenSurface::Edge { from, to, others },
                    };
                    return (Some((q, problem)), compared, vertex, split);
                }
            }
        }
        if *places.entry(place).or_insert(q) != q {
            return (Some((q, OpenSurface::Coincident)), compared, vertex, split);
        }
    }
    (None, compared, vertex, split)
}

/// The edges of no other quad (counted in `edges`) split at T-junctions: such an edge may run
/// along the edges of several quads (a face split in two beside a whole one), so it is split at the
/// ends of the other lone edges that lie on it (within [`CLOSE`] of it, of its quad's scale), and
/// its pieces are counted in `edges` in its place; each must then be an edge of exactly one other
/// quad, as a whole edge must. The ends are kept sorted along each axis, and an edge looks through
/// those within its reach along the axis it spans least (an edge along x, those of nearly its y).
///
/// Returns each edge split, `(quad, edge)` to the vertices along it (its ends included), or the
/// quad at which the search gave up after `budget` looks.
fn split_at_junctions(
    quads: &[LooseQuad],
    vertex: &[usize],
    edges: &mut HashMap<(usize, usize), usize>,
    budget: usize,
) -> Result<Splits, (usize, OpenSurface)> {
    let corner = |i: usize| quads[i / 4].corners[i % 4];
    let lone: Vec<(usize, usize)> = (0..quads.len())
        .flat_map(|q| (0..4).map(move |k| (q, k)))
        .filter(|&(q, k)| edges[&edge_of(vertex, q, EDGES[k])] == 1)
        .collect();
    let mut ends: Vec<usize> = lone
        .iter()
        .flat_map(|&(q, k)| [vertex[4 * q + EDGES[k].0], vertex[4 * q + EDGES[k].1]])
        .collect();
    ends.sort_unstable();
    ends.dedup();
    let by_axis: [Vec<(f64, usize)>; 3] = std::array::from_fn(|axis| {
        let mut sorted: Vec<(f64, usize)> = ends.iter().map(|&v| (corner(v)[axis], v)).collect();
        sorted.sort_by(|x, y| x.0.total_cmp(&y.0));
        sorted
    });
    let mut split: Splits = HashMap::new();
    let mut looked = 0;
    for &(q, k) in &lone {
        let (va, vb) = (vertex[4 * q + EDGES[k].0], vertex[4 * q + EDGES[k].1]);
        let (a, b) = (corner(va), corner(vb));
        let len = (b - a).length();
        if !(len > 0.0 && len.is_finite()) {
            continue;
        }
        let dir = (b - a) / len;
        let tol = CLOSE * quads[q].scale;
        let axis = (b - a).abs().min_position();
        let (lo, hi) = (a[axis].min(b[axis]) - tol, a[axis].max(b[axis]) + tol);
        let sorted = &by_axis[axis];
        let first = sorted.partition_point(|&(x, _)| x < lo);
        let mut on: Vec<(f64, usize)> = Vec::new();
        for &(x, v) in &sorted[first..] {
            if x > hi {
                break;
            }
            looked += 1;
            if looked > budget {
                let edges = lone.len();
                return Err((q, OpenSurface::UncheckedJunctions { edges }));
            }
            let p = corner(v) - a;
            let t = p.dot(dir);
            if v != va && v != vb && t > tol && t < len - tol && (p - dir * t).length() <= tol {
                on.push((t, v));
            }
        }
        if on.is_empty() {
            continue;
        }
        on.sort_by(|x, y| x.0.total_cmp(&y.0));
        let path: Vec<usize> = std::iter::once(va)
            .chain(on.iter().map(|&(_, v)| v))
            .chain(std::iter::once(vb))
            .collect();
        *edges.entry(pair(va, vb)).or_default() -= 1;
        for w in path.windows(2) {
            *edges.entry(pair(w[0], w[1])).or_default() += 1;
        }
        split.insert((q, k), path);
    }
    Ok(split)
}

/// A quad other than `q` with an edge along part of the segment from `from` to `to` (both its
/// ends within [`CLOSE`] of the segment's line, overlapping it by more than that): where an open
/// edge is a mismatch along a line rather than a gap. Looked for once, when a boundary is refused.
fn along(quads: &[LooseQuad], q: usize, from: Point3, to: Point3) -> Option<usize> {
    let d = to - from;
    let len = d.length();
    if !(len > 0.0 && len.is_finite()) {
        return None;
    }
    let dir = d / len;
    (0..quads.len()).filter(|&r| r != q).find(|&r| {
        let tol = CLOSE * quads[q].scale.max(quads[r].scale);
        let c = &quads[r].corners;
        EDGES.iter().any(|&(a, b)| {
            let (pa, pb) = (c[a] - from, c[b] - from);
            let (ta, tb) = (pa.dot(dir), pb.dot(dir));
            let off = |p: Point3, t: f64| (p - dir * t).length();
            off(pa, ta) <= tol
                && off(pb, tb) <= tol
                && ta.max(tb).min(len) - ta.min(tb).max(0.0) > tol
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ids::MaterialId;
    use crate::vec::Vec3;

    fn loose(q: Point3, u: Vec3, v: Vec3, index: usize) -> LooseQuad {
        let quad = Quad::new(q, u, v, MaterialId(0)).unwrap();
        LooseQuad::new(&quad, Transform::IDENTITY, GroupId(0), index)
    }

    /// A large quad and many small ones near the origin: the small quads' corners are all in one
    /// cell of a grid sized by the large quad, and each was compared with every corner kept before
    /// it (4,096 small quads: 134 million comparisons; at the scene's limit of 2^20 quads, hours).
    /// Taken level by level, each corner meets a handful. The verdict is the same.
    #[test]
    fn small_quads_beside_a_large_one_are_not_compared_with_each_other() {
        let mut quads = vec![loose(Point3::new(1e6, 0.0, 0.0), Vec3::X, Vec3::Y, 0)];
        for k in 0..4096 {
            let q = Point3::new((k % 64) as f64 * 2e-7, (k / 64) as f64 * 2e-7, 0.0);
            quads.push(loose(q, Vec3::X * 1e-7, Vec3::Y * 1e-7, k + 1));
        }
        let (open, compared) = first_open_counted(&quads, MAX_LOOKUPS);
        assert!(
            matches!(open, Some((0, OpenSurface::Edge { others: 0, .. }))),
            "{open:?}"
        );
        assert!(compared <= 8 * 4 * quads.len(), "{compared} comparisons");
    }

    /// Quads of many scales, each with a corner in the origin's cell of its level's grid (but not
    /// within its tolerance of the origin), and many small quads at the origin: each small corner
    /// is looked for in every level above its own. Past [`MAX_LOOKUPS`] the check
    /// gives up, naming the quad it had reached, instead of taking minutes.
    #[test]
    fn a_search_past_its_budget_gives_up() {
        let (x, y) = (Vec3::X, Vec3::Y);
        // (sizes whose squared area a double holds: 2^0 to 2^249, and 1e-70)
        let mut quads: Vec<LooseQuad> = (0..250)
            .map(|k| {
                let size = 2f64.powi(k);
                // (a corner in the origin's cell of its level, but three tolerances from it)
                let q = Point3::new(3.0 * CLOSE * size, 0.0, 0.0);
                loose(q, x * size, y * size, k as usize)
            })
            .collect();
        // (the budget of the test: MAX_LOOKUPS would take seconds)
        let budget = 1 << 18;
        let small = budget / (4 * 250) + 1;
        for k in 0..small {
            let q = Point3::new(k as f64 * 2e-70, 0.0, 0.0);
            quads.push(loose(q, x * 1e-70, y * 1e-70, 250 + k));
        }
        let (open, compared) = first_open_counted(&quads, budget);
        let Some((q, OpenSurface::Unchecked { levels })) = open else {
            panic!("{open:?} after {compared} comparisons");
        };
        assert!(q >= 250 && levels > 250, "{q} {levels}");
        // With the boundary's budget the search ends with a verdict on the same quads: the small
        // budget alone made it give up.
        let (open, _) = first_open_counted(&quads, MAX_LOOKUPS);
        assert!(
            !matches!(open, Some((_, OpenSurface::Unchecked { .. }))),
            "{open:?}"
        );
    }

    /// Levels do not part corners that are one: a box whose faces have scales a level apart (a
    /// corner at 1, one at 1 + 2^-40) closes, corners that meet across levels found from below.
    /// The unit cube at `o` turned by `to`, its face at z = 1 in two halves (cut at x = `cut`) and
    /// its bottom cut at x = 0.4: nine quads with T-junctions along four of its edges.
    fn split_cube(o: Point3, cut: f64, to: Transform, index: usize) -> Vec<LooseQuad> {
        let (x, y, z) = (Vec3::X, Vec3::Y, Vec3::Z);
        let faces = [
            (Point3::new(0.0, 0.0, 1.0), cut * x, y),
            (Point3::new(cut, 0.0, 1.0), (1.0 - cut) * x, y),
            (Point3::new(1.0, 0.0, 1.0), -z, y),
            (Point3::new(1.0, 0.0, 0.0), -x, y),
            (Point3::ZERO, z, y),
            (Point3::new(0.0, 1.0, 1.0), x, -z),
            (Point3::ZERO, 0.4 * x, z),
            (Point3::new(0.4, 0.0, 0.0), 0.6 * x, z),
        ];
        faces
            .iter()
            .enumerate()
            .map(|(k, &(q, u, v))| {
                let quad = Quad::new(o + q, u, v, MaterialId(0)).unwrap();
                LooseQuad::new(&quad, to, GroupId(0), index + k)
            })
            .collect()
    }

    #[test]
    fn faces_split_beside_whole_ones_close_stretch_by_stretch() {
        let turn = Transform::rotate_y(15.0).then(Transform::translate(Vec3::new(0.1, 0.7, 3.0)));
        for to in [Transform::IDENTITY, turn] {
            for cut in [0.5, 0.4, 1.0 / 3.0] {
                let one = split_cube(Point3::ZERO, cut, to, 0);
                assert_eq!(first_open(&one), None, "cut at {cut}");
                // two of them apart are two closed surfaces
                let mut two = one.clone();
                two.extend(split_cube(Point3::new(3.0, 0.0, 0.0), cut, to, 8));
                let c = closed_components(&two).expect("closed");
                assert!(c[..8].iter().all(|&k| k == c[0]) && c[8..].iter().all(|&k| k == c[8]));
                assert_ne!(c[0], c[8]);
                // without the first half, open along the stretch it covered
                let open = first_open(&one[1..]);
                assert!(
                    matches!(open, Some((_, OpenSurface::Edge { others: 0, .. }))),
                    "{open:?}"
                );
            }
        }
    }

    /// Many lone edges along one line (a row of quads apart, each with edges on the line y = 0):
    /// looking for the corners along each edge stops at the budget, with its own reason.
    #[test]
    fn a_search_for_junctions_past_its_budget_gives_up() {
        let quads: Vec<LooseQuad> = (0..2000)
            .map(|k| {
                loose(
                    Point3::new(k as f64 * 0.25, 0.0, 0.0),
                    Vec3::X * 0.5,
                    Vec3::Z,
                    k,
                )
            })
            .collect();
        let (open, _) = first_open_counted(&quads, 1 << 16);
        assert!(
            matches!(open, Some((_, OpenSurface::UncheckedJunctions { .. }))),
            "{open:?}"
        );
    }

    #[test]
    fn corners_of_quads_of_different_levels_meet() {
        let d = 1.0 + 2f64.powi(-40);
        let (x, y, z) = (Vec3::X, Vec3::Y, Vec3::Z);
        let o = Point3::ZERO;
        let quads = [
            loose(o, x, y, 0),
            loose(o + z, x, y, 1),
            loose(o, y, z, 2),
            loose(o + x * d, y, z, 3),
            loose(o, x, z, 4),
            loose(o + y, x, z, 5),
        ];
        // (the face at x = d has scale d + 1 > 2: a level above the others)
        assert!(level(quads[3].scale) > level(quads[0].scale));
        assert_eq!(first_open(&quads), None);
    }

    /// Two boxes of six quads apart are two closed surfaces, numbered in order; one box is one;
    /// quads that leave a gap are none.
    #[test]
    fn closed_surfaces_are_told_apart_by_shared_edges() {
        let (x, y, z) = (Vec3::X, Vec3::Y, Vec3::Z);
        let cube = |o: Point3, k: usize| {
            [
                loose(o, x, y, k),
                loose(o + z, x, y, k + 1),
                loose(o, y, z, k + 2),
                loose(o + x, y, z, k + 3),
                loose(o, x, z, k + 4),
                loose(o + y, x, z, k + 5),
            ]
        };
        let one = cube(Point3::ZERO, 0);
        assert_eq!(closed_components(&one), Some(vec![0; 6]));
        let two: Vec<LooseQuad> = cube(Point3::new(3.0, 0.0, 0.0), 0)
            .into_iter()
            .chain(cube(Point3::ZERO, 6))
            .collect();
        let mut want = vec![0; 6];
        want.extend([1; 6]);
        assert_eq!(closed_components(&two), Some(want));
        assert_eq!(closed_components(&one[1..]), None);
    }
}
