//! A node of the tree and its importance as seen from a point (pbrt-v4's
//! `LightBounds::Importance`, in `f64`, with a conservative zero test). The derivation is in
//! `docs/derivations.md`, Part V.

use glam::DVec3;

use super::cone::Bound;

/// The zero test `cos θ' < cos θ_e − COS_MARGIN`: a light is ruled out only when it is
/// outside its emission cone by this much (rounding never rules out a light that emits).
const COS_MARGIN: f64 = 1e-6;
/// The least value of the two cosine factors of a nonzero importance.
const COS_FLOOR: f64 = 1e-6;
/// The least squared distance (a point exactly on a point light).
const D2_FLOOR: f64 = 1e-200;
/// The margin on `cos(θ_o + θ_e)` of the half-space test, as [`COS_MARGIN`] for the cone test.
const FRONT_MARGIN: f64 = 1e-6;
/// The half-space test applies where `cos(θ_o + θ_e) − FRONT_MARGIN ≥ −MAX_SLACK`: emitted
/// directions make at most about `π/2 + MAX_SLACK` with the axis (diffuse emitters with a
/// narrow cone of normals).
const MAX_SLACK: f64 = 1e-3;
/// The half-space test rules a node out only when `p` lies behind the plane through its
/// box's rearmost corner by this fraction of the coordinates' size (rounding is ~10⁻¹⁶).
const PLANE_MARGIN: f64 = 1e-9;

/// One node: an interior node's first child follows it, `index` is its second child; a
/// leaf's `index` is its light.
#[derive(Clone, Debug)]
pub(super) struct Node {
    center: DVec3,
    radius2: f64,
    axis: DVec3,
    cos_o: f64,
    sin_o: f64,
    cos_e: f64,
    pub phi: f64,
    two_sided: bool,
    /// One-sided with `θ_o + θ_e` at most about `π/2`: its lights emit only to the front
    /// of the plane `axis · x = axis · center − support`, up to `slack` (the half-space test).
    front_only: bool,
    /// `max(0, FRONT_MARGIN − cos(θ_o + θ_e))`: every emitted direction `ω` has
    /// `axis · ω > −slack`.
    slack: f64,
    /// The radius of the bounding sphere.
    radius: f64,
    /// `Σ_k |axis_k| h_k` (`h` the box's half extents): `axis · center` less the least
    /// `axis · x` over the box.
    support: f64,
    /// `|center|₁ + support`: the scale of the half-space test's rounding.
    scale: f64,
    pub leaf: bool,
    pub index: usize,
    /// The node's lights: leaves `first_leaf..end_leaf` in depth-first order.
    pub first_leaf: u32,
    pub end_leaf: u32,
    /// The squared distance from the centre beyond which the descent stops here and picks
    /// among the node's lights by power (infinite: never).
    pub cut_r2: f64,
}

/// `cos(max(0, θa − θb))` from the sines and cosines.
#[inline]
fn cos_sub_clamped(sin_a: f64, cos_a: f64, sin_b: f64, cos_b: f64) -> f64 {
    if cos_a > cos_b {
        1.0
    } else {
        cos_a * cos_b + sin_a * sin_b
    }
}

/// `sin(max(0, θa − θb))` from the sines and cosines.
#[inline]
fn sin_sub_clamped(sin_a: f64, cos_a: f64, sin_b: f64, cos_b: f64) -> f64 {
    if cos_a > cos_b {
        0.0
    } else {
        sin_a * cos_b - cos_a * sin_b
    }
}

#[inline]
fn sin_of(cos: f64) -> f64 {
    (1.0 - cos * cos).max(0.0).sqrt()
}

