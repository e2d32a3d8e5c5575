//! Bounding volume hierarchy: built top-down by the surface-area heuristic over binned centroids
//! (Wald, "On fast Construction of SAH-based Bounding Volume Hierarchies", 2007; pbrt-v4's
//! `BVHAggregate`), stored flat in depth-first order (a node's first child follows it, the second is
//! at an index).
//!
//! For traversal the binary tree is collapsed into a 4-wide one ([`Bvh4`], as Embree's and pbrt's
//! wide BVHs): every node holds the boxes of up to four children in structure-of-arrays form, so one
//! ray is tested against all four boxes in a handful of vector instructions, and the children hit are
//! visited nearest entry first (`Scene::hit_group`).

use crate::aabb::Aabb;
use crate::vec::Vec3;

/// A node of the flattened tree.
#[derive(Clone, Copy, Debug)]
pub struct Node {
    pub bounds: Aabb,
    /// Leaf: index of the first item; interior: index of the second child.
    pub offset: u32,
    /// Number of items in a leaf; 0 for an interior node.
    pub count: u16,
}

/// A flattened BVH over items `0..n`; `order[i]` is the original index of the `i`-th item in leaf order.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    pub nodes: Vec<Node>,
    pub order: Vec<u32>,
}

const BINS: usize = 16;
/// Most items a leaf may hold.
const MAX_LEAF: usize = 8;
/// Most items a leaf may hold that are tested one by one.
const MAX_SINGLES: usize = 4;
/// Cost of one traversal step relative to one primitive test.
const TRAVERSAL_COST: f64 = 0.5;
/// Cost of testing a packet of up to [`PACKET`] packable items (quads tested together) relative to
/// one primitive test.
const PACKET_COST: f64 = 2.0;
/// Number of packable items tested together.
pub const PACKET: usize = 4;

/// What testing an item in a leaf costs, relative to one primitive test: the surface-area heuristic
/// weighs each side of a split by the cost of what it holds, not just its count.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ItemCost {
    /// Tested [`PACKET`] at a time with its kind (quads): `PACKET_COST` per packet in a leaf.
    Packed,
    /// Tested alone at this cost (a sphere: 1; an instance: the transform and its own tree).
    Single(f64),
}

impl ItemCost {
    /// The item's share of a split's cost.
    fn share(self) -> f64 {
        match self {
            ItemCost::Packed => PACKET_COST / PACKET as f64,
            ItemCost::Single(c) => c,
        }
    }
}

struct Item {
    bounds: Aabb,
    centroid: Vec3,
    index: u32,
    cost: ItemCost,
}

impl Bvh {
    /// Build over the bounding boxes of the items.
    pub fn build(bounds: &[Aabb]) -> Bvh {
        Self::build_with_costs(bounds, &vec![ItemCost::Single(1.0); bounds.len()])
    }

    /// Build over the bounding boxes of the items, each with the cost of testing it: a leaf costs
    /// `PACKET_COST` per packet of packed items plus the cost of each other item, so the heuristic
    /// keeps quads together and gives costly items (instances) boxes of their own.
    pub fn build_with_costs(bounds: &[Aabb], costs: &[ItemCost]) -> Bvh {
        assert_eq!(bounds.len(), costs.len());
        let mut items: Vec<Item> = bounds
            .iter()
            .zip(costs)
            .enumerate()
            .map(|(i, (b, &cost))| Item {
                bounds: *b,
                centroid: b.centroid(),
                index: i as u32,
                cost,
            })
            .collect();
        let mut bvh = Bvh {
            nodes: Vec::with_capacity(2 * bounds.len()),
            order: Vec::with_capacity(bounds.len()),
        };
        if !items.is_empty() {
            bvh.build_node(&mut items[..]);
        }
        bvh
    }

    /// Bounds of everything in the tree.
    pub fn bounds(&self) -> Aabb {
        self.nodes.first().map_or(Aabb::EMPTY, |n| n.bounds)
    }

