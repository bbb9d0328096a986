//! Smooth conductor (Mitsuba's `conductor`): a mirror with a Fresnel term.

use super::fresnel::fresnel_conductor;
use glam::{Vec2, Vec3};
use mcrt::integrator::{Bsdf, BsdfFlags, BsdfSample};

/// The Fresnel term of a conductor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Fresnel {
    /// Reflects everything (Mitsuba's `material = "none"`).
    Perfect,
    /// Complex index of refraction `eta + i k` per RGB channel (outside: vacuum).
    Complex {
        /// Real part.
        eta: Vec3,
        /// Imaginary part.
        k: Vec3,
    },
}

impl Fresnel {
    /// Reflectance for a direction with cosine `cos_i` against the (micro)surface normal.
    #[inline]
    pub fn eval(&self, cos_i: f32) -> Vec3 {
        match *self {
            Fresnel::Perfect => Vec3::ONE,
            Fresnel::Complex { eta, k } => fresnel_conductor(cos_i, eta, k),
        }
    }
}

/// A smooth mirror: a Dirac delta in the reflected direction, weight `F · scale`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Conductor {
    /// Fresnel term.
    pub fresnel: Fresnel,
    /// Scale on the reflectance.
    pub specular_reflectance: Vec3,
}

impl Bsdf for Conductor {
    fn flags(&self) -> BsdfFlags {
        BsdfFlags {
            delta: true,
            ..BsdfFlags::default()
        }
    }

    eval_and_pdf_of_a_delta_bsdf!();

    #[inline]
    fn samples_component(&self) -> bool {
        false
    }

    fn sample(&self, wo: Vec3, _u1: f32, _u2: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        Some(BsdfSample {
            wi: Vec3::new(-wo.x, -wo.y, wo.z),
            weight: self.fresnel.eval(wo.z) * self.specular_reflectance,
            pdf: 1.0,
            delta: true,
            eta: 1.0,
        })
    }
}
