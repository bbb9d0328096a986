//! The directional quadtree: a piecewise-constant density over the unit square of
//! [`square_to_sphere`](super::square_to_sphere), refined where the recorded energy is.

use super::map::{sphere_to_square, square_to_sphere, SQUARE_TO_SPHERE_JACOBIAN};
use glam::{Vec2, Vec3};
use std::sync::OnceLock;

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

/// The point `u` of the unit square as fixed-point coordinates per axis, clamped into the
/// square (a NaN coordinate puts the point at the centre), whose bits from the highest are
/// the halves a descent takes: the same halves as halving the coordinates in `f64`
/// ([`quadrant`]), which is exact for the `f32` coordinates down to 63 levels. (`⌊u·2⁶³⌋`,
/// shifted up by one: the conversion to a signed integer is a few instructions fewer than to
/// an unsigned one; the lowest bit, a 64th level, is 0.)
#[inline]
fn fixed_point(u: Vec2) -> [u64; 2] {
    if u.is_nan() {
        return [1 << 63; 2];
    }
    // `as` saturates: below 0 gives 0, 1 and above all ones but the lowest bit (the last
    // cell, as the clamp to just below 1 of the `f64` descent).
    let fix = |v: f32| ((f64::from(v) * 9_223_372_036_854_775_808.0) as i64 as u64) << 1;
    [fix(u.x), fix(u.y)]
}

