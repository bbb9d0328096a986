//! The directional quadtree: a piecewise-constant density over the unit square of
//! [`square_to_sphere`](super::square_to_sphere), refined where the recorded energy is.

use super::map::{sphere_to_square, square_to_sphere, SQUARE_TO_SPHERE_JACOBIAN};
use glam::{Vec2, Vec3};
use std::sync::OnceLock;

mod selection;
mod splat;
mod walk;

use walk::{fixed_point, next_quadrant, pick, quadrant, Cell};

use selection::SELECTION_CANDIDATES;

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

/// What the density's walk reads of a node ([`DQuadTree::pdf_square`]), derived from its
/// sums once per trained tree (no division per lookup): 32 bytes, aligned, so that a node is
/// half a cache line and never straddles two (the walk's loads are dependent, and each miss
/// waits for the last).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[repr(C, align(32))]
struct Shares {
    /// The node's children, as in [`Node`] (so that a lookup reads this array alone).
    child: [u32; 4],
    /// What a descent through each quadrant multiplies the density by: 4 × the quadrant's
    /// share of the node's energy, or 1 in a uniform node (so that the density's walk needs
    /// no branch).
    factor: [f32; 4],
}

/// What sampling reads beyond [`Shares`] ([`DQuadTree::sample_square`]): the share of the
/// left column (quadrants 0 and 2) and of the lower quadrant within each column, kept apart
/// so that the density's walk, far more frequent, reads 32 bytes per node.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[repr(C, align(16))]
struct Split {
    left: f32,
    lower: [f32; 2],
    /// Whether the node holds any energy (a node without is uniform).
    any: bool,
}

