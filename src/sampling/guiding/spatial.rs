//! The spatial half of the SD-tree: a binary tree over a cube around the scene, splitting at
//! the midpoint along x, y, z in turn, with a [`DQuadTree`] in every leaf.

use super::filter::{jitter, record_key, GuidingFilter};
use super::quadtree::DQuadTree;
use super::records::GuidingRecords;
use glam::{Vec2, Vec3};

/// A node of the spatial tree: an inner node (the children's indices, the split axis is the
/// depth modulo 3) or a leaf (the index of its [`Leaf`]). Small, so that the descent to a
/// leaf touches little memory.
#[derive(Debug, Clone, Copy, PartialEq)]
enum SNode {
    Inner([u32; 2]),
    Leaf(u32),
}

/// A spatial leaf's directional tree, the number of records it took, and its depth in the
/// spatial tree (which gives the size of its box, for the spatial filter).
#[derive(Debug, Clone, PartialEq)]
struct Leaf {
    tree: DQuadTree,
    samples: u64,
    depth: u32,
}

/// The deepest spatial subdivision (a leaf's cube is then `2^-(DEPTH/3)` of the whole).
const MAX_SPATIAL_DEPTH: u32 = 48;

/// Bits of each axis's grid coordinate per level of [`SdTree::leaf_index`] (the deepest
/// split halves an axis this often).
const AXIS_BITS: u32 = MAX_SPATIAL_DEPTH / 3;

/// The levels per axis that [`SdTree::top`] resolves at once: a grid of `2^(3·TOP_BITS)`
/// cells, each with the node the descent reaches after `3·TOP_BITS` levels.
const TOP_BITS: u32 = 4;

/// The flag of an entry of [`SdTree::top`] that is a leaf's index rather than a node's.
const TOP_LEAF: u32 = 1 << 31;

/// An SD-tree (Müller, Gross & Novák 2017, "Practical Path Guiding for Efficient
/// Light-Transport Simulation", CGF 36(4)): a binary tree over space whose leaves hold
/// directional quadtrees ([`DQuadTree`]) of the radiance arriving in them.
///
/// One tree plays two parts in the training iterations ([`GuidingSchedule`](super::GuidingSchedule)):
/// the tree of the previous iteration guides ([`SdTree::distribution`]) while a tree with
/// the refined structure and no energy ([`SdTree::refined`]) collects the records of the
/// current one ([`SdTree::record`], [`SdTree::merge`]).
///
/// Determinism: energies are `f64` sums in the order the records arrive. Workers record into
/// their own [`GuidingRecords`] (per tile), and the renderer merges these buffers in a fixed
/// order (tile order), so that the tree, and the image guided by it, is the same at any
/// thread count. (Atomic float adds are not associative, hence not deterministic.)
///
/// ```
/// use mcrt::glam::{Vec2, Vec3};
/// use mcrt::sampling::guiding::SdTree;
///
/// let mut t = SdTree::new(Vec3::splat(-1.0), Vec3::splat(1.0));
/// // Light arrives from +z everywhere.
/// for i in 0..1000 {
///     let p = Vec3::new((i % 10) as f32 / 5.0 - 1.0, 0.0, 0.0);
///     t.record(p, Vec3::Z, 1.0, 1.0);
/// }
/// let guide = t.clone();
/// let next = t.refined(100.0, 0.01, 20); // structure for the next iteration
/// assert!(next.leaf_count() > 1);
/// let d = guide.distribution(Vec3::ZERO);
/// assert!(d.pdf(Vec3::Z) > 10.0 * d.pdf(-Vec3::Z));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct SdTree {
    min: Vec3,
    size: f32,
    nodes: Vec<SNode>,
    leaves: Vec<Leaf>,
    /// Whether the leaves learn the guided path tracer's selection probability.
    learn_selection: bool,
    /// The filters applied to the records ([`SdTree::set_filter`]).
    filter: GuidingFilter,
    /// The scene's bounds, inside the cube: where the spatial filter clamps its points.
    scene: [Vec3; 2],
    /// Per cell of a grid of `2^TOP_BITS` cells per axis, the node that the descent of
    /// [`SdTree::leaf_index`] reaches after `3·TOP_BITS` levels, or the index of the leaf it
    /// reaches before (or there) with [`TOP_LEAF`] set, so that a lookup skips those levels
    /// (and, most often, the nodes). Derived from `nodes` ([`SdTree::index_top`]) whenever
    /// their structure changes.
    top: Vec<u32>,
}