    fn build_node(&mut self, items: &mut [Item]) -> usize {
        let me = self.nodes.len();
        let bounds = items.iter().fold(Aabb::EMPTY, |a, it| a.union(&it.bounds));
        self.nodes.push(Node {
            bounds,
            offset: 0,
            count: 0,
        });
        let n = items.len();
        let make_leaf = |bvh: &mut Bvh, items: &mut [Item]| {
            bvh.nodes[me].offset = bvh.order.len() as u32;
            bvh.nodes[me].count = items.len() as u16;
            bvh.order.extend(items.iter().map(|it| it.index));
            me
        };
        if n == 1 {
            return make_leaf(self, items);
        }
        let cbounds = items
            .iter()
            .fold(Aabb::EMPTY, |a, it| a.include(it.centroid));
        let extent = cbounds.max - cbounds.min;
        let axis = if extent.x >= extent.y && extent.x >= extent.z {
            0
        } else if extent.y >= extent.z {
            1
        } else {
            2
        };
        let (lo, span) = (cbounds.min[axis], extent[axis]);
        let mid = if span <= 0.0 || span.is_nan() {
            // All centroids coincide: no split can separate them; split by count unless small.
            if n <= MAX_LEAF {
                return make_leaf(self, items);
            }
            n / 2
        } else {
            // Binned SAH.
            let bin_of = |c: f64| (((c - lo) / span * BINS as f64) as usize).min(BINS - 1);
            let mut counts = [0usize; BINS];
            let mut weights = [0.0; BINS];
            let mut boxes = [Aabb::EMPTY; BINS];
            for it in items.iter() {
                let b = bin_of(it.centroid[axis]);
                counts[b] += 1;
                weights[b] += it.cost.share();
                boxes[b] = boxes[b].union(&it.bounds);
            }
            // Sweep from the right, then from the left, costing every split between bins.
            let mut right_area = [0.0; BINS];
            let mut right_count = [0usize; BINS];
            let mut right_weight = [0.0; BINS];
            let (mut acc, mut cnt, mut wt) = (Aabb::EMPTY, 0, 0.0);
            for b in (1..BINS).rev() {
                acc = acc.union(&boxes[b]);
                cnt += counts[b];
                wt += weights[b];
                right_area[b] = acc.area();
                right_count[b] = cnt;
                right_weight[b] = wt;
            }
            let (mut acc, mut cnt, mut wt) = (Aabb::EMPTY, 0, 0.0);
            let mut best = (f64::INFINITY, 0);
            for b in 0..BINS - 1 {
                acc = acc.union(&boxes[b]);
                cnt += counts[b];
                wt += weights[b];
                if cnt == 0 || right_count[b + 1] == 0 {
                    continue;
                }
                let cost = wt * acc.area() + right_weight[b + 1] * right_area[b + 1];
                if cost < best.0 {
                    best = (cost, b);
                }
            }
            let area = bounds.area().max(f64::MIN_POSITIVE);
            let split_cost = TRAVERSAL_COST + best.0 / area;
            let (packed, single) = items.iter().fold((0, 0.0), |(p, c), it| match it.cost {
                ItemCost::Packed => (p + 1, c),
                ItemCost::Single(x) => (p, c + x),
            });
            let leaf_cost = (packed as usize).div_ceil(PACKET) as f64 * PACKET_COST + single;
            let singles = n - packed as usize;
            if n <= MAX_LEAF && singles <= MAX_SINGLES && split_cost >= leaf_cost {
                return make_leaf(self, items);
            }
            if best.0.is_infinite() {
                n / 2
            } else {
                let split_bin = best.1;
                // Partition in place: items of bins <= split_bin go left.
                let mut i = 0;
                for j in 0..n {
                    if bin_of(items[j].centroid[axis]) <= split_bin {
                        items.swap(i, j);
                        i += 1;
                    }
                }
                i
            }
        };
        let mid = if mid == 0 || mid == n {
            items.sort_by(|a, b| a.centroid[axis].total_cmp(&b.centroid[axis]));
            n / 2
        } else {
            mid
        };
        let (left, right) = items.split_at_mut(mid);
        self.build_node(left);
        let second = self.build_node(right);
        self.nodes[me].offset = second as u32;
        me
    }
}

/// A node of the 4-wide tree: the boxes of up to four children, coordinate by coordinate
/// (`min[axis][child]`), and what each child is.
#[derive(Clone, Copy, Debug)]
pub struct Node4 {
    pub min: [[f64; 4]; 3],
    pub max: [[f64; 4]; 3],
    /// An interior child's node index, a leaf's index in [`Bvh4::leaves`] with [`LEAF`] set, or
    /// [`EMPTY`].
    pub child: [u32; 4],
}

