//! Blend of two materials (Mitsuba's `blendbsdf`) with a constant weight.

use super::{AnyBsdf, Sided};
use glam::{Vec2, Vec3};
use mcrt::integrator::{is_positive, Bsdf, BsdfFlags, BsdfSample};

/// `(1 − w) f₀ + w f₁`, a linear blend of two materials (Mitsuba 3's `blendbsdf`, with a
/// constant `weight`; Mitsuba also takes a texture). The pdf is the same blend of the
/// two pdfs. Sampling picks material 1 with probability `w` (and `u1` rescaled to the
/// chosen part of [0, 1) for its own choice), then returns the mixture's `f cos θ_i / pdf`
/// for a direction with a density, or the chosen material's own weight for a Dirac one
/// (whose probability is scaled by the choice's).
#[derive(Debug, Clone, PartialEq)]
pub struct Blend {
    /// Weight `w` of the second material, in [0, 1].
    pub weight: f32,
    /// The first material (weight `1 − w`).
    pub first: Box<Sided<AnyBsdf>>,
    /// The second material (weight `w`).
    pub second: Box<Sided<AnyBsdf>>,
}

impl Blend {
    /// Blends the non-delta parts: `(f, pdf)` of the mixture.
    fn mix(&self, a: (Vec3, f32), b: (Vec3, f32)) -> (Vec3, f32) {
        let w = self.weight;
        (a.0 * (1.0 - w) + b.0 * w, a.1 * (1.0 - w) + b.1 * w)
    }
}

impl Bsdf for Blend {
    fn flags(&self) -> BsdfFlags {
        let (a, b) = (self.first.flags(), self.second.flags());
        BsdfFlags {
            smooth: a.smooth || b.smooth,
            delta: a.delta || b.delta,
            glossy: a.glossy || b.glossy,
            transmission: a.transmission || b.transmission,
        }
    }

    eval_and_pdf_from_eval_pdf!();

    fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        self.mix(self.first.eval_pdf(wo, wi), self.second.eval_pdf(wo, wi))
    }

    fn eval_adjoint(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        let w = self.weight;
        self.first.eval_adjoint(wo, wi) * (1.0 - w) + self.second.eval_adjoint(wo, wi) * w
    }

    fn sample(&self, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        let w = self.weight;
        let (chosen, p, u1) = if u1 < w {
            (&self.second, w, u1 / w)
        } else {
            (&self.first, 1.0 - w, (u1 - w) / (1.0 - w))
        };
        let mut s = chosen.sample(wo, u1.clamp(0.0, 1.0 - f32::EPSILON / 2.0), u2)?;
        if s.delta {
            s.pdf *= p;
            return Some(s);
        }
        let (f, pdf) = self.eval_pdf(wo, s.wi);
        if !is_positive(pdf) || !pdf.is_finite() {
            return None;
        }
        s.weight = f / pdf;
        s.pdf = pdf;
        Some(s)
    }
}
