//! Opacity mask (Mitsuba's `mask`): a material that is partly not there.

use super::{AnyBsdf, Sided};
use glam::{Vec2, Vec3};
use mcrt::integrator::{Bsdf, BsdfFlags, BsdfSample};

/// A material of opacity `α` (Mitsuba 3's `mask`, with a constant `opacity`): `α` times the
/// nested material, and with probability `1 − α` light passes straight through
/// (`wi = −wo`, weight 1), a Dirac transmission that changes nothing along the ray. As in
/// Mitsuba 3's path tracer, passing through is a scattering event: it counts toward
/// `max_depth`, and shadow rays stop at the surface (Mitsuba's occlusion tests do not look
/// at masks either). `eval` and `pdf` are `α` times the nested material's. (Mitsuba 3's
/// `path` also drops the estimate of a camera path that only passed through masks and
/// then escaped into an empty background; we keep it: `docs/bsdf-models.md`, "Blend and
/// mask".)
#[derive(Debug, Clone, PartialEq)]
pub struct Mask {
    /// Opacity α in [0, 1].
    pub opacity: f32,
    /// The material where the surface is opaque.
    pub inner: Box<Sided<AnyBsdf>>,
}

impl Bsdf for Mask {
    fn flags(&self) -> BsdfFlags {
        BsdfFlags {
            delta: true,
            transmission: true,
            ..self.inner.flags()
        }
    }

    fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        self.inner.eval(wo, wi) * self.opacity
    }

    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.inner.pdf(wo, wi) * self.opacity
    }

    fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        let (f, pdf) = self.inner.eval_pdf(wo, wi);
        (f * self.opacity, pdf * self.opacity)
    }

    fn eval_adjoint(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        self.inner.eval_adjoint(wo, wi) * self.opacity
    }

    fn sample(&self, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        let a = self.opacity;
        if u1 < a {
            let u1 = (u1 / a).clamp(0.0, 1.0 - f32::EPSILON / 2.0);
            let mut s = self.inner.sample(wo, u1, u2)?;
            s.pdf *= a;
            return Some(s);
        }
        Some(BsdfSample {
            wi: -wo,
            weight: Vec3::ONE,
            pdf: 1.0 - a,
            delta: true,
            eta: 1.0,
        })
    }
}