/// A node's [`Shares`] and [`Split`].
fn shares_of(n: &Node) -> (Shares, Split) {
    let total = n.total();
    if total.is_nan() || total <= 0.0 {
        let sh = Shares {
            child: n.child,
            factor: [1.0; 4],
        };
        return (sh, Split::default());
    }
    let s = n.sum;
    let col = |x: usize| s[x] + s[x + 2];
    let lower = |x: usize| {
        if col(x) > 0.0 {
            (s[x] / col(x)) as f32
        } else {
            0.5
        }
    };
    let sh = Shares {
        child: n.child,
        factor: s.map(|e| 4.0 * (e / total) as f32),
    };
    let split = Split {
        left: (col(0) / total) as f32,
        lower: [lower(0), lower(1)],
        any: true,
    };
    (sh, split)
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
#[derive(Debug, Clone)]
pub struct DQuadTree {
    nodes: Vec<Node>,
    /// Per candidate of [`SELECTION_CANDIDATES`], the estimated second moment of the
    /// one-sample estimator that would select the guide with that probability (sums over
    /// the selection records), and the number of records.
    selection: [f64; SELECTION_CANDIDATES.len()],
    selection_records: u64,
    /// What lookups derive from the above, made at the first lookup after the last record.
    derived: OnceLock<Derived>,
}

/// See [`DQuadTree::derived`].
#[derive(Debug, Clone)]
struct Derived {
    shares: Vec<Shares>,
    splits: Vec<Split>,
    selection: Option<f32>,
}

impl PartialEq for DQuadTree {
    /// Trees are equal when their nodes (structure and energy) and selection sums are.
    fn eq(&self, other: &Self) -> bool {
        self.nodes == other.nodes
            && self.selection == other.selection
            && self.selection_records == other.selection_records
    }
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
            selection: [0.0; SELECTION_CANDIDATES.len()],
            selection_records: 0,
            derived: OnceLock::new(),
        }
    }

    /// The nodes' shares and the selection probability, derived at the first call after a
    /// change.
    #[inline]
    fn derived(&self) -> &Derived {
        self.derived.get_or_init(|| {
            let (shares, splits) = self.nodes.iter().map(shares_of).unzip();
            Derived {
                shares,
                splits,
                selection: self.best_selection(),
            }
        })
    }

    #[inline]
    fn shares(&self) -> &[Shares] {
        &self.derived().shares
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
        self.record_square(sphere_to_square(dir), value);
    }

    /// [`DQuadTree::record`] of the direction whose point of the square
    /// ([`sphere_to_square`](super::sphere_to_square)) is `u`, for a caller that has mapped
    /// it already.
    pub(crate) fn record_square(&mut self, u: Vec2, value: f64) {
        if !(value >= 0.0 && value.is_finite()) {
            return;
        }
        self.derived.take();
        let mut c = fixed_point(u);
        let mut n = 0usize;
        loop {
            let q = next_quadrant(&mut c);
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
        // Without branches on the point (its quadrants are bits, a uniform node's factor is
        // 1): the walk's branches are taken at random, and mispredicted ones cost more than
        // its arithmetic. The factors are finite and non-negative, so a zero stays zero.
        let mut c = fixed_point(u);
        let shares = self.shares();
        let mut pdf = 1.0f32;
        let mut n = 0usize;
        loop {
            let q = next_quadrant(&mut c);
            let sh = &shares[n];
            pdf *= sh.factor[q];
            match sh.child[q] {
                0 => break,
                c => n = c as usize,
            }
        }
        pdf
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
        self.sample_cell(u).0
    }

    /// [`DQuadTree::sample_square`], with the leaf cell the point was drawn in: its
    /// quadrants' bits per axis ([`fixed_point`]'s highest `depth` bits), its depth, and its
    /// density, multiplied along the walk exactly as [`DQuadTree::pdf_square`] does.
    fn sample_cell(&self, u: Vec2) -> (Vec2, Cell) {
        let mut x = [
            f64::from(u.x).clamp(0.0, ONE_MINUS_EPS_F64),
            f64::from(u.y).clamp(0.0, ONE_MINUS_EPS_F64),
        ];
        if x.iter().any(|v| v.is_nan()) {
            x = [0.5, 0.5];
        }
        let (mut origin, mut size) = ([0.0f64; 2], 1.0f64);
        let d = self.derived();
        let mut cell = Cell {
            bits: [0; 2],
            depth: 0,
            pdf: 1.0,
        };
        let mut n = 0usize;
        loop {
            let (sh, sp) = (&d.shares[n], &d.splits[n]);
            let q = if sp.any {
                let bx = pick(&mut x[0], f64::from(sp.left));
                let by = pick(&mut x[1], f64::from(sp.lower[bx]));
                bx + 2 * by
            } else {
                let (q, y) = quadrant(x);
                x = y;
                q
            };
            size *= 0.5;
            origin[0] += (q & 1) as f64 * size;
            origin[1] += (q >> 1) as f64 * size;
            cell.bits = [
                cell.bits[0] << 1 | (q & 1) as u64,
                cell.bits[1] << 1 | (q >> 1) as u64,
            ];
            cell.depth += 1;
            cell.pdf *= sh.factor[q];
            match sh.child[q] {
                0 => break,
                c => n = c as usize,
            }
        }
        let px = (origin[0] + x[0] * size).clamp(0.0, ONE_MINUS_EPS_F64);
        let py = (origin[1] + x[1] * size).clamp(0.0, ONE_MINUS_EPS_F64);
        let p =
            Vec2::new(px as f32, py as f32).min(Vec2::splat(crate::sampling::ONE_MINUS_EPSILON));
        (p, cell)
    }

    /// A direction drawn from the tree with `u ∈ [0, 1)²`, and its density per steradian,
    /// which is exactly [`DQuadTree::pdf`] of that direction.
    pub fn sample(&self, u: Vec2) -> (Vec3, f32) {
        let (d, pdf, _) = self.sample_on_square(u);
        (d, pdf)
    }

    /// [`DQuadTree::sample`], with the direction's point of the square
    /// ([`sphere_to_square`](super::sphere_to_square) of it, which its density was read at),
    /// so that recording the direction need not map it again.
    #[inline]
    pub(crate) fn sample_on_square(&self, u: Vec2) -> (Vec3, f32, Vec2) {
        let (p, cell) = self.sample_cell(u);
        let d = square_to_sphere(p);
        let s = sphere_to_square(d);
        // The point mapped back to the square is nearly always in the cell it was drawn in,
        // whose density the walk multiplied as `pdf_square` would (the same factors in the
        // same order); only one that rounding moved to another cell walks again.
        let pdf = if cell.contains(s) {
            cell.pdf
        } else {
            self.pdf_square(s)
        };
        (d, pdf / SQUARE_TO_SPHERE_JACOBIAN, s)
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
