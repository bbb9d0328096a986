//! What the 4-wide and the 8-wide BVH ([`super::Bvh4`], [`super::Bvh8`]) share: the binary
//! SAH hierarchy collapsed into nodes of up to `WIDTH` children by repeatedly opening the
//! interior child of largest surface area (Wald, Benthin & Boulos 2008, "Getting Rid of
//! Packets", IEEE Symposium on Interactive Ray Tracing), the leaves numbered as they are
//! reached, and the accessors of their ranges of stored primitives.

use super::bvh::Bvh;
use super::{vec_bytes, Aabb};
use glam::Vec3A;
use std::ops::Range;

/// Marks a stack entry or child as a leaf: `LEAF | leaf index`.
pub(super) const LEAF: u32 = 1 << 31;
/// An empty child slot (never entered: its lane is not in the node's `valid` bits).
pub(super) const EMPTY: u32 = u32::MAX;

/// The most children a node may have (the gathering buffer's size).
const MAX_WIDTH: usize = 8;

/// A node of up to `WIDTH` children, their boxes stored by coordinate (lane = child).
pub(crate) trait WideNode {
    /// Children per node (at most [`MAX_WIDTH`]).
    const WIDTH: usize;
    /// A node with no children (every lane [`EMPTY`], its box inverted).
    fn empty() -> Self;
    /// The children's codes: a node index, `LEAF | leaf index` or [`EMPTY`].
    fn children(&self) -> &[u32];
    /// Makes lane `lane` the child `code` with the box `lo..hi`.
    fn set_child(&mut self, lane: usize, lo: Vec3A, hi: Vec3A, code: u32);
}

/// Implements [`WideNode`] for a node type with fields `lo` and `hi` (three coordinates of
/// `width` lanes; `inf` and `neg_inf` are lanes of ±∞), `child` and `valid`.
macro_rules! wide_node {
    ($node:ty, $width:literal, $inf:expr, $neg_inf:expr) => {
        impl super::wide_bvh::WideNode for $node {
            const WIDTH: usize = $width;

            fn empty() -> Self {
                Self {
                    lo: [$inf; 3],
                    hi: [$neg_inf; 3],
                    child: [super::wide_bvh::EMPTY; $width],
                    valid: 0,
                }
            }

            fn children(&self) -> &[u32] {
                &self.child
            }

            fn set_child(&mut self, lane: usize, lo: glam::Vec3A, hi: glam::Vec3A, code: u32) {
                for a in 0..3 {
                    self.lo[a][lane] = lo[a];
                    self.hi[a][lane] = hi[a];
                }
                self.child[lane] = code;
                self.valid |= 1 << lane;
            }
        }
    };
}
pub(super) use wide_node;

/// A wide BVH of nodes `N`, its box tests run as `S` says (the 8-wide tree's lanes; nothing
/// for the 4-wide tree).
#[derive(Debug, Clone)]
pub(crate) struct WideBvh<N, S = ()> {
    pub(super) nodes: Vec<N>,
    /// The root: a node index or a leaf code (a scene of at most four primitives).
    pub(super) root: u32,
    order: Vec<u32>,
    /// Leaf `k` holds the stored primitives `leaves[k].0 .. leaves[k].0 + leaves[k].1`; the
    /// ranges partition the stored order.
    pub(super) leaves: Vec<(u32, u32)>,
    /// Levels of wide nodes on the longest root-to-leaf path.
    pub(super) depth: usize,
    /// How the box tests run.
    pub(super) simd: S,
}

impl<N: WideNode, S> WideBvh<N, S> {
    /// Builds the binary SAH BVH over the bounds and collapses it, every binary subtree of
    /// at most `merge` primitives made one leaf (its primitives are contiguous in the stored
    /// order); the binary leaves stay leaves whatever `merge`.
    pub(super) fn build_with(bounds: &[Aabb], merge: u32, simd: S) -> Self {
        let bvh = Bvh::build(bounds);
        let mut out = Self {
            nodes: Vec::with_capacity(bvh.node_count() / (N::WIDTH - 2) + 1),
            root: EMPTY,
            order: bvh.order().to_vec(),
            leaves: Vec::with_capacity(bounds.len() / 2 + 1),
            depth: 0,
            simd,
        };
        if !bounds.is_empty() {
            let spans = Spans::new(&bvh, merge);
            out.root = out.collapse(&bvh, &spans, 0);
            out.depth = out.node_depth(out.root);
        }
        out
    }

    /// Heap bytes held (nodes, order and leaf ranges).
    pub(crate) fn heap_bytes(&self) -> usize {
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

    /// The stored primitives of leaf `k` (positions in [`WideBvh::order`]); the leaves'
    /// ranges partition the stored order. Empty past the end.
    pub(crate) fn leaf(&self, k: usize) -> Range<u32> {
        self.leaves
            .get(k)
            .map_or(0..0, |&(first, n)| first..first + n)
    }

    /// Levels of wide nodes below and including `code` (0 for a leaf).
    fn node_depth(&self, code: u32) -> usize {
        if code & LEAF != 0 || code == EMPTY {
            return 0;
        }
        let n = &self.nodes[code as usize];
        1 + n
            .children()
            .iter()
            .map(|&c| self.node_depth(c))
            .max()
            .unwrap_or(0)
    }

    /// The code of binary node `b`: a leaf code, or the index of its wide node.
    fn collapse(&mut self, bvh: &Bvh, spans: &Spans, b: usize) -> u32 {
        if let Some(range) = spans.leaf(b) {
            debug_assert!(self.leaves.len() < LEAF as usize, "leaf code overflow");
            self.leaves.push(range);
            return LEAF | (self.leaves.len() - 1) as u32;
        }
        // Up to `WIDTH` children, gathered without allocating (`kids[..len]`).
        let [first, second] = bvh.children(b);
        let mut kids = [0usize; MAX_WIDTH];
        kids[..2].copy_from_slice(&[first, second]);
        let mut len = 2;
        debug_assert!(N::WIDTH <= MAX_WIDTH);
        while len < N::WIDTH {
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
        self.nodes.push(N::empty());
        for (lane, &k) in kids[..len].iter().enumerate() {
            let code = self.collapse(bvh, spans, k);
            let (lo, hi) = bvh.node_box(k);
            self.nodes[me].set_child(lane, lo, hi, code);
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
