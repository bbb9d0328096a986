//! Smooth dielectric (Mitsuba's `dielectric`): specular reflection and refraction.

use super::fresnel::fresnel_dielectric;
use glam::{Vec2, Vec3};
use mcrt::integrator::{Bsdf, BsdfFlags, BsdfSample};

/// A smooth interface between two dielectrics. Sampling picks reflection with probability
/// `F` and refraction with `1 − F`, so the weights are the tints alone, except that
/// refracted radiance is scaled by `1/η²` (radiance is not invariant across the interface;
/// Veach 1997, thesis, section 5.2) with η the relative index crossed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dielectric {
    /// Relative index of refraction, interior over exterior.
    pub eta: f32,
    /// Scale on reflection.
    pub specular_reflectance: Vec3,
    /// Scale on transmission.
    pub specular_transmittance: Vec3,
}

impl Bsdf for Dielectric {
    fn flags(&self) -> BsdfFlags {
        BsdfFlags {
            delta: true,
            transmission: true,
            ..BsdfFlags::default()
        }
    }

    eval_and_pdf_of_a_delta_bsdf!();

    fn sample(&self, wo: Vec3, u1: f32, _u2: Vec2) -> Option<BsdfSample> {
        let (r, cos_t, eta_it, eta_ti) = fresnel_dielectric(wo.z, self.eta);
        if u1 < r {
            return Some(BsdfSample {
                wi: Vec3::new(-wo.x, -wo.y, wo.z),
                weight: self.specular_reflectance,
                pdf: r,
                delta: true,
                eta: 1.0,
            });
        }
        let wi = Vec3::new(-eta_ti * wo.x, -eta_ti * wo.y, cos_t);
        Some(BsdfSample {
            wi: wi.normalize(),
            weight: self.specular_transmittance * (eta_ti * eta_ti),
            pdf: 1.0 - r,
            delta: true,
            eta: eta_it,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refraction_obeys_snell() {
        let d = Dielectric {
            eta: 1.5,
            specular_reflectance: Vec3::ONE,
            specular_transmittance: Vec3::ONE,
        };
        let wo = Vec3::new(0.6, 0.0, 0.8);
        let s = d.sample(wo, 0.99, Vec2::ZERO).expect("refracts");
        assert!(s.wi.z < 0.0 && s.wi.is_finite());
        let sin_t = (1.0 - s.wi.z * s.wi.z).sqrt();
        assert!((0.6 - 1.5 * sin_t).abs() < 1e-5);
        assert!((s.wi.length() - 1.0).abs() < 1e-5);
        assert!((s.weight.x - 1.0 / 2.25).abs() < 1e-5 && s.eta == 1.5);
        // The reverse path, from inside: the direction and the scale invert.
        let s2 = d.sample(s.wi, 0.99, Vec2::ZERO).expect("refracts out");
        assert!((s2.wi - wo).length() < 1e-4 && (s2.weight.x - 2.25).abs() < 1e-3);
    }
}
