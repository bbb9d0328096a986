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
    pub leaf: bool,
    pub index: usize,
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
    pub fn new(b: &Bound, leaf: bool, index: usize) -> Self {
        let half = 0.5 * (b.max - b.min);
        Self {
            center: b.centroid(),
            radius2: half.length_squared(),
            axis: b.axis,
            cos_o: b.cos_o,
            sin_o: sin_of(b.cos_o),
            cos_e: b.cos_e,
            phi: b.phi,
            two_sided: b.two_sided,
            leaf,
            index,
        }
    }

    /// The importance of the node's lights at `p` (normal `n`, unit, or `None`):
    /// `Φ · cos θ' · cos θ'_i / d²`, 0 only where no light of the node can reach `p`.
    pub fn importance(&self, p: DVec3, n: Option<DVec3>) -> f64 {
        let v = p - self.center;
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