impl SdTree {
    /// An empty tree over the cube around the box from `min` to `max` (the scene's bounds):
    /// every point's distribution is the uniform sphere. A box that is empty or not finite
    /// becomes the unit cube at the origin.
    pub fn new(min: Vec3, max: Vec3) -> Self {
        let (min, size, scene) =
            if min.is_finite() && max.is_finite() && (max - min).max_element() > 0.0 {
                let size = (max - min).max_element();
                // A margin, so that points on the box's faces are inside.
                let lo = min - Vec3::splat(size * 1e-3);
                (lo, size * 1.002, [min.min(max), max.max(min)])
            } else {
                (Vec3::ZERO, 1.0, [Vec3::ZERO, Vec3::ONE])
            };
        let mut t = Self {
            min,
            size,
            nodes: vec![SNode::Leaf(0)],
            leaves: vec![Leaf {
                tree: DQuadTree::new(),
                samples: 0,
                depth: 0,
            }],
            learn_selection: false,
            filter: GuidingFilter::NONE,
            scene,
            top: Vec::new(),
        };
        t.index_top();
        t
    }

    /// Fills [`SdTree::top`] from the nodes: for each grid cell, descends `3·TOP_BITS`
    /// levels (or to a leaf) with the cell's high coordinate bits, as [`SdTree::leaf_index`]
    /// would.
    fn index_top(&mut self) {
        let n = 1u32 << TOP_BITS;
        let shift = AXIS_BITS - TOP_BITS;
        self.top = (0..n * n * n)
            .map(|i| {
                let c = [i / (n * n), (i / n) % n, i % n].map(|v| v << shift);
                let node = self.descend(c, 0, 0, 3 * TOP_BITS).0;
                match self.nodes[node] {
                    SNode::Leaf(l) => l | TOP_LEAF,
                    SNode::Inner(_) => node as u32,
                }
            })
            .collect();
    }

    /// From node `n` at `depth`, the node reached by the grid coordinates `c` (each of
    /// [`AXIS_BITS`] bits) at depth `stop`, or the leaf reached before; and its depth.
    #[inline]
    fn descend(&self, c: [u32; 3], mut n: usize, mut depth: u32, stop: u32) -> (usize, u32) {
        while depth < stop {
            match self.nodes[n] {
                SNode::Inner(ch) => {
                    let bit = (c[(depth % 3) as usize] >> (AXIS_BITS - 1 - depth / 3)) & 1;
                    n = ch[bit as usize] as usize;
                    depth += 1;
                }
                SNode::Leaf(_) => break,
            }
        }
        (n, depth)
    }

    /// Whether this tree, and those [`SdTree::refined`] makes from it, learn in each leaf
    /// the probability with which the guided path tracer samples the guide rather than the
    /// BSDF ([`DQuadTree::selection_probability`]), from what
    /// [`GuidedPathTracer::li`](crate::integrator::GuidedPathTracer::li) records. Off by
    /// default: the tracer then samples the guide with its fixed `guide_probability`.
    pub fn learn_selection(&mut self, on: bool) {
        self.learn_selection = on;
    }

