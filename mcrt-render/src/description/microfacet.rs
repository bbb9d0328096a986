//! The rough surface of the microfacet materials (`roughconductor`, `roughdielectric`,
//! `roughplastic`): one value holds every microfacet parameter, so that a parameter added
//! here reaches every rough material, and the loader and the normal distribution (`Ndf::of`)
//! are the only other places that name it.

use super::{MicrofacetKind, Roughness};

/// A rough material's microfacet parameters, each already checked.
///
/// ```
/// use mcrt_render::description::{Microfacet, MicrofacetKind, Roughness};
///
/// let m = Microfacet::new(MicrofacetKind::Ggx, Roughness::new(0.3)?);
/// assert!(m.sample_visible); // Mitsuba 3's default
/// assert_eq!(Microfacet::DEFAULT.alpha, Roughness::DEFAULT);
/// assert!(!m.is_anisotropic());
/// let brushed = Microfacet::anisotropic(MicrofacetKind::Ggx, Roughness::new(0.05)?, Roughness::new(0.3)?);
/// assert!(brushed.is_anisotropic());
/// # Ok::<(), mcrt_render::validate::Invalid>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Microfacet {
    /// The normal distribution (`distribution`, default Beckmann).
    pub distribution: MicrofacetKind,
    /// Roughness α (`alpha`, default 0.1), or αᵤ along the shading tangent `dp/du`
    /// (`alpha_u`).
    pub alpha: Roughness,
    /// Roughness αᵥ along the bitangent (`alpha_v`); equal to `alpha` for an isotropic
    /// surface.
    pub alpha_v: Roughness,
    /// Sample the normals visible from the incident direction (`sample_visible`, default
    /// true), else the whole distribution: the same expected value, more noise.
    pub sample_visible: bool,
}

impl Microfacet {
    /// Mitsuba 3's defaults: Beckmann, α = 0.1, visible normals.
    pub const DEFAULT: Microfacet = Microfacet {
        distribution: MicrofacetKind::Beckmann,
        alpha: Roughness::DEFAULT,
        alpha_v: Roughness::DEFAULT,
        sample_visible: true,
    };

    /// Distribution `distribution` of isotropic roughness `alpha`, the other parameters at
    /// their defaults.
    pub const fn new(distribution: MicrofacetKind, alpha: Roughness) -> Self {
        Self {
            distribution,
            alpha,
            alpha_v: alpha,
            ..Self::DEFAULT
        }
    }

    /// Distribution `distribution` with roughness `alpha_u` along the shading tangent
    /// `dp/du` and `alpha_v` along the bitangent, the other parameters at their defaults.
    pub const fn anisotropic(
        distribution: MicrofacetKind,
        alpha_u: Roughness,
        alpha_v: Roughness,
    ) -> Self {
        Self {
            distribution,
            alpha: alpha_u,
            alpha_v,
            ..Self::DEFAULT
        }
    }

    /// Whether αᵤ ≠ αᵥ: the surface then turns with the shading tangent.
    pub fn is_anisotropic(&self) -> bool {
        self.alpha != self.alpha_v
    }
}

impl Default for Microfacet {
    fn default() -> Self {
        Self::DEFAULT
    }
}
