//! A node of the binary tree as built, with what its importance as seen from a point needs
//! (pbrt-v4's `LightBounds::Importance`), and that importance in `f64` with a conservative
//! zero test (the tests' reference for the `f32` lanes of `wide.rs`, which the descent
//! uses). The derivation is in `docs/derivations.md`, Part V.

use glam::DVec3;

use super::cone::Bound;

/// The zero test `cos θ' < cos θ_e − COS_MARGIN`: a light is ruled out only when it is
/// outside its emission cone by this much (rounding never rules out a light that emits).
#[cfg(test)]
const COS_MARGIN: f64 = 1e-6;
/// The least value of the two cosine factors of a nonzero importance.
#[cfg(test)]
const COS_FLOOR: f64 = 1e-6;
/// The least squared distance (a point exactly on a point light).
#[cfg(test)]
const D2_FLOOR: f64 = 1e-200;
/// The margin on `cos(θ_o + θ_e)` of the half-space test, as [`COS_MARGIN`] for the cone test.
const FRONT_MARGIN: f64 = 1e-6;
/// The half-space test applies where `cos(θ_o + θ_e) − FRONT_MARGIN ≥ −MAX_SLACK`: emitted
/// directions make at most about `π/2 + MAX_SLACK` with the axis (diffuse emitters with a
/// narrow cone of normals).
const MAX_SLACK: f64 = 1e-3;
/// The half-space test rules a node out only when `p` lies behind the plane through its
/// box's rearmost corner by this fraction of the coordinates' size (rounding is ~10⁻¹⁶).
#[cfg(test)]
const PLANE_MARGIN: f64 = 1e-9;

/// One child's bounds as one lane of a wide node holds them, in `f32`, rounded so that the
/// bound stays conservative: the sphere and the box's support grown by the rounding of the
/// centre, the cones widened (cosines rounded down).
#[derive(Clone, Copy, Debug)]
pub(super) struct Lane {
    pub center: [f32; 3],
    pub radius2: f32,
    pub radius: f32,
    pub axis: [f32; 3],
    pub cos_o: f32,
    pub sin_o: f32,
    pub cos_e: f32,
    pub phi: f32,
    pub two_sided: bool,
    pub front_only: bool,
    pub slack: f32,
    pub support: f32,
    pub scale: f32,
}

/// `x ≥ 0` rounded up to `f32` (`f32::MAX` at most).
fn up(x: f64) -> f32 {
    let y = x as f32;
    let y = if f64::from(y) >= x { y } else { y.next_up() };
    y.min(f32::MAX)
}

/// `x` rounded down to `f32`.
fn down(x: f64) -> f32 {
    let y = x as f32;
    if f64::from(y) <= x {
        y
    } else {
        y.next_down()
    }
}

/// One node: an interior node's first child follows it, `index` is its second child; a
/// leaf's `index` is its light.
#[derive(Clone, Debug)]
pub(super) struct Node {
    center: DVec3,
    radius2: f64,
    axis: DVec3,
    cos_o: f64,
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
#[cfg(test)]
#[inline]
fn cos_sub_clamped(sin_a: f64, cos_a: f64, sin_b: f64, cos_b: f64) -> f64 {
    if cos_a > cos_b {
        1.0
    } else {
        cos_a * cos_b + sin_a * sin_b
    }
}

/// `sin(max(0, θa − θb))` from the sines and cosines.
#[cfg(test)]
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

    /// The node's bounds as one lane of a wide node (see [`Lane`]).
    pub fn lane(&self) -> Lane {
        let c = self.center.as_vec3();
        let err = (c.as_dvec3() - self.center).length();
        let radius = (self.radius + err) * (1.0 + 1e-6);
        let cos_o = down(self.cos_o);
        Lane {
            center: c.to_array(),
            radius2: up(radius * radius),
            radius: up(radius),
            axis: self.axis.as_vec3().to_array(),
            cos_o,
            sin_o: sin_of(f64::from(cos_o)) as f32,
            cos_e: down(self.cos_e),
            phi: up(self.phi),
            two_sided: self.two_sided,
            front_only: self.front_only,
            slack: up(self.slack),
            support: up(self.support + err),
            scale: up(self.scale + err),
        }
    }

    /// The centre and the squared cut distance in `f32` (see [`Node::allow_cut`]).
    pub fn cut_f32(&self) -> (glam::Vec3, f32) {
        (self.center.as_vec3(), self.cut_r2 as f32)
    }

    /// Whether the node's lights are alike enough to be chosen among by power from far
    /// away (normals within `acos(min_cos_o)` of each other, emission at least as wide as
    /// `acos(max_cos_e)`): then [`Node::cut_at`] holds from `1/tau` radii on.
    pub fn allow_cut(&mut self, min_cos_o: f64, max_cos_e: f64, tau: f64) {
        if !self.leaf && self.cos_o >= min_cos_o && self.cos_e <= max_cos_e {
            self.cut_r2 = self.radius2 / (tau * tau);
        }
    }

    /// The importance of the node's lights at `p` (normal `n`, unit, or `None`):
    /// `Φ · cos θ' · cos θ'_i / d²`, 0 only where no light of the node can reach `p`.
    #[cfg(test)]
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
        let sin_o = sin_of(self.cos_o);
        let cos_x = cos_sub_clamped(sin_w, cos_w, sin_o, self.cos_o);
        let sin_x = sin_sub_clamped(sin_w, cos_w, sin_o, self.cos_o);
        let cos_p = cos_sub_clamped(sin_x, cos_x, sin_b, cos_b);
        if cos_p < self.cos_e - COS_MARGIN {
            return 0.0;
        }
        let mut importance = self.phi * cos_p.max(COS_FLOOR) / dist2.max(D2_FLOOR);
        if let Some(n) = n {
            // θ_i: the angle between ±n and the direction to the centre, less θ_b, bounded
            // as `cos(θ_i − θ_b) ≤ cos θ_i + sin θ_b` (a weight only: not part of the zero).
            let cos_i = wi.dot(n).abs().min(1.0);
            importance *= (cos_i + sin_b).clamp(COS_FLOOR, 1.0);
        }
        importance
    }
}