    /// What the learned selection probabilities promise: over the leaves that learned one
    /// ([`DQuadTree::selection_probability`]), the sum of the estimated second moments of
    /// the one-sample estimator with BSDF sampling alone over the sum with each leaf's best
    /// probability, `Σ M_0 / Σ min_j M_j`, at least 1. The records weigh each vertex by the
    /// path throughput before it, so this is the factor by which guiding would lower the
    /// second moment of the paths' directional choices; a second moment includes the
    /// squared mean, which guiding does not change, so their variance would fall by more.
    /// `None` where no leaf learned a probability, or the sums are not finite.
    ///
    /// ```
    /// use mcrt::glam::Vec3;
    /// use mcrt::sampling::guiding::SdTree;
    ///
    /// let mut t = SdTree::new(Vec3::splat(-1.0), Vec3::ONE);
    /// t.learn_selection(true);
    /// assert_eq!(t.selection_gain(), None); // nothing recorded yet
    /// ```
    pub fn selection_gain(&self) -> Option<f64> {
        let (mut m0, mut best) = (0.0f64, 0.0f64);
        for l in &self.leaves {
            if let Some((a, b)) = l.tree.selection_moments() {
                m0 += a;
                best += b;
            }
        }
        (best > 0.0 && m0.is_finite()).then(|| (m0 / best).max(1.0))
    }

    /// Whether the tree learns the selection probability ([`SdTree::learn_selection`]).
    pub fn learns_selection(&self) -> bool {
        self.learn_selection
    }

    /// Sets the filters through which this tree, and those [`SdTree::refined`] makes from
    /// it, take their records ([`GuidingFilter`]; none by default). They change what the
    /// tree learns from the records, not the densities it gives for what it learned.
    pub fn set_filter(&mut self, filter: GuidingFilter) {
        self.filter = filter;
    }

    /// The filters through which the tree takes its records ([`SdTree::set_filter`]).
    pub fn filter(&self) -> GuidingFilter {
        self.filter
    }

    /// The lower corner and the side of the tree's cube.
    pub fn bounds(&self) -> (Vec3, f32) {
        (self.min, self.size)
    }

    /// The number of spatial leaves.
    pub fn leaf_count(&self) -> usize {
        self.leaves.len()
    }

    /// The number of records the tree took.
    pub fn sample_count(&self) -> u64 {
        self.leaves.iter().map(|l| l.samples).sum()
    }

    /// The index of the leaf containing `p` (a point outside the cube, or with NaN
    /// coordinates, is clamped to it). The point is placed on a grid of `2^16` cells per axis
    /// (the deepest split halves an axis 16 times), and each level reads the next bit of the
    /// axis it splits.
    /// The first `3·TOP_BITS` levels are read from [`SdTree::top`].
    #[inline]
    fn leaf_index(&self, p: Vec3) -> usize {
        let scale = (1u32 << AXIS_BITS) as f32;
        // As `(clamp_unit(v) * scale).min(scale - 1.0)` (the scaling is exact, and `max`
        // takes a NaN to 0), with a conversion that needs no saturation.
        let cell = |v: f32| (v * scale).max(0.0).min(scale - 1.0) as i32 as u32;
        let x = (p - self.min) / self.size;
        let c = [cell(x.x), cell(x.y), cell(x.z)];
        let shift = AXIS_BITS - TOP_BITS;
        let g = (((c[0] >> shift) << TOP_BITS | (c[1] >> shift)) << TOP_BITS) | (c[2] >> shift);
        let t = self.top[g as usize];
        if t & TOP_LEAF != 0 {
            return (t & !TOP_LEAF) as usize;
        }
        let (n, _) = self.descend(c, t as usize, 3 * TOP_BITS, MAX_SPATIAL_DEPTH);
        match self.nodes[n] {
            SNode::Leaf(l) => l as usize,
            // Unreachable: `refined` splits no deeper than `MAX_SPATIAL_DEPTH`.
            SNode::Inner(_) => 0,
        }
    }

    /// The directional distribution of the radiance arriving at `p`.
    pub fn distribution(&self, p: Vec3) -> &DQuadTree {
        &self.leaves[self.leaf_index(p)].tree
    }

    /// Records radiance (a scalar, such as the mean of the RGB channels) arriving at `p`
    /// along the unit direction `dir`, sampled with density `pdf` per steradian: adds
    /// `radiance / pdf` to the directional tree of `p`'s leaf and counts one record there
    /// (through the tree's filters, [`SdTree::set_filter`]). A record whose `pdf` is not
    /// positive and finite is ignored; a radiance that is negative or not finite counts as a
    /// record of zero energy.
    pub fn record(&mut self, p: Vec3, dir: Vec3, radiance: f32, pdf: f32) {
        let square = super::sphere_to_square(dir);
        let i = self.leaf_index(p);
        self.record_at(i, p, square, radiance, pdf, 0);
    }

