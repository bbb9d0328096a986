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

use glam::{DVec3, Vec3};

pub use bounds::{LightBounds, LightBvhError};
use build::Builder;
use cone::Bound;
use node::Node;

/// The largest `f64` below 1: the remapped sample value stays in `[0, 1)`.
const ONE_BELOW: f64 = 1.0 - f64::EPSILON / 2.0;

/// A bounding volume hierarchy over lights that picks one light at a shading point with
/// probability in proportion to its importance there (after Conty Estevez & Kulla 2018,
/// "Importance Sampling of Many Lights with Adaptive Tree Splitting", Proc. ACM CGIT 1(2),
/// as in pbrt-v4's `BVHLightSampler`).
///
/// Each node bounds its lights' box, normals, emission spread and power; [`LightBvh::sample`]
/// descends from the root choosing a child with probability `I₀/(I₀ + I₁)`, the children's
/// importances at the point (power over squared distance, times bounds on the emitter's and
/// the receiver's cosines). [`LightBvh::pmf`] repeats the same arithmetic along the light's
/// path, so the two agree bit for bit. The importance is 0 only where no light of the node
/// can reach the point (behind every emitter: outside the cones its bounding sphere allows,
/// or behind the plane of its box for lights that face one way); where both children of a
/// node are 0 the descent goes on by power, so the probabilities always sum to 1 unless the
/// root's importance is 0 (then nothing is sampled). Lights of power 0 are never chosen. Below a
/// node whose lights face one way and which the point sees from afar, the descent stops
/// and picks among its lights by power (the *cut*, which saves the deep levels where the
/// importances differ little). The derivations are in `docs/derivations.md`, Part V.
///
/// Build `O(n log n)` (binned surface area orientation heuristic, one light per leaf,
/// depth at most `min(64, 2⌈log₂ n⌉ + 8)`); `sample` and `pmf` `O(log n)`.
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
    nodes: Vec<Node>,
    /// Per input light: its leaf's bit trail and its place in depth-first order.
    trails: Vec<Option<(u64, u32)>>,
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

