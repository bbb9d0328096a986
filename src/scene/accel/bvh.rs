//! A bounding volume hierarchy built with the binned surface area heuristic, flattened in
//! depth-first order.
//!
//! Build: at every node the centroids are binned into [`BINS`] bins along each of the three
//! axes and the split with the least SAH cost (traversal cost 1, intersection cost 1 per
//! primitive) is taken (Wald 2007, "On fast Construction of SAH-based Bounding Volume
//! Hierarchies", IEEE Symposium on Interactive Ray Tracing). A node with at most
//! [`MAX_LEAF`] primitives becomes a leaf when that is no costlier than its best split.
//! Nodes store their boxes padded by a relative 2⁻²⁰ ([`Aabb::padded`]). Rays traverse the
//! 4-wide tree collapsed from this one ([`super::Bvh4`]), not this binary tree.

use super::aabb::Aabb;
use glam::{Vec3, Vec3A};

/// Number of SAH bins per axis.
pub(crate) const BINS: usize = 16;
/// Largest number of primitives in a leaf.
pub(crate) const MAX_LEAF: usize = 4;
/// Depth beyond which the build splits at the median, so the traversal stack stays bounded.
const MEDIAN_DEPTH: u32 = 36;

/// A flattened node: 48 bytes (bounds in SIMD lanes).
#[derive(Debug, Clone, Copy)]
struct Node {
    min: Vec3A,
    max: Vec3A,
    /// Leaf: first primitive. Interior: index of the second child (the first is `self + 1`).
    offset: u32,
    /// Number of primitives (0 for an interior node).
    count: u16,
    /// Split axis of an interior node (kept for diagnostics).
    axis: u16,
}

/// A BVH over primitives given by their bounds. The primitives must be stored in the order
/// [`Bvh::order`] reports, so that a leaf covers a contiguous range of them.
#[derive(Debug, Clone)]
pub(crate) struct Bvh {
    nodes: Vec<Node>,
    order: Vec<u32>,
}

struct Builder<'a> {
    bounds: &'a [Aabb],
    centroids: Vec<Vec3>,
    index: Vec<u32>,
    nodes: Vec<Node>,
}

impl Bvh {
    /// Builds the hierarchy over primitives with the given bounds.
    pub(crate) fn build(bounds: &[Aabb]) -> Self {
        let mut b = Builder {
            bounds,
            centroids: bounds.iter().map(Aabb::center).collect(),
            index: (0..bounds.len() as u32).collect(),
            nodes: Vec::with_capacity(2 * bounds.len().max(1)),
        };
        if bounds.is_empty() {
            b.nodes.push(Node {
                min: Vec3A::splat(f32::INFINITY),
                max: Vec3A::splat(f32::NEG_INFINITY),
                offset: 0,
                count: 0,
                axis: 0,
            });
        } else {
            b.build(0, bounds.len(), 0);
        }
        Self {
            nodes: b.nodes,
            order: b.index,
        }
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
}

impl Builder<'_> {
    /// Builds the subtree over `index[start..end]` and returns its node index.
    fn build(&mut self, start: usize, end: usize, depth: u32) -> usize {
        let me = self.nodes.len();
        let ids = &self.index[start..end];
        let bounds = ids
            .iter()
            .fold(Aabb::EMPTY, |b, &i| b.union(self.bounds[i as usize]));
        let padded = bounds.padded();
        self.nodes.push(Node {
            min: padded.min.into(),
            max: padded.max.into(),
            offset: start as u32,
            count: (end - start) as u16,
            axis: 0,
        });
        let n = end - start;
        if n == 1 {
            return me;
        }
        let split = if depth >= MEDIAN_DEPTH {
            None
        } else {
            self.sah_split(start, end, &bounds)
        };
        let (axis, mid) = match split {
            Some(s) => s,
            None if n <= MAX_LEAF => return me,
            None => self.median_split(start, end),
        };
        self.build(start, mid, depth + 1);
        let second = self.build(mid, end, depth + 1);
        let node = &mut self.nodes[me];
        node.offset = second as u32;
        node.count = 0;
        node.axis = axis as u16;
        me
    }

