//! The directional quadtree: a piecewise-constant density over the unit square of
//! [`square_to_sphere`](super::square_to_sphere), refined where the recorded energy is.

use super::map::{sphere_to_square, square_to_sphere, SQUARE_TO_SPHERE_JACOBIAN};
use glam::{Vec2, Vec3};

/// The largest `f64` below 1: where the rescaled sample values are clamped.
const ONE_MINUS_EPS_F64: f64 = 1.0 - f64::EPSILON / 2.0;

/// One node: four quadrants (index `x + 2y` with `x, y ∈ {0, 1}` the halves of the node's
/// square), each with the energy recorded in it and its child node (0: a leaf quadrant; the
/// root, node 0, is nobody's child).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct Node {
    sum: [f64; 4],
    child: [u32; 4],
}

impl Node {
    #[inline]
    fn total(&self) -> f64 {
        self.sum[0] + self.sum[1] + self.sum[2] + self.sum[3]
    }
}

/// Where the quadrant's node, and in it the point `x` (rescaled to the quadrant), lies.
#[inline]
fn quadrant(x: [f64; 2]) -> (usize, [f64; 2]) {
    let mut q = 0;
    let mut y = [0.0; 2];
    for k in 0..2 {
        if x[k] < 0.5 {
            y[k] = x[k] * 2.0;
        } else {
            y[k] = x[k] * 2.0 - 1.0;
            q |= 1 << k;
        }
        y[k] = y[k].clamp(0.0, ONE_MINUS_EPS_F64);
    }
    (q, y)
}

/// A directional quadtree (Müller, Gross & Novák 2017, "Practical Path Guiding for Efficient
/// Light-Transport Simulation", CGF 36(4)): a density on the sphere, piecewise constant over
/// the cells of an adaptive quadtree on the equal-area square
/// ([`square_to_sphere`](super::square_to_sphere)), proportional to the energy recorded in
/// each cell.
///
/// [`DQuadTree::sample`] and [`DQuadTree::pdf`] agree exactly: `sample` returns the `pdf` of
/// the direction it returns. A tree with no energy (new, or trained on nothing but zeros) is
/// the uniform sphere, `1/(4π)`; no input gives NaN.
///
/// ```
/// use mcrt::glam::{Vec2, Vec3};
/// use mcrt::sampling::guiding::DQuadTree;
///
/// let mut t = DQuadTree::new();
/// assert!((t.pdf(Vec3::Z) - 1.0 / (4.0 * std::f32::consts::PI)).abs() < 1e-7);
/// t.record(Vec3::Z, 1.0); // all energy near the north pole
/// let t = t.refined(0.01, 20);
/// let (d, pdf) = t.sample(Vec2::new(0.5, 0.5));
/// assert_eq!(pdf, t.pdf(d));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct DQuadTree {
    nodes: Vec<Node>,
}

impl Default for DQuadTree {
    fn default() -> Self {
        Self::new()
    }
}

/// Where a node of a refined tree takes its energy from: a node of the old tree, or a share
/// of a leaf quadrant of the old tree (split evenly among its four sub-quadrants).
#[derive(Clone, Copy)]
enum Source {
    Node(u32),
    Uniform(f64),
}

impl DQuadTree {
    /// A tree of one node with no energy: the uniform sphere.
    pub fn new() -> Self {
        Self {
            nodes: vec![Node::default()],
        }
    }

    /// The number of nodes (each has four quadrants).
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// The depth of the deepest leaf quadrant (1 for a single node).
    pub fn depth(&self) -> u32 {
        let mut best = 0;
        let mut stack = vec![(0u32, 1u32)];
        while let Some((n, d)) = stack.pop() {
            best = best.max(d);
            for &c in &self.nodes[n as usize].child {
                if c != 0 {
                    stack.push((c, d + 1));
                }
            }
        }
        best
    }

    /// The energy recorded in the whole tree.
    pub fn total(&self) -> f64 {
        self.nodes[0].total()
    }

    /// Adds `value` (an estimate of the radiance arriving along the unit direction `dir`
    /// divided by the density it was sampled with) to the cells containing `dir`. A value
    /// that is negative, NaN or infinite is ignored.
    pub fn record(&mut self, dir: Vec3, value: f64) {
        if !(value >= 0.0 && value.is_finite()) {
            return;
        }
        let u = sphere_to_square(dir);
        let mut x = [f64::from(u.x), f64::from(u.y)];
        let mut n = 0usize;
        loop {
            let (q, y) = quadrant(x);
            x = y;
            let node = &mut self.nodes[n];
            node.sum[q] += value;
            match node.child[q] {
                0 => break,
                c => n = c as usize,
            }
        }
    }

    /// The density of [`DQuadTree::sample_square`] at the point `u` of the unit square, per
    /// unit area (1 for the uniform tree); 0 in cells without energy.
    pub fn pdf_square(&self, u: Vec2) -> f32 {
        let mut x = [
            f64::from(u.x).clamp(0.0, ONE_MINUS_EPS_F64),
            f64::from(u.y).clamp(0.0, ONE_MINUS_EPS_F64),
        ];
        if x.iter().any(|v| v.is_nan()) {
            x = [0.5, 0.5];
        }
        let mut pdf = 1.0f64;
        let mut n = 0usize;
        loop {
            let node = &self.nodes[n];
            let (q, y) = quadrant(x);
            x = y;
            let total = node.total();
            if total > 0.0 {
                pdf *= 4.0 * node.sum[q] / total;
                if pdf <= 0.0 {
                    return 0.0;
                }
            }
            match node.child[q] {
                0 => break,
                c => n = c as usize,
            }
        }
        pdf as f32
    }

