//! The build: binned SAOH splits (Conty Estevez & Kulla 2018; pbrt-v4's
//! `BVHLightSampler::buildBVH`, 12 buckets per axis), one light per leaf, with a depth
//! budget that keeps the tree `O(log n)` deep, and the bit trail of every leaf.

use glam::DVec3;

use super::cone::Bound;
use super::node::Node;

/// Buckets per axis of the binned split search.
const BUCKETS: usize = 12;

/// The box extents below this fraction of a node's largest extent count as this fraction
/// in the SAOH area (point lights would otherwise cost nothing).
const MIN_EXTENT_FRACTION: f64 = 1e-3;

/// A light with power > 0: its index in the input and its bounds.
pub(super) type Item = (usize, Bound);

/// `⌈log₂ m⌉` for `m ≥ 1`.
pub(super) fn ceil_log2(m: usize) -> u32 {
    usize::BITS - (m.max(1) - 1).leading_zeros()
}

/// The depth limit for `n` lights: `min(64, 2⌈log₂ n⌉ + 8)` (the wide tree's trails, two bits
/// per level, are `u128`).
pub(super) fn max_depth(n: usize) -> u32 {
    (2 * ceil_log2(n) + 8).min(64)
}

/// The tree under construction.
pub(super) struct Builder {
    pub nodes: Vec<Node>,
    /// The bit trail of each input light's leaf and the leaf's place in depth-first order
    /// (`None`: power 0, not in the tree).
    pub trails: Vec<Option<(u64, u32)>>,
    /// The power of each leaf, in depth-first order.
    pub leaf_power: Vec<f64>,
    /// The light of each leaf, in depth-first order.
    pub leaf_light: Vec<usize>,
    pub depth: u32,
    max_depth: u32,
}

impl Builder {
    /// A builder for `n_lights` input lights of which `n_items` have power > 0.
    pub fn new(n_lights: usize, n_items: usize) -> Self {
        Self {
            nodes: Vec::with_capacity(2 * n_items),
            trails: vec![None; n_lights],
            leaf_power: Vec::with_capacity(n_items),
            leaf_light: Vec::with_capacity(n_items),
            depth: 0,
            max_depth: max_depth(n_items),
        }
    }

    /// Builds the subtree of `items` (non-empty) at `depth` with the bit trail `trail`;
    /// returns its bounds. The node goes at the end of `nodes`, its first child right after.
    pub fn build(&mut self, items: &mut [Item], depth: u32, trail: u64) -> Bound {
        let first_leaf = self.leaf_light.len() as u32;
        if let [(light, b)] = items {
            self.nodes
                .push(Node::new(b, true, *light, (first_leaf, first_leaf + 1)));
            self.trails[*light] = Some((trail, first_leaf));
            self.leaf_power.push(b.phi);
            self.leaf_light.push(*light);
            self.depth = self.depth.max(depth);
            return *b;
        }
        let mid = self.split(items, depth);
        let at = self.nodes.len();
        self.nodes.push(Node::new(&Bound::EMPTY, false, 0, (0, 0)));
        let (first, second) = items.split_at_mut(mid);
        let b0 = self.build(first, depth + 1, trail);
        let second_at = self.nodes.len();
        let b1 = self.build(second, depth + 1, trail | 1 << depth);
        let b = b0.union(&b1);
        let end = self.leaf_light.len() as u32;
        self.nodes[at] = Node::new(&b, false, second_at, (first_leaf, end));
        b
    }

    /// Partitions `items` (two or more) and returns the size of the first part: the
    /// cheapest binned SAOH split whose larger side fits the depth budget, else the median
    /// along the widest axis of the centroids.
    fn split(&self, items: &mut [Item], depth: u32) -> usize {
        let m = items.len();
        // Each side must fit in the levels left below it.
        let budget = self.max_depth - depth - 1;
        let mut bounds = Bound::EMPTY;
        let (mut cmin, mut cmax) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
        for (_, b) in items.iter() {
            bounds = bounds.union(b);
            cmin = cmin.min(b.centroid());
            cmax = cmax.max(b.centroid());
        }
        let diag = bounds.max - bounds.min;
        let min_extent = MIN_EXTENT_FRACTION * diag.max_element();
        let extent = cmax - cmin;
        let bucket = |c: DVec3, dim: usize| -> usize {
            let t = (c[dim] - cmin[dim]) / extent[dim];
            ((BUCKETS as f64 * t) as usize).min(BUCKETS - 1)
        };
        let mut best: Option<(f64, usize, usize)> = None;
        for dim in 0..3 {
            if extent[dim] <= 0.0 {
                continue;
            }
            let mut buckets = [Bound::EMPTY; BUCKETS];
            let mut counts = [0usize; BUCKETS];
            for (_, b) in items.iter() {
                let k = bucket(b.centroid(), dim);
                buckets[k] = buckets[k].union(b);
                counts[k] += 1;
            }
            // right[k]: the union of buckets k.. .
            let mut right = [Bound::EMPTY; BUCKETS];
            let mut acc = Bound::EMPTY;
            for k in (0..BUCKETS).rev() {
                acc = acc.union(&buckets[k]);
                right[k] = acc;
            }
            let mut left = Bound::EMPTY;
            let mut n_left = 0;
            for k in 0..BUCKETS - 1 {
                left = left.union(&buckets[k]);
                n_left += counts[k];
                let n_right = m - n_left;
                if n_left == 0 || n_right == 0 || ceil_log2(n_left.max(n_right)) > budget {
                    continue;
                }
                let cost =
                    left.cost(diag, dim, min_extent) + right[k + 1].cost(diag, dim, min_extent);
                if best.is_none_or(|(c, _, _)| cost < c) {
                    best = Some((cost, dim, k));
                }
            }
        }
        if let Some((_, dim, k)) = best {
            return partition(items, |b| bucket(b.centroid(), dim) <= k);
        }
        // The median: both halves fit the budget (⌈log₂ ⌈m/2⌉⌉ = ⌈log₂ m⌉ − 1).
        let mid = m / 2;
        if extent.max_element() > 0.0 {
            let dim = extent.max_position();
            items.select_nth_unstable_by(mid, |a, b| {
                a.1.centroid()[dim].total_cmp(&b.1.centroid()[dim])
            });
        }
        mid
    }
}

/// Moves the items for which `left` holds to the front; returns their number.
fn partition(items: &mut [Item], left: impl Fn(&Bound) -> bool) -> usize {
    let mut first = 0;
    for i in 0..items.len() {
        if left(&items[i].1) {
            items.swap(first, i);
            first += 1;
        }
    }
    first
}
