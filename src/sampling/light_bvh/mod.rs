//! Choosing one light among many in proportion to a bound on its contribution at a point:
//! the light BVH ([`LightBvh`]) over the [`LightBounds`] of each light.
//!
//! The importance of a node, its zero test and the build cost are derived in
//! `docs/derivations.md`, Part V.

mod bounds;
mod build;
mod cone;
mod node;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_bound;
mod wide;

use glam::Vec3;

pub use bounds::{LightBounds, LightBvhError};
use build::Builder;
use cone::Bound;
use wide::{Query, Wide, WIDTH};

/// The largest `f32` below 1: the remapped sample value stays in `[0, 1)`.
const ONE_BELOW: f32 = 1.0 - f32::EPSILON / 2.0;

/// A bounding volume hierarchy over lights that picks one light at a shading point with
/// probability in proportion to its importance there (after Conty Estevez & Kulla 2018,
/// "Importance Sampling of Many Lights with Adaptive Tree Splitting", Proc. ACM CGIT 1(2),
/// as in pbrt-v4's `BVHLightSampler`).
///
/// Each node bounds its lights' box, normals, emission spread and power. The tree is built
/// binary and walked with up to four children per node; [`LightBvh::sample`] descends from
/// the root choosing a child with probability `I_s/Σ I`, the children's importances at the
/// point (power over squared distance, times bounds on the emitter's and the receiver's
/// cosines), the four evaluated at once in `f32` lanes. [`LightBvh::pmf`] repeats the same
/// arithmetic along the light's path, so the two agree bit for bit. The importance is 0 only
/// where no light of the node can reach the point (behind every emitter: outside the cones
/// its bounding sphere allows, or behind the plane of its box for lights that face one way,
/// with margins that cover the `f32` rounding); where every child of a node is 0 the descent
/// goes on by power, so the probabilities always sum to 1 unless every child of the root is 0
/// (then nothing is sampled). Lights of power 0 are never chosen. Below a node whose lights
/// face one way and which the point sees from afar, the descent stops and picks among its
/// lights by power (the *cut*, which saves the deep levels where the importances differ
/// little). The derivations are in `docs/derivations.md`, Part V.
///
/// Build `O(n log n)` (binned surface area orientation heuristic, one light per leaf,
/// depth at most `min(64, 2⌈log₂ n⌉ + 8)`, then collapsed to four children per node);
/// `sample` and `pmf` `O(log n)`.
///
/// ```
/// use mcrt::glam::Vec3;
/// use mcrt::sampling::light_bvh::{LightBounds, LightBvh};
///
/// let lights = [
///     LightBounds::point(Vec3::new(0.0, 2.0, 0.0), 10.0),
///     // A ceiling panel facing down.
///     LightBounds::planar(Vec3::new(-1.0, 3.0, -1.0), Vec3::new(1.0, 3.0, 1.0), Vec3::NEG_Y, false, 50.0),
///     LightBounds::point(Vec3::new(100.0, 2.0, 0.0), 10.0),
///     // A panel above the ceiling, facing up: it cannot light the floor.
///     LightBounds::planar(Vec3::new(-1.0, 4.0, -1.0), Vec3::new(1.0, 4.0, 1.0), Vec3::Y, false, 50.0),
/// ];
/// let bvh = LightBvh::new(&lights).unwrap();
/// let (p, n) = (Vec3::ZERO, Vec3::Y); // a point on the floor
/// let (light, prob) = bvh.sample(p, n, 0.3).unwrap();
/// assert_eq!(prob, bvh.pmf(p, n, light));
/// let total: f32 = (0..lights.len()).map(|i| bvh.pmf(p, n, i)).sum();
/// assert!((total - 1.0).abs() < 1e-6);
/// assert!(bvh.pmf(p, n, 2) < bvh.pmf(p, n, 0)); // far away
/// assert_eq!(bvh.pmf(p, n, 3), 0.0); // facing away
/// ```
#[derive(Clone, Debug)]
pub struct LightBvh {
    /// The collapsed tree, root first (empty when no light has power > 0).
    nodes: Vec<Wide>,
    /// Per input light: its leaf's trail (two bits per level, the lane taken) and its place
    /// in depth-first order.
    trails: Vec<Option<(u128, u32)>>,
    /// The prefix sums of the leaves' powers in depth-first order (`cdf[k]`: leaves `..k`).
    cdf: Vec<f64>,
    /// The light of each leaf in depth-first order.
    leaf_light: Vec<usize>,
    depth: u32,
}

/// The cut (derivations, Part V §6): below a node whose lights' normals lie within
/// `acos(CUT_MIN_COS_O)` of each other and emit at least as widely as `acos(CUT_MAX_COS_E)`,
/// seen from at least `1/CUT_TAU` of its radii away, the descent stops and picks among the
/// node's lights by power.
const CUT_MIN_COS_O: f64 = 0.9;
/// See [`CUT_MIN_COS_O`].
const CUT_MAX_COS_E: f64 = 0.5;
/// See [`CUT_MIN_COS_O`].
const CUT_TAU: f64 = 0.45;

