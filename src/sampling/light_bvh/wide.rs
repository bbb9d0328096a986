//! The tree the descent walks: the binary SAOH tree collapsed to nodes of up to four
//! children, whose bounds are stored lane by lane in `f32` so that one pass of 4-wide
//! vector arithmetic gives the four children's importances at a point (derivations, Part V
//! §7: the `f32` bound and its margins).

// glam's `Vec4` is four SSE2 lanes on x86-64 (NEON on aarch64), so the library needs no
// SIMD crate of its own (the dependency diet, `downstream/tests/dependencies.rs`).
use glam::{Vec3, Vec4 as f32x4};

use super::node::{Lane, Node};

/// Children per node.
pub(super) const WIDTH: usize = 4;

/// The zero test `cos θ' < cos θ_e − COS_MARGIN` in `f32`: a cosine computed in `f32` from
/// cosines and sines (a sine from `√(1 − c²)` is off by up to `√(2δ)` for a cosine off by
/// `δ ≈ 3·10⁻⁷`) is within `10⁻³` of its value, so a light that emits is never ruled out.
const COS_MARGIN: f32 = 2e-3;
/// The least value of the two cosine factors of a nonzero importance.
const COS_FLOOR: f32 = 1e-6;
/// The least squared distance (a point exactly on a point light).
const D2_FLOOR: f32 = 1e-30;
/// The half-space test rules a child out only when `p` lies behind the plane of its box's
/// rearmost corner by this fraction of the coordinates' size (`f32` rounding is ~10⁻⁷).
const PLANE_MARGIN: f32 = 1e-5;

/// The lane-wise square root (glam's `Vec4` has none; the four are one `sqrtps` where the
/// compiler vectorises them).
#[inline]
fn sqrt4(v: f32x4) -> f32x4 {
    f32x4::from_array(v.to_array().map(f32::sqrt))
}

/// The query of a descent, splatted once for all its nodes: the point, its coordinates in
/// four lanes, `PLANE_MARGIN·|p|₁` (the point's share of the half-space test's margin) and
/// the unit normal's coordinates (or `None`).
#[derive(Clone, Copy, Debug)]
pub(super) struct Query {
    pub p: Vec3,
    px: f32x4,
    py: f32x4,
    pz: f32x4,
    margin: f32x4,
    n: Option<[f32x4; 3]>,
}

impl Query {
    /// The query at `p` (finite) with `|p|₁ = p_l1` and unit normal `n` (or `None`).
    #[inline(always)]
    pub fn new(p: Vec3, p_l1: f32, n: Option<Vec3>) -> Self {
        Self {
            p,
            px: f32x4::splat(p.x),
            py: f32x4::splat(p.y),
            pz: f32x4::splat(p.z),
            margin: f32x4::splat(PLANE_MARGIN * p_l1),
            n: n.map(|n| [f32x4::splat(n.x), f32x4::splat(n.y), f32x4::splat(n.z)]),
        }
    }
}

/// The largest importance of a lane: four of them sum to a finite `f32`.
pub(super) const MAX_WEIGHT: f32 = f32::MAX / 8.0;

/// One node of the collapsed tree: its children's bounds lane by lane (an unused lane has
/// power 0 and gets importance 0), what each child is, and the node's own cut.
#[derive(Clone, Debug)]
pub(super) struct Wide {
    cx: f32x4,
    cy: f32x4,
    cz: f32x4,
    radius2: f32x4,
    ax: f32x4,
    ay: f32x4,
    az: f32x4,
    cos_o: f32x4,
    sin_o: f32x4,
    /// `cos θ_e − COS_MARGIN`: the zero test's threshold.
    cos_e_margin: f32x4,
    /// The children's powers (clamped to [`MAX_WEIGHT`]): the choice where every importance
    /// is 0.
    pub phi: f32x4,
    /// `Φ / max(r², D2_FLOOR)`: the importance at a point inside the bounding sphere.
    near: f32x4,
    /// `−1` for a two-sided child (its `cos θ_w` is taken in absolute value), else `1`.
    flip: f32x4,
    slack: f32x4,
    /// The half-space test's terms that do not depend on the point, rounded up:
    /// `support + σ·r + PLANE_MARGIN·scale` where the test applies, `+∞` where it does not.
    plane_base: f32x4,
    /// Per lane: the child's node in the wide tree, or its leaf (depth-first) when a leaf.
    pub child: [u32; WIDTH],
    /// Bit `s`: lane `s` is a leaf.
    pub leaf_bits: u8,
    /// The node's centre and the squared distance from it beyond which the descent stops here
    /// and picks among its lights by power (infinite: never).
    center: Vec3,
    cut_r2: f32,
    /// The node's lights: leaves `first_leaf..end_leaf` in depth-first order.
    pub first_leaf: u32,
    pub end_leaf: u32,
}

