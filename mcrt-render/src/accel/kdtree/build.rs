//! The O(N log N) SAH build (Wald & Havran 2006's sorted-event sweep, with bounding-box
//! splits): the node recursion.
//!
//! A node finds its cheapest plane with the sweep of `sah.rs`. The chosen split classifies
//! every primitive as left, right or both from the split axis's events, and each of the
//! three lists is then filtered into the two children's in order, so both stay sorted:
//! O(events) per node, O(N log N) in all after the one sort at the root.
//!
//! Bounds for any input: the depth is at most `8 + 1.3 log₂ N` ([`depth_limit`]), and the
//! references (a primitive listed once per leaf it meets) are at most
//! [`REFS_PER_PRIM`]` · N`. Each node gets a budget of references, the root `REFS_PER_PRIM ·
//! N`; a split whose children would list more primitives than the node's budget is not
//! made (the node stays a leaf), and otherwise the children share the budget in proportion
//! to their counts (rounded down, so each keeps at least its count). Overlapping
//! primitives that straddle every plane (a stack of shifted copies of one triangle) would
//! otherwise be duplicated at every level. Interior nodes with an empty child form chains no
//! longer than the depth limit, so the nodes are O(N log N) too.

use super::sah::{best_split, sorted_events, usable, Event, Split};
use super::{KdTree, Node, MAX_DEPTH};
use crate::accel::aabb::Aabb;

/// Most references per primitive in the whole tree (see the module docs).
pub(crate) const REFS_PER_PRIM: usize = 16;

/// Where a primitive goes at the current split.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Side {
    Left,
    Right,
    Both,
}

struct Builder {
    side: Vec<Side>,
    nodes: Vec<Node>,
    items: Vec<u32>,
    max_depth: u32,
    depth: u32,
}

/// Builds the tree (see the module docs).
pub(super) fn build(prims: &[Aabb]) -> KdTree {
    let boxes: Vec<Option<Aabb>> = prims.iter().map(usable).collect();
    let live = boxes.iter().flatten().count();
    let bounds = boxes.iter().flatten().fold(Aabb::EMPTY, |b, p| b.union(*p));
    let events = [0, 1, 2].map(|axis| sorted_events(&boxes, axis));
    let mut b = Builder {
        side: vec![Side::Both; prims.len()],
        nodes: Vec::with_capacity(2 * live + 1),
        items: Vec::with_capacity(2 * live),
        max_depth: depth_limit(live),
        depth: 0,
    };
    b.node(bounds, events, live, 0, REFS_PER_PRIM * live);
    KdTree {
        nodes: b.nodes,
        items: b.items,
        bounds,
        depth: b.depth,
    }
}

/// The build's depth limit, `8 + 1.3 log₂ N` (the rule of thumb in Pharr, Jakob & Humphreys
/// 2016, "Physically Based Rendering", 3rd ed., section 4.4), at most [`MAX_DEPTH`].
fn depth_limit(n: usize) -> u32 {
    let log2 = (n.max(1) as f64).log2();
    ((8.0 + 1.3 * log2).round() as u32).min(MAX_DEPTH)
}

impl Builder {
    /// Builds the subtree for `voxel` over the primitives with `events` (`n` of them, `n ≤
    /// budget`), listing at most `budget` references in its leaves.
    fn node(&mut self, voxel: Aabb, events: [Vec<Event>; 3], n: usize, depth: u32, budget: usize) {
        self.depth = self.depth.max(depth);
        let me = self.nodes.len();
        let split = if depth < self.max_depth {
            best_split(&voxel, &events, n).filter(|s| s.left + s.right <= budget)
        } else {
            None
        };
        let Some(s) = split else {
            self.leaf(&events[0]);
            return;
        };
        let both = (s.left + s.right).max(1);
        let share = |k: usize| (budget as u128 * k as u128 / both as u128) as usize;
        self.nodes.push(Node::leaf(0, 0)); // patched below
        self.classify(&events[s.axis], s.pos);
        let (left, right) = self.divide(events, &s);
        let (mut lo_voxel, mut hi_voxel) = (voxel, voxel);
        lo_voxel.max[s.axis] = s.pos;
        hi_voxel.min[s.axis] = s.pos;
        self.node(lo_voxel, left, s.left, depth + 1, share(s.left));
        let above = self.nodes.len() as u32;
        self.node(hi_voxel, right, s.right, depth + 1, share(s.right));
        self.nodes[me] = Node::interior(s.axis, s.pos, above);
    }

