//! The microfacet normal distribution shared by the rough materials: GGX or Beckmann, with
//! Smith masking, sampled by its visible normals (Mitsuba's `sample_visible`, the default)
//! or by the whole distribution.

use crate::description::{Microfacet, MicrofacetKind};
use glam::{Vec2, Vec3};
use mcrt::sampling::warp::{
    Beckmann, BeckmannAnisotropic, BeckmannAnisotropicVisible, BeckmannVisible, Ggx,
    GgxAnisotropic, GgxAnisotropicVisible, GgxVisible, MicrofacetDistribution, Warp,
};
use mcrt::sampling::SamplingError;

/// The normal distribution of a rough material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Ndf {
    /// GGX (Trowbridge–Reitz).
    Ggx(Ggx),
    /// Beckmann.
    Beckmann(Beckmann),
    /// GGX, sampled from the whole distribution (`sample_visible = false`).
    GgxAll(Ggx),
    /// Beckmann, sampled from the whole distribution (`sample_visible = false`).
    BeckmannAll(Beckmann),
    /// Anisotropic GGX (αᵤ ≠ αᵥ); `true`: sampled by its visible normals.
    GgxAnisotropic(GgxAnisotropic, bool),
    /// Anisotropic Beckmann (αᵤ ≠ αᵥ); `true`: sampled by its visible normals.
    BeckmannAnisotropic(BeckmannAnisotropic, bool),
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

    /// The distribution of a rough material's checked parameters: it cannot fail, and
    /// nothing checks the roughness again (the visible normals are built per direction from
    /// this distribution, [`Ndf::visible`]).
    ///
    /// `sample_visible` (Mitsuba's default) samples the normals visible from the incident
    /// direction; otherwise the whole distribution, `D(m) cos θ_m` (the same expected value,
    /// more noise).
    pub fn of(m: &Microfacet) -> Self {
        let (kind, sample_visible) = (m.distribution, m.sample_visible);
        if m.is_anisotropic() {
            return Self::anisotropic(m);
        }
        // A `Roughness` lies in [10⁻⁴, 10], inside the warps' [10⁻⁴, 10⁴].
        let a = m.alpha.get();
        let ggx = || Ggx::new(a).unwrap_or_else(|e| unreachable!("Roughness {a}: {e}"));
        let beckmann = || Beckmann::new(a).unwrap_or_else(|e| unreachable!("Roughness {a}: {e}"));
        match (kind, sample_visible) {
            (MicrofacetKind::Ggx, true) => Ndf::Ggx(ggx()),
            (MicrofacetKind::Beckmann, true) => Ndf::Beckmann(beckmann()),
            (MicrofacetKind::Ggx, false) => Ndf::GgxAll(ggx()),
            (MicrofacetKind::Beckmann, false) => Ndf::BeckmannAll(beckmann()),
        }
    }

    /// The anisotropic distribution of `m` (αᵤ along the local x axis).
    fn anisotropic(m: &Microfacet) -> Self {
        let (au, av) = (m.alpha.get(), m.alpha_v.get());
        // A `Roughness` lies in [10⁻⁴, 10], inside the warps' [10⁻⁴, 10⁴].
        match m.distribution {
            MicrofacetKind::Ggx => Ndf::GgxAnisotropic(
                GgxAnisotropic::new(au, av)
                    .unwrap_or_else(|e| unreachable!("Roughness ({au}, {av}): {e}")),
                m.sample_visible,
            ),
            MicrofacetKind::Beckmann => Ndf::BeckmannAnisotropic(
                BeckmannAnisotropic::new(au, av)
                    .unwrap_or_else(|e| unreachable!("Roughness ({au}, {av}): {e}")),
                m.sample_visible,
            ),
        }
    }

    /// (αᵤ, αᵥ), equal for an isotropic distribution.
    pub fn alphas(&self) -> (f32, f32) {
        match self {
            Ndf::Ggx(g) | Ndf::GgxAll(g) => (g.alpha(), g.alpha()),
            Ndf::Beckmann(b) | Ndf::BeckmannAll(b) => (b.alpha(), b.alpha()),
            Ndf::GgxAnisotropic(g, _) => g.alphas(),
            Ndf::BeckmannAnisotropic(b, _) => b.alphas(),
        }
    }

    /// The same distribution (GGX or Beckmann, sampled the same way) with the roughness
    /// (`alpha_u`, `alpha_v`) a texture gives at a hit, taken as Mitsuba 3 takes it: below
    /// 10⁻⁴ (and NaN) raised to 10⁻⁴ (Mitsuba's `MicrofacetDistribution::configure`), above
    /// 10⁴ lowered to it (the warps' range); isotropic when the two are equal. Only
    /// textured materials call it, once per hit.
    pub fn with_alphas(&self, alpha_u: f32, alpha_v: f32) -> Self {
        let limit = |a: f32| if a >= 1e-4 { a.min(1e4) } else { 1e-4 };
        let (u, v) = (limit(alpha_u), limit(alpha_v));
        let (ggx, visible) = match *self {
            Ndf::Ggx(_) => (true, true),
            Ndf::Beckmann(_) => (false, true),
            Ndf::GgxAll(_) => (true, false),
            Ndf::BeckmannAll(_) => (false, false),
            Ndf::GgxAnisotropic(_, visible) => (true, visible),
            Ndf::BeckmannAnisotropic(_, visible) => (false, visible),
        };
        // Clamped, not checked: this runs at every hit of a textured roughness.
        match (u == v, ggx, visible) {
            (true, true, true) => Ndf::Ggx(Ggx::clamped(u)),
            (true, false, true) => Ndf::Beckmann(Beckmann::clamped(u)),
            (true, true, false) => Ndf::GgxAll(Ggx::clamped(u)),
            (true, false, false) => Ndf::BeckmannAll(Beckmann::clamped(u)),
            (false, true, _) => Ndf::GgxAnisotropic(GgxAnisotropic::clamped(u, v), visible),
            (false, false, _) => {
                Ndf::BeckmannAnisotropic(BeckmannAnisotropic::clamped(u, v), visible)
            }
        }
    }

    /// Whether the distribution is anisotropic (it turns with the shading tangent).
    #[inline]
    pub fn is_anisotropic(&self) -> bool {
        matches!(self, Ndf::GgxAnisotropic(..) | Ndf::BeckmannAnisotropic(..))
    }

    /// The normals visible from `wo` (above the surface); `None` if `wo` is not a valid
    /// direction for the warp. Only `wo` is checked: the roughness was, once.
    #[inline]
    pub fn visible(&self, wo: Vec3) -> Option<VisibleNdf> {
        Some(match self {
            Ndf::Ggx(g) => VisibleNdf::Ggx(GgxVisible::from_distribution(*g, wo).ok()?),
            Ndf::Beckmann(b) => {
                VisibleNdf::Beckmann(BeckmannVisible::from_distribution(*b, wo).ok()?)
            }
            Ndf::GgxAll(g) => VisibleNdf::GgxAll(*g),
            Ndf::BeckmannAll(b) => VisibleNdf::BeckmannAll(*b),
            Ndf::GgxAnisotropic(g, true) => {
                VisibleNdf::GgxAnisotropic(GgxAnisotropicVisible::new(*g, wo).ok()?)
            }
            Ndf::BeckmannAnisotropic(b, true) => VisibleNdf::BeckmannAnisotropic(Box::new(
                BeckmannAnisotropicVisible::new(*b, wo).ok()?,
            )),
            Ndf::GgxAnisotropic(g, false) => VisibleNdf::GgxAnisotropicAll(*g),
            Ndf::BeckmannAnisotropic(b, false) => VisibleNdf::BeckmannAnisotropicAll(*b),
        })
    }

    /// D(m), per steradian of m; 0 for m.z ≤ 0.
    #[inline]
    pub fn d(&self, m: Vec3) -> f32 {
        match self {
            Ndf::Ggx(g) | Ndf::GgxAll(g) => g.d(m),
            Ndf::Beckmann(b) | Ndf::BeckmannAll(b) => b.d(m),
            Ndf::GgxAnisotropic(g, _) => g.d(m),
            Ndf::BeckmannAnisotropic(b, _) => b.d(m),
        }
    }

    /// Smith masking G₁(w, m) (Mitsuba's rational Λ for Beckmann); 0 on a facet's back.
    #[inline]
    pub fn g1(&self, w: Vec3, m: Vec3) -> f32 {
        match self {
            Ndf::Ggx(g) | Ndf::GgxAll(g) => g.g1(w, m),
            Ndf::Beckmann(b) | Ndf::BeckmannAll(b) => b.g1(w, m),
            Ndf::GgxAnisotropic(g, _) => g.g1(w, m),
            Ndf::BeckmannAnisotropic(b, _) => b.g1(w, m),
        }
    }

    /// Separable Smith shadowing-masking G₁(wo, m) G₁(wi, m).
    #[inline]
    pub fn g(&self, wo: Vec3, wi: Vec3, m: Vec3) -> f32 {
        match self {
            Ndf::Ggx(g) | Ndf::GgxAll(g) => g.g(wo, wi, m),
            Ndf::Beckmann(b) | Ndf::BeckmannAll(b) => b.g(wo, wi, m),
            Ndf::GgxAnisotropic(g, _) => g.g(wo, wi, m),
            Ndf::BeckmannAnisotropic(b, _) => b.g(wo, wi, m),
        }
    }

    /// Density of the visible normal `m` seen from `wo` (above the surface), per steradian
    /// of m: G₁(wo) max(0, wo·m) D(m) / cos θ_o.
    #[inline]
    pub fn pdf_visible(&self, wo: Vec3, m: Vec3) -> f32 {
        self.visible(wo).map_or(0.0, |v| v.pdf(m))
    }

    /// A normal visible from `wo` (above the surface) and its density
    /// ([`Ndf::pdf_visible`]); `None` if `wo` is not a valid direction for the warp.
    #[inline]
    pub fn sample_visible(&self, wo: Vec3, u: Vec2) -> Option<(Vec3, f32)> {
        Some(self.visible(wo)?.sample_with_pdf(u))
    }
}

