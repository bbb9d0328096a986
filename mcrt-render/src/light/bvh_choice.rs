//! The choice of a light for next-event estimation among many: a [`LightBvh`] over every
//! light with a position (each emitting triangle of a mesh a light of its own; points,
//! spots, projectors, and rectangles, disks, spheres and cylinders whole), beside the lights
//! without one (the environment, directional lights), which are chosen by power as before.
//!
//! With `Φ_u` the power of the lights without a position and `Φ` all lights' power, one
//! value `u` chooses between the two groups, `P(unbounded) = Φ_u/Φ`, and is rescaled to
//! `[0, 1)` for the choice within the group: by power among the unbounded lights, by the
//! BVH's importance at the shading point among the others. A light's probability is the
//! product, and [`BvhChoice::pmf`] repeats it, so that the MIS weights of BSDF-sampled
//! hits use the density that sampling had. Every light that can reach the point keeps a
//! positive probability (the BVH's importance is 0 only where a light cannot reach the
//! point), so the estimator stays unbiased: the choice moves samples, never light.

use glam::Vec3;
use mcrt::sampling::distribution::AliasTable;
use mcrt::sampling::light_bvh::{LightBounds, LightBvh};
use mcrt::sampling::ONE_MINUS_EPSILON;

/// Lights with a position (emitting triangles counted one by one) above which the BVH
/// chooses: below, the per-point choice of `choice.rs` (up to its `MAX_SPATIAL` lights) or
/// the power choice stand, as before. Measured in `docs/renderer.md`, "Choosing among many
/// lights".
pub(crate) const BVH_MIN_LIGHTS: usize = super::choice::MAX_SPATIAL;

/// When next-event estimation chooses its light by the light BVH.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LightBvhUse {
    /// Above 16 lights with a position, each emitting triangle of a mesh counted (the
    /// default); below, by power over distance (all lights placed) or by power.
    #[default]
    Auto,
    /// Whenever a light has a position.
    Always,
    /// Never: by power over distance up to 16 lights that all have a position, by power
    /// beyond (the choice before the BVH).
    Never,
}

impl LightBvhUse {
    /// Parses `auto`, `on` or `off`.
    pub fn parse(s: &str) -> Option<Self> {
        Some(match s {
            "auto" => Self::Auto,
            "on" => Self::Always,
            "off" => Self::Never,
            _ => return None,
        })
    }
}

/// One light of the BVH: a light, and its triangle when it is one triangle of a mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct BvhEntry {
    /// The light's index in `Lights::lights`.
    pub(crate) light: u32,
    /// The triangle, or `None` for the whole light.
    pub(crate) triangle: Option<u32>,
}

/// The choice of a light: unbounded lights by power, the others by the BVH.
#[derive(Debug, Clone)]
pub(crate) struct BvhChoice {
    bvh: LightBvh,
    entries: Vec<BvhEntry>,
    /// Per light: the index of its first entry (a mesh's triangle `k` is `first + k`), or
    /// `None` for an unbounded light.
    first: Vec<Option<u32>>,
    /// The unbounded lights' indices and their power distribution.
    unbounded: Vec<u32>,
    unbounded_power: Option<AliasTable>,
    /// Per light: its place in `unbounded`.
    unbounded_slot: Vec<Option<u32>>,
    /// `Φ_u/Φ`: the probability of choosing among the unbounded lights.
    p_unbounded: f32,
}

/// A light chosen by [`BvhChoice::sample`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Chosen {
    /// The light's index.
    pub(crate) light: usize,
    /// Its triangle, when the BVH chose one triangle of a mesh.
    pub(crate) triangle: Option<u32>,
    /// The probability of the choice.
    pub(crate) pick: f32,
}