    /// The size along x, y and z of leaf `i`'s box: the cube's side halved once per split
    /// along the axis above it (the split at depth `d` is along axis `d mod 3`).
    fn leaf_extent(&self, i: usize) -> Vec3 {
        let d = self.leaves[i].depth;
        let halvings = |axis: u32| ((d + 2 - axis) / 3) as i32;
        Vec3::new(
            self.size * 0.5f32.powi(halvings(0)),
            self.size * 0.5f32.powi(halvings(1)),
            self.size * 0.5f32.powi(halvings(2)),
        )
    }

    /// The leaf that takes a record at `p` whose own leaf is `i`: `i`, or with the spatial
    /// filter the leaf of a point drawn uniformly in the box of `i`'s size centred on `p`
    /// (clamped to the scene's bounds), drawn by the hash `key` of the record (Müller 2019,
    /// "Practical Path Guiding in Production", its stochastic box filter).
    fn filtered_leaf(&self, i: usize, p: Vec3, key: u64) -> usize {
        if !self.filter.spatial {
            return i;
        }
        let q = p + (jitter(key) - Vec3::splat(0.5)) * self.leaf_extent(i);
        if !q.is_finite() {
            return i;
        }
        self.leaf_index(q.clamp(self.scene[0], self.scene[1]))
    }

    /// [`SdTree::record`] of the direction whose point of the square is `square`, for the
    /// record at `p` whose own leaf is `i` and whose jitter key is `index` (hashed with the
    /// record); returns the index of the leaf that took it.
    fn record_at(
        &mut self,
        i: usize,
        p: Vec3,
        square: Vec2,
        radiance: f32,
        pdf: f32,
        index: u64,
    ) -> usize {
        if !(pdf > 0.0 && pdf.is_finite()) {
            return i;
        }
        let j = self.filtered_leaf(i, p, record_key(p, square, index));
        let value = f64::from(radiance) / f64::from(pdf);
        let directional = self.filter.directional;
        let leaf = &mut self.leaves[j];
        leaf.samples += 1;
        if directional {
            leaf.tree.record_square_filtered(square, value);
        } else {
            leaf.tree.record_square(square, value);
        }
        j
    }

    /// Records every entry of `records`, in order (and, if the tree learns the selection
    /// probability, what the tracer recorded of its choices, in the leaf of the record's
    /// own position: the spatial filter moves the radiance only). The spatial filter's
    /// jitter is a hash of each record and its index in `records`, so the tree does not
    /// depend on which thread filled or merged the buffer.
    pub fn merge(&mut self, records: &GuidingRecords) {
        let learn = self.learn_selection;
        for (k, s) in records.stored().iter().enumerate() {
            let r = &s.record;
            let i = self.leaf_index(r.p);
            self.record_at(i, r.p, s.square, r.radiance, r.pdf, k as u64);
            if let (true, Some(sel)) = (learn, s.selection) {
                let t = &mut self.leaves[i].tree;
                t.record_selection(sel.integrand, sel.p_guide, sel.p_bsdf, r.pdf);
            }
        }
    }

    /// The tree that collects the records of the next iteration, after this one collected
    /// those of an iteration: the same spatial tree with every leaf that took more than
    /// `spatial_threshold` records split in two (and again, assuming the records halve with
    /// each split, until under the threshold: the paper's `c·√(2^k)`, c = 12000), each new
    /// leaf with a copy of its parent's directional tree; every directional tree refined by
    /// [`DQuadTree::refined`]`(rho, max_depth)`. No energy and no records.
    pub fn refined(&self, spatial_threshold: f64, rho: f64, max_depth: u32) -> SdTree {
        let mut out = SdTree {
            min: self.min,
            size: self.size,
            nodes: Vec::with_capacity(self.nodes.len()),
            leaves: Vec::with_capacity(self.leaves.len()),
            learn_selection: self.learn_selection,
            filter: self.filter,
            scene: self.scene,
            top: Vec::new(),
        };
        // (old node, new node, depth)
        out.nodes.push(SNode::Inner([0, 0]));
        let mut stack = vec![(0usize, 0usize, 0u32)];
        while let Some((o, ni, depth)) = stack.pop() {
            match self.nodes[o] {
                SNode::Inner(c) => {
                    let a = out.push_placeholder();
                    let b = out.push_placeholder();
                    out.nodes[ni] = SNode::Inner([a as u32, b as u32]);
                    stack.push((c[0] as usize, a, depth + 1));
                    stack.push((c[1] as usize, b, depth + 1));
                }
                SNode::Leaf(l) => {
                    let Leaf { tree, samples, .. } = &self.leaves[l as usize];
                    let fresh = tree.refined(rho, max_depth);
                    out.split_leaf(ni, fresh, *samples as f64, spatial_threshold, depth);
                }
            }
        }
        out.index_top();
        out
    }

