//! Mitsuba 3's `principled` BSDF (the Disney BSDF): a diffuse lobe with retro-reflection,
//! flatness and sheen, a main anisotropic GGX lobe whose Fresnel blends a dielectric, a
//! tinted dielectric and a metal, and a GTR1 clearcoat; with `spec_trans` > 0 the main
//! lobe also refracts (`principled_transmission.rs`). The model and where
//! each term comes from: `docs/bsdf-models.md`, section "Principled".

use super::fresnel_dielectric;
use super::principled_lobes::{
    clearcoat_alpha, gtr1_d, gtr1_sample, r0_of_eta, schlick, schlick_weight, smith_g1_isotropic,
    AnisoGgx,
};
use crate::description::PrincipledParams;
use glam::{Vec2, Vec3};
use mcrt::integrator::{is_positive, Bsdf, BsdfFlags, BsdfSample};
use mcrt::sampling::warp::{CosineHemisphere, Warp};
use mcrt::sampling::SamplingError;
use std::f32::consts::FRAC_1_PI;

/// Roughness of the clearcoat's Smith masking (Burley 2012, §5.6).
const CLEARCOAT_G_ALPHA: f32 = 0.25;
/// Normal-incidence reflectance of the clearcoat (index 1.5; Burley 2012, §5.6).
const CLEARCOAT_R0: f32 = 0.04;

/// The principled BSDF of Burley 2012 ("Physically Based Shading at Disney", SIGGRAPH
/// course notes) with the diffuse split of Burley 2015 ("Extending the Disney BRDF to a
/// BSDF with Integrated Subsurface Scattering", SIGGRAPH course notes), as Mitsuba 3 defines
/// it; see [`PrincipledParams`] for the parameters. Without transmission (`spec_trans` =
/// 0) it is one-sided: black when `wo` or `wi` is below the surface. `f · cos θ_i` is
///
/// - diffuse, weight `(1 − metallic)(1 − spec_trans)`: `cos θ_i base/π · ((1 − flatness)
///   (f_d + f_retro) + flatness · f_ss)`; sheen, weight `1 − metallic` (0 when
///   `spec_trans` = 1): `cos θ_i f_sheen`;
/// - main specular: `F(wo·h) D(h) G₁(wo) G₁(wi) / (4 cos θ_o)`, anisotropic GGX;
/// - clearcoat: `clearcoat/4 · F_s(wo·h) D_gtr1(h) G₁(wo) G₁(wi) · cos θ_i` (Mitsuba leaves
///   out the `1/(4 cos θ_o cos θ_i)` here, and so do we, to match it);
/// - with `spec_trans` > 0, refraction through the main lobe on both sides and reflection
///   from the back (`eval_pdf_two_sided`).
///
/// Sampling picks a lobe with probabilities proportional to `(1 − metallic)(1 − spec_trans)
/// · diffuse_reflectance_sampling_rate`, `main_specular_sampling_rate` and `clearcoat/4 ·
/// clearcoat_sampling_rate`, then draws a cosine-weighted direction, a visible GGX normal
/// or a GTR1 normal; the pdf is the mixture of the three.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Principled {
    /// The parameters, as given.
    pub params: PrincipledParams,
    pub(super) ggx: AnisoGgx,
    pub(super) clearcoat_alpha: f32,
    /// Probabilities of sampling the diffuse, main specular and clearcoat lobes on the
    /// front side (sum 1, or all 0 when every rate is 0).
    pub(super) probs: [f32; 3],
}

impl Principled {
    /// The material with parameters `params`.
    ///
    /// # Errors
    /// A parameter out of range ([`PrincipledParams::check`]).
    pub fn new(params: PrincipledParams) -> Result<Self, SamplingError> {
        params.check()?;
        let p = &params;
        let weights = [
            (1.0 - p.metallic) * (1.0 - p.spec_trans) * p.diffuse_reflectance_sampling_rate,
            p.main_specular_sampling_rate,
            0.25 * p.clearcoat * p.clearcoat_sampling_rate,
        ];
        let total: f32 = weights.iter().sum();
        let probs = if total > 0.0 {
            weights.map(|w| w / total)
        } else {
            [0.0; 3]
        };
        Ok(Self {
            params,
            ggx: AnisoGgx::new(p.roughness, p.anisotropic),
            clearcoat_alpha: clearcoat_alpha(p.clearcoat_gloss),
            probs,
        })
    }

    /// Set the base colour (what a texture on `base_color` does at each hit).
    pub fn set_base_color(&mut self, c: Vec3) {
        self.params.base_color = c;
    }