    /// The density of [`DQuadTree::sample`] at the direction `dir`, per steradian:
    /// [`DQuadTree::pdf_square`] over the Jacobian `4π`.
    pub fn pdf(&self, dir: Vec3) -> f32 {
        self.pdf_square(sphere_to_square(dir)) / SQUARE_TO_SPHERE_JACOBIAN
    }

    /// A point of the unit square drawn from the tree with `u ∈ [0, 1)²` (each node chooses a
    /// column by its energy with `u.x`, a quadrant in it with `u.y`, and passes the rescaled
    /// values on; a leaf quadrant is uniform). A node without energy is uniform.
    pub fn sample_square(&self, u: Vec2) -> Vec2 {
        let mut x = [
            f64::from(u.x).clamp(0.0, ONE_MINUS_EPS_F64),
            f64::from(u.y).clamp(0.0, ONE_MINUS_EPS_F64),
        ];
        if x.iter().any(|v| v.is_nan()) {
            x = [0.5, 0.5];
        }
        let (mut origin, mut size) = ([0.0f64; 2], 1.0f64);
        let mut n = 0usize;
        loop {
            let node = &self.nodes[n];
            let s = node.sum;
            let q = if node.total() > 0.0 {
                let p_left = (s[0] + s[2]) / node.total();
                let bx = pick(&mut x[0], p_left);
                let col = s[bx] + s[bx + 2];
                let p_bottom = if col > 0.0 { s[bx] / col } else { 0.5 };
                let by = pick(&mut x[1], p_bottom);
                bx + 2 * by
            } else {
                let (q, y) = quadrant(x);
                x = y;
                q
            };
            size *= 0.5;
            origin[0] += (q & 1) as f64 * size;
            origin[1] += (q >> 1) as f64 * size;
            match node.child[q] {
                0 => break,
                c => n = c as usize,
            }
        }
        let px = (origin[0] + x[0] * size).clamp(0.0, ONE_MINUS_EPS_F64);
        let py = (origin[1] + x[1] * size).clamp(0.0, ONE_MINUS_EPS_F64);
        Vec2::new(px as f32, py as f32).min(Vec2::splat(crate::sampling::ONE_MINUS_EPSILON))
    }

    /// A direction drawn from the tree with `u ∈ [0, 1)²`, and its density per steradian,
    /// which is exactly [`DQuadTree::pdf`] of that direction.
    pub fn sample(&self, u: Vec2) -> (Vec3, f32) {
        let d = square_to_sphere(self.sample_square(u));
        (d, self.pdf(d))
    }

    /// The tree for the next training iteration, with no energy: every quadrant holding more
    /// than the fraction `rho` of this tree's energy (the paper's ρ = 0.01) is subdivided,
    /// down to `max_depth` levels (the paper's 20); a quadrant of a leaf is judged by an even
    /// share of the leaf's energy. Quadrants with less are merged. A tree with no energy is
    /// refined as if uniform.
    pub fn refined(&self, rho: f64, max_depth: u32) -> DQuadTree {
        let total = self.total();
        let mut out = DQuadTree::new();
        let mut stack = vec![(0usize, Source::Node(0), 1u32)];
        while let Some((ni, src, depth)) = stack.pop() {
            for q in 0..4 {
                let (energy, child_src) = match src {
                    Source::Node(o) => {
                        let node = &self.nodes[o as usize];
                        let e = node.sum[q];
                        match node.child[q] {
                            0 => (e, Source::Uniform(e)),
                            c => (e, Source::Node(c)),
                        }
                    }
                    Source::Uniform(e) => (e / 4.0, Source::Uniform(e / 4.0)),
                };
                let fraction = if total > 0.0 {
                    energy / total
                } else {
                    0.25f64.powi(depth as i32)
                };
                if depth < max_depth && fraction > rho {
                    let c = out.nodes.len();
                    out.nodes.push(Node::default());
                    out.nodes[ni].child[q] = c as u32;
                    stack.push((c, child_src, depth + 1));
                }
            }
        }
        out
    }
}

/// Chooses the lower half with probability `p` and rescales `x` to the chosen half: 0 when
/// `x < p`, else 1.
#[inline]
fn pick(x: &mut f64, p: f64) -> usize {
    let b = if *x < p {
        *x /= p;
        0
    } else {
        *x = (*x - p) / (1.0 - p);
        1
    };
    *x = x.clamp(0.0, ONE_MINUS_EPS_F64);
    if x.is_nan() {
        *x = 0.5;
    }
    b
}

/// The tree as a [`Warp`](crate::sampling::warp::Warp) to the sphere (density per
/// steradian), for the chi-square harness and anything else that takes warps.
impl crate::sampling::warp::Warp for DQuadTree {
    type Point = Vec3;
    #[inline]
    fn sample(&self, u: Vec2) -> Vec3 {
        DQuadTree::sample(self, u).0
    }
    #[inline]
    fn pdf(&self, p: Vec3) -> f32 {
        DQuadTree::pdf(self, p)
    }
    #[inline]
    fn sample_with_pdf(&self, u: Vec2) -> (Vec3, f32) {
        DQuadTree::sample(self, u)
    }
}