    fn push_placeholder(&mut self) -> usize {
        self.nodes.push(SNode::Inner([0, 0]));
        self.nodes.len() - 1
    }

    /// Makes node `ni` a leaf with `tree`, or, while `samples` exceeds `threshold`, an inner
    /// node whose halves each get `samples / 2`.
    fn split_leaf(&mut self, ni: usize, tree: DQuadTree, samples: f64, threshold: f64, depth: u32) {
        let mut stack = vec![(ni, samples, depth)];
        while let Some((n, s, d)) = stack.pop() {
            if s > threshold && d < MAX_SPATIAL_DEPTH {
                let a = self.push_placeholder();
                let b = self.push_placeholder();
                self.nodes[n] = SNode::Inner([a as u32, b as u32]);
                stack.push((a, s / 2.0, d + 1));
                stack.push((b, s / 2.0, d + 1));
            } else {
                self.nodes[n] = SNode::Leaf(self.leaves.len() as u32);
                self.leaves.push(Leaf {
                    tree: tree.clone(),
                    samples: 0,
                    depth: d,
                });
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::unit::clamp_unit;

    /// The grid of the first levels gives the leaf of the full descent from the root, for
    /// a tree split unevenly (deep around a cluster of records, shallow elsewhere).
    #[test]
    fn leaf_index_with_the_top_grid_equals_the_full_descent() {
        let mut t = SdTree::new(Vec3::splat(-1.0), Vec3::ONE);
        for round in 0..4 {
            for i in 0..4000 {
                let f = i as f32 / 4000.0;
                let p = Vec3::new(
                    0.3 + 0.01 * f,
                    0.2 - 0.02 * f,
                    -0.7 + 0.005 * (i % 7) as f32,
                );
                t.record(p, Vec3::Z, 1.0, 1.0);
                t.record(Vec3::splat(f * 2.0 - 1.0), Vec3::X, 1.0, 1.0);
            }
            t = t.refined(50.0 / (round + 1) as f64, 0.01, 20);
        }
        assert!(t.leaf_count() > 100, "{}", t.leaf_count());
        let scale = (1u32 << AXIS_BITS) as f32;
        let mut seen = std::collections::HashSet::new();
        for i in 0..20_000u32 {
            let h = |k: u32| ((i.wrapping_mul(2_654_435_761).wrapping_add(k * 40_503)) >> 8) as f32;
            let p = Vec3::new(h(1) % 1000.0, h(2) % 997.0, h(3) % 991.0) / 500.0 - 1.0;
            let p = if i % 2 == 0 {
                p * 0.02 + Vec3::new(0.3, 0.2, -0.7)
            } else {
                p
            };
            let x = (p - t.min) / t.size;
            let cell = |v: f32| (clamp_unit(v) * scale).min(scale - 1.0) as u32;
            let (n, _) = t.descend([cell(x.x), cell(x.y), cell(x.z)], 0, 0, MAX_SPATIAL_DEPTH);
            let SNode::Leaf(l) = t.nodes[n] else {
                panic!("descent ended at an inner node");
            };
            assert_eq!(t.leaf_index(p), l as usize, "{p}");
            seen.insert(l);
        }
        assert!(seen.len() > 50, "{}", seen.len());
    }
}