    /// The base colour over its luminance (white for a black base): the hue that
    /// `spec_tint` and `sheen_tint` blend toward (Burley 2012, §5.3 "Ctint").
    pub(super) fn tint(&self) -> Vec3 {
        let c = self.params.base_color;
        let lum = c.dot(Vec3::new(0.212671, 0.715160, 0.072169));
        if lum > 0.0 {
            c / lum
        } else {
            Vec3::ONE
        }
    }

    /// The main lobe's Fresnel term at `cos = wo·h`: `(1 − metallic)(1 − spec_tint) ·
    /// F_dielectric + (1 − metallic) spec_tint · Schlick(tint · R0(η)) + metallic ·
    /// Schlick(base_color)` (Burley 2012, §5.3 and §5.5).
    pub(super) fn main_fresnel(&self, cos: f32, tint: Vec3) -> Vec3 {
        let p = &self.params;
        let dielectric = fresnel_dielectric(cos, p.eta).0;
        let schlick3 = |r0: Vec3| {
            Vec3::new(
                schlick(r0.x, cos, p.eta),
                schlick(r0.y, cos, p.eta),
                schlick(r0.z, cos, p.eta),
            )
        };
        let mut f = Vec3::splat((1.0 - p.metallic) * (1.0 - p.spec_tint) * dielectric);
        if p.spec_tint > 0.0 {
            f += (1.0 - p.metallic) * p.spec_tint * schlick3(tint * r0_of_eta(p.eta));
        }
        if p.metallic > 0.0 {
            f += p.metallic * schlick3(p.base_color);
        }
        f
    }

    /// The diffuse lobe's `f · cos θ_i` and the sheen's, both without their weights
    /// (Burley 2015, §5.3, eqs. 4–5 for `f_d` and `f_retro`; Burley 2012, §5.3 for the
    /// flat `f_ss`, after Hanrahan and Krueger, and the sheen).
    fn diffuse(&self, wo: Vec3, wi: Vec3, h: Vec3, tint: Vec3) -> (Vec3, Vec3) {
        let p = &self.params;
        let (fo, fi) = (schlick_weight(wo.z), schlick_weight(wi.z));
        let cos_d = h.dot(wi);
        let mut shape = 0.0;
        if p.flatness < 1.0 {
            let rr = 2.0 * p.roughness * cos_d * cos_d;
            let f_d = (1.0 - 0.5 * fo) * (1.0 - 0.5 * fi);
            let f_retro = rr * (fo + fi + fo * fi * (rr - 1.0));
            shape += (1.0 - p.flatness) * (f_d + f_retro);
        }
        if p.flatness > 0.0 {
            let f90 = p.roughness * cos_d * cos_d;
            let fss = (1.0 + (f90 - 1.0) * fo) * (1.0 + (f90 - 1.0) * fi);
            let f_ss = 1.25 * (fss * (1.0 / (wo.z + wi.z) - 0.5) + 0.5);
            shape += p.flatness * f_ss;
        }
        let f = p.base_color * (FRAC_1_PI * shape);
        let mut sheen = Vec3::ZERO;
        if p.sheen > 0.0 {
            let c_sheen = Vec3::ONE + p.sheen_tint * (tint - Vec3::ONE);
            sheen = schlick_weight(cos_d) * p.sheen * c_sheen;
        }
        (f * wi.z, sheen * wi.z)
    }
}

impl Principled {
    /// The front-side reflection lobes besides the main one, for `wo` and `wi` above the
    /// surface with half-vector `h`: clearcoat, and diffuse with retro-reflection, flatness
    /// and sheen (weight `(1 − metallic)(1 − spec_trans)`); their `f · cos θ_i` and their
    /// share of the pdf.
    pub(super) fn front_lobes(&self, wo: Vec3, wi: Vec3, h: Vec3, tint: Vec3) -> (Vec3, f32) {
        let p = &self.params;
        let mut f = Vec3::ZERO;
        let mut pdf = 0.0;
        let cos_ih = wi.dot(h);
        if p.clearcoat > 0.0 {
            let d_c = gtr1_d(h.z, self.clearcoat_alpha);
            let g_c = smith_g1_isotropic(wo, CLEARCOAT_G_ALPHA)
                * smith_g1_isotropic(wi, CLEARCOAT_G_ALPHA);
            let f_c = schlick(CLEARCOAT_R0, wo.dot(h), 1.5);
            f += Vec3::splat(0.25 * p.clearcoat * f_c * d_c * g_c * wi.z);
            if is_positive(cos_ih) {
                pdf += self.probs[2] * d_c * h.z / (4.0 * cos_ih);
            }
        }
        // Mitsuba weighs the sheen by 1 − metallic alone, and drops it with the diffuse
        // lobe when spec_trans = 1.
        let brdf = (1.0 - p.metallic) * (1.0 - p.spec_trans);
        if brdf > 0.0 {
            let (diffuse, sheen) = self.diffuse(wo, wi, h, tint);
            f += brdf * diffuse + (1.0 - p.metallic) * sheen;
        }
        pdf += self.probs[0] * CosineHemisphere.pdf(wi);
        (f, pdf)
    }
}