/// The quadrant of the fixed-point point `c` ([`fixed_point`]) in its current node, and `c`
/// rescaled to that quadrant: the top bit of each coordinate, shifted out.
#[inline(always)]
fn next_quadrant(c: &mut [u64; 2]) -> usize {
    let q = (c[0] >> 63) | ((c[1] >> 63) << 1);
    c[0] <<= 1;
    c[1] <<= 1;
    q as usize
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

/// The candidates for the probability of sampling the guide that a tree judges
/// ([`DQuadTree::selection_probability`]).
pub(crate) const SELECTION_CANDIDATES: [f32; 10] =
    [0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9];

/// The fewest selection records from which a tree gives a selection probability.
const MIN_SELECTION_RECORDS: u64 = 64;

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

    /// The probability with which the guided path tracer should sample this tree rather
    /// than the BSDF, learned from what it saw while the tree trained: the candidate of
    /// 0, 0.1, …, 0.9 with the least estimated second moment of the one-sample estimator
    /// `F/q_α`, `q_α = α·p_guide + (1 − α)·p_bsdf` (the smallest on ties). The estimate is
    /// `Σ F²/(q·q_α)` over the records, each sampled with the mixture `q` in use then
    /// (importance sampling of `∫F²/q_α`). `None` before 64 records, or where the tree
    /// did not learn ([`SdTree::learn_selection`](super::SdTree::learn_selection)).
    ///
    /// The estimate judges the candidates with the density of the guide that sampled the
    /// records, older than this tree; the guide improves as it trains, so the choice errs
    /// towards the BSDF.
    pub fn selection_probability(&self) -> Option<f32> {
        self.derived().selection
    }

    fn best_selection(&self) -> Option<f32> {
        if self.selection_records < MIN_SELECTION_RECORDS {
            return None;
        }
        let mut best: Option<(f64, f32)> = None;
        for (m, a) in self.selection.iter().zip(SELECTION_CANDIDATES) {
            if m.is_finite() && best.is_none_or(|(b, _)| *m < b) {
                best = Some((*m, a));
            }
        }
        best.map(|(_, a)| a)
    }

    /// Adds one selection record: a direction sampled with the mixture density `pdf`, where
    /// the guide's density is `p_guide`, the BSDF's `p_bsdf` and the integrand
    /// `F = f·|cos θ|·L` is `integrand`. A candidate under which the direction has zero
    /// density while `F > 0` gets an infinite second moment. Records with a density that
    /// is not positive and finite, or an integrand that is negative or not finite, are
    /// ignored.
    pub(crate) fn record_selection(&mut self, integrand: f32, p_guide: f32, p_bsdf: f32, pdf: f32) {
        let ok = |x: f32| x >= 0.0 && x.is_finite();
        if !(pdf > 0.0 && pdf.is_finite() && ok(integrand) && ok(p_guide) && ok(p_bsdf)) {
            return;
        }
        self.derived.take();
        let f2 = f64::from(integrand) * f64::from(integrand);
        if p_bsdf > 0.0 {
            // Every candidate's density is positive (`1 − α ≥ 0.1`): the same sums without a
            // branch per candidate, which the compiler vectorises.
            let (pg, pb, pdf) = (f64::from(p_guide), f64::from(p_bsdf), f64::from(pdf));
            for (m, a) in self.selection.iter_mut().zip(SELECTION_CANDIDATES) {
                let q = f64::from(a) * pg + f64::from(1.0 - a) * pb;
                *m += f2 / (pdf * q);
            }
            self.selection_records += 1;
            return;
        }
        for (m, a) in self.selection.iter_mut().zip(SELECTION_CANDIDATES) {
            let q = f64::from(a) * f64::from(p_guide) + f64::from(1.0 - a) * f64::from(p_bsdf);
            if q > 0.0 {
                *m += f2 / (f64::from(pdf) * q);
            } else if f2 > 0.0 {
                *m = f64::INFINITY;
            }
        }
        self.selection_records += 1;
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

    /// The side of the leaf cell of the square containing `u` (`2^-depth`).
    fn leaf_side(&self, u: Vec2) -> f64 {
        let mut c = fixed_point(u);
        let (mut n, mut side) = (0usize, 0.5f64);
        loop {
            let q = next_quadrant(&mut c);
            match self.nodes[n].child[q] {
                0 => return side,
                c => (n, side) = (c as usize, side * 0.5),
            }
        }
    }

    /// [`DQuadTree::record_square`] through the directional box filter (Müller 2019,
    /// "Practical Path Guiding in Production"): `value` is spread over the
    /// square of the side of the leaf cell containing `u`, centred on `u`, each cell taking
    /// the share of it that it overlaps. The box is shifted inside the square along
    /// `cos θ` (x; the poles are its edges) and wraps around along `φ` (y, periodic), so
    /// the whole `value` is recorded. A value that is negative, NaN or infinite is ignored.
    pub(crate) fn record_square_filtered(&mut self, u: Vec2, value: f64) {
        if !(value >= 0.0 && value.is_finite()) {
            return;
        }
        let u = [
            f64::from(u.x).clamp(0.0, ONE_MINUS_EPS_F64),
            f64::from(u.y).clamp(0.0, ONE_MINUS_EPS_F64),
        ];
        if u.iter().any(|v| v.is_nan()) {
            return;
        }
        let side = self.leaf_side(Vec2::new(u[0] as f32, u[1] as f32));
        let density = value / (side * side);
        let x0 = (u[0] - 0.5 * side).clamp(0.0, 1.0 - side);
        let y0 = u[1] - 0.5 * side;
        let x = [x0, x0 + side];
        if y0 < 0.0 {
            self.splat([x, [y0 + 1.0, 1.0]], density);
            self.splat([x, [0.0, y0 + side]], density);
        } else if y0 + side > 1.0 {
            self.splat([x, [y0, 1.0]], density);
            self.splat([x, [0.0, y0 + side - 1.0]], density);
        } else {
            self.splat([x, [y0, y0 + side]], density);
        }
    }

    /// Adds `density` times the area of overlap with the box `[x0, x1] × [y0, y1]` (inside
    /// the unit square) to every quadrant that overlaps it, at every level.
    fn splat(&mut self, b: [[f64; 2]; 2], density: f64) {
        self.derived.take();
        self.splat_node(0, [0.0; 2], 1.0, &b, density);
    }

    /// [`DQuadTree::splat`] below node `n`, whose square has the lower corner `origin` and
    /// the side `side` (recursive: at most 20 levels).
    fn splat_node(&mut self, n: usize, origin: [f64; 2], side: f64, b: &[[f64; 2]; 2], d: f64) {
        let h = 0.5 * side;
        for q in 0..4 {
            let o = [
                origin[0] + (q & 1) as f64 * h,
                origin[1] + (q >> 1) as f64 * h,
            ];
            let w = |k: usize| (b[k][1].min(o[k] + h) - b[k][0].max(o[k])).max(0.0);
            let area = w(0) * w(1);
            if area > 0.0 {
                let node = &mut self.nodes[n];
                node.sum[q] += d * area;
                let c = node.child[q];
                if c != 0 {
                    self.splat_node(c as usize, o, h, b, d);
                }
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

/// The leaf cell a sample was drawn in ([`DQuadTree::sample_cell`]).
#[derive(Debug, Clone, Copy)]
struct Cell {
    /// Per axis, the halves the walk took, the first in the highest of `depth` bits.
    bits: [u64; 2],
    depth: u32,
    /// The density of [`DQuadTree::pdf_square`] in the cell.
    pdf: f32,
}

impl Cell {
    /// Whether the point `u` of the square is in the cell: the highest `depth` bits of its
    /// fixed-point coordinates ([`fixed_point`]), the quadrants `pdf_square` would walk,
    /// are the cell's.
    #[inline]
    fn contains(&self, u: Vec2) -> bool {
        if self.depth == 0 || self.depth > 63 {
            return false;
        }
        let c = fixed_point(u);
        let shift = 64 - self.depth;
        (c[0] >> shift) == self.bits[0] && (c[1] >> shift) == self.bits[1]
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
