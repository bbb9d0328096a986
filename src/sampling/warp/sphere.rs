//! Uniform directions on the whole unit sphere.

use super::{InvertibleWarp, Warp};
use crate::sampling::unit::clamp_unit2;
use crate::sampling::warp::polar::{azimuth_to_unit, direction, one_minus_cos_theta};
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// Uniform directions on the unit sphere S²; pdf `1/(4π)` per unit solid angle (steradian).
///
/// Mapping (Archimedes' hat-box theorem, by inversion of the CDF of z):
/// `z = 1 − 2u₁`, `φ = 2πu₂`, `sin θ = 2√(u₁(1 − u₁))` (computed so, not from z, so the
/// poles stay accurate). Inverse: `u₁ = (1 − z)/2`, with `1 − z = (x² + y²)/(1 + z)` near the
/// north pole; `u₂ = atan2(y, x)/(2π)` mapped into `[0, 1)`.
///
/// Citation: J. Arvo, 2001, "Stratified sampling of 2-manifolds", SIGGRAPH course notes
/// (the z-uniform construction). Derivation: `docs/derivations.md`.
///
/// Directions passed to [`Warp::pdf`] and [`InvertibleWarp::invert`] are expected to be unit
/// length; other finite inputs give finite, meaningless values.
///
/// ```
/// use mcrt::glam::Vec2;
/// use mcrt::sampling::warp::{InvertibleWarp, UniformSphere, Warp};
///
/// let w = UniformSphere.sample(Vec2::new(0.25, 0.5));
/// assert!((w.length() - 1.0).abs() < 1e-6 && (w.z - 0.5).abs() < 1e-6);
/// assert!((UniformSphere.pdf(w) - 0.25 / std::f32::consts::PI).abs() < 1e-7);
/// assert!((UniformSphere.invert(w) - Vec2::new(0.25, 0.5)).abs().max_element() < 1e-6);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct UniformSphere;

/// The constant density of [`UniformSphere`], per steradian.
const INV_FOUR_PI: f32 = 0.25 / PI;

impl Warp for UniformSphere {
    type Point = Vec3;

    #[inline]
    fn sample(&self, u: Vec2) -> Vec3 {
        let z = 1.0 - 2.0 * u.x;
        let sin_theta = 2.0 * (u.x * (1.0 - u.x)).max(0.0).sqrt();
        direction(sin_theta, z, u.y)
    }

    /// `1/(4π)` per steradian for every finite direction; 0 for non-finite input.
    #[inline]
    fn pdf(&self, w: Vec3) -> f32 {
        if w.is_finite() {
            INV_FOUR_PI
        } else {
            0.0
        }
    }
}

impl InvertibleWarp for UniformSphere {
    #[inline]
    fn invert(&self, w: Vec3) -> Vec2 {
        let u1 = 0.5 * one_minus_cos_theta(w);
        clamp_unit2(u1, azimuth_to_unit(w.x, w.y))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn poles_and_equator() {
        let n = UniformSphere.sample(Vec2::new(0.0, 0.3));
        assert!(n.is_finite() && (n - Vec3::Z).length() < 1e-7);
        let s = UniformSphere.sample(Vec2::new(crate::sampling::ONE_MINUS_EPSILON, 0.3));
        assert!(s.is_finite() && (s + Vec3::Z).length() < 1e-3);
        let e = UniformSphere.sample(Vec2::new(0.5, 0.25));
        assert!(e.is_finite() && (e - Vec3::Y).length() < 1e-6);
    }

    #[test]
    fn pdf_is_constant() {
        let p = UniformSphere.pdf(Vec3::new(0.0, 0.6, -0.8));
        assert!(p.is_finite() && (p - 1.0 / (4.0 * PI)).abs() < 1e-8);
        assert_eq!(UniformSphere.pdf(Vec3::new(f32::NAN, 0.0, 1.0)), 0.0);
    }

    #[test]
    fn round_trip() {
        for i in 1..10 {
            for j in 1..10 {
                let u = Vec2::new(i as f32 / 10.0, j as f32 / 10.0);
                let back = UniformSphere.invert(UniformSphere.sample(u));
                assert!(back.is_finite() && (back - u).abs().max_element() < 1e-6);
            }
        }
    }

    #[test]
    fn tiny_u_keeps_its_angle() {
        let u = Vec2::new(1e-12, 0.0);
        let w = UniformSphere.sample(u);
        // sin θ = 2√(u₁) = 2e-6 even though z rounds to 1.
        assert!(w.is_finite() && (w.x - 2e-6).abs() < 1e-11);
        let back = UniformSphere.invert(w);
        assert!(back.is_finite() && ((back.x - 1e-12) / 1e-12).abs() < 1e-5);
    }
}