impl Node {
    /// A node with the bounds `b`.
    pub fn new(b: &Bound, leaf: bool, index: usize, leaves: (u32, u32)) -> Self {
        let half = 0.5 * (b.max - b.min);
        let sin_o = sin_of(b.cos_o);
        let cos_oe = b.cos_o * b.cos_e - sin_o * sin_of(b.cos_e);
        let slack = (FRONT_MARGIN - cos_oe).max(0.0);
        let front_only = !b.two_sided && b.cos_o >= 0.0 && b.cos_e >= 0.0 && slack <= MAX_SLACK;
        let support = b.axis.abs().dot(half);
        let center = b.centroid();
        Self {
            center,
            radius2: half.length_squared(),
            axis: b.axis,
            cos_o: b.cos_o,
            sin_o,
            cos_e: b.cos_e,
            phi: b.phi,
            two_sided: b.two_sided,
            front_only,
            slack,
            radius: half.length(),
            support,
            scale: center.abs().element_sum() + support,
            leaf,
            index,
            first_leaf: leaves.0,
            end_leaf: leaves.1,
            cut_r2: f64::INFINITY,
        }
    }

    /// Whether the node's lights are alike enough to be chosen among by power from far
    /// away (normals within `acos(min_cos_o)` of each other, emission at least as wide as
    /// `acos(max_cos_e)`): then [`Node::cut_at`] holds from `1/tau` radii on.
    pub fn allow_cut(&mut self, min_cos_o: f64, max_cos_e: f64, tau: f64) {
        if !self.leaf && self.cos_o >= min_cos_o && self.cos_e <= max_cos_e {
            self.cut_r2 = self.radius2 / (tau * tau);
        }
    }

    /// Whether the descent stops at this node for the point `p`: `|p − centre|² ≥ cut_r2`.
    #[inline]
    pub fn cut_at(&self, p: DVec3) -> bool {
        (p - self.center).length_squared() >= self.cut_r2
    }

    /// The importance of the node's lights at `p` (normal `n`, unit, or `None`):
    /// `Φ · cos θ' · cos θ'_i / d²`, 0 only where no light of the node can reach `p`.
    pub fn importance(&self, p: DVec3, n: Option<DVec3>) -> f64 {
        let v = p - self.center;
        // Behind the plane of the box's rearmost corner, across the lights' normals: every
        // emitted direction points to the front (derivations, Part V §2).
        if self.front_only
            && self.axis.dot(v) + self.support + self.slack * (v.abs().element_sum() + self.radius)
                < -PLANE_MARGIN * (self.scale + p.abs().element_sum())
        {
            return 0.0;
        }
        let dist2 = v.length_squared();
        // Inside the bounding sphere every direction is possible.
        if dist2 <= self.radius2 {
            return self.phi / self.radius2.max(D2_FLOOR);
        }
        let dist = dist2.sqrt();
        let wi = v / dist;
        // θ_w: the angle between the axis and the direction from the centre to p.
        let mut cos_w = self.axis.dot(wi).clamp(-1.0, 1.0);
        if self.two_sided {
            cos_w = cos_w.abs();
        }
        let sin_w = sin_of(cos_w);
        // θ_b: the half-angle of the bounding sphere seen from p.
        let sin2_b = (self.radius2 / dist2).min(1.0);
        let sin_b = sin2_b.sqrt();
        let cos_b = (1.0 - sin2_b).sqrt();
        // θ' = max(0, θ_w − θ_o − θ_b): the least angle between a normal and p.
        let cos_x = cos_sub_clamped(sin_w, cos_w, self.sin_o, self.cos_o);
        let sin_x = sin_sub_clamped(sin_w, cos_w, self.sin_o, self.cos_o);
        let cos_p = cos_sub_clamped(sin_x, cos_x, sin_b, cos_b);
        if cos_p < self.cos_e - COS_MARGIN {
            return 0.0;
        }
        let mut importance = self.phi * cos_p.max(COS_FLOOR) / dist2.max(D2_FLOOR);
        if let Some(n) = n {
            // θ_i: the angle between ±n and the direction to the centre, less θ_b.
            let cos_i = wi.dot(n).abs().min(1.0);
            let cos_pi = cos_sub_clamped(sin_of(cos_i), cos_i, sin_b, cos_b);
            importance *= cos_pi.max(COS_FLOOR);
        }
        importance
    }
}