impl Bsdf for Principled {
    fn flags(&self) -> BsdfFlags {
        BsdfFlags {
            smooth: true,
            glossy: true,
            transmission: self.params.spec_trans > 0.0,
            ..BsdfFlags::default()
        }
    }

    eval_and_pdf_from_eval_pdf!();

    fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        if self.params.spec_trans > 0.0 {
            return self.eval_pdf_two_sided(wo, wi, false);
        }
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        let Some(h) = (wo + wi).try_normalize() else {
            return (Vec3::ZERO, 0.0);
        };
        let tint = self.tint();
        let cos_ih = wi.dot(h);
        // Main specular lobe.
        let d = self.ggx.d(h);
        let g = self.ggx.g1(wo, h) * self.ggx.g1(wi, h);
        let f = self.main_fresnel(wo.dot(h), tint) * (d * g / (4.0 * wo.z));
        let mut pdf = 0.0;
        if is_positive(cos_ih) {
            pdf += self.probs[1] * self.ggx.pdf_visible(wo, h) / (4.0 * cos_ih);
        }
        let (f_front, pdf_front) = self.front_lobes(wo, wi, h, tint);
        (f + f_front, pdf + pdf_front)
    }

    fn eval_adjoint(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        if self.params.spec_trans > 0.0 {
            return self.eval_pdf_two_sided(wo, wi, true).0;
        }
        self.eval(wo, wi)
    }

    fn sample(&self, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        if self.params.spec_trans > 0.0 {
            return self.sample_two_sided(wo, u1, u2);
        }
        if wo.z <= 0.0 {
            return None;
        }
        let [p_diffuse, p_main, _] = self.probs;
        let wi = if u1 < p_diffuse {
            CosineHemisphere.sample(u2)
        } else {
            let m = if u1 < p_diffuse + p_main {
                self.ggx.sample_visible(wo, u2)?
            } else {
                gtr1_sample(u2, self.clearcoat_alpha)
            };
            2.0 * wo.dot(m) * m - wo
        };
        if wi.z <= 0.0 {
            return None;
        }
        let (f, pdf) = self.eval_pdf(wo, wi);
        BsdfSample::from_value(wi, f, pdf, 1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every sample, at the edges of the unit square and for directions on both sides and
    /// at grazing angles, has a finite weight and a positive finite pdf that equals
    /// [`Bsdf::pdf`] at its direction, with and without transmission.
    #[test]
    fn samples_at_edge_inputs_are_finite_and_consistent() {
        let last = 1.0 - f32::EPSILON / 2.0; // 1 − 2⁻²⁴
        let d = PrincipledParams::default();
        let cases = [
            d,
            PrincipledParams {
                roughness: 0.0,
                anisotropic: 1.0,
                metallic: 0.5,
                clearcoat: 1.0,
                clearcoat_gloss: 1.0,
                ..d
            },
            PrincipledParams {
                spec_trans: 1.0,
                roughness: 0.05,
                ..d
            },
            PrincipledParams {
                spec_trans: 0.5,
                eta: 0.7,
                sheen: 1.0,
                ..d
            },
        ];
        let wos = [
            Vec3::Z,
            Vec3::new(0.6, 0.0, 0.8),
            Vec3::new(0.0, 0.9999, 0.01).normalize(),
            Vec3::new(0.3, -0.4, -0.866).normalize(),
        ];
        let mut n = 0;
        for p in cases {
            let b = Principled::new(p).expect("valid");
            for wo in wos {
                for u1 in [0.0, 0.3, 0.7, last] {
                    for u2 in [0.0, 0.5, last] {
                        for u3 in [0.0, 0.5, last] {
                            let Some(s) = b.sample(wo, u1, Vec2::new(u2, u3)) else {
                                continue;
                            };
                            let pdf = b.pdf(wo, s.wi);
                            n += 1;
                            assert!(
                                s.weight.is_finite()
                                    && s.pdf.is_finite()
                                    && s.pdf > 0.0
                                    && (pdf - s.pdf).abs() <= 1e-4 * s.pdf,
                                "{p:?} wo {wo} u {u1} {u2} {u3}: {s:?}, pdf {pdf}"
                            );
                        }
                    }
                }
            }
        }
        assert!(n > 300, "only {n} samples");
    }
}
