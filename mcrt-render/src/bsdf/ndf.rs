//! The microfacet normal distribution shared by the rough materials: GGX or Beckmann, with
//! Smith masking and visible-normal sampling.

use glam::{Vec2, Vec3};
use mcrt::sampling::warp::{
    Beckmann, BeckmannVisible, Ggx, GgxVisible, MicrofacetDistribution, Warp,
};
use mcrt::sampling::SamplingError;

/// The normal distribution of a rough material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Ndf {
    /// GGX (Trowbridge–Reitz).
    Ggx(Ggx),
    /// Beckmann.
    Beckmann(Beckmann),
}

impl Ndf {
    /// GGX (`ggx`) or Beckmann of roughness `alpha`.
    ///
    /// # Errors
    /// `alpha` outside the microfacet warps' range `[10⁻⁴, 10⁴]`.
    pub fn new(ggx: bool, alpha: f32) -> Result<Self, SamplingError> {
        Ok(if ggx {
            Ndf::Ggx(Ggx::new(alpha)?)
        } else {
            Ndf::Beckmann(Beckmann::new(alpha)?)
        })
    }

    /// D(m), per steradian of m; 0 for m.z ≤ 0.
    #[inline]
    pub fn d(&self, m: Vec3) -> f32 {
        match self {
            Ndf::Ggx(g) => g.d(m),
            Ndf::Beckmann(b) => b.d(m),
        }
    }

    /// Smith masking G₁(w, m) (Mitsuba's rational Λ for Beckmann); 0 on a facet's back.
    #[inline]
    pub fn g1(&self, w: Vec3, m: Vec3) -> f32 {
        match self {
            Ndf::Ggx(g) => g.g1(w, m),
            Ndf::Beckmann(b) => b.g1(w, m),
        }
    }

    /// Separable Smith shadowing-masking G₁(wo, m) G₁(wi, m).
    #[inline]
    pub fn g(&self, wo: Vec3, wi: Vec3, m: Vec3) -> f32 {
        match self {
            Ndf::Ggx(g) => g.g(wo, wi, m),
            Ndf::Beckmann(b) => b.g(wo, wi, m),
        }
    }

    /// Density of the visible normal `m` seen from `wo` (above the surface), per steradian
    /// of m: G₁(wo) max(0, wo·m) D(m) / cos θ_o.
    #[inline]
    pub fn pdf_visible(&self, wo: Vec3, m: Vec3) -> f32 {
        match self {
            Ndf::Ggx(g) => GgxVisible::new(g.alpha(), wo).map_or(0.0, |v| v.pdf(m)),
            Ndf::Beckmann(b) => BeckmannVisible::new(b.alpha(), wo).map_or(0.0, |v| v.pdf(m)),
        }
    }

    /// A normal visible from `wo` (above the surface) and its density
    /// ([`Ndf::pdf_visible`]); `None` if `wo` is not a valid direction for the warp.
    #[inline]
    pub fn sample_visible(&self, wo: Vec3, u: Vec2) -> Option<(Vec3, f32)> {
        Some(match self {
            Ndf::Ggx(g) => GgxVisible::new(g.alpha(), wo).ok()?.sample_with_pdf(u),
            Ndf::Beckmann(b) => BeckmannVisible::new(b.alpha(), wo).ok()?.sample_with_pdf(u),
        })
    }
}
