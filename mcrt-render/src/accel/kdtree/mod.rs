//! A kd-tree built with the surface area heuristic in O(N log N) (Wald & Havran 2006, "On
//! building fast kd-trees for ray tracing, and on doing that in O(N log N)", IEEE Symposium on
//! Interactive Ray Tracing; the SAH of MacDonald & Booth 1990, "Heuristics for ray tracing
//! using space subdivision", The Visual Computer 6(3)).
//!
//! Build (`build.rs`, the sweep in `sah.rs`): every primitive's box, padded by a relative 2⁻²⁰ ([`Aabb::padded`]),
//! gives a start and an end event per axis; the three event lists are sorted once, and at
//! every node a sweep over them finds the plane of least SAH cost
//! `λ · (K_T + K_I · (A_L N_L + A_R N_R) / A)` ([`TRAVERSAL_COST`], [`INTERSECTION_COST`],
//! λ = [`EMPTY_BONUS`] when one side is empty). A node becomes a leaf when no plane is
//! cheaper than `K_I · N` or at the depth limit; otherwise its lists are split stably into
//! the children's, so that they stay sorted without another sort. Planes are candidates at
//! box bounds only ("bounding-box splits": a primitive crossing a plane is listed on both
//! sides with its whole box, not clipped to the child).
//!
//! Traversal (`traverse.rs`): front to back with a stack of far children and their entry
//! distances; a closest-hit search skips any far child entered beyond the nearest hit so
//! far. Primitives may sit in several leaves: a hit is accepted wherever it lies (below the
//! current bound), so a primitive found through one leaf is found at its true distance, and
//! the search ends only when every leaf entered before that distance has been visited.
//! `docs/geometry.md` ("Kd-tree") gives the details and the reasons for the padding.

mod build;
mod sah;
mod traverse;

use super::aabb::Aabb;

/// Cost of one traversal step, `K_T` (the value of Wald & Havran 2006's experiments).
pub(crate) const TRAVERSAL_COST: f64 = 15.0;
/// Cost of one primitive intersection, `K_I` (the value of Wald & Havran 2006's experiments).
pub(crate) const INTERSECTION_COST: f64 = 20.0;
/// Factor λ on the cost of a split that leaves one side empty, favouring cutting off empty
/// space (Wald & Havran 2006, λ = 0.8).
pub(crate) const EMPTY_BONUS: f64 = 0.8;
/// Hard limit on the depth of the tree (and so on the traversal stack); the build's own
/// limit, `8 + 1.3 log₂ N`, stays below it for any N that fits in memory.
pub(crate) const MAX_DEPTH: u32 = 64;

/// A node in 8 bytes. Interior: `a` holds the split position's bits and `b` the axis (0–2)
/// in its low two bits and the index of the child above the plane in the others (the child
/// below is the next node). Leaf: `a` is the first entry in [`KdTree::items`] and `b` is
/// `3 | count << 2`.
#[derive(Debug, Clone, Copy)]
struct Node {
    a: u32,
    b: u32,
}

impl Node {
    const LEAF: u32 = 3;

    fn leaf(first: u32, count: u32) -> Self {
        Self {
            a: first,
            b: Self::LEAF | count << 2,
        }
    }

    fn interior(axis: usize, pos: f32, above: u32) -> Self {
        Self {
            a: pos.to_bits(),
            b: axis as u32 | above << 2,
        }
    }

    /// The split axis (3 for a leaf): below 4, so it indexes four-lane arrays unchecked.
    #[inline(always)]
    fn axis(self) -> usize {
        (self.b & 3) as usize
    }

    #[inline(always)]
    fn is_leaf(self) -> bool {
        self.b & 3 == Self::LEAF
    }

    #[inline(always)]
    fn split(self) -> f32 {
        f32::from_bits(self.a)
    }

    /// Interior: the child above the plane. Leaf: the number of primitives.
    #[inline(always)]
    fn upper(self) -> u32 {
        self.b >> 2
    }
}

/// A kd-tree over primitives given by their bounds (in input order: [`super::Accel::order`]
/// is the identity for it). Boxes that are empty or hold a NaN are left out (no ray can meet
/// them); infinite coordinates are clamped to the largest finite float. Up to 2³¹
/// primitives (the build's events keep the index in 31 bits).
#[derive(Debug, Clone)]
pub(crate) struct KdTree {
    nodes: Vec<Node>,
    /// The primitives of the leaves, leaf by leaf (a primitive may appear in several).
    items: Vec<u32>,
    /// The root voxel: the union of the padded primitive boxes.
    bounds: Aabb,
    /// Levels below the root on the longest path (0 for a single leaf).
    depth: u32,
}

/// Size figures of a built [`KdTree`] (for the tests).
#[cfg(test)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct KdTreeStats {
    /// Interior nodes and leaves.
    pub nodes: usize,
    /// Leaves, empty ones included.
    pub leaves: usize,
    /// Leaves with no primitive (cut-off empty space).
    pub empty_leaves: usize,
    /// Primitive references summed over the leaves (≥ the primitive count: a primitive
    /// crossing a split plane is listed on both sides).
    pub references: usize,
    /// Levels below the root on the longest path.
    pub depth: u32,
}

impl KdTree {
    /// Builds the tree over primitives with the given bounds.
    pub(crate) fn build(prims: &[Aabb]) -> Self {
        build::build(prims)
    }

    /// Heap bytes held (nodes and leaf entries).
    pub(crate) fn heap_bytes(&self) -> usize {
        super::vec_bytes(&self.nodes) + super::vec_bytes(&self.items)
    }

    /// The root voxel (empty when no primitive has a usable box).
    #[cfg(test)]
    pub(crate) fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// Node, leaf and reference counts and the depth.
    #[cfg(test)]
    pub(crate) fn stats(&self) -> KdTreeStats {
        let leaves: Vec<Node> = self.nodes.iter().copied().filter(|n| n.is_leaf()).collect();
        KdTreeStats {
            nodes: self.nodes.len(),
            leaves: leaves.len(),
            empty_leaves: leaves.iter().filter(|n| n.upper() == 0).count(),
            references: self.items.len(),
            depth: self.depth,
        }
    }

    /// The primitives of leaf `n`.
    #[inline(always)]
    fn leaf_items(&self, n: Node) -> &[u32] {
        let first = n.a as usize;
        &self.items[first..first + n.upper() as usize]
    }
}