/// The nodes of the binary tree over `lights` (valid, some of power > 0), as built.
#[cfg(test)]
fn binary_nodes(lights: &[LightBounds]) -> Vec<node::Node> {
    let mut items: Vec<(usize, Bound)> = lights
        .iter()
        .enumerate()
        .filter(|(_, l)| l.power > 0.0)
        .map(|(i, l)| (i, Bound::from_light(l)))
        .collect();
    let mut builder = Builder::new(lights.len(), items.len());
    builder.build(&mut items, 0, 0);
    builder.nodes
}

/// A node's children's weights and their sum (finite: each weight is at most
/// `wide::MAX_WEIGHT`).
#[inline(always)]
fn with_sum(w: [f32; WIDTH]) -> ([f32; WIDTH], f32) {
    (w, (w[0] + w[1]) + (w[2] + w[3]))
}

/// The probability of a child of weight `w > 0` among children of summed weight `sum`:
/// never 0.
#[inline(always)]
fn share(w: f32, sum: f32) -> f64 {
    f64::from((w / sum).max(f32::MIN_POSITIVE))
}

/// The lane chosen by `t ∈ [0, Σw)` among the weights `w` (some positive): the first
/// positive lane whose running sum exceeds `t`, else the last positive lane; and the sum of
/// the weights before it.
#[inline(always)]
fn pick_lane(w: &[f32; WIDTH], t: f32) -> (usize, f32) {
    let mut acc = 0.0;
    let mut pick = (0, 0.0);
    for (s, &ws) in w.iter().enumerate() {
        if ws > 0.0 {
            pick = (s, acc);
            if t < acc + ws {
                break;
            }
            acc += ws;
        }
    }
    pick
}

/// The probability of a path whose every step was positive, as a positive `f32`.
#[inline]
fn to_probability(p: f64) -> f32 {
    (p as f32).max(f32::from_bits(1))
}

impl LightBvh {
    /// Builds the tree over `lights` (light `i` of the slice is index `i` of
    /// [`LightBvh::sample`] and [`LightBvh::pmf`]). An empty slice is valid and samples
    /// nothing.
    ///
    /// # Errors
    /// [`LightBvhError::InvalidLight`] for the first light with a NaN or infinite field, a
    /// box with `max < min`, a cosine outside `[−1, 1]`, a zero axis (unless
    /// `cos_theta_o = −1`) or a power that is negative.
    pub fn new(lights: &[LightBounds]) -> Result<Self, LightBvhError> {
        for (i, l) in lights.iter().enumerate() {
            l.validate(i)?;
        }
        let mut items: Vec<(usize, Bound)> = lights
            .iter()
            .enumerate()
            .filter(|(_, l)| l.power > 0.0)
            .map(|(i, l)| (i, Bound::from_light(l)))
            .collect();
        let mut builder = Builder::new(lights.len(), items.len());
        if !items.is_empty() {
            builder.build(&mut items, 0, 0);
        }
        let mut cdf = Vec::with_capacity(builder.leaf_power.len() + 1);
        let mut acc = 0.0f64;
        cdf.push(acc);
        for &phi in &builder.leaf_power {
            acc += phi;
            cdf.push(acc);
        }
        let mut bin = builder.nodes;
        for node in &mut bin {
            // Every light of a cut node must keep a positive share of the sums.
            let (a, b) = (node.first_leaf as usize, node.end_leaf as usize);
            if cdf[a..=b].windows(2).all(|w| w[1] > w[0]) {
                node.allow_cut(CUT_MIN_COS_O, CUT_MAX_COS_E, CUT_TAU);
            }
        }
        let (nodes, trails, depth) = if bin.is_empty() {
            (Vec::new(), builder.trails.iter().map(|_| None).collect(), 0)
        } else {
            let wide = wide::collapse(&bin, builder.leaf_light.len());
            let trails = builder
                .trails
                .iter()
                .map(|t| t.map(|(_, leaf)| (wide.trails[leaf as usize].0, leaf)))
                .collect();
            let depth = wide.trails.iter().map(|t| t.1).max().unwrap_or(0);
            (wide.nodes, trails, depth)
        };
        Ok(Self {
            nodes,
            trails,
            cdf,
            leaf_light: builder.leaf_light,
            depth,
        })
    }

    /// Whether some node is cut at `p` (for the tests: the cut is exercised).
    #[cfg(test)]
    fn cuts_at(&self, p: Vec3) -> bool {
        self.nodes.iter().skip(1).any(|n| n.cut_at(p))
    }

    /// The probability of leaf `k` (depth-first) among the leaves of `node` by power.
    #[inline]
    fn power_share(&self, node: &Wide, k: usize) -> f64 {
        let total = self.cdf[node.end_leaf as usize] - self.cdf[node.first_leaf as usize];
        (self.cdf[k + 1] - self.cdf[k]) / total
    }

