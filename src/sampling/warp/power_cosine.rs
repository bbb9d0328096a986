//! Power-cosine lobes about +z: the Phong/Blinn family, resolved in f32 up to exponent 10⁶.

use super::{InvertibleWarp, Warp};
use crate::sampling::error::check_param;
use crate::sampling::unit::clamp_unit2;
use crate::sampling::warp::polar::{
    azimuth_to_unit, direction, one_minus_cos_theta, sin_from_one_minus_cos,
};
use crate::sampling::SamplingError;
use glam::{Vec2, Vec3};

/// Directions on the upper hemisphere with pdf `(n + 1)/(2π) cosⁿθ` per steradian.
///
/// Mapping (inversion of P(cos θ) = cos^{n+1}θ): `cos θ = u₁^{1/(n+1)}`, `φ = 2πu₂`. It is
/// evaluated as `ℓ = ln(u₁)/(n + 1)`, `cos θ = exp(ℓ)`, `1 − cos θ = −expm1(ℓ)` and
/// `sin θ = √((1 − cos θ)(1 + cos θ))`, so a lobe of exponent 10⁶ (width ~10⁻³ rad) keeps full
/// f32 relative precision in `sin θ` although its z rounds to 1. `pdf` and `invert` take
/// `1 − cos θ = (x² + y²)/(1 + z)` near the pole and `cosⁿθ = exp(n · ln_1p(−(1 − cos θ)))`.
///
/// **Blinn's NDF.** With the exponent `n` of the Blinn–Phong normal distribution
/// `D(h) = (n + 2)/(2π) cosⁿθ_h` (normalised so that `∫ D(h) cos θ_h dω_h = 1`):
/// - sampling the half-vector proportionally to `D(h)` itself, as the course notes do, is
///   `PowerCosineHemisphere::new(n)`: `cos θ_h = u₁^{1/(n+1)}`, pdf `(n + 1)/(2π) cosⁿθ_h`;
/// - sampling it proportionally to `D(h) cos θ_h` (the microfacet convention, the one Mitsuba
///   uses for its NDFs) is `PowerCosineHemisphere::new(n + 1)`: pdf
///   `(n + 2)/(2π) cos^{n+1}θ_h = D(h) cos θ_h`.
///
/// Either way, the reflected direction `wi = 2(wo·h)h − wo` has the pdf
/// `p(wi) = p(h) / (4 |wo·h|)` per steradian (the Jacobian of the reflection map).
///
/// Citation: J. F. Blinn, 1977, "Models of Light Reflection for Computer Synthesized
/// Pictures", SIGGRAPH; sampling as in P. Shirley, 2000, "Realistic Ray Tracing", A K Peters.
/// Derivation: `docs/derivations.md`.
///
/// Directions passed to [`Warp::pdf`] and [`InvertibleWarp::invert`] are expected to be unit
/// length; other finite vectors give finite, meaningless values.
///
/// ```
/// use mcrt::glam::Vec2;
/// use mcrt::sampling::warp::{InvertibleWarp, PowerCosineHemisphere, Warp};
///
/// let lobe = PowerCosineHemisphere::new(1e6).unwrap();
/// let u = Vec2::new(0.5, 0.25);
/// let (w, pdf) = lobe.sample_with_pdf(u);
/// // 1 − cos θ = ln 2 / (10⁶ + 1); sin θ ≈ √(2 ln 2 · 10⁻⁶).
/// assert!((w.y - (2.0 * 2f32.ln() * 1e-6).sqrt()).abs() < 1e-8);
/// assert!(((pdf - lobe.pdf(w)) / pdf).abs() < 1e-4);
/// assert!((lobe.invert(w) - u).length() < 1e-5);
/// assert!(PowerCosineHemisphere::new(-1.0).is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PowerCosineHemisphere {
    exponent: f32,
    norm: f32,
}

impl PowerCosineHemisphere {
    /// The lobe `cosⁿθ` with `n = exponent`, finite and ≥ 0 (0 is the uniform hemisphere,
    /// 1 the cosine-weighted one). Tested up to 10⁶.
    pub fn new(exponent: f32) -> Result<Self, SamplingError> {
        let n = check_param("exponent", exponent, "finite and >= 0", |n| n >= 0.0)?;
        Ok(Self {
            exponent: n,
            norm: ((f64::from(n) + 1.0) / std::f64::consts::TAU) as f32,
        })
    }

    /// The exponent `n`.
    #[must_use]
    pub fn exponent(&self) -> f32 {
        self.exponent
    }