/// `x ≥ 0` (or `+∞`) rounded up to `f32`.
fn round_up(x: f64) -> f32 {
    let y = x as f32;
    if f64::from(y) >= x {
        y
    } else {
        y.next_up()
    }
}

/// What one lane of a [`Wide`] holds for an unused slot: power 0 and harmless bounds.
const EMPTY_LANE: Lane = Lane {
    center: [0.0; 3],
    radius2: 1.0,
    radius: 1.0,
    axis: [0.0, 0.0, 1.0],
    cos_o: 1.0,
    sin_o: 0.0,
    cos_e: 1.0,
    phi: 0.0,
    two_sided: false,
    front_only: false,
    slack: 0.0,
    support: 0.0,
    scale: 0.0,
};

impl Wide {
    /// The node for the binary node `own` with the children `kids` (binary nodes, at most
    /// [`WIDTH`]) whose places in the wide tree are `child` (leaves: their depth-first index).
    fn new(own: &Node, kids: &[&Node], child: [u32; WIDTH]) -> Self {
        let lanes: Vec<Lane> = (0..WIDTH)
            .map(|s| kids.get(s).map_or(EMPTY_LANE, |k| k.lane()))
            .collect();
        let f = |g: fn(&Lane) -> f32| {
            f32x4::from_array([g(&lanes[0]), g(&lanes[1]), g(&lanes[2]), g(&lanes[3])])
        };
        let mut leaf_bits = 0u8;
        for (s, k) in kids.iter().enumerate() {
            if k.leaf {
                leaf_bits |= 1 << s;
            }
        }
        let (center, cut_r2) = own.cut_f32();
        let plane_base = |l: &Lane| {
            if l.front_only {
                round_up(
                    f64::from(l.support)
                        + f64::from(l.slack) * f64::from(l.radius)
                        + f64::from(PLANE_MARGIN) * f64::from(l.scale),
                )
            } else {
                f32::INFINITY
            }
        };
        Self {
            cx: f(|l| l.center[0]),
            cy: f(|l| l.center[1]),
            cz: f(|l| l.center[2]),
            radius2: f(|l| l.radius2),
            ax: f(|l| l.axis[0]),
            ay: f(|l| l.axis[1]),
            az: f(|l| l.axis[2]),
            cos_o: f(|l| l.cos_o),
            sin_o: f(|l| l.sin_o),
            cos_e_margin: f(|l| l.cos_e - COS_MARGIN),
            phi: f(|l| l.phi.min(MAX_WEIGHT)),
            near: f(|l| l.phi / l.radius2.max(D2_FLOOR)),
            flip: f(|l| if l.two_sided { -1.0 } else { 1.0 }),
            slack: f(|l| l.slack),
            plane_base: f32x4::from_array([
                plane_base(&lanes[0]),
                plane_base(&lanes[1]),
                plane_base(&lanes[2]),
                plane_base(&lanes[3]),
            ]),
            child,
            leaf_bits,
            center,
            cut_r2,
            first_leaf: own.first_leaf,
            end_leaf: own.end_leaf,
        }
    }

    /// A node whose one lane is `node` (for the tests).
    #[cfg(test)]
    pub fn single(node: &Node) -> Self {
        Self::new(node, &[node], [0; WIDTH])
    }

    /// Whether lane `s` is a leaf.
    #[inline]
    pub fn is_leaf(&self, s: usize) -> bool {
        self.leaf_bits >> s & 1 == 1
    }

    /// Whether the descent stops at this node for the point `p`.
    #[inline]
    pub fn cut_at(&self, p: Vec3) -> bool {
        (p - self.center).length_squared() >= self.cut_r2
    }

