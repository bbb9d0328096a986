//! f64 references of the microfacet normal distributions, sampled with pdf D(m) cos θ per
//! steradian (Walter, Marschner, Li, Torrance 2007, "Microfacet Models for Refraction through
//! Rough Surfaces", EGSR).

use crate::reference::Reference;
use mcrt::glam::{DVec2, DVec3};
use std::f64::consts::{PI, TAU};

/// The normal with tan²θ = `tan2` and azimuth 2πu₂.
fn normal(tan2: f64, u2: f64) -> DVec3 {
    let c = 1.0 / (1.0 + tan2).sqrt();
    let s = tan2.sqrt() * c;
    let (sp, cp) = (TAU * u2).sin_cos();
    DVec3::new(s * cp, s * sp, c)
}

/// (tan²θ, cos θ) of a direction; `None` below the horizon.
fn tan2_cos(m: DVec3) -> Option<(f64, f64)> {
    let m = m.normalize();
    (m.z > 0.0).then(|| ((m.x * m.x + m.y * m.y) / (m.z * m.z), m.z))
}

/// Beckmann: tan²θ = −α² ln(1 − u₁).
pub struct RefBeckmann {
    /// Roughness α.
    pub alpha: f64,
}

impl RefBeckmann {
    fn density(&self, tan2: f64, c: f64) -> f64 {
        let a2 = self.alpha * self.alpha;
        (-tan2 / a2).exp() / (PI * a2 * c * c * c)
    }
}

impl Reference for RefBeckmann {
    fn sample(&self, u: DVec2) -> (DVec3, f64) {
        let tan2 = -self.alpha * self.alpha * (-u.x).ln_1p();
        let c = 1.0 / (1.0 + tan2).sqrt();
        (normal(tan2, u.y), self.density(tan2, c))
    }
    fn pdf(&self, m: DVec3) -> f64 {
        tan2_cos(m).map_or(0.0, |(t, c)| self.density(t, c))
    }
}

/// GGX (Trowbridge–Reitz): tan²θ = α² u₁ / (1 − u₁).
pub struct RefGgx {
    /// Roughness α.
    pub alpha: f64,
}

impl RefGgx {
    fn density(&self, tan2: f64, c: f64) -> f64 {
        let a2 = self.alpha * self.alpha;
        let k = a2 + tan2;
        a2 / (PI * c * c * c * k * k)
    }
}

impl Reference for RefGgx {
    fn sample(&self, u: DVec2) -> (DVec3, f64) {
        let tan2 = self.alpha * self.alpha * u.x / (1.0 - u.x);
        let c = 1.0 / (1.0 + tan2).sqrt();
        (normal(tan2, u.y), self.density(tan2, c))
    }
    fn pdf(&self, m: DVec3) -> f64 {
        tan2_cos(m).map_or(0.0, |(t, c)| self.density(t, c))
    }
}

/// GGX visible normals by the spherical-cap method (Dupuy, Benyoub 2023, "Sampling Visible
/// GGX Normals with Spherical Caps", Computer Graphics Forum): in the configuration stretched
/// to α = 1, h = c + wᵢ′ with c uniform on the cap z ≥ −wᵢ′.z (height from u₁, azimuth 2πu₂);
/// pdf G₁(wᵢ) max(0, wᵢ·m) D(m) / cos θᵢ per steradian.
pub struct RefGgxVisible {
    alpha: f64,
    wi: DVec3,
    /// wᵢ stretched to α = 1.
    w: DVec3,
    /// 1 / ((1 + Λ(wᵢ)) cos θᵢ).
    scale: f64,
}

impl RefGgxVisible {
    /// Roughness `alpha`, incident direction `wi` (normalised here; z > 0).
    pub fn new(alpha: f64, wi: DVec3) -> Self {
        let wi = wi.normalize();
        let w = DVec3::new(alpha * wi.x, alpha * wi.y, wi.z).normalize();
        let tan2_i = (wi.x * wi.x + wi.y * wi.y) / (wi.z * wi.z);
        let lambda = ((1.0 + alpha * alpha * tan2_i).sqrt() - 1.0) / 2.0;
        let scale = 1.0 / ((1.0 + lambda) * wi.z);
        Self {
            alpha,
            wi,
            w,
            scale,
        }
    }
}

impl Reference for RefGgxVisible {
    fn sample(&self, u: DVec2) -> (DVec3, f64) {
        let (a, w) = (self.alpha, self.w);
        let t = (1.0 - u.x) * (1.0 + w.z);
        let one_plus_z = t + (w.x * w.x + w.y * w.y) / (1.0 + w.z);
        let one_minus_z = (1.0 + w.z) - t;
        let s = (one_plus_z * one_minus_z).max(0.0).sqrt();
        let (sp, cp) = (TAU * u.y).sin_cos();
        let h = DVec3::new(s * cp + w.x, s * sp + w.y, t);
        let m = DVec3::new(a * h.x, a * h.y, h.z).normalize();
        (m, self.pdf(m))
    }
    fn pdf(&self, m: DVec3) -> f64 {
        let m = m.normalize();
        let dot = self.wi.dot(m);
        if m.z <= 0.0 || dot <= 0.0 {
            return 0.0;
        }
        let (t, c) = ((m.x * m.x + m.y * m.y) / (m.z * m.z), m.z);
        RefGgx { alpha: self.alpha }.density(t, c) / c * dot * self.scale
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// pdf = 1 / |Jacobian| by central differences, as for the other references.
    #[test]
    fn pdf_is_the_inverse_jacobian() {
        let wi = DVec3::new(0.6, 0.0, 0.8);
        let refs: [Box<dyn Reference>; 6] = [
            Box::new(RefGgxVisible::new(0.5, wi)),
            Box::new(RefGgxVisible::new(0.05, wi)),
            Box::new(RefBeckmann { alpha: 0.5 }),
            Box::new(RefBeckmann { alpha: 0.05 }),
            Box::new(RefGgx { alpha: 0.5 }),
            Box::new(RefGgx { alpha: 0.05 }),
        ];
        let h = 1e-7;
        for r in refs {
            for i in 1..8 {
                let u = DVec2::new(i as f64 / 8.0, 0.3);
                let d = |e: DVec2| (r.sample(u + e).0 - r.sample(u - e).0) / (2.0 * h);
                let jac = d(DVec2::new(h, 0.0)).cross(d(DVec2::new(0.0, h))).length();
                let (m, p) = r.sample(u);
                let err = (p * jac - 1.0).abs();
                assert!(p.is_finite() && err < 1e-5, "{u} {err}");
                let again = r.pdf(m);
                assert!(again.is_finite() && ((again - p) / p).abs() < 1e-12);
            }
        }
    }
}
