//! Rough plastic (Mitsuba's `roughplastic`): a diffuse base under a rough dielectric coating.

use super::fresnel::fresnel_dielectric;
use super::ndf::Ndf;
use super::plastic::{coated_albedo, sampling_weight, specular_probability};
use glam::{Vec2, Vec3};
use mcrt::integrator::{is_positive, Bsdf, BsdfFlags, BsdfSample};
use mcrt::sampling::warp::{CosineHemisphere, Warp};
use mcrt::sampling::SamplingError;
use std::f32::consts::FRAC_1_PI;

/// Entries of the transmittance table over cos θ ∈ [0, 1] (Mitsuba 3's resolution).
const TABLE: usize = 64;

/// A Lambertian base of albedo ρ under a rough dielectric coating of relative index η, the
/// model of Weidlich and Wilkie 2007 ("Arbitrarily Layered Micro-Facet Surfaces",
/// GRAPHITE) as Mitsuba 3 builds it:
///
/// - microfacet reflection `F(wo·h) D(h) G(wo, wi, h) / (4 cos θ_o cos θ_i)` on the coating,
///   times `specular_reflectance`;
/// - a diffuse part `T(θ_o) T(θ_i) ρ' / (π η²)`, with `T(θ)` the fraction of light from
///   direction θ that the rough interface transmits (tabulated at 64 cosines and
///   interpolated linearly) and ρ' the albedo after internal scattering, as for
///   [`Plastic`](super::Plastic) but with the rough interface's hemispherical reflectance
///   seen from inside.
///
/// Both tables are integrals over the visible normals (Heitz 2018, JCGT 7(4)) of Fresnel
/// times Smith masking of the outgoing direction, by a composite Gauss–Legendre rule in
/// the warp's unit square. Sampling picks the specular lobe (visible normals) with
/// [`Plastic`](super::Plastic)'s specular probability of `1 − T(θ_o)`, else a cosine-weighted
/// direction; the weight is the whole `f cos θ_i / pdf` of the mixture. One-sided.
/// Derivations: `docs/bsdf-models.md`, "Rough plastic".
#[derive(Debug, Clone, PartialEq)]
pub struct RoughPlastic {
    /// The coating's normal distribution.
    pub ndf: Ndf,
    /// Albedo ρ of the base, linear RGB.
    pub diffuse_reflectance: Vec3,
    /// Scale on the coating's reflection.
    pub specular_reflectance: Vec3,
    /// Relative index of refraction, coating over exterior.
    pub eta: f32,
    /// Whether the internal scattering tints (`ρ / (1 − ρ R_int)`).
    pub nonlinear: bool,
    /// `T(θ)` at cos θ = i / 63 (the first at 10⁻⁶).
    /// Shared, so that the per-hit copies of a textured material do not allocate.
    transmittance: std::sync::Arc<[f32; TABLE]>,
    /// `R_int`: the interface's reflectance seen from inside, over a cosine-weighted
    /// hemisphere.
    internal_reflectance: f32,
    /// Mitsuba's specular sampling weight.
    specular_sampling_weight: f32,
}

impl RoughPlastic {
    /// Rough plastic; `ggx` selects GGX (else Beckmann) of roughness `alpha`; `eta` is
    /// coating over exterior. Integrates the tables (about 10⁵ evaluations).
    ///
    /// # Errors
    /// `alpha` outside the microfacet warps' range `[10⁻⁴, 10⁴]`.
    pub fn new(
        ggx: bool,
        alpha: f32,
        diffuse: Vec3,
        specular: Vec3,
        eta: f32,
        nonlinear: bool,
    ) -> Result<Self, SamplingError> {
        Ok(Self::with_ndf(
            Ndf::new(ggx, alpha)?,
            diffuse,
            specular,
            eta,
            nonlinear,
        ))
    }

    /// Rough plastic whose coating has normal distribution `ndf` (checked when it was
    /// made); `eta` is coating over exterior. Integrates the tables.
    pub fn with_ndf(ndf: Ndf, diffuse: Vec3, specular: Vec3, eta: f32, nonlinear: bool) -> Self {
        let mut transmittance = [0.0f32; TABLE];
        let mut internal = 0.0f64;
        for (i, t) in transmittance.iter_mut().enumerate() {
            let mu = (i as f32 / (TABLE - 1) as f32).max(1e-6);
            let w = Vec3::new((1.0 - mu * mu).sqrt(), 0.0, mu);
            *t = interface_albedo(&ndf, w, eta, false, 8) as f32;
            internal += interface_albedo(&ndf, w, 1.0 / eta, true, 16) * f64::from(mu);
        }
        Self {
            ndf,
            diffuse_reflectance: diffuse,
            specular_reflectance: specular,
            eta,
            nonlinear,
            transmittance: std::sync::Arc::new(transmittance),
            // 2 ∫ R(μ) μ dμ as the mean over the table's cosines (Mitsuba's rule).
            internal_reflectance: (2.0 * internal / TABLE as f64) as f32,
            specular_sampling_weight: sampling_weight(diffuse, specular),
        }
    }

    /// `T(θ)` at cosine `mu` ∈ [0, 1], interpolated linearly in the table.
    #[inline]
    pub fn transmittance(&self, mu: f32) -> f32 {
        let x = mu.clamp(0.0, 1.0) * (TABLE - 1) as f32;
        let i = (x as usize).min(TABLE - 2);
        let w = x - i as f32;
        self.transmittance[i] * (1.0 - w) + self.transmittance[i + 1] * w
    }

