//! The von Mises–Fisher density on the sphere.

use super::henyey_greenstein::one_minus_and_plus_cos;
use super::{InvertibleWarp, Warp};
use crate::sampling::error::check_param;
use crate::sampling::unit::{clamp_unit, clamp_unit2};
use crate::sampling::warp::polar::{azimuth_to_unit, direction};
use crate::sampling::SamplingError;
use glam::{Vec2, Vec3};
use std::f64::consts::PI;

/// Directions on the sphere with the von Mises–Fisher density about +z,
/// `κ e^{−κ(1 − cos θ)} / (2π (1 − e^{−2κ}))` per steradian (`κ = 0`: uniform).
///
/// Mapping (inversion of the CDF in `1 − cos θ`, written with `ln_1p` and `expm1` so that it
/// holds from `κ → 0` to `κ = 10⁴` and beyond without overflow):
/// `1 − cos θ = −ln(1 + u₁ expm1(−2κ))/κ`, `sin θ = √((1 − cos θ)(1 + cos θ))`, `φ = 2πu₂`.
/// Inverse: `u₁ = expm1(−κ(1 − cos θ))/expm1(−2κ)`, `u₂ = φ/(2π)`. The normalisation
/// `κ/(1 − e^{−2κ})` never overflows since `e^{κ cos θ}` is not formed.
///
/// Citation: W. Jakob, 2012, "Numerically stable sampling of the von Mises Fisher distribution
/// on S² (and other tricks)", technical note. Derivation: `docs/derivations.md`.
///
/// ```
/// use mcrt::glam::Vec2;
/// use mcrt::sampling::warp::{InvertibleWarp, VonMisesFisher, Warp};
///
/// let v = VonMisesFisher::new(1e4).unwrap();
/// let (w, pdf) = v.sample_with_pdf(Vec2::new(0.5, 0.25));
/// assert!(w.is_finite() && w.z > 0.99 && pdf.is_finite());
/// assert!((v.invert(w) - Vec2::new(0.5, 0.25)).length() < 1e-4);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VonMisesFisher {
    kappa: f64,
    /// `expm1(−2κ)`, in `[−1, 0]`.
    expm1_2k: f64,
    /// The peak density `κ/(2π(1 − e^{−2κ}))` (`1/(4π)` at `κ = 0`).
    peak: f64,
}

impl VonMisesFisher {
    /// The density with concentration `κ = kappa ≥ 0`. Errors unless `kappa` is finite,
    /// `≥ 0` and at most 10¹⁰ (a lobe of about 10⁻⁵ rad, where the samples' `x² + y²` still
    /// resolves in `f32`).
    pub fn new(kappa: f32) -> Result<Self, SamplingError> {
        let k = check_param("kappa", kappa, "finite, in [0, 1e10]", |k| {
            (0.0..=1e10).contains(&k)
        })?;
        let kappa = f64::from(k);
        let expm1_2k = (-2.0 * kappa).exp_m1();
        let peak = if kappa > 0.0 {
            kappa / (2.0 * PI * -expm1_2k)
        } else {
            1.0 / (4.0 * PI)
        };
        Ok(Self {
            kappa,
            expm1_2k,
            peak,
        })
    }

    /// The concentration `κ`.
    #[must_use]
    pub fn kappa(&self) -> f32 {
        self.kappa as f32
    }
}

impl Warp for VonMisesFisher {
    type Point = Vec3;

    #[inline]
    fn sample(&self, u: Vec2) -> Vec3 {
        let u1 = f64::from(clamp_unit(u.x));
        let omc = if self.kappa > 0.0 {
            (-(u1 * self.expm1_2k).ln_1p() / self.kappa).clamp(0.0, 2.0)
        } else {
            2.0 * u1
        };
        let sin = (omc * (2.0 - omc)).max(0.0).sqrt();
        direction(sin as f32, (1.0 - omc) as f32, u.y)
    }

    /// `κ e^{−κ(1 − cos θ)}/(2π(1 − e^{−2κ}))` per steradian for unit `w`; 0 for NaN.
    #[inline]
    fn pdf(&self, w: Vec3) -> f32 {
        if !w.is_finite() {
            return 0.0;
        }
        let (omc, _) = one_minus_and_plus_cos(w);
        (self.peak * (-self.kappa * omc).exp()) as f32
    }
}

impl InvertibleWarp for VonMisesFisher {
    #[inline]
    fn invert(&self, w: Vec3) -> Vec2 {
        let (omc, _) = one_minus_and_plus_cos(w);
        let u1 = if self.kappa > 0.0 {
            (-self.kappa * omc).exp_m1() / self.expm1_2k
        } else {
            0.5 * omc
        };
        clamp_unit2(
            if u1.is_nan() { 0.0 } else { u1 as f32 },
            azimuth_to_unit(w.x, w.y),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extremes_are_finite_and_round_trip() {
        for kappa in [0.0f32, 1e-30, 1e-3, 1.0, 100.0, 1e4, 1e10] {
            let v = VonMisesFisher::new(kappa).unwrap();
            for u in [0.0, 1e-7, 0.3, 0.9, 1.0 - 2f32.powi(-24)] {
                let w = v.sample(Vec2::new(u, 0.3));
                let pdf = v.pdf(w);
                assert!(
                    w.is_finite() && pdf.is_finite() && pdf > 0.0,
                    "{kappa} {u}: {w} {pdf}"
                );
                assert!((w.length() - 1.0).abs() < 1e-6);
                if u > 0.0 && u < 0.95 {
                    let back = v.invert(w);
                    assert!(
                        back.is_finite() && (back.x - u).abs() < 1e-4,
                        "{kappa} {u} {back}"
                    );
                }
            }
        }
        for bad in [-1.0, f32::NAN, f32::INFINITY, 1e11] {
            assert!(VonMisesFisher::new(bad).is_err());
        }
    }
}
