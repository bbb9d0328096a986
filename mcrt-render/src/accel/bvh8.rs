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
use super::lanes8::Simd8;
use super::wide_bvh::WideBvh;

pub(super) use super::wide_bvh::{EMPTY, LEAF};

/// Eight child boxes by coordinate (lane = child), and the children: a node index, or a
/// leaf `LEAF | leaf index`, or [`EMPTY`]. 256 bytes, aligned to them.
#[derive(Debug, Clone, Copy)]
#[repr(C, align(64))]
pub(crate) struct Node8 {
    pub(super) lo: [[f32; 8]; 3],
    pub(super) hi: [[f32; 8]; 3],
    pub(super) child: [u32; 8],
    /// Bit `i` set when child `i` is not [`EMPTY`].
    pub(super) valid: u32,
}

super::wide_bvh::wide_node!(Node8, 8, [f32::INFINITY; 8], [f32::NEG_INFINITY; 8]);

/// The 8-wide BVH.
pub(crate) type Bvh8 = WideBvh<Node8, Simd8>;

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
        Self::build_with(bounds, merge, Simd8::detect())
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
}

super::leaf_queries::leaf_queries!(Bvh8);

#[cfg(test)]
#[path = "bvh8_tests.rs"]
mod tests;
