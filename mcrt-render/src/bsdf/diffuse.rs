//! Lambertian reflection (Mitsuba's `diffuse`), one-sided.

use glam::{Vec2, Vec3};
use mcrt::integrator::{is_positive, Bsdf, BsdfFlags, BsdfSample};
use mcrt::sampling::warp::{CosineHemisphere, Warp};
use std::f32::consts::FRAC_1_PI;

/// A Lambertian reflector: `f = ρ / π` above the surface, black from below. Sampled by the
/// cosine-weighted hemisphere (pdf cos θ / π per steradian), so the sample weight is ρ.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Diffuse {
    /// Albedo ρ, linear RGB.
    pub reflectance: Vec3,
}

impl Bsdf for Diffuse {
    #[inline]
    fn flags(&self) -> BsdfFlags {
        BsdfFlags {
            smooth: true,
            ..BsdfFlags::default()
        }
    }

    #[inline]
    fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Vec3::ZERO;
        }
        self.reflectance * (FRAC_1_PI * wi.z)
    }

    #[inline]
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z <= 0.0 {
            return 0.0;
        }
        CosineHemisphere.pdf(wi)
    }

    #[inline]
    fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return (Vec3::ZERO, 0.0);
        }
        let c = FRAC_1_PI * wi.z;
        (self.reflectance * c, c)
    }

    #[inline]
    fn samples_component(&self) -> bool {
        false
    }

    #[inline]
    fn sample(&self, wo: Vec3, _u1: f32, u2: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let (wi, pdf) = CosineHemisphere.sample_with_pdf(u2);
        if !is_positive(pdf) {
            return None;
        }
        Some(BsdfSample {
            wi,
            weight: self.reflectance,
            pdf,
            delta: false,
            eta: 1.0,
        })
    }
}
