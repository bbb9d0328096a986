//! A bounding volume hierarchy built with the binned surface area heuristic, flattened in
//! depth-first order.
//!
//! Build: at every node the centroids are binned into [`BINS`](super::bvh_node::BINS) bins along each of the three
//! axes and the split with the least SAH cost (traversal cost 1, intersection cost 1 per
//! primitive) is taken (Wald 2007, "On fast Construction of SAH-based Bounding Volume
//! Hierarchies", IEEE Symposium on Interactive Ray Tracing). A node with at most
//! [`MAX_LEAF`](super::bvh_node::MAX_LEAF) primitives becomes a leaf when that is no costlier than its best split.
//! Nodes store their boxes padded by a relative 2⁻²⁰ ([`Aabb::padded`]). Rays traverse the
//! 4-wide tree collapsed from this one ([`super::Bvh4`]), not this binary tree.

use super::aabb::Aabb;
use super::bvh_node::Node;
use glam::Vec3A;

/// A BVH over primitives given by their bounds. The primitives must be stored in the order
/// [`Bvh::order`] reports, so that a leaf covers a contiguous range of them.
#[derive(Debug, Clone)]
pub(crate) struct Bvh {
    nodes: Vec<Node>,
    order: Vec<u32>,
}

impl Bvh {
    /// Builds the hierarchy over primitives with the given bounds (subtrees of many
    /// primitives in parallel; the tree does not depend on the number of threads).
    pub(crate) fn build(bounds: &[Aabb]) -> Self {
        Self::build_with(bounds, super::bvh_build::PARALLEL_MIN)
    }

    /// [`Bvh::build`], with subtrees of at least `parallel_min` primitives built in parallel.
    pub(super) fn build_with(bounds: &[Aabb], parallel_min: usize) -> Self {
        if bounds.is_empty() {
            return Self {
                nodes: vec![Node {
                    min: Vec3A::splat(f32::INFINITY),
                    max: Vec3A::splat(f32::NEG_INFINITY),
                    offset: 0,
                    count: 0,
                    axis: 0,
                }],
                order: Vec::new(),
            };
        }
        let (nodes, order) = super::bvh_build::build(bounds, parallel_min);
        Self { nodes, order }
    }

    /// `order[i]` is the input index of the primitive that must be stored at position `i`.
    pub(crate) fn order(&self) -> &[u32] {
        &self.order
    }

    /// Leaf `b`'s primitive range (first, count), or `None` for an interior node.
    pub(super) fn leaf(&self, b: usize) -> Option<(u32, u32)> {
        let n = &self.nodes[b];
        (n.count > 0).then_some((n.offset, u32::from(n.count)))
    }

    /// The two children of interior node `b`.
    pub(super) fn children(&self, b: usize) -> [usize; 2] {
        [b + 1, self.nodes[b].offset as usize]
    }

    /// The (padded) box of node `b`.
    pub(super) fn node_box(&self, b: usize) -> (Vec3A, Vec3A) {
        (self.nodes[b].min, self.nodes[b].max)
    }

    /// The surface area of node `b`'s box.
    pub(super) fn area(&self, b: usize) -> f32 {
        let e = (self.nodes[b].max - self.nodes[b].min).max(Vec3A::ZERO);
        2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
    }

    /// Number of nodes.
    pub(crate) fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// The nodes, for tests comparing builds.
    #[cfg(test)]
    pub(super) fn nodes_for_tests(&self) -> &[Node] {
        &self.nodes
    }
}

#[cfg(test)]
mod tests {
    use super::super::bvh_node::MAX_LEAF;
    use super::*;
    use glam::Vec3;

    fn boxes(n: usize) -> Vec<Aabb> {
        (0..n)
            .map(|i| {
                let p = Vec3::new(i as f32, (i * 7 % 5) as f32, (i * 3 % 11) as f32);
                Aabb::from_points(&[p, p + Vec3::splat(0.5)])
            })
            .collect()
    }

    #[test]
    fn order_is_a_permutation_and_leaves_are_small() {
        let b = boxes(1000);
        let bvh = Bvh::build(&b);
        let mut o = bvh.order().to_vec();
        o.sort_unstable();
        assert!(o.iter().enumerate().all(|(i, &v)| i as u32 == v));
        assert!(bvh.nodes.iter().all(|n| (n.count as usize) <= MAX_LEAF));
        assert!(bvh.node_count() < 2 * 1000);
    }
}