/// Marks a child of a [`Node4`] as a leaf.
pub const LEAF: u32 = 1 << 31;
/// An unused child slot of a [`Node4`].
pub const EMPTY: u32 = u32::MAX;

/// A leaf of the 4-wide tree: the items `first..first + count` in leaf order ([`Bvh::order`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Leaf4 {
    pub first: u32,
    pub count: u32,
}

/// The binary tree collapsed into a 4-wide tree; node 0 is the root.
#[derive(Clone, Debug, Default)]
pub struct Bvh4 {
    pub nodes: Vec<Node4>,
    pub leaves: Vec<Leaf4>,
}

impl Bvh4 {
    /// Collapse `bvh`: each 4-wide node takes the two children of a binary node and keeps opening
    /// its largest interior child (by surface area) until it has four children or only leaves.
    pub fn from_binary(bvh: &Bvh) -> Bvh4 {
        let mut out = Bvh4::default();
        if !bvh.nodes.is_empty() {
            out.node(bvh, 0);
        }
        out
    }

    /// Is the ray's `[t_min, t_max]` interval overlapped by the boxes of node `n`? Returns each
    /// child's entry parameter and a bit mask of those hit. `neg[a]` says whether `inv_dir[a]` is
    /// negative (so the near slab is `max`), as in pbrt-v4's `Bounds3::IntersectP`; a NaN slab (a zero
    /// direction component lying on the plane) constrains nothing. An empty slot's box
    /// (`min = +inf`, `max = -inf`) is entered at `+inf` and left at `-inf`: never hit.
    #[inline(always)]
    pub fn hit_children(
        n: &Node4,
        origin: [f64; 3],
        inv_dir: [f64; 3],
        neg: [bool; 3],
        t_min: f64,
        t_max: f64,
    ) -> ([f64; 4], u32) {
        let mut near = [t_min; 4];
        let mut far = [t_max; 4];
        for a in 0..3 {
            let (lo, hi) = if neg[a] {
                (&n.max[a], &n.min[a])
            } else {
                (&n.min[a], &n.max[a])
            };
            for i in 0..4 {
                let t0 = (lo[i] - origin[a]) * inv_dir[a];
                let t1 = (hi[i] - origin[a]) * inv_dir[a];
                near[i] = if t0 > near[i] { t0 } else { near[i] };
                far[i] = if t1 < far[i] { t1 } else { far[i] };
            }
        }
        let mut mask = 0;
        for i in 0..4 {
            // 1 + 2 gamma(3) makes the far side conservative against rounding (pbrt-v4).
            let hit = near[i] <= far[i] * (1.0 + 6.0 * f64::EPSILON);
            mask |= (hit as u32) << i;
        }
        (near, mask)
    }

