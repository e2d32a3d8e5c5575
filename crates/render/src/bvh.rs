//! Bounding volume hierarchy: built top-down by the surface-area heuristic over binned centroids
//! (Wald, "On fast Construction of SAH-based Bounding Volume Hierarchies", 2007; pbrt-v4's
//! `BVHAggregate`), stored flat in depth-first order (a node's first child follows it, the second is
//! at an index), and traversed iteratively with a small stack, nearer child first by the sign of the
//! ray direction on the split axis.

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
    /// Split axis of an interior node (0, 1, 2).
    pub axis: u8,
}

/// A flattened BVH over items `0..n`; `order[i]` is the original index of the `i`-th item in leaf order.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    pub nodes: Vec<Node>,
    pub order: Vec<u32>,
}

const BINS: usize = 16;
const MAX_LEAF: usize = 4;
/// Cost of one traversal step relative to one primitive test.
const TRAVERSAL_COST: f64 = 0.5;

struct Item {
    bounds: Aabb,
    centroid: Vec3,
    index: u32,
}

impl Bvh {
    /// Build over the bounding boxes of the items.
    pub fn build(bounds: &[Aabb]) -> Bvh {
        let mut items: Vec<Item> = bounds
            .iter()
            .enumerate()
            .map(|(i, b)| Item {
                bounds: *b,
                centroid: b.centroid(),
                index: i as u32,
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
            axis: 0,
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
            let mut boxes = [Aabb::EMPTY; BINS];
            for it in items.iter() {
                let b = bin_of(it.centroid[axis]);
                counts[b] += 1;
                boxes[b] = boxes[b].union(&it.bounds);
            }
            // Sweep from the right, then from the left, costing every split between bins.
            let mut right_area = [0.0; BINS];
            let mut right_count = [0usize; BINS];
            let (mut acc, mut cnt) = (Aabb::EMPTY, 0);
            for b in (1..BINS).rev() {
                acc = acc.union(&boxes[b]);
                cnt += counts[b];
                right_area[b] = acc.area();
                right_count[b] = cnt;
            }
            let (mut acc, mut cnt) = (Aabb::EMPTY, 0);
            let mut best = (f64::INFINITY, 0);
            for b in 0..BINS - 1 {
                acc = acc.union(&boxes[b]);
                cnt += counts[b];
                if cnt == 0 || right_count[b + 1] == 0 {
                    continue;
                }
                let cost = cnt as f64 * acc.area() + right_count[b + 1] as f64 * right_area[b + 1];
                if cost < best.0 {
                    best = (cost, b);
                }
            }
            let area = bounds.area().max(f64::MIN_POSITIVE);
            let split_cost = TRAVERSAL_COST + best.0 / area;
            if n <= MAX_LEAF && split_cost >= n as f64 {
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
        self.nodes[me].axis = axis as u8;
        me
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
}