/// The probabilities of the two children from their weights (`w₀ + w₁ > 0`); a child of
/// positive weight never gets probability 0.
#[inline]
fn child_probabilities(w0: f64, w1: f64) -> (f64, f64) {
    let sum = w0 + w1;
    let p = |w: f64| {
        if w > 0.0 {
            (w / sum).max(f64::MIN_POSITIVE)
        } else {
            0.0
        }
    };
    (p(w0), p(w1))
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
        let mut nodes = builder.nodes;
        for node in &mut nodes {
            // Every light of a cut node must keep a positive share of the sums.
            let (a, b) = (node.first_leaf as usize, node.end_leaf as usize);
            if cdf[a..=b].windows(2).all(|w| w[1] > w[0]) {
                node.allow_cut(CUT_MIN_COS_O, CUT_MAX_COS_E, CUT_TAU);
            }
        }
        Ok(Self {
            nodes,
            trails: builder.trails,
            cdf,
            leaf_light: builder.leaf_light,
            depth: builder.depth,
        })
    }

    /// Whether some interior node is cut at `p` (for the tests: the cut is exercised).
    #[cfg(test)]
    fn cuts_at(&self, p: Vec3) -> bool {
        self.nodes.iter().any(|n| n.cut_at(p.as_dvec3()))
    }

    /// The probability of leaf `k` (depth-first) among the leaves of `node` by power.
    #[inline]
    fn power_share(&self, node: &Node, k: usize) -> f64 {
        let total = self.cdf[node.end_leaf as usize] - self.cdf[node.first_leaf as usize];
        (self.cdf[k + 1] - self.cdf[k]) / total
    }

    /// A leaf (depth-first) of `node` chosen by power with `u ∈ [0, 1)`.
    #[inline]
    fn pick_by_power(&self, node: &Node, u: f64) -> usize {
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

    /// The depth of the deepest leaf (the root is depth 0): at most
    /// `min(64, 2⌈log₂ n⌉ + 8)` for `n` lights of power > 0.
    pub fn depth(&self) -> u32 {
        self.depth
    }

    /// The point as `f64` and the unit normal (`None` when `n` is zero or not finite), or
    /// `None` when `p` is not finite.
    fn query(p: Vec3, n: Vec3) -> Option<(DVec3, Option<DVec3>)> {
        if !p.is_finite() {
            return None;
        }
        let n = n.as_dvec3();
        let len = n.length();
        let n = (n.is_finite() && len > 0.0).then(|| n / len);
        Some((p.as_dvec3(), n))
    }

    /// The children's probabilities at node `at` (interior): importances, or powers when
    /// both importances are 0.
    #[inline]
    fn step(&self, at: usize, p: DVec3, n: Option<DVec3>) -> (f64, f64, usize) {
        let (c0, c1) = (&self.nodes[at + 1], &self.nodes[self.nodes[at].index]);
        let (i0, i1) = (c0.importance(p, n), c1.importance(p, n));
        let (p0, p1) = if i0 + i1 > 0.0 {
            child_probabilities(i0, i1)
        } else {
            child_probabilities(c0.phi, c1.phi)
        };
        (p0, p1, self.nodes[at].index)
    }

    /// Chooses a light at the point `p` with shading normal `n` (zero in a medium or when
    /// unknown; the importance then has no receiver cosine) from one sample value `u` in
    /// `[0, 1)`. Returns the light's index and the probability of choosing it (equal to
    /// [`LightBvh::pmf`]), or `None` when there is no light of power > 0, when no light can
    /// reach `p`, or when `p` is not finite. A NaN `u` counts as 0.
    pub fn sample(&self, p: Vec3, n: Vec3, u: f32) -> Option<(usize, f32)> {
        let (p, n) = Self::query(p, n)?;
        let root = self.nodes.first()?;
        if root.importance(p, n) <= 0.0 {
            return None;
        }
        let mut u = f64::from(crate::sampling::unit::clamp_unit(u));
        let mut prob = 1.0f64;
        let mut at = 0;
        while !self.nodes[at].leaf {
            let node = &self.nodes[at];
            if node.cut_at(p) {
                let k = self.pick_by_power(node, u);
                prob *= self.power_share(node, k);
                return Some((self.leaf_light[k], to_probability(prob)));
            }
            let (p0, p1, second) = self.step(at, p, n);
            if u < p0 {
                prob *= p0;
                u = (u / p0).min(ONE_BELOW);
                at += 1;
            } else {
                prob *= p1;
                u = ((u - p0) / p1).clamp(0.0, ONE_BELOW);
                at = second;
            }
        }
        Some((self.nodes[at].index, to_probability(prob)))
    }

    /// The probability that [`LightBvh::sample`] at `p` with normal `n` chooses `light`
    /// (the same arithmetic along the light's path, so it equals the probability `sample`
    /// returns bit for bit). 0 for a light of power 0, an index out of range, or a `p` that
    /// is not finite; 0 for a light that cannot reach `p`, except below a cut, where the
    /// lights of a node are chosen by power (a light that can reach `p` is never 0).
    pub fn pmf(&self, p: Vec3, n: Vec3, light: usize) -> f32 {
        let (Some((p, n)), Some(&Some((mut trail, leaf)))) =
            (Self::query(p, n), self.trails.get(light))
        else {
            return 0.0;
        };
        if self.nodes[0].importance(p, n) <= 0.0 {
            return 0.0;
        }
        let mut prob = 1.0f64;
        let mut at = 0;
        while !self.nodes[at].leaf {
            let node = &self.nodes[at];
            if node.cut_at(p) {
                prob *= self.power_share(node, leaf as usize);
                return to_probability(prob);
            }
            let (p0, p1, second) = self.step(at, p, n);
            let (pc, next) = if trail & 1 == 0 {
                (p0, at + 1)
            } else {
                (p1, second)
            };
            if pc == 0.0 {
                return 0.0;
            }
            prob *= pc;
            at = next;
            trail >>= 1;
        }
        to_probability(prob)
    }
}