/// The normals of an [`Ndf`] visible from one direction ([`Ndf::visible`]).
#[derive(Debug, Clone, PartialEq)]
pub enum VisibleNdf {
    /// Visible GGX normals.
    Ggx(GgxVisible),
    /// Visible Beckmann normals.
    Beckmann(BeckmannVisible),
    /// All GGX normals, density `D(m) cos θ_m` whatever the direction.
    GgxAll(Ggx),
    /// All Beckmann normals, density `D(m) cos θ_m` whatever the direction.
    BeckmannAll(Beckmann),
    /// Visible anisotropic GGX normals.
    GgxAnisotropic(GgxAnisotropicVisible),
    /// Visible anisotropic Beckmann normals (boxed: the isotropic variants stay small).
    BeckmannAnisotropic(Box<BeckmannAnisotropicVisible>),
    /// All anisotropic GGX normals, density `D(m) cos θ_m`.
    GgxAnisotropicAll(GgxAnisotropic),
    /// All anisotropic Beckmann normals, density `D(m) cos θ_m`.
    BeckmannAnisotropicAll(BeckmannAnisotropic),
}

impl VisibleNdf {
    /// A visible normal.
    #[inline]
    pub fn sample(&self, u: Vec2) -> Vec3 {
        match self {
            Self::Ggx(v) => v.sample(u),
            Self::Beckmann(v) => v.sample(u),
            Self::GgxAll(v) => v.sample(u),
            Self::BeckmannAll(v) => v.sample(u),
            Self::GgxAnisotropic(v) => v.sample(u),
            Self::BeckmannAnisotropic(v) => v.sample(u),
            Self::GgxAnisotropicAll(v) => v.sample(u),
            Self::BeckmannAnisotropicAll(v) => v.sample(u),
        }
    }

