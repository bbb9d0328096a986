//! A 4-wide BVH: the binary SAH hierarchy collapsed so that every node holds up to four
//! children whose boxes are tested at once in SIMD lanes (as in Wald, Benthin & Boulos 2008,
//! "Getting Rid of Packets: Efficient SIMD Single-Ray Traversal using Multi-branching BVHs",
//! IEEE Symposium on Interactive Ray Tracing). Collapsing repeatedly opens the interior child
//! of largest surface area until four children are gathered.
//!
//! Leaves are numbered; a child code is a node index, `LEAF | leaf index` or [`EMPTY`], and
//! [`Bvh4::leaf`] gives a leaf's range of stored primitives. Queries either call back per
//! primitive ([`Bvh4::closest`], [`Bvh4::any`]) or per leaf ([`Bvh4::closest_leaf`],
//! [`Bvh4::any_leaf`], which `Geometry` uses to test a leaf's quads and triangles as SIMD
//! packets).
//! Traversal is in `traverse.rs`.

use super::aabb::Aabb;
use super::bvh::Bvh;
use glam::Vec4;

/// Marks a stack entry or child as a leaf: `LEAF | leaf index`.
pub(super) const LEAF: u32 = 1 << 31;
/// An empty child slot (never entered: its lane is not in [`Node4::valid`]).
pub(super) const EMPTY: u32 = u32::MAX;

/// Four child boxes by coordinate (lane = child), and the children: a node index, or a leaf
/// `LEAF | leaf index`, or [`EMPTY`].
#[derive(Debug, Clone, Copy)]
pub(super) struct Node4 {
    pub(super) lo: [Vec4; 3],
    pub(super) hi: [Vec4; 3],
    pub(super) child: [u32; 4],
    /// Bit `i` set when child `i` is not [`EMPTY`].
    pub(super) valid: u32,
}

/// The 4-wide BVH.
#[derive(Debug, Clone)]
pub(crate) struct Bvh4 {
    pub(super) nodes: Vec<Node4>,
    /// The root: a node index or a leaf code (a scene of at most four primitives).
    pub(super) root: u32,
    order: Vec<u32>,
    /// Leaf `k` holds the stored primitives `leaves[k].0 .. leaves[k].0 + leaves[k].1`; the
    /// ranges partition the stored order.
    leaves: Vec<(u32, u32)>,
    /// Levels of 4-wide nodes on the longest root-to-leaf path.
    pub(super) depth: usize,
}

impl Bvh4 {
    /// Builds the binary SAH BVH over the bounds and collapses it.
    pub(crate) fn build(bounds: &[Aabb]) -> Self {
        let bvh = Bvh::build(bounds);
        let mut out = Self {
            nodes: Vec::with_capacity(bvh.node_count() / 2 + 1),
            root: EMPTY,
            order: bvh.order().to_vec(),
            leaves: Vec::with_capacity(bounds.len() / 2 + 1),
            depth: 0,
        };
        if !bounds.is_empty() {
            out.root = out.collapse(&bvh, 0);
            out.depth = out.node_depth(out.root);
        }
        out
    }

    /// Heap bytes held (nodes, order and leaf ranges).
    pub(crate) fn heap_bytes(&self) -> usize {
        use super::vec_bytes;
        vec_bytes(&self.nodes) + vec_bytes(&self.order) + vec_bytes(&self.leaves)
    }

    /// `order[i]` is the input index of the primitive to store at position `i`.
    pub(crate) fn order(&self) -> &[u32] {
        &self.order
    }

    /// Number of leaves.
    pub(crate) fn leaf_count(&self) -> usize {
        self.leaves.len()
    }

    /// The stored primitives of leaf `k` (positions in [`Bvh4::order`]); the leaves'
    /// ranges partition the stored order. Empty past the end.
    pub(crate) fn leaf(&self, k: usize) -> std::ops::Range<u32> {
        self.leaves
            .get(k)
            .map_or(0..0, |&(first, n)| first..first + n)
    }

    /// Levels of 4-wide nodes below and including `code` (0 for a leaf).
    fn node_depth(&self, code: u32) -> usize {
        if code & LEAF != 0 || code == EMPTY {
            return 0;
        }
        let n = &self.nodes[code as usize];
        1 + n
            .child
            .iter()
            .map(|&c| self.node_depth(c))
            .max()
            .unwrap_or(0)
    }

