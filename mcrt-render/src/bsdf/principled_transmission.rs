//! The principled BSDF with specular transmission (`spec_trans` > 0): both sides of the
//! surface, the main GGX lobe reflecting and refracting (Walter et al. 2007), tinted by
//! `√base_color` when refracted; the diffuse, sheen and clearcoat lobes stay on the front
//! side. Derivation: `docs/bsdf-models.md`, section "Principled".

use super::fresnel_dielectric;
use super::principled::Principled;
use glam::{Vec2, Vec3};
use mcrt::integrator::{is_positive, BsdfSample};
use mcrt::sampling::warp::{CosineHemisphere, Warp};

impl Principled {
    /// `f · |cos θ_i|` (radiance, or importance when `adjoint`) and the pdf, on either side.
    ///
    /// The half-vector is `wo + wi` (reflection) or `wo + η_path wi` (refraction, `η_path`
    /// the index of `wi`'s side over `wo`'s), turned to the upper hemisphere. Refraction:
    /// `bsdf (1 − F) D G |wo·h| |wi·h| / (|cos θ_o| (wo·h + η_path wi·h)²) · √base` for
    /// radiance, times `η_path²` for importance (Walter, Marschner, Li, Torrance 2007,
    /// "Microfacet Models for Refraction through Rough Surfaces", EGSR, eq. 21; Burley 2015,
    /// "Extending the Disney BRDF to a BSDF with Integrated Subsurface Scattering", §4).
    /// The back side reflects with `bsdf · F`. The pdf splits the main lobe between
    /// reflection and refraction by the Fresnel term at `h`, as Mitsuba 3 does.
    pub(super) fn eval_pdf_two_sided(&self, wo: Vec3, wi: Vec3, adjoint: bool) -> (Vec3, f32) {
        let p = &self.params;
        let (ci, co) = (wo.z, wi.z);
        if ci == 0.0 || co == 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        let front = ci > 0.0;
        let reflect = ci * co > 0.0;
        let eta_path = if front { p.eta } else { 1.0 / p.eta };
        let h = if reflect { wo + wi } else { wo + eta_path * wi };
        let Some(mut h) = h.try_normalize() else {
            return (Vec3::ZERO, 0.0);
        };
        if h.z < 0.0 {
            h = -h;
        }
        let d = self.ggx.d(h);
        let g = self.ggx.g1(wo, h) * self.ggx.g1(wi, h);
        if !is_positive(d) || !is_positive(g) {
            return (Vec3::ZERO, 0.0);
        }
        let (cos_oh, cos_ih) = (wo.dot(h), wi.dot(h));
        let fresnel = fresnel_dielectric(cos_oh, p.eta).0;
        let bsdf = (1.0 - p.metallic) * p.spec_trans;
        let tint = self.tint();
        let wo_up = if front { wo } else { -wo };
        let visible = self.ggx.pdf_visible(wo_up, h);
        // Probabilities of main reflection and refraction (front: of the lobe choice too).
        let (p_reflect, p_refract) = if front {
            (
                self.probs[1] * (1.0 - bsdf * (1.0 - fresnel)),
                self.probs[1] * bsdf * (1.0 - fresnel),
            )
        } else {
            (fresnel, 1.0 - fresnel)
        };
        if !reflect {
            let denom = cos_oh + eta_path * cos_ih;
            let mut t = bsdf * (1.0 - fresnel) * d * g * (cos_oh * cos_ih).abs()
                / (ci.abs() * denom * denom);
            if adjoint {
                t *= eta_path * eta_path;
            }
            let f = p.base_color.max(Vec3::ZERO).powf(0.5) * t;
            let pdf = p_refract * visible * eta_path * eta_path * cos_ih.abs() / (denom * denom);
            return (f, pdf);
        }
        let fresnel_main = if front {
            self.main_fresnel(cos_oh, tint)
        } else {
            Vec3::splat(bsdf * fresnel)
        };
        let mut f = fresnel_main * (d * g / (4.0 * ci.abs()));
        let mut pdf = p_reflect * visible / (4.0 * cos_ih.abs());
        if front {
            let (f_front, pdf_front) = self.front_lobes(wo, wi, h, tint);
            f += f_front;
            pdf += pdf_front;
        }
        (f, pdf)
    }

    /// A sample on either side: on the front the lobe is picked as for reflection only;
    /// the main lobe's visible normal (seen from `wo` turned to the upper side) then
    /// reflects or refracts with the probabilities of
    /// [`Principled::eval_pdf_two_sided`], from the rest of `u1`.
    pub(super) fn sample_two_sided(&self, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        let p = &self.params;
        let front = wo.z > 0.0;
        let [p_diffuse, p_main, _] = self.probs;
        let mut u = u1;
        if front {
            if u1 < p_diffuse {
                return self.finish(wo, CosineHemisphere.sample(u2), None);
            }
            if u1 >= p_diffuse + p_main {
                let m = super::principled_lobes::gtr1_sample(u2, self.clearcoat_alpha);
                return self.finish(wo, 2.0 * wo.dot(m) * m - wo, None);
            }
            u = ((u1 - p_diffuse) / p_main).clamp(0.0, 1.0);
        }
        let wo_up = if front { wo } else { -wo };
        let m = self.ggx.sample_visible(wo_up, u2)?;
        let (fresnel, cos_t, eta_it, eta_ti) = fresnel_dielectric(wo.dot(m), p.eta);
        let bsdf = (1.0 - p.metallic) * p.spec_trans;
        let p_reflect = if front {
            1.0 - bsdf * (1.0 - fresnel)
        } else {
            fresnel
        };
        if u < p_reflect {
            self.finish(wo, 2.0 * wo.dot(m) * m - wo, None)
        } else {
            // Refraction about m (Walter et al. 2007, eq. 40).
            let wi = m * (wo.dot(m) * eta_ti + cos_t) - wo * eta_ti;
            self.finish(wo, wi.try_normalize()?, Some(eta_it))
        }
    }

    /// The sample of direction `wi`, a refraction into relative index `eta` or (`None`) a
    /// reflection, with the BSDF's own value and density; `None` if `wi` ended on the
    /// wrong side for what was sampled (the density is that of the other event there).
    fn finish(&self, wo: Vec3, wi: Vec3, refraction: Option<f32>) -> Option<BsdfSample> {
        let crosses = wo.z * wi.z < 0.0;
        if crosses != refraction.is_some() || wi.z == 0.0 {
            return None;
        }
        let (f, pdf) = self.eval_pdf_two_sided(wo, wi, false);
        BsdfSample::from_value(wi, f, pdf, refraction.unwrap_or(1.0))
    }
}