    /// The density of visible normal `m`, per steradian of m.
    #[inline]
    pub fn pdf(&self, m: Vec3) -> f32 {
        match self {
            Self::Ggx(v) => v.pdf(m),
            Self::Beckmann(v) => v.pdf(m),
            Self::GgxAll(v) => v.pdf(m),
            Self::BeckmannAll(v) => v.pdf(m),
            Self::GgxAnisotropic(v) => v.pdf(m),
            Self::BeckmannAnisotropic(v) => v.pdf(m),
            Self::GgxAnisotropicAll(v) => v.pdf(m),
            Self::BeckmannAnisotropicAll(v) => v.pdf(m),
        }
    }

    /// A visible normal and its density.
    #[inline]
    pub fn sample_with_pdf(&self, u: Vec2) -> (Vec3, f32) {
        match self {
            Self::Ggx(v) => v.sample_with_pdf(u),
            Self::Beckmann(v) => v.sample_with_pdf(u),
            Self::GgxAll(v) => v.sample_with_pdf(u),
            Self::BeckmannAll(v) => v.sample_with_pdf(u),
            Self::GgxAnisotropic(v) => v.sample_with_pdf(u),
            Self::BeckmannAnisotropic(v) => v.sample_with_pdf(u),
            Self::GgxAnisotropicAll(v) => v.sample_with_pdf(u),
            Self::BeckmannAnisotropicAll(v) => v.sample_with_pdf(u),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `sample_visible = false` draws from the whole distribution: density `D(m) cos θ_m`,
    /// which `pdf_visible` reports too, whatever the direction; masking and D unchanged.
    #[test]
    fn sampling_all_normals_has_the_distributions_density() {
        let alpha = crate::description::Roughness::new(0.3).expect("a roughness");
        let wo = Vec3::new(0.6, 0.0, 0.8);
        for kind in [MicrofacetKind::Ggx, MicrofacetKind::Beckmann] {
            let visible = Microfacet::new(kind, alpha);
            let all = Microfacet {
                sample_visible: false,
                ..visible
            };
            let (visible, all) = (Ndf::of(&visible), Ndf::of(&all));
            for u in [
                Vec2::new(0.1, 0.7),
                Vec2::new(0.9, 0.2),
                Vec2::new(0.5, 0.5),
            ] {
                let (m, pdf) = all.sample_visible(wo, u).expect("a normal");
                let want = all.d(m) * m.z;
                assert!((pdf - want).abs() <= 1e-5 * want, "{kind:?}: {pdf} {want}");
                assert_eq!(all.pdf_visible(wo, m), pdf);
                assert_eq!(all.d(m), visible.d(m));
                assert_eq!(all.g(wo, wo, m), visible.g(wo, wo, m));
                assert_ne!(visible.pdf_visible(wo, m), pdf);
            }
        }
    }

    /// A textured roughness keeps the distribution's kind and sampling, is limited to the
    /// warps' range as Mitsuba raises small values, and is anisotropic only when unequal.
    #[test]
    fn textured_alphas_keep_the_kind() {
        let alpha = crate::description::Roughness::new(0.3).expect("a roughness");
        let ggx_all = Ndf::of(&Microfacet {
            sample_visible: false,
            ..Microfacet::new(MicrofacetKind::Ggx, alpha)
        });
        assert!(matches!(ggx_all.with_alphas(0.2, 0.2), Ndf::GgxAll(g) if g.alpha() == 0.2));
        let b = Ndf::of(&Microfacet::new(MicrofacetKind::Beckmann, alpha));
        let aniso = b.with_alphas(0.05, 0.4);
        assert!(matches!(aniso, Ndf::BeckmannAnisotropic(_, true)));
        assert_eq!(aniso.alphas(), (0.05, 0.4));
        assert_eq!(b.with_alphas(0.0, f32::NAN).alphas(), (1e-4, 1e-4));
        assert_eq!(b.with_alphas(1e9, 1e9).alphas(), (1e4, 1e4));
        assert_eq!(aniso.with_alphas(0.3, 0.3), b);
    }
}