    fn node(&mut self, bvh: &Bvh, root: usize) -> u32 {
        let me = self.nodes.len();
        // A missing child's box lies beyond every ray (see `hit_children`).
        self.nodes.push(Node4 {
            min: [[f64::INFINITY; 4]; 3],
            max: [[f64::NEG_INFINITY; 4]; 3],
            child: [EMPTY; 4],
        });
        let mut kids: Vec<usize> = if bvh.nodes[root].count > 0 {
            vec![root]
        } else {
            vec![root + 1, bvh.nodes[root].offset as usize]
        };
        while kids.len() < 4 {
            let open = kids
                .iter()
                .enumerate()
                .filter(|(_, k)| bvh.nodes[**k].count == 0)
                .max_by(|a, b| {
                    let area = |k: usize| bvh.nodes[k].bounds.area();
                    area(*a.1).total_cmp(&area(*b.1))
                })
                .map(|(i, _)| i);
            let Some(i) = open else { break };
            let k = kids.swap_remove(i);
            kids.push(k + 1);
            kids.push(bvh.nodes[k].offset as usize);
        }
        for (slot, &k) in kids.iter().enumerate() {
            let b = &bvh.nodes[k];
            for a in 0..3 {
                self.nodes[me].min[a][slot] = b.bounds.min[a];
                self.nodes[me].max[a][slot] = b.bounds.max[a];
            }
            let child = if b.count > 0 {
                self.leaves.push(Leaf4 {
                    first: b.offset,
                    count: b.count as u32,
                });
                LEAF | (self.leaves.len() as u32 - 1)
            } else {
                self.node(bvh, k)
            };
            self.nodes[me].child[slot] = child;
        }
        me as u32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_item_is_in_exactly_one_leaf_and_inside_its_node() {
        let mut bounds = Vec::new();
        for i in 0..500 {
            let c = Vec3::new((i * 37 % 101) as f64, (i * 53 % 89) as f64, (i % 7) as f64);
            bounds.push(Aabb::from_points(c, c + Vec3::splat(1.0 + (i % 3) as f64)));
        }
        // Coincident items too.
        for _ in 0..20 {
            bounds.push(Aabb::from_points(Vec3::ZERO, Vec3::ONE));
        }
        let bvh = Bvh::build(&bounds);
        let mut seen = vec![0; bounds.len()];
        for node in &bvh.nodes {
            if node.count > 0 {
                for k in node.offset as usize..node.offset as usize + node.count as usize {
                    let item = bvh.order[k] as usize;
                    seen[item] += 1;
                    let b = bounds[item];
                    assert!(
                        node.bounds.min.cmple(b.min).all() && node.bounds.max.cmpge(b.max).all()
                    );
                }
            }
        }
        assert!(seen.iter().all(|&s| s == 1));
    }

    #[test]
    fn the_wide_tree_holds_every_leaf_once_and_its_boxes_agree_with_the_slab_test() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_xoshiro::Xoshiro256PlusPlus::seed_from_u64(5);
        let mut bounds = Vec::new();
        for _ in 0..300 {
            let c = Vec3::new(
                rng.random_range(-10.0..10.0),
                rng.random_range(-10.0..10.0),
                rng.random_range(-10.0..10.0),
            );
            bounds.push(Aabb::from_points(
                c,
                c + Vec3::splat(rng.random_range(0.0..2.0)),
            ));
        }
        let bvh = Bvh::build(&bounds);
        let wide = Bvh4::from_binary(&bvh);
        let mut seen = vec![0; bounds.len()];
        for leaf in &wide.leaves {
            for k in leaf.first..leaf.first + leaf.count {
                seen[bvh.order[k as usize] as usize] += 1;
            }
        }
        assert!(seen.iter().all(|&s| s == 1));
        let mut slots = 0;
        for _ in 0..2_000 {
            let o = Vec3::new(
                rng.random_range(-15.0..15.0),
                rng.random_range(-15.0..15.0),
                rng.random_range(-15.0..15.0),
            );
            // Some directions with a zero (or negative zero) component.
            let mut d = Vec3::new(
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
                rng.random_range(-1.0..1.0),
            );
            match rng.random_range(0..4) {
                0 => d.x = 0.0,
                1 => d.y = -0.0,
                _ => {}
            }
            let inv = d.recip();
            let neg = [inv.x < 0.0, inv.y < 0.0, inv.z < 0.0];
            let t_min = [0.0, f64::NEG_INFINITY][rng.random_range(0..2)];
            let t_max = [f64::INFINITY, 3.0][rng.random_range(0..2)];
            for n in &wide.nodes {
                let (near, mask) =
                    Bvh4::hit_children(n, o.to_array(), inv.to_array(), neg, t_min, t_max);
                for (i, &entry) in near.iter().enumerate() {
                    let hit = mask & (1 << i) != 0;
                    if n.child[i] == EMPTY {
                        assert!(!hit, "an empty slot was hit");
                        continue;
                    }
                    slots += 1;
                    let b = Aabb {
                        min: Vec3::new(n.min[0][i], n.min[1][i], n.min[2][i]),
                        max: Vec3::new(n.max[0][i], n.max[1][i], n.max[2][i]),
                    };
                    // Conservative: whenever the binary tree's slab test enters the box, so does
                    // this one, no later.
                    if let Some(t) = b.hit(o, inv, t_min, t_max) {
                        assert!(hit && entry <= t, "{o} {d} {b:?}");
                    }
                }
            }
        }
        assert!(slots > 100_000);
    }
}
