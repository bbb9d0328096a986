//! Thin dielectric (Mitsuba's `thindielectric`): a pane of glass of negligible thickness.

use super::fresnel::fresnel_dielectric;
use glam::{Vec2, Vec3};
use mcrt::integrator::{Bsdf, BsdfFlags, BsdfSample};

/// A thin slab with two parallel smooth faces: light is either reflected about the normal
/// or passes straight through (the two refractions cancel), with every internal bounce
/// summed. With `R` the reflectance of one face, the slab reflects
/// `R' = R + (1 − R)² R / (1 − R²)` (the geometric series of bounces inside, absorption-free)
/// and transmits `1 − R'`. Sampling picks reflection with probability `R'`, so the weights
/// are the tints alone. The same from both sides.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ThinDielectric {
    /// Relative index of refraction, slab over surroundings.
    pub eta: f32,
    /// Scale on reflection.
    pub specular_reflectance: Vec3,
    /// Scale on transmission.
    pub specular_transmittance: Vec3,
}

impl ThinDielectric {
    /// The slab's total reflectance `R'` for a direction with cosine `cos_o` (either side).
    #[inline]
    pub fn reflectance(&self, cos_o: f32) -> f32 {
        let (r, _, _, _) = fresnel_dielectric(cos_o.abs(), self.eta);
        if r < 1.0 {
            let t = 1.0 - r;
            r + t * t * r / (1.0 - r * r)
        } else {
            1.0
        }
    }
}

impl Bsdf for ThinDielectric {
    fn flags(&self) -> BsdfFlags {
        BsdfFlags {
            delta: true,
            transmission: true,
            ..BsdfFlags::default()
        }
    }

    eval_and_pdf_of_a_delta_bsdf!();

    fn sample(&self, wo: Vec3, u1: f32, _u2: Vec2) -> Option<BsdfSample> {
        if !wo.is_finite() {
            return None;
        }
        let r = self.reflectance(wo.z);
        let (wi, weight, pdf) = if u1 < r {
            (Vec3::new(-wo.x, -wo.y, wo.z), self.specular_reflectance, r)
        } else {
            (-wo, self.specular_transmittance, 1.0 - r)
        };
        Some(BsdfSample {
            wi,
            weight,
            pdf,
            delta: true,
            eta: 1.0,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slab_reflectance_sums_the_internal_bounces() {
        let b = ThinDielectric {
            eta: 1.5,
            specular_reflectance: Vec3::ONE,
            specular_transmittance: Vec3::ONE,
        };
        // At normal incidence R = 0.04: R' = 2R / (1 + R) = 0.0769…
        let r = b.reflectance(1.0);
        assert!(r.is_finite() && (r - 0.08 / 1.04).abs() < 1e-6, "{r}");
        assert_eq!(b.reflectance(-1.0), r);
        let s = b
            .sample(Vec3::new(0.6, 0.0, -0.8), 0.5, Vec2::ZERO)
            .expect("sample");
        assert_eq!(s.wi, Vec3::new(-0.6, 0.0, 0.8));
        assert!(s.delta && s.eta == 1.0 && s.weight == Vec3::ONE);
    }
}