    /// A leaf (depth-first) of `node` chosen by power with `u ∈ [0, 1)`.
    #[inline]
    fn pick_by_power(&self, node: &Wide, u: f64) -> usize {
        let (a, b) = (node.first_leaf as usize, node.end_leaf as usize);
        let t = self.cdf[a] + u * (self.cdf[b] - self.cdf[a]);
        a + self.cdf[a + 1..b].partition_point(|&c| c <= t)
    }

    /// The number of lights given to [`LightBvh::new`] (including those of power 0).
    pub fn len(&self) -> usize {
        self.trails.len()
    }

    /// Whether no light was given.
    pub fn is_empty(&self) -> bool {
        self.trails.is_empty()
    }

    /// The number of levels of the (4-wide) tree above the deepest leaf: a lone light is at
    /// depth 1; at most `min(64, 2⌈log₂ n⌉ + 8)` for `n` lights of power > 0 (the binary
    /// tree's bound), about `⌈log₄ n⌉` for lights spread evenly.
    pub fn depth(&self) -> u32 {
        self.depth
    }

    /// The query at `p` with the unit normal of `n` (none when `n` is zero or not finite),
    /// or `None` when `p` is not finite.
    #[inline(always)]
    fn query(p: Vec3, n: Vec3) -> Option<Query> {
        if !p.is_finite() {
            return None;
        }
        let len = n.length();
        let n = (n.is_finite() && len > 0.0).then(|| n / len);
        Some(Query::new(p, p.abs().element_sum(), n))
    }

    /// The children's weights at node `at` and their sum: importances, or powers when every
    /// importance is 0 (below the root; all 0 at the root when no light reaches `p`).
    #[inline(always)]
    fn step(&self, at: usize, q: &Query) -> ([f32; WIDTH], f32) {
        let node = &self.nodes[at];
        let (w, sum) = with_sum(node.importances(q).to_array());
        if at == 0 || sum > 0.0 {
            (w, sum)
        } else {
            with_sum(node.phi.to_array())
        }
    }

    /// Chooses a light at the point `p` with shading normal `n` (zero in a medium or when
    /// unknown; the importance then has no receiver cosine) from one sample value `u` in
    /// `[0, 1)`. Returns the light's index and the probability of choosing it (equal to
    /// [`LightBvh::pmf`]), or `None` when there is no light of power > 0, when no light can
    /// reach `p`, or when `p` is not finite. A NaN `u` counts as 0.
    pub fn sample(&self, p: Vec3, n: Vec3, u: f32) -> Option<(usize, f32)> {
        let q = Self::query(p, n)?;
        if self.nodes.is_empty() {
            return None;
        }
        let mut u = crate::sampling::unit::clamp_unit(u);
        let mut prob = 1.0f64;
        let mut at = 0;
        loop {
            let node = &self.nodes[at];
            // The root is never cut: its importances say whether any light reaches p.
            if at != 0 && node.cut_at(q.p) {
                let k = self.pick_by_power(node, f64::from(u));
                prob *= self.power_share(node, k);
                return Some((self.leaf_light[k], to_probability(prob)));
            }
            let (w, sum) = self.step(at, &q);
            if sum <= 0.0 {
                return None;
            }
            let t = u * sum;
            let (s, before) = pick_lane(&w, t);
            prob *= share(w[s], sum);
            u = ((t - before) / w[s]).clamp(0.0, ONE_BELOW);
            if node.is_leaf(s) {
                let k = node.child[s] as usize;
                return Some((self.leaf_light[k], to_probability(prob)));
            }
            at = node.child[s] as usize;
        }
    }

    /// The probability that [`LightBvh::sample`] at `p` with normal `n` chooses `light`
    /// (the same arithmetic along the light's path, so it equals the probability `sample`
    /// returns bit for bit). 0 for a light of power 0, an index out of range, or a `p` that
    /// is not finite; 0 for a light that cannot reach `p`, except below a cut, where the
    /// lights of a node are chosen by power (a light that can reach `p` is never 0).
    pub fn pmf(&self, p: Vec3, n: Vec3, light: usize) -> f32 {
        let (Some(q), Some(&Some((mut trail, leaf)))) = (Self::query(p, n), self.trails.get(light))
        else {
            return 0.0;
        };
        let mut prob = 1.0f64;
        let mut at = 0;
        loop {
            let node = &self.nodes[at];
            if at != 0 && node.cut_at(q.p) {
                prob *= self.power_share(node, leaf as usize);
                return to_probability(prob);
            }
            let (w, sum) = self.step(at, &q);
            let s = (trail & 3) as usize;
            if w[s] <= 0.0 {
                return 0.0;
            }
            prob *= share(w[s], sum);
            if node.is_leaf(s) {
                return to_probability(prob);
            }
            at = node.child[s] as usize;
            trail >>= 2;
        }
    }
}
