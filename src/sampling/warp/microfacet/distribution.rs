//! The [`MicrofacetDistribution`] trait: NDF and Smith masking, as the BSDFs use them.

use glam::Vec3;

/// A microfacet normal distribution with Smith masking, in the z-up local frame.
///
/// Implemented by [`Beckmann`](super::Beckmann) and [`Ggx`](super::Ggx); the BSDFs are
/// written against this trait.
///
/// ```
/// use mcrt::glam::Vec3;
/// use mcrt::sampling::warp::{Ggx, MicrofacetDistribution};
///
/// // The microfacet part of a rough mirror, D G / (4 cos θi cos θo), at the half vector.
/// let ggx = Ggx::new(0.2).unwrap();
/// let (wi, wo) = (Vec3::new(0.3, 0.0, 0.954), Vec3::new(-0.5, 0.1, 0.86));
/// let m = (wi + wo).normalize();
/// let f = ggx.d(m) * ggx.g(wi, wo, m) / (4.0 * wi.z * wo.z);
/// assert!(f.is_finite() && f > 0.0);
/// assert!(ggx.g(wi, wo, m) <= ggx.g_height_correlated(wi, wo, m));
/// ```
pub trait MicrofacetDistribution {
    /// The roughness α.
    fn alpha(&self) -> f32;

    /// The normal distribution function D(m), per unit solid angle of m, normalised in
    /// projected area: ∫ D(m) cos θ_m dω_m = 1. Zero for m.z ≤ 0. `m` need not be exactly
    /// unit length.
    fn d(&self, m: Vec3) -> f32;

    /// Smith's Λ(w), which depends only on |tan θ_w|; 0 at the normal, +∞ at grazing.
    fn lambda(&self, w: Vec3) -> f32;

    /// Smith masking G₁(w, m) = 1/(1 + Λ(w)), and 0 when (w·m)(w·n) ≤ 0 (a facet seen from
    /// its back side).
    fn g1(&self, w: Vec3, m: Vec3) -> f32 {
        if w.dot(m) * w.z <= 0.0 {
            return 0.0;
        }
        1.0 / (1.0 + self.lambda(w))
    }

    /// Shadowing-masking G(wi, wo, m) = G₁(wi, m) G₁(wo, m): Smith's **separable** form,
    /// which is what Mitsuba 3's `MicrofacetDistribution::G` (used by `roughconductor` and
    /// `roughdielectric`) computes. See [`MicrofacetDistribution::g_height_correlated`] for
    /// the height-correlated form.
    fn g(&self, wi: Vec3, wo: Vec3, m: Vec3) -> f32 {
        self.g1(wi, m) * self.g1(wo, m)
    }

    /// Height-correlated Smith G₂ = 1/(1 + Λ(wi) + Λ(wo)), and 0 when either direction sees
    /// the back of m ((w·m)(w·n) ≤ 0). Not Mitsuba 3's default; offered for comparison.
    fn g_height_correlated(&self, wi: Vec3, wo: Vec3, m: Vec3) -> f32 {
        if wi.dot(m) * wi.z <= 0.0 || wo.dot(m) * wo.z <= 0.0 {
            return 0.0;
        }
        1.0 / (1.0 + self.lambda(wi) + self.lambda(wo))
    }
}
