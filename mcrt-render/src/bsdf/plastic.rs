//! Smooth plastic (Mitsuba's `plastic`): a diffuse base under a smooth dielectric coating.

use super::fresnel::{fresnel_dielectric, fresnel_diffuse_reflectance};
use glam::{Vec2, Vec3};
use mcrt::integrator::{is_positive, Bsdf, BsdfFlags, BsdfSample};
use mcrt::sampling::warp::{CosineHemisphere, Warp};
use std::f32::consts::FRAC_1_PI;

/// The split of sampling effort between a coated material's specular and diffuse parts, as
/// Mitsuba 3 makes it: the specular part gets weight `s = mean(specular) / (mean(diffuse) +
/// mean(specular))` times its energy `E` (the Fresnel reflectance, or 1 − the diffuse
/// transmittance), the diffuse part `(1 − s)(1 − E)`; returns the specular probability.
#[inline]
pub(super) fn specular_probability(sampling_weight: f32, specular_energy: f32) -> f32 {
    let ps = specular_energy * sampling_weight;
    let pd = (1.0 - specular_energy) * (1.0 - sampling_weight);
    if ps + pd > 0.0 {
        ps / (ps + pd)
    } else {
        0.0
    }
}

/// Mitsuba 3's weight `s` of [`specular_probability`] from the two reflectances.
#[inline]
pub(super) fn sampling_weight(diffuse: Vec3, specular: Vec3) -> f32 {
    let (d, s) = (diffuse.element_sum() / 3.0, specular.element_sum() / 3.0);
    if d + s > 0.0 {
        s / (d + s)
    } else {
        0.5
    }
}

/// The diffuse albedo after the coating's internal scattering: light reflected by the base
/// bounces between base and coating, which sends back the fraction `F_dr` of it (the
/// hemispherical average of Fresnel reflectance from inside). Summing the bounces gives
/// `ρ / (1 − ρ F_dr)` (`nonlinear`, which also shifts colours toward saturation), and
/// Mitsuba's default keeps the denominator colourless, `ρ / (1 − F_dr)`.
#[inline]
pub(super) fn coated_albedo(rho: Vec3, internal_reflectance: f32, nonlinear: bool) -> Vec3 {
    if nonlinear {
        rho / (Vec3::ONE - rho * internal_reflectance)
    } else {
        rho / (1.0 - internal_reflectance)
    }
}

/// A Lambertian base of albedo ρ under a smooth dielectric of relative index η (Weidlich and
/// Wilkie 2007, "Arbitrarily Layered Micro-Facet Surfaces", GRAPHITE, with the bounces
/// between base and coating summed as Mitsuba 3 sums them):
///
/// - a Dirac reflection of weight `F(θ_o)` times `specular_reflectance`;
/// - a diffuse part `(1 − F(θ_o)) (1 − F(θ_i)) ρ' / (π η²)`: light refracts in, scatters
///   at the base, and refracts out, its radiance scaled by 1/η² on the way. The coating
///   sends back the fraction `F_dr` of the light leaving the base (the hemispherical
///   Fresnel reflectance from inside), and the bounces sum to `ρ' = ρ / (1 − ρ F_dr)`
///   (`nonlinear`) or, Mitsuba's default, `ρ' = ρ / (1 − F_dr)`.
///
/// Sampling picks the reflection with Mitsuba's probability `F s / (F s + (1 − F)(1 − s))`,
/// `F = F(θ_o)` and `s` the mean specular reflectance over the sum of the mean specular and
/// diffuse ones, else draws a cosine-weighted direction. One-sided: black from below. Derivations:
/// `docs/bsdf-models.md`, "Plastic".
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plastic {
    /// Albedo ρ of the base, linear RGB.
    pub diffuse_reflectance: Vec3,
    /// Scale on the coating's reflection.
    pub specular_reflectance: Vec3,
    /// Relative index of refraction, coating over exterior.
    pub eta: f32,
    /// Whether the internal scattering tints (`ρ / (1 − ρ F_dr)`).
    pub nonlinear: bool,
    /// `F_dr`, the hemispherical Fresnel reflectance seen from inside.
    fdr_int: f32,
    /// Mitsuba's specular sampling weight.
    specular_sampling_weight: f32,
}