    /// A leaf over the primitives starting in `events` (each has one start), in index order.
    fn leaf(&mut self, events: &[Event]) {
        let first = self.items.len();
        self.items.extend(
            events
                .iter()
                .filter(|e| e.is_start())
                .map(|e| e.prim() as u32),
        );
        self.items[first..].sort_unstable();
        let count = (self.items.len() - first) as u32;
        self.nodes.push(Node::leaf(first as u32, count));
    }

    /// Sets the side of every primitive of the node for a split at `pos`: left if its box
    /// ends at or before `pos`, right if it starts at or after, else both.
    fn classify(&mut self, events: &[Event], pos: f32) {
        for e in events {
            self.side[e.prim()] = if e.is_start() {
                if e.pos >= pos {
                    Side::Right
                } else {
                    Side::Both
                }
            } else if e.pos <= pos {
                Side::Left
            } else {
                continue;
            };
        }
    }

    /// Splits the event lists stably by the sides set by [`Builder::classify`].
    fn divide(&self, events: [Vec<Event>; 3], s: &Split) -> ([Vec<Event>; 3], [Vec<Event>; 3]) {
        let mut left = [(); 3].map(|_| Vec::with_capacity(2 * s.left));
        let mut right = [(); 3].map(|_| Vec::with_capacity(2 * s.right));
        for (axis, list) in events.into_iter().enumerate() {
            for e in list {
                match self.side[e.prim()] {
                    Side::Left => left[axis].push(e),
                    Side::Right => right[axis].push(e),
                    Side::Both => {
                        left[axis].push(e);
                        right[axis].push(e);
                    }
                }
            }
        }
        (left, right)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn cube(x: f32, size: f32) -> Aabb {
        Aabb::from_points(&[Vec3::new(x, 0.0, 0.0), Vec3::new(x + size, 1.0, 1.0)])
    }

    /// The tree of `sah::tests::sah_picks_the_plane_by_hand`: the root splits at the three
    /// cubes; below, x = 1 cuts off the empty space (cost 0.8 · (15 + 20 · 6 / 38) = 14.5 <
    /// 20) and the three equal cubes share a leaf.
    #[test]
    fn tree_of_the_hand_example() {
        let boxes = [
            cube(0.0, 1.0),
            cube(9.0, 1.0),
            cube(9.0, 1.0),
            cube(9.0, 1.0),
        ];
        let tree = build(&boxes);
        assert_eq!(tree.nodes[0].axis(), 0);
        assert_eq!(tree.nodes[0].split(), usable(&boxes[1]).unwrap().min.x);
        let st = tree.stats();
        assert_eq!(st.references, 4, "{st:?}");
        assert!(st.empty_leaves >= 1, "{st:?}");
        // No plane pays (see `sah::tests::leaf_when_no_split_pays`): one leaf.
        assert_eq!(build(&[cube(0.0, 1.0), cube(0.05, 1.0)]).stats().nodes, 1);
        let same = build(&[cube(0.0, 1.0); 5]).stats();
        assert_eq!((same.nodes, same.references), (1, 5));
    }

    /// Every leaf lists every primitive whose padded box meets its voxel (what traversal
    /// relies on), the event lists stay sorted down the tree, and the depth stays in its
    /// limit, on a few thousand scattered boxes of mixed sizes.
    #[test]
    fn leaves_cover_their_voxels() {
        let mut s = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 40) as f32 / (1u64 << 24) as f32
        };
        let boxes: Vec<Aabb> = (0..3000)
            .map(|_| {
                let c = Vec3::new(next(), next(), next()) * 10.0;
                let h = Vec3::new(next(), next(), next()) * if next() < 0.1 { 2.0 } else { 0.2 };
                Aabb::from_points(&[c - h, c + h])
            })
            .collect();
        let tree = build(&boxes);
        let st = tree.stats();
        assert!(st.depth <= depth_limit(boxes.len()), "{st:?}");
        assert!(
            st.leaves > 100 && st.references < 10 * boxes.len(),
            "{st:?}"
        );
        assert_covers(&tree, &boxes);
    }

    /// Every leaf of `tree` lists every primitive whose padded box meets its voxel, and
    /// every plane lies inside its voxel.
    fn assert_covers(tree: &KdTree, boxes: &[Aabb]) {
        let st = tree.stats();
        let padded: Vec<Aabb> = boxes.iter().filter_map(usable).collect();
        let mut todo = vec![(0usize, tree.bounds())];
        let mut leaves = 0;
        while let Some((i, v)) = todo.pop() {
            let n = tree.nodes[i];
            if n.is_leaf() {
                leaves += 1;
                let items = tree.leaf_items(n);
                for (k, p) in padded.iter().enumerate() {
                    let meets = (0..3).all(|a| p.min[a] < v.max[a] && p.max[a] > v.min[a]);
                    // Leaves list their primitives in index order.
                    let listed = items.binary_search(&(k as u32)).is_ok();
                    assert!(!meets || listed, "leaf {i} misses {k}");
                }
                continue;
            }
            let (a, pos) = (n.axis(), n.split());
            assert!(
                pos > v.min[a] && pos < v.max[a],
                "plane outside voxel at {i}"
            );
            let (mut lo, mut hi) = (v, v);
            lo.max[a] = pos;
            hi.min[a] = pos;
            todo.push((i + 1, lo));
            todo.push((n.upper() as usize, hi));
        }
        assert_eq!(leaves, st.leaves);
    }

    /// Shifted copies of one flat box (each straddles nearly every plane across x, so SAH
    /// splits duplicated them level after level), copies of one box and flat boxes in one
    /// plane: the references stay within `REFS_PER_PRIM · N`, the depth within its limit,
    /// and the leaves still cover their voxels.
    #[test]
    fn overlapping_boxes_stay_bounded() {
        let flat = |d: f32| {
            Aabb::from_points(&[Vec3::new(-0.5 + d, -0.5, 0.0), Vec3::new(0.5 + d, 0.5, 0.0)])
        };
        let n = 4000;
        let shifted: Vec<Aabb> = (0..n).map(|i| flat(i as f32 * 1e-4)).collect();
        let same = vec![flat(0.0); n];
        let plane: Vec<Aabb> = (0..n)
            .map(|i| {
                let p = Vec3::new((i % 64) as f32, (i / 64) as f32, 0.0) * 0.1;
                Aabb::from_points(&[p, p + Vec3::new(0.5, 0.5, 0.0)])
            })
            .collect();
        for boxes in [shifted, same, plane] {
            let tree = build(&boxes);
            let st = tree.stats();
            assert!(st.references <= REFS_PER_PRIM * n, "{st:?}");
            assert!(st.depth <= depth_limit(n), "{st:?}");
            assert_covers(&tree, &boxes);
        }
    }

    /// No usable box, NaN and empty boxes, infinite coordinates: a tree that answers.
    #[test]
    fn degenerate_inputs_build() {
        assert_eq!(build(&[]).stats().references, 0);
        let nan = Aabb {
            min: Vec3::NAN,
            max: Vec3::ONE,
        };
        let inf = Aabb {
            min: Vec3::splat(f32::NEG_INFINITY),
            max: Vec3::ZERO,
        };
        let tree = build(&[nan, Aabb::EMPTY, inf, cube(1.0, 1.0)]);
        assert_eq!(tree.stats().references, 2);
        assert!(tree.bounds().min.is_finite() && tree.bounds().max.is_finite());
    }
}