impl BvhChoice {
    /// The choice over `entries` with their `bounds`, beside the unbounded lights
    /// `unbounded` (indices into `power`, the lights' powers); `lights` lights in all.
    /// `None` when the tree cannot be built (a bound that is not finite) or nothing emits.
    pub(crate) fn new(
        lights: usize,
        entries: Vec<BvhEntry>,
        bounds: &[LightBounds],
        unbounded: Vec<u32>,
        power: &[f32],
    ) -> Option<Self> {
        let bvh = LightBvh::new(bounds).ok()?;
        let mut first = vec![None; lights];
        for (k, e) in entries.iter().enumerate().rev() {
            first[e.light as usize] = Some(k as u32);
        }
        let mut unbounded_slot = vec![None; lights];
        for (k, &i) in unbounded.iter().enumerate() {
            unbounded_slot[i as usize] = Some(k as u32);
        }
        let u_power: Vec<f32> = unbounded.iter().map(|&i| power[i as usize]).collect();
        let total: f64 = power.iter().map(|&p| f64::from(p)).sum();
        let u_total: f64 = u_power.iter().map(|&p| f64::from(p)).sum();
        let bounded_emits = bounds.iter().any(|b| b.power > 0.0);
        let p_unbounded = match (bounded_emits, u_total > 0.0) {
            (false, false) => return None,
            (false, true) => 1.0,
            (true, false) => 0.0,
            (true, true) => (u_total / total) as f32,
        };
        Some(Self {
            bvh,
            entries,
            first,
            unbounded,
            unbounded_power: AliasTable::new(&u_power).ok(),
            unbounded_slot,
            p_unbounded,
        })
    }

    /// The number of lights in the tree.
    pub(crate) fn bvh_lights(&self) -> usize {
        self.entries.len()
    }

    /// Chooses a light at the point `p` with shading normal `n` from `u ∈ [0, 1)`; `None`
    /// when no light can reach `p`.
    #[inline]
    pub(crate) fn sample(&self, p: Vec3, n: Vec3, u: f32) -> Option<Chosen> {
        let pu = self.p_unbounded;
        if u < pu {
            let rest = (u / pu).min(ONE_MINUS_EPSILON);
            let (k, pmf) = self.unbounded_power.as_ref()?.sample_with_pmf(rest);
            return Some(Chosen {
                light: self.unbounded[k] as usize,
                triangle: None,
                pick: pu * pmf,
            });
        }
        let rest = ((u - pu) / (1.0 - pu)).clamp(0.0, ONE_MINUS_EPSILON);
        let (k, prob) = self.bvh.sample(p, n, rest)?;
        let e = self.entries[k];
        Some(Chosen {
            light: e.light as usize,
            triangle: e.triangle,
            pick: (1.0 - pu) * prob,
        })
    }

    /// The probability that [`BvhChoice::sample`] at `p` with normal `n` chooses light
    /// `light` (its triangle `prim` for a mesh split into triangles; ignored otherwise).
    #[inline]
    pub(crate) fn pmf(&self, p: Vec3, n: Vec3, light: usize, prim: u32) -> f32 {
        if let Some(Some(slot)) = self.unbounded_slot.get(light) {
            let pmf = self
                .unbounded_power
                .as_ref()
                .map_or(0.0, |t| t.pmf(*slot as usize));
            return self.p_unbounded * pmf;
        }
        let Some(Some(first)) = self.first.get(light) else {
            return 0.0;
        };
        let k = match self.entries[*first as usize].triangle {
            Some(_) => *first as usize + prim as usize,
            None => *first as usize,
        };
        match self.entries.get(k) {
            Some(e) if e.light as usize == light => {
                (1.0 - self.p_unbounded) * self.bvh.pmf(p, n, k)
            }
            _ => 0.0,
        }
    }

    /// Whether light `light` is split into triangles.
    #[inline]
    pub(crate) fn by_triangle(&self, light: usize) -> bool {
        matches!(self.first.get(light), Some(Some(f)) if self.entries[*f as usize].triangle.is_some())
    }
}
