//! Rough conductor (Mitsuba's `roughconductor`): Cook–Torrance microfacet reflection with
//! GGX or Beckmann normals, sampled with visible normals.

use super::conductor::Fresnel;
use super::ndf::Ndf;
use super::ndf::VisibleNdf;
use glam::{Vec2, Vec3};
use mcrt::integrator::{is_positive, Bsdf, BsdfFlags, BsdfSample};
use mcrt::sampling::SamplingError;

/// Microfacet reflection `f = F(wo·h) D(h) G(wo, wi, h) / (4 cos θ_o cos θ_i)` with Mitsuba's
/// separable Smith `G = G1(wo) G1(wi)`; the half-vector is drawn from the visible normals
/// seen from `wo` (density `G1(wo) max(0, wo·h) D(h) / cos θ_o`), mapped to `wi` by the
/// reflection Jacobian `1 / (4 |wi·h|)`. The sample weight is `f cos θ_i / pdf`.
///
/// Walter, Marschner, Li, Torrance 2007, "Microfacet Models for Refraction through Rough
/// Surfaces", EGSR; Heitz 2018, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoughConductor {
    /// The normal distribution.
    pub ndf: Ndf,
    /// Fresnel term.
    pub fresnel: Fresnel,
    /// Scale on the reflectance.
    pub specular_reflectance: Vec3,
}

impl RoughConductor {
    /// A rough conductor; `ggx` selects GGX (else Beckmann) of roughness `alpha`.
    ///
    /// # Errors
    /// `alpha` outside the microfacet warps' range `[10⁻⁴, 10⁴]`.
    pub fn new(
        ggx: bool,
        alpha: f32,
        fresnel: Fresnel,
        specular_reflectance: Vec3,
    ) -> Result<Self, SamplingError> {
        Ok(Self::with_ndf(
            Ndf::new(ggx, alpha)?,
            fresnel,
            specular_reflectance,
        ))
    }

    /// A rough conductor of normal distribution `ndf` (checked when it was made).
    pub fn with_ndf(ndf: Ndf, fresnel: Fresnel, specular_reflectance: Vec3) -> Self {
        Self {
            ndf,
            fresnel,
            specular_reflectance,
        }
    }
}

impl Bsdf for RoughConductor {
    fn flags(&self) -> BsdfFlags {
        BsdfFlags {
            smooth: true,
            glossy: true,
            ..BsdfFlags::default()
        }
    }

    eval_and_pdf_from_eval_pdf!();

    fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        let h = (wo + wi).normalize_or_zero();
        self.eval_pdf_at(wo, wi, h, |h| self.ndf.pdf_visible(wo, h))
    }

    #[inline]
    fn samples_component(&self) -> bool {
        false
    }

    fn sample(&self, wo: Vec3, _u1: f32, u2: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let (wi, f, pdf) = self.sample_with(&self.ndf.visible(wo)?, wo, u2)?;
        BsdfSample::from_value(wi, f, pdf, 1.0)
    }
}

impl RoughConductor {
    /// [`Bsdf::eval_pdf`] at the half-vector `h` of `wo` and `wi` (both above the surface),
    /// with `pdf_visible(h)` the density of visible normals seen from `wo`.
    #[inline]
    fn eval_pdf_at(
        &self,
        wo: Vec3,
        wi: Vec3,
        h: Vec3,
        pdf_visible: impl FnOnce(Vec3) -> f32,
    ) -> (Vec3, f32) {
        let d = self.ndf.d(h);
        let dot = wi.dot(h);
        if !is_positive(d) || !is_positive(dot) {
            return (Vec3::ZERO, 0.0);
        }
        let g = self.ndf.g(wo, wi, h);
        let f = self.fresnel.eval(wo.dot(h)) * self.specular_reflectance * (d * g / (4.0 * wo.z));
        let pdf = pdf_visible(h) / (4.0 * dot);
        (f, pdf)
    }

    /// A direction reflected about a visible normal drawn from `visible` (the warp of the
    /// normals visible from `wo`, built once and used for the density too), with
    /// `f · cos θ_i` and the pdf as [`Bsdf::eval_pdf`] gives them.
    #[inline]
    fn sample_with(&self, visible: &VisibleNdf, wo: Vec3, u2: Vec2) -> Option<(Vec3, Vec3, f32)> {
        let m = visible.sample(u2);
        let wi = 2.0 * wo.dot(m) * m - wo;
        if wi.z <= 0.0 {
            return None;
        }
        let h = (wo + wi).normalize_or_zero();
        let (f, pdf) = self.eval_pdf_at(wo, wi, h, |h| visible.pdf(h));
        Some((wi, f, pdf))
    }
}
