//! Rough dielectric (Mitsuba's `roughdielectric`): microfacet reflection and refraction at
//! the interface between two dielectrics, with GGX or Beckmann normals.

use super::fresnel::fresnel_dielectric;
use super::ndf::Ndf;
use glam::{Vec2, Vec3};
use mcrt::integrator::{is_positive, Bsdf, BsdfFlags, BsdfSample};
use mcrt::sampling::SamplingError;

/// A rough interface of relative index `eta` (inside over outside; the inside is below the
/// surface, `z < 0`), after Walter, Marschner, Li, Torrance 2007, "Microfacet Models for
/// Refraction through Rough Surfaces", EGSR, with Mitsuba 3's conventions:
///
/// - reflection `F(wo·h) D(h) G(wo, wi, h) / (4 |cos θ_o| |cos θ_i|)` with `h` the half
///   vector; refraction `(1 − F) D G |wo·h| |wi·h| / (|cos θ_o| |cos θ_i| (wo·h + η wi·h)²)`
///   with `h ∝ −(wo + η wi)` and η the index of `wi`'s side over `wo`'s. That is the
///   radiance form, which already holds the `1/η²` of radiance crossing the interface
///   (Veach 1997, thesis, section 5.2); [`Bsdf::eval_adjoint`] gives the importance form,
///   without it. Separable Smith G, zero where either direction sees a facet's back.
/// - Sampling draws `h` from the normals visible from `wo` (mirrored above the surface when
///   `wo` is inside; Heitz 2018, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4)),
///   then chooses reflection with probability `F(wo·h)` and refraction otherwise, mapped to
///   `wi` by the reflection Jacobian `1/(4 |wi·h|)` or the refraction Jacobian
///   `η² |wi·h| / (wo·h + η wi·h)²` (Walter et al. 2007, eqs. 14 and 17).
///
/// Derivation of the densities and weights: `docs/bsdf-models.md`, "Rough dielectric".
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoughDielectric {
    /// The normal distribution.
    pub ndf: Ndf,
    /// Relative index of refraction, interior over exterior.
    pub eta: f32,
    /// Scale on reflection.
    pub specular_reflectance: Vec3,
    /// Scale on transmission.
    pub specular_transmittance: Vec3,
}

impl RoughDielectric {
    /// A rough interface; `ggx` selects GGX (else Beckmann) of roughness `alpha`, `eta` is
    /// interior over exterior.
    ///
    /// # Errors
    /// `alpha` outside the microfacet warps' range `[10⁻⁴, 10⁴]`.
    pub fn new(
        ggx: bool,
        alpha: f32,
        eta: f32,
        specular_reflectance: Vec3,
        specular_transmittance: Vec3,
    ) -> Result<Self, SamplingError> {
        Ok(Self::with_ndf(
            Ndf::new(ggx, alpha)?,
            eta,
            specular_reflectance,
            specular_transmittance,
        ))
    }

    /// A rough interface of normal distribution `ndf` (checked when it was made); `eta` is
    /// interior over exterior.
    pub fn with_ndf(
        ndf: Ndf,
        eta: f32,
        specular_reflectance: Vec3,
        specular_transmittance: Vec3,
    ) -> Self {
        Self {
            ndf,
            eta,
            specular_reflectance,
            specular_transmittance,
        }
    }

    /// `f · |cos θ_i|` and the pdf of `wi`, in radiance form or (`adjoint`) importance form.
    fn eval_pdf_mode(&self, wo: Vec3, wi: Vec3, adjoint: bool) -> (Vec3, f32) {
        let (co, ci) = (wo.z, wi.z);
        if co == 0.0 || ci == 0.0 || !(co.is_finite() && ci.is_finite()) {
            return (Vec3::ZERO, 0.0);
        }
        let reflect = co * ci > 0.0;
        // The index of wi's side over wo's.
        let eta = if co > 0.0 { self.eta } else { 1.0 / self.eta };
        let h = if reflect { wo + wi } else { wo + eta * wi };
        let h = h.normalize_or_zero();
        let m = if h.z < 0.0 { -h } else { h };
        if m == Vec3::ZERO {
            return (Vec3::ZERO, 0.0);
        }
        let pdf_m = self.ndf.pdf_visible(wo * co.signum(), m);
        self.eval_pdf_at(wo, wi, m, pdf_m, adjoint)
    }

    /// The same at the microfacet normal `m` (upper hemisphere) that maps `wo` to `wi`,
    /// whose visible-normal density seen from `wo` is `pdf_m`.
    #[inline]
    fn eval_pdf_at(&self, wo: Vec3, wi: Vec3, m: Vec3, pdf_m: f32, adjoint: bool) -> (Vec3, f32) {
        let (co, ci) = (wo.z, wi.z);
        let (dot_o, dot_i) = (wo.dot(m), wi.dot(m));
        // Neither direction may see the back of the facet.
        if dot_o * co <= 0.0 || dot_i * ci <= 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        let d = self.ndf.d(m);
        if !is_positive(d) {
            return (Vec3::ZERO, 0.0);
        }
        let g = self.ndf.g(wo, wi, m);
        let (f, _, eta_it, _) = fresnel_dielectric(dot_o, self.eta);
        if co * ci > 0.0 {
            let value = self.specular_reflectance * (f * d * g / (4.0 * co.abs()));
            return (value, pdf_m * f / (4.0 * dot_i.abs()));
        }
        let denom = dot_o + eta_it * dot_i;
        let denom2 = denom * denom;
        if !is_positive(denom2) {
            return (Vec3::ZERO, 0.0);
        }
        let mut t = (1.0 - f) * d * g * (dot_o * dot_i).abs() / (co.abs() * denom2);
        if adjoint {
            t *= eta_it * eta_it;
        }
        let jacobian = eta_it * eta_it * dot_i.abs() / denom2;
        (
            self.specular_transmittance * t,
            pdf_m * (1.0 - f) * jacobian,
        )
    }
}