    /// The four children's importances at the query `q`: `Φ · cos θ' · cos θ'_i / d²` as in
    /// `Node::importance`, in `f32`, 0 only where no light of the child can reach `q.p` (and
    /// for unused lanes), never NaN, at most [`MAX_WEIGHT`].
    #[inline(always)]
    pub fn importances(&self, q: &Query) -> f32x4 {
        let zero = f32x4::ZERO;
        let one = f32x4::ONE;
        let vx = q.px - self.cx;
        let vy = q.py - self.cy;
        let vz = q.pz - self.cz;
        // Behind the plane of the box's rearmost corner (derivations, Part V §2).
        let l1 = vx.abs() + vy.abs() + vz.abs();
        let plane = self.ax * vx
            + self.ay * vy
            + self.az * vz
            + self.slack * l1
            + self.plane_base
            + q.margin;
        let behind = plane.cmplt(zero);
        let dist2 = vx * vx + vy * vy + vz * vz;
        let inside = dist2.cmple(self.radius2);
        let inv = one / sqrt4(dist2);
        let (wx, wy, wz) = (vx * inv, vy * inv, vz * inv);
        // θ_w: between the axis and the direction from the centre to p. (Cosines a few ulps
        // outside [−1, 1] are harmless: the sines below are of `max(0, 1 − c²)`, and a bound
        // that comes out at most a few ulps high stays a bound.)
        let cos_w = self.ax * wx + self.ay * wy + self.az * wz;
        let cos_w = cos_w.max(cos_w * self.flip);
        let sin_w = sqrt4((one - cos_w * cos_w).max(zero));
        // θ_b: the half-angle of the bounding sphere seen from p (outside it, `r² < d²`; the
        // lanes inside get `near` below).
        let sin2_b = self.radius2 / dist2;
        let sin_b = sqrt4(sin2_b);
        let cos_b = sqrt4(one - sin2_b);
        // θ_x = θ_w − θ_o, and θ' = max(0, θ_x − θ_b): 0 where θ_x ≤ 0 (`sin θ_x ≤ 0`) or
        // θ_x ≤ θ_b.
        let cos_x = cos_w * self.cos_o + sin_w * self.sin_o;
        let sin_x = sin_w * self.cos_o - cos_w * self.sin_o;
        let flat = sin_x.cmple(zero) | cos_x.cmpgt(cos_b);
        let cos_p = f32x4::select(flat, one, cos_x * cos_b + sin_x * sin_b);
        let outside_e = cos_p.cmplt(self.cos_e_margin);
        let floor = f32x4::splat(COS_FLOOR);
        let mut imp = self.phi * cos_p.max(floor) / dist2;
        if let Some([nx, ny, nz]) = q.n {
            // θ_i: between ±n and the direction to the centre, less θ_b, bounded as
            // `cos(θ_i − θ_b) ≤ cos θ_i + sin θ_b` (this factor is a weight, not part of the
            // zero test, so it only needs to stay positive).
            let cos_i = (wx * nx + wy * ny + wz * nz).abs();
            imp *= (cos_i + sin_b).min(one).max(floor);
        }
        let imp = f32x4::select(inside, self.near, f32x4::select(outside_e, zero, imp));
        // The half-space test holds inside the bounding sphere too.
        let imp = f32x4::select(behind, zero, imp);
        // NaN (an overflowing query) → 0; large → MAX_WEIGHT.
        f32x4::select(imp.cmpgt(zero), imp.min(f32x4::splat(MAX_WEIGHT)), zero)
    }
}

/// The wide tree of the binary tree `bin` (root at 0): nodes in depth-first order from the
/// root, and per binary leaf its trail (two bits per level: the lane taken) and depth.
pub(super) struct Collapsed {
    pub nodes: Vec<Wide>,
    /// Per depth-first leaf: the lanes taken from the root, two bits per level, and the
    /// number of levels.
    pub trails: Vec<(u128, u32)>,
}

/// Collapses `bin` (non-empty) into nodes of up to [`WIDTH`] children, opening at each step
/// the interior child with the most lights (so the tree stays balanced). Each wide level
/// takes at least one binary level, so the wide tree is no deeper than the binary one.
pub(super) fn collapse(bin: &[Node], n_leaves: usize) -> Collapsed {
    let mut out = Collapsed {
        nodes: Vec::new(),
        trails: vec![(0, 0); n_leaves],
    };
    collapse_at(bin, 0, 0, 0, &mut out);
    out
}

/// The number of lights below binary node `k`.
fn lights(bin: &[Node], k: usize) -> u32 {
    bin[k].end_leaf - bin[k].first_leaf
}

/// Adds the wide node for binary node `at` (at wide depth `depth`, reached by `trail`) and
/// its subtree; returns its index.
fn collapse_at(bin: &[Node], at: usize, depth: u32, trail: u128, out: &mut Collapsed) -> u32 {
    let mut kids: Vec<usize> = if bin[at].leaf {
        vec![at]
    } else {
        vec![at + 1, bin[at].index]
    };
    while kids.len() < WIDTH {
        let widest = (0..kids.len())
            .filter(|&j| !bin[kids[j]].leaf)
            .max_by_key(|&j| (lights(bin, kids[j]), usize::MAX - j));
        let Some(j) = widest else { break };
        let k = kids[j];
        kids.splice(j..=j, [k + 1, bin[k].index]);
    }
    let me = out.nodes.len();
    // A placeholder, replaced below once the children's places are known.
    out.nodes.push(Wide::new(&bin[at], &[], [0; WIDTH]));
    let mut child = [0u32; WIDTH];
    for (s, &k) in kids.iter().enumerate() {
        let t = trail | (s as u128) << (2 * depth);
        child[s] = if bin[k].leaf {
            out.trails[bin[k].first_leaf as usize] = (t, depth + 1);
            bin[k].first_leaf
        } else {
            collapse_at(bin, k, depth + 1, t, out)
        };
    }
    let refs: Vec<&Node> = kids.iter().map(|&k| &bin[k]).collect();
    out.nodes[me] = Wide::new(&bin[at], &refs, child);
    me as u32
}