impl Plastic {
    /// Smooth plastic. `eta` (coating over exterior) must be positive; the loader checks.
    pub fn new(diffuse: Vec3, specular: Vec3, eta: f32, nonlinear: bool) -> Self {
        Self {
            diffuse_reflectance: diffuse,
            specular_reflectance: specular,
            eta,
            nonlinear,
            fdr_int: fresnel_diffuse_reflectance(1.0 / eta),
            specular_sampling_weight: sampling_weight(diffuse, specular),
        }
    }

    /// The diffuse part at cosines `co`, `ci` > 0 without the cosine of `wi` and 1/π.
    #[inline]
    fn diffuse(&self, f_o: f32, ci: f32) -> Vec3 {
        let (f_i, _, _, _) = fresnel_dielectric(ci, self.eta);
        coated_albedo(self.diffuse_reflectance, self.fdr_int, self.nonlinear)
            * ((1.0 - f_o) * (1.0 - f_i) / (self.eta * self.eta))
    }
}

impl Bsdf for Plastic {
    fn flags(&self) -> BsdfFlags {
        BsdfFlags {
            smooth: true,
            delta: true,
            ..BsdfFlags::default()
        }
    }

    eval_and_pdf_from_eval_pdf!();

    fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        let (f_o, _, _, _) = fresnel_dielectric(wo.z, self.eta);
        let p_spec = specular_probability(self.specular_sampling_weight, f_o);
        let c = FRAC_1_PI * wi.z;
        (self.diffuse(f_o, wi.z) * c, (1.0 - p_spec) * c)
    }

    fn sample(&self, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let (f_o, _, _, _) = fresnel_dielectric(wo.z, self.eta);
        let p_spec = specular_probability(self.specular_sampling_weight, f_o);
        if u1 < p_spec {
            return Some(BsdfSample {
                wi: Vec3::new(-wo.x, -wo.y, wo.z),
                weight: self.specular_reflectance * (f_o / p_spec),
                pdf: p_spec,
                delta: true,
                eta: 1.0,
            });
        }
        let (wi, pdf_dir) = CosineHemisphere.sample_with_pdf(u2);
        let pdf = (1.0 - p_spec) * pdf_dir;
        if !is_positive(pdf) || wi.z <= 0.0 {
            return None;
        }
        Some(BsdfSample {
            wi,
            weight: self.diffuse(f_o, wi.z) / (1.0 - p_spec),
            pdf,
            delta: false,
            eta: 1.0,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn white_plastic_reflects_everything() {
        // ρ = 1: the specular F(θ_o) plus the diffuse part's albedo (1 − F(θ_o)) (1 − F_ext)
        // / (η² (1 − F_int)), where 1 − F_ext = η² (1 − F_int) up to the fits' error.
        let b = Plastic::new(Vec3::ONE, Vec3::ONE, 1.5, false);
        for cos in [1.0f32, 0.5, 0.1] {
            let wo = Vec3::new((1.0 - cos * cos).sqrt(), 0.0, cos);
            let n = 400;
            let mut diffuse = 0.0f64;
            for i in 0..n {
                for j in 0..n {
                    let u = Vec2::new((i as f32 + 0.5) / n as f32, (j as f32 + 0.5) / n as f32);
                    let wi = CosineHemisphere.sample(u);
                    diffuse += f64::from(b.eval(wo, wi).x / CosineHemisphere.pdf(wi));
                }
            }
            let total = diffuse / (n * n) as f64 + f64::from(fresnel_dielectric(cos, 1.5).0);
            assert!(
                total.is_finite() && (total - 1.0).abs() < 3e-3,
                "{cos}: {total}"
            );
        }
    }
}
