//! The flattened node of a [`Bvh`](super::bvh::Bvh) and the limits of its build, shared by
//! the tree and by the build that makes its nodes (`bvh_build.rs`).

use glam::Vec3A;

/// Number of SAH bins per axis.
pub(crate) const BINS: usize = 16;
/// Largest number of primitives in a leaf.
pub(crate) const MAX_LEAF: usize = 4;
/// Depth beyond which the build splits at the median, so the traversal stack stays bounded.
pub(super) const MEDIAN_DEPTH: u32 = 36;

/// A flattened node: 48 bytes (bounds in SIMD lanes).
#[derive(Debug, Clone, Copy)]
pub(super) struct Node {
    pub(super) min: Vec3A,
    pub(super) max: Vec3A,
    /// Leaf: first primitive. Interior: index of the second child (the first is `self + 1`).
    pub(super) offset: u32,
    /// Number of primitives (0 for an interior node).
    pub(super) count: u16,
    /// Split axis of an interior node (kept for diagnostics).
    pub(super) axis: u16,
}