impl Bsdf for RoughDielectric {
    fn flags(&self) -> BsdfFlags {
        BsdfFlags {
            smooth: true,
            glossy: true,
            transmission: true,
            ..BsdfFlags::default()
        }
    }

    fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        self.eval_pdf_mode(wo, wi, false).0
    }

    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.eval_pdf_mode(wo, wi, false).1
    }

    fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        self.eval_pdf_mode(wo, wi, false)
    }

    fn eval_adjoint(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        self.eval_pdf_mode(wo, wi, true).0
    }

    fn sample(&self, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        let co = wo.z;
        if co == 0.0 || !co.is_finite() {
            return None;
        }
        let (m, pdf_m) = self.ndf.sample_visible(wo * co.signum(), u2)?;
        if !is_positive(pdf_m) {
            return None;
        }
        let dot_o = wo.dot(m);
        let (f, cos_t, eta_it, eta_ti) = fresnel_dielectric(dot_o, self.eta);
        let (wi, eta) = if u1 < f {
            (2.0 * dot_o * m - wo, 1.0)
        } else {
            // Snell's law about m; cos_t carries the sign of the far side.
            let wi = m * (dot_o * eta_ti + cos_t) - wo * eta_ti;
            (wi.normalize_or_zero(), eta_it)
        };
        let (value, pdf) = self.eval_pdf_at(wo, wi, m, pdf_m, false);
        BsdfSample::from_value(wi, value, pdf, eta)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn glass() -> RoughDielectric {
        RoughDielectric::new(true, 0.3, 1.5, Vec3::ONE, Vec3::ONE).expect("valid")
    }

    #[test]
    fn reciprocity_of_radiance_and_importance_forms() {
        // f(wo, wi) = f*(wi, wo): the adjoint of a pair is the radiance form swapped, once
        // the cosines that eval multiplies in are divided out.
        let b = glass();
        let pairs = [
            (Vec3::new(0.3, 0.1, 0.9), Vec3::new(-0.2, 0.3, -0.93)),
            (Vec3::new(-0.5, 0.2, -0.84), Vec3::new(0.4, -0.1, 0.91)),
            (Vec3::new(0.6, 0.0, 0.8), Vec3::new(-0.5, 0.1, 0.86)),
        ];
        for (wo, wi) in pairs {
            let (wo, wi) = (wo.normalize(), wi.normalize());
            let f = b.eval(wo, wi).x / wi.z.abs();
            let f_adj = b.eval_adjoint(wi, wo).x / wo.z.abs();
            assert!(f.is_finite() && f > 0.0, "{wo} {wi}: {f}");
            assert!((f - f_adj).abs() <= 1e-4 * f, "{wo} {wi}: {f} vs {f_adj}");
        }
    }

    #[test]
    fn refraction_scales_radiance_by_the_index_ratio() {
        // Radiance form over importance form = 1/η² with η the index of wi's side over wo's.
        let b = glass();
        let wo = Vec3::new(0.3, 0.0, 0.954).normalize();
        let wi = Vec3::new(-0.1, 0.05, -0.99).normalize();
        let ratio = b.eval(wo, wi).x / b.eval_adjoint(wo, wi).x;
        assert!(
            ratio.is_finite() && (ratio - 1.0 / 2.25).abs() < 1e-5,
            "{ratio}"
        );
        let ratio = b.eval(wi, wo).x / b.eval_adjoint(wi, wo).x;
        assert!(ratio.is_finite() && (ratio - 2.25).abs() < 1e-4, "{ratio}");
    }

    #[test]
    fn samples_land_on_both_sides_from_either_side() {
        let b = glass();
        for wo in [Vec3::new(0.3, 0.0, 0.954), Vec3::new(0.3, 0.0, -0.954)] {
            let wo = wo.normalize();
            let r = b.sample(wo, 0.01, Vec2::new(0.3, 0.6)).expect("reflects");
            let t = b.sample(wo, 0.99, Vec2::new(0.3, 0.6)).expect("refracts");
            assert!(r.wi.z * wo.z > 0.0 && r.eta == 1.0);
            assert!(t.wi.z * wo.z < 0.0);
            let want_eta = if wo.z > 0.0 { 1.5 } else { 1.0 / 1.5 };
            assert!((t.eta - want_eta).abs() < 1e-6 && (t.wi.length() - 1.0).abs() < 1e-5);
        }
    }
}