    /// The code of binary node `b`: a leaf code, or the index of its 4-wide node.
    fn collapse(&mut self, bvh: &Bvh, b: usize) -> u32 {
        if let Some(range) = bvh.leaf(b) {
            debug_assert!(self.leaves.len() < LEAF as usize, "leaf code overflow");
            self.leaves.push(range);
            return LEAF | (self.leaves.len() - 1) as u32;
        }
        // Up to four children, gathered without allocating (`kids[..len]`).
        let [first, second] = bvh.children(b);
        let (mut kids, mut len) = ([first, second, 0, 0], 2);
        while len < 4 {
            let open = kids[..len]
                .iter()
                .enumerate()
                .filter(|(_, &k)| bvh.leaf(k).is_none())
                .max_by(|a, b| bvh.area(*a.1).total_cmp(&bvh.area(*b.1)))
                .map(|(i, _)| i);
            let Some(i) = open else { break };
            // As `Vec::swap_remove(i)` then pushing both children.
            let k = kids[i];
            kids[i] = kids[len - 1];
            [kids[len - 1], kids[len]] = bvh.children(k);
            len += 1;
        }
        let kids = &kids[..len];
        let me = self.nodes.len();
        self.nodes.push(Node4 {
            lo: [Vec4::splat(f32::INFINITY); 3],
            hi: [Vec4::splat(f32::NEG_INFINITY); 3],
            child: [EMPTY; 4],
            valid: 0,
        });
        for (lane, &k) in kids.iter().enumerate() {
            let code = self.collapse(bvh, k);
            let (lo, hi) = bvh.node_box(k);
            let n = &mut self.nodes[me];
            for a in 0..3 {
                n.lo[a][lane] = lo[a];
                n.hi[a][lane] = hi[a];
            }
            n.child[lane] = code;
            n.valid |= 1 << lane;
        }
        me as u32
    }
}

super::leaf_queries::leaf_queries!(Bvh4);

#[cfg(test)]
mod tests {
    use super::super::LeafQueries;
    use super::*;
    use glam::Vec3;

    #[test]
    fn identical_boxes_still_build() {
        let b = vec![Aabb::from_points(&[Vec3::ZERO, Vec3::ONE]); 300];
        let bvh = Bvh4::build(&b);
        let mut hits = 0;
        bvh.any(Vec3::new(0.5, 0.5, -1.0), Vec3::Z, f32::INFINITY, |_, _| {
            hits += 1;
            false
        });
        assert_eq!(hits, 300);
    }

    #[test]
    fn leaves_partition_the_stored_order_and_leaf_walks_reach_them() {
        for n in [0usize, 1, 4, 5, 37, 500] {
            let b: Vec<Aabb> = (0..n)
                .map(|i| {
                    let p = Vec3::new((i % 7) as f32, (i / 7 % 5) as f32, (i / 35) as f32);
                    Aabb::from_points(&[p, p + Vec3::splat(0.5)])
                })
                .collect();
            let bvh = Bvh4::build(&b);
            let mut ranges: Vec<_> = (0..bvh.leaf_count()).map(|k| bvh.leaf(k)).collect();
            ranges.sort_by_key(|r| r.start);
            let mut next = 0;
            for r in ranges {
                assert!(
                    r.start == next && r.end > r.start && r.len() <= 4,
                    "n {n} {r:?}"
                );
                next = r.end;
            }
            assert_eq!(next as usize, n);
            assert!(bvh.leaf(bvh.leaf_count()).is_empty());
            // A ray along +x through the first row: every leaf on it is visited once.
            let o = Vec3::new(-1.0, 0.25, 0.25);
            let mut seen = vec![0; bvh.leaf_count()];
            bvh.any_leaf(o, Vec3::X, f32::INFINITY, |k, _| {
                seen[k as usize] += 1;
                false
            });
            let on_row = |k: usize| {
                bvh.leaf(k).any(|i| {
                    let bx = b[bvh.order()[i as usize] as usize];
                    bx.min.y <= 0.25 && bx.min.z <= 0.25
                })
            };
            for (k, &s) in seen.iter().enumerate() {
                assert!(s <= 1 && (s == 1 || !on_row(k)), "n {n} leaf {k} seen {s}");
            }
            // The closest walk shrinks the bound to the first box's face.
            let bound = bvh.closest_leaf(o, Vec3::X, f32::INFINITY, |k, t| {
                for i in bvh.leaf(k as usize) {
                    let hit = b[bvh.order()[i as usize] as usize].min.x + 1.0;
                    if on_row(k as usize) && hit < *t {
                        *t = hit;
                    }
                }
            });
            assert_eq!(bound, if n == 0 { f32::INFINITY } else { 1.0 }, "n {n}");
        }
    }

    #[test]
    fn empty_bvh_finds_nothing() {
        let bvh = Bvh4::build(&[]);
        assert!(!bvh.any(Vec3::ZERO, Vec3::Z, 1.0, |_, _| true));
    }

    #[test]
    fn small_scenes_and_leaf_roots() {
        for n in [1usize, 3, 4, 5, 17, 200] {
            let b: Vec<Aabb> = (0..n)
                .map(|i| {
                    let p = Vec3::new(i as f32 * 2.0, 0.0, 0.0);
                    Aabb::from_points(&[p, p + Vec3::ONE])
                })
                .collect();
            let bvh = Bvh4::build(&b);
            let mut seen = vec![false; n];
            bvh.any(Vec3::new(-1.0, 0.5, 0.5), Vec3::X, f32::INFINITY, |i, _| {
                seen[i as usize] = true;
                false
            });
            assert!(seen.iter().all(|&s| s), "n = {n}");
            let t = bvh.closest(
                Vec3::new(-1.0, 0.5, 0.5),
                Vec3::X,
                f32::INFINITY,
                |i, tm| {
                    let t = 1.0 + 2.0 * b[bvh.order()[i as usize] as usize].min.x / 2.0;
                    (t < tm).then_some(t)
                },
            );
            assert_eq!(t, Some(1.0));
        }
        assert!(!Bvh4::build(&[]).any(Vec3::ZERO, Vec3::X, 1.0, |_, _| true));
    }
}
