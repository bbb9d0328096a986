//! An 8-wide BVH: the binary SAH hierarchy collapsed so that every node holds up to eight
//! children, whose boxes are stored by coordinate (eight lanes per coordinate) and tested at
//! once: with AVX2 where the processor has it, else as two 4-lane halves ([`Simd8`]). This
//! is the 4-wide tree's scheme ([`super::Bvh4`]; Wald, Benthin & Boulos 2008) at the width
//! Embree uses on AVX2 machines (Wald et al. 2014, "Embree: A Kernel Framework for
//! Efficient CPU Ray Tracing", ACM TOG 33(4)). Collapsing repeatedly opens the interior child
//! of largest surface area until eight children are gathered.
//!
//! The leaves are the binary tree's leaves (at most four primitives each), the same as the
//! 4-wide tree's, or with [`Bvh8::build_merging`] binary subtrees of up to eight primitives
//! merged into one leaf (for the geometry's 8-lane leaf tests). Child codes and leaf
//! numbering follow [`super::Bvh4`]'s. Traversal is in `traverse8.rs`.

use super::aabb::Aabb;
use super::bvh::Bvh;
use super::lanes8::Simd8;

/// Marks a stack entry or child as a leaf: `LEAF | leaf index`.
pub(super) const LEAF: u32 = 1 << 31;
/// An empty child slot (never entered: its lane is not in [`Node8::valid`]).
pub(super) const EMPTY: u32 = u32::MAX;

/// Eight child boxes by coordinate (lane = child), and the children: a node index, or a
/// leaf `LEAF | leaf index`, or [`EMPTY`]. 256 bytes, aligned to them.
#[derive(Debug, Clone, Copy)]
#[repr(C, align(64))]
pub(super) struct Node8 {
    pub(super) lo: [[f32; 8]; 3],
    pub(super) hi: [[f32; 8]; 3],
    pub(super) child: [u32; 8],
    /// Bit `i` set when child `i` is not [`EMPTY`].
    pub(super) valid: u32,
}

/// The 8-wide BVH.
#[derive(Debug, Clone)]
pub(crate) struct Bvh8 {
    pub(super) nodes: Vec<Node8>,
    /// The root: a node index or a leaf code (a scene of at most four primitives).
    pub(super) root: u32,
    order: Vec<u32>,
    /// Leaf `k` holds the stored primitives `leaves[k].0 .. leaves[k].0 + leaves[k].1`; the
    /// ranges partition the stored order.
    leaves: Vec<(u32, u32)>,
    /// Levels of 8-wide nodes on the longest root-to-leaf path.
    pub(super) depth: usize,
    /// How the box tests run.
    pub(super) simd: Simd8,
}

impl Bvh8 {
    /// Builds the binary SAH BVH over the bounds and collapses it; box tests use the widest
    /// lanes the processor has. The leaves are the binary tree's.
    pub(crate) fn build(bounds: &[Aabb]) -> Self {
        Self::build_merging(bounds, 0)
    }

    /// [`Bvh8::build`], with every binary subtree of at most `merge` primitives made one
    /// leaf (its primitives are contiguous in the stored order); the binary leaves stay
    /// leaves whatever `merge`.
    pub(crate) fn build_merging(bounds: &[Aabb], merge: u32) -> Self {
        let bvh = Bvh::build(bounds);
        let mut out = Self {
            nodes: Vec::with_capacity(bvh.node_count() / 6 + 1),
            root: EMPTY,
            order: bvh.order().to_vec(),
            leaves: Vec::with_capacity(bounds.len() / 2 + 1),
            depth: 0,
            simd: Simd8::detect(),
        };
        if !bounds.is_empty() {
            let spans = Spans::new(&bvh, merge);
            out.root = out.collapse(&bvh, &spans, 0);
            out.depth = out.node_depth(out.root);
        }
        out
    }

    /// How the box tests run.
    pub(crate) fn simd(&self) -> Simd8 {
        self.simd
    }

    /// This tree with its box tests run on `simd` (tests compare both paths).
    #[cfg(test)]
    pub(crate) fn with_simd(mut self, simd: Simd8) -> Self {
        self.simd = simd;
        self
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

    /// The stored primitives of leaf `k` (positions in [`Bvh8::order`]); the leaves'
    /// ranges partition the stored order. Empty past the end.
    pub(crate) fn leaf(&self, k: usize) -> std::ops::Range<u32> {
        self.leaves
            .get(k)
            .map_or(0..0, |&(first, n)| first..first + n)
    }

    /// Levels of 8-wide nodes below and including `code` (0 for a leaf).
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

    /// The code of binary node `b`: a leaf code, or the index of its 8-wide node.
    fn collapse(&mut self, bvh: &Bvh, spans: &Spans, b: usize) -> u32 {
        if let Some(range) = spans.leaf(b) {
            debug_assert!(self.leaves.len() < LEAF as usize, "leaf code overflow");
            self.leaves.push(range);
            return LEAF | (self.leaves.len() - 1) as u32;
        }
        // Up to eight children, gathered without allocating (`kids[..len]`).
        let [first, second] = bvh.children(b);
        let mut kids = [0usize; 8];
        kids[..2].copy_from_slice(&[first, second]);
        let mut len = 2;
        while len < 8 {
            let open = kids[..len]
                .iter()
                .enumerate()
                .filter(|(_, &k)| spans.leaf(k).is_none())
                .max_by(|a, b| bvh.area(*a.1).total_cmp(&bvh.area(*b.1)))
                .map(|(i, _)| i);
            let Some(i) = open else { break };
            // As `Vec::swap_remove(i)` then pushing both children.
            let k = kids[i];
            kids[i] = kids[len - 1];
            [kids[len - 1], kids[len]] = bvh.children(k);
            len += 1;
        }
        let me = self.nodes.len();
        self.nodes.push(Node8 {
            lo: [[f32::INFINITY; 8]; 3],
            hi: [[f32::NEG_INFINITY; 8]; 3],
            child: [EMPTY; 8],
            valid: 0,
        });
        for (lane, &k) in kids[..len].iter().enumerate() {
            let code = self.collapse(bvh, spans, k);
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

/// Which binary nodes become leaves, and their primitive ranges.
struct Spans {
    /// `Some((first, count))` for a binary node that becomes a leaf.
    leaf: Vec<Option<(u32, u32)>>,
}

impl Spans {
    /// Binary leaves, and subtrees of at most `merge` primitives (a binary node's children
    /// come after it, so the subtree ranges are gathered bottom-up).
    fn new(bvh: &Bvh, merge: u32) -> Self {
        let mut range = vec![(0, 0); bvh.node_count()];
        let mut leaf = vec![None; bvh.node_count()];
        for b in (0..bvh.node_count()).rev() {
            range[b] = match bvh.leaf(b) {
                Some(r) => {
                    leaf[b] = Some(r);
                    r
                }
                None => {
                    let [l, r] = bvh.children(b).map(|c| range[c]);
                    debug_assert_eq!(l.0 + l.1, r.0, "a subtree's primitives are contiguous");
                    let r = (l.0, l.1 + r.1);
                    if r.1 <= merge {
                        leaf[b] = Some(r);
                    }
                    r
                }
            };
        }
        Self { leaf }
    }

    /// Binary node `b`'s range if it becomes a leaf.
    fn leaf(&self, b: usize) -> Option<(u32, u32)> {
        self.leaf[b]
    }
}

super::leaf_queries::leaf_queries!(Bvh8);

#[cfg(test)]
#[path = "bvh8_tests.rs"]
mod tests;