    /// `cosⁿθ` from `ln cos θ`, with `cos⁰θ = 1` even on the horizon.
    #[inline]
    fn cos_pow_n(&self, ln_cos: f32) -> f32 {
        if self.exponent == 0.0 {
            1.0
        } else {
            (self.exponent * ln_cos).exp()
        }
    }

    /// `ln cos θ` of a direction with z ≥ 0, from the stable `1 − cos θ`.
    #[inline]
    fn ln_cos(w: Vec3) -> f32 {
        (-one_minus_cos_theta(w).min(1.0)).ln_1p()
    }
}

impl Warp for PowerCosineHemisphere {
    type Point = Vec3;

    #[inline]
    fn sample(&self, u: Vec2) -> Vec3 {
        let l = u.x.max(0.0).ln() / (self.exponent + 1.0);
        let t = -l.exp_m1();
        direction(sin_from_one_minus_cos(t), l.exp(), u.y)
    }

    /// `(n + 1)/(2π) cosⁿθ` per steradian for z ≥ 0, 0 below or for non-finite input.
    #[inline]
    fn pdf(&self, w: Vec3) -> f32 {
        if w.z >= 0.0 && w.is_finite() {
            self.norm * self.cos_pow_n(Self::ln_cos(w))
        } else {
            0.0
        }
    }

    #[inline]
    fn sample_with_pdf(&self, u: Vec2) -> (Vec3, f32) {
        let l = u.x.max(0.0).ln() / (self.exponent + 1.0);
        let t = -l.exp_m1();
        let w = direction(sin_from_one_minus_cos(t), l.exp(), u.y);
        (w, self.norm * self.cos_pow_n(l))
    }
}

impl InvertibleWarp for PowerCosineHemisphere {
    #[inline]
    fn invert(&self, w: Vec3) -> Vec2 {
        let u1 = ((self.exponent + 1.0) * Self::ln_cos(w)).exp();
        clamp_unit2(u1, azimuth_to_unit(w.x, w.y))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::warp::{CosineHemisphere, UniformHemisphere};
    use std::f32::consts::PI;

    #[test]
    fn rejects_bad_exponents() {
        for n in [-1e-3, f32::NAN, f32::INFINITY] {
            assert!(PowerCosineHemisphere::new(n).is_err());
        }
    }

    #[test]
    fn low_exponents_match_known_lobes() {
        let n0 = PowerCosineHemisphere::new(0.0).unwrap();
        let n1 = PowerCosineHemisphere::new(1.0).unwrap();
        let w = Vec3::new(0.6, 0.0, 0.8);
        assert!((n0.pdf(w) - UniformHemisphere.pdf(w)).abs() < 1e-7);
        assert!((n1.pdf(w) - CosineHemisphere.pdf(w)).abs() < 1e-7);
        assert!((n0.pdf(Vec3::X) - 0.5 / PI).abs() < 1e-7);
        assert_eq!(n1.pdf(Vec3::X), 0.0);
        assert_eq!(n1.pdf(Vec3::new(0.0, 0.6, -0.8)), 0.0);
    }

    #[test]
    fn horizon_sample_is_finite() {
        for n in [0.0, 1.0, 1e6] {
            let lobe = PowerCosineHemisphere::new(n).unwrap();
            let (w, pdf) = lobe.sample_with_pdf(Vec2::new(0.0, 0.3));
            assert!(w.is_finite() && pdf.is_finite() && w.z.abs() < 1e-6);
        }
    }

    #[test]
    fn huge_exponent_pdf_at_pole_and_round_trip() {
        let lobe = PowerCosineHemisphere::new(1e6).unwrap();
        let p = lobe.pdf(Vec3::Z);
        let expect = (1e6 + 1.0) / (2.0 * std::f64::consts::PI);
        assert!(p.is_finite() && ((f64::from(p) - expect) / expect).abs() < 1e-6);
        for i in 1..20 {
            for j in 1..20 {
                let u = Vec2::new(i as f32 / 20.0, j as f32 / 20.0);
                let (w, pdf) = lobe.sample_with_pdf(u);
                let back = lobe.invert(w);
                assert!(
                    back.is_finite() && (back - u).abs().max_element() < 1e-5,
                    "{u}"
                );
                let again = lobe.pdf(w);
                assert!(
                    again.is_finite() && ((again - pdf) / pdf).abs() < 1e-4,
                    "{u}"
                );
            }
        }
    }
}