    /// The interface's reflectance seen from inside over a cosine-weighted hemisphere.
    pub fn internal_reflectance(&self) -> f32 {
        self.internal_reflectance
    }
}

/// 4-point Gauss–Legendre nodes on [0, 1] and their weights.
const GL4: [(f64, f64); 4] = [
    (0.069_431_844_202_973_71, 0.173_927_422_568_726_9),
    (0.330_009_478_207_571_9, 0.326_072_577_431_273_1),
    (0.669_990_521_792_428_1, 0.326_072_577_431_273_1),
    (0.930_568_155_797_026_3, 0.173_927_422_568_726_9),
];

/// The fraction of light from `w` (above the surface) that a rough interface of relative
/// index `eta` (far side over near side) reflects (`reflect`) or transmits, counting what
/// the facets mask on the way out: `∫ F G₁(w', m) dP(m)` (or `1 − F`) over the normals
/// visible from `w`, by a composite 4-point Gauss–Legendre rule on `parts × parts`
/// sub-squares of the visible-normal warp's unit square.
fn interface_albedo(ndf: &Ndf, w: Vec3, eta: f32, reflect: bool, parts: usize) -> f64 {
    let mut sum = 0.0f64;
    let h = 1.0 / parts as f64;
    for i in 0..parts * 4 {
        let (xi, wx) = GL4[i % 4];
        let x = ((i / 4) as f64 + xi) * h;
        for j in 0..parts * 4 {
            let (yj, wy) = GL4[j % 4];
            let y = ((j / 4) as f64 + yj) * h;
            let u = Vec2::new(x as f32, y as f32);
            let Some((m, _)) = ndf.sample_visible(w, u) else {
                continue;
            };
            let dot = w.dot(m);
            let (f, cos_t, _, eta_ti) = fresnel_dielectric(dot, eta);
            let value = if reflect {
                let out = 2.0 * dot * m - w;
                if out.z > 0.0 {
                    f * ndf.g1(out, m)
                } else {
                    0.0
                }
            } else {
                let out = m * (dot * eta_ti + cos_t) - w * eta_ti;
                if out.z < 0.0 && f < 1.0 {
                    (1.0 - f) * ndf.g1(out, m)
                } else {
                    0.0
                }
            };
            sum += f64::from(value) * wx * wy * h * h;
        }
    }
    sum
}

impl Bsdf for RoughPlastic {
    fn flags(&self) -> BsdfFlags {
        BsdfFlags {
            smooth: true,
            glossy: true,
            ..BsdfFlags::default()
        }
    }

    eval_and_pdf_from_eval_pdf!();

    fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        let (co, ci) = (wo.z, wi.z);
        if co <= 0.0 || ci <= 0.0 || !(co.is_finite() && ci.is_finite()) {
            return (Vec3::ZERO, 0.0);
        }
        let t_o = self.transmittance(co);
        let p_spec = specular_probability(self.specular_sampling_weight, 1.0 - t_o);
        let c = FRAC_1_PI * ci;
        let albedo = coated_albedo(
            self.diffuse_reflectance,
            self.internal_reflectance,
            self.nonlinear,
        );
        let mut value = albedo * (c * t_o * self.transmittance(ci) / (self.eta * self.eta));
        let mut pdf = (1.0 - p_spec) * c;
        let h = (wo + wi).normalize_or_zero();
        let d = self.ndf.d(h);
        if is_positive(d) {
            let (f, _, _, _) = fresnel_dielectric(wo.dot(h), self.eta);
            let g = self.ndf.g(wo, wi, h);
            value += self.specular_reflectance * (f * d * g / (4.0 * co));
            pdf += p_spec * self.ndf.pdf_visible(wo, h) / (4.0 * wi.dot(h));
        }
        (value, pdf)
    }

    fn sample(&self, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 || !wo.z.is_finite() {
            return None;
        }
        let p_spec = specular_probability(
            self.specular_sampling_weight,
            1.0 - self.transmittance(wo.z),
        );
        let wi = if u1 < p_spec {
            let (m, _) = self.ndf.sample_visible(wo, u2)?;
            2.0 * wo.dot(m) * m - wo
        } else {
            CosineHemisphere.sample(u2)
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

    #[test]
    fn tables_agree_with_a_finer_rule_and_the_smooth_limit() {
        let b =
            RoughPlastic::new(false, 0.1, Vec3::splat(0.5), Vec3::ONE, 1.5, false).expect("valid");
        let w = Vec3::new(0.6, 0.0, 0.8);
        let fine = interface_albedo(&b.ndf, w, 1.5, false, 32);
        let t = b.transmittance(0.8);
        assert!(
            t.is_finite() && (f64::from(t) - fine).abs() < 2e-3,
            "{t} vs {fine}"
        );
        // Nearly smooth: T(θ) → 1 − F(θ), R_int → the smooth interface's F_dr from inside.
        let s =
            RoughPlastic::new(true, 1e-3, Vec3::splat(0.5), Vec3::ONE, 1.5, false).expect("valid");
        for mu in [1.0f32, 0.5, 0.2] {
            let want = 1.0 - fresnel_dielectric(mu, 1.5).0;
            let got = s.transmittance(mu);
            assert!(
                got.is_finite() && (got - want).abs() < 2e-3,
                "{mu}: {got} vs {want}"
            );
        }
        let fdr = super::super::fresnel::fresnel_diffuse_reflectance(1.0 / 1.5);
        let r = s.internal_reflectance();
        assert!(r.is_finite() && (r - fdr).abs() < 0.02, "{r} vs {fdr}");
    }
}