    /// The best binned SAH split as (axis, partition point), or `None` if a leaf is at least
    /// as cheap (only allowed for small nodes) or the centroids cannot be separated.
    fn sah_split(&mut self, start: usize, end: usize, bounds: &Aabb) -> Option<(usize, usize)> {
        let ids = &self.index[start..end];
        let cb = ids
            .iter()
            .fold(Aabb::EMPTY, |b, &i| b.grow(self.centroids[i as usize]));
        let ext = cb.extent();
        let n = end - start;
        let mut best: Option<(f32, usize, usize)> = None; // (cost, axis, bin)
        for axis in 0..3 {
            if ext[axis] <= 0.0 {
                continue;
            }
            let scale = BINS as f32 / ext[axis];
            let bin_of = |c: Vec3| (((c[axis] - cb.min[axis]) * scale) as usize).min(BINS - 1);
            let mut cnt = [0usize; BINS];
            let mut bb = [Aabb::EMPTY; BINS];
            for &i in ids {
                let k = bin_of(self.centroids[i as usize]);
                cnt[k] += 1;
                bb[k] = bb[k].union(self.bounds[i as usize]);
            }
            // Sweep from the right, then from the left.
            let mut right_area = [0.0f32; BINS];
            let (mut acc, mut c) = (Aabb::EMPTY, 0usize);
            let mut right_cnt = [0usize; BINS];
            for k in (1..BINS).rev() {
                acc = acc.union(bb[k]);
                c += cnt[k];
                right_area[k] = acc.surface_area();
                right_cnt[k] = c;
            }
            let (mut acc, mut c) = (Aabb::EMPTY, 0usize);
            for k in 0..BINS - 1 {
                acc = acc.union(bb[k]);
                c += cnt[k];
                let (nr, nl) = (right_cnt[k + 1], c);
                if nl == 0 || nr == 0 {
                    continue;
                }
                let cost = acc.surface_area() * nl as f32 + right_area[k + 1] * nr as f32;
                if best.is_none_or(|(b, _, _)| cost < b) {
                    best = Some((cost, axis, k));
                }
            }
        }
        let (cost, axis, bin) = best?;
        let area = bounds.surface_area();
        let split_cost = 1.0 + if area > 0.0 { cost / area } else { n as f32 };
        if n <= MAX_LEAF && n as f32 <= split_cost {
            return None;
        }
        let scale = BINS as f32 / ext[axis];
        let (lo, cents) = (cb.min[axis], &self.centroids);
        let slice = &mut self.index[start..end];
        let mid = partition(slice, |&i| {
            let k = (((cents[i as usize][axis] - lo) * scale) as usize).min(BINS - 1);
            k <= bin
        });
        (mid > 0 && mid < n).then_some((axis, start + mid))
    }

    /// Splits at the median centroid along the widest centroid axis.
    fn median_split(&mut self, start: usize, end: usize) -> (usize, usize) {
        let cents = &self.centroids;
        let cb = self.index[start..end]
            .iter()
            .fold(Aabb::EMPTY, |b, &i| b.grow(cents[i as usize]));
        let axis = cb.extent().max_position();
        let mid = (end - start) / 2;
        self.index[start..end].select_nth_unstable_by(mid, |&a, &b| {
            cents[a as usize][axis].total_cmp(&cents[b as usize][axis])
        });
        (axis, start + mid)
    }
}

/// Moves the elements satisfying `pred` to the front; returns how many there are.
fn partition(s: &mut [u32], pred: impl Fn(&u32) -> bool) -> usize {
    let mut k = 0;
    for i in 0..s.len() {
        if pred(&s[i]) {
            s.swap(i, k);
            k += 1;
        }
    }
    k
}

#[cfg(test)]
mod tests {
    use super::*;

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
