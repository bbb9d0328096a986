//! The course quiz's density on the hemisphere: `p(ω) ∝ θ / sin θ`.

use super::{InvertibleWarp, Warp};
use crate::sampling::unit::clamp_unit2;
use crate::sampling::warp::polar::{azimuth_to_unit, direction};
use glam::{Vec2, Vec3};
use std::f32::consts::{FRAC_2_PI, FRAC_PI_2, PI};

/// `4/π³`, the normalisation of `θ / sin θ` over the hemisphere.
const NORM: f32 = 4.0 / (PI * PI * PI);

/// Below this θ, `θ / sin θ = 1 + θ²/6 + …` is 1 to f32 precision.
const SMALL_THETA: f32 = 1e-4;

/// Directions on the upper hemisphere with pdf `p(ω) = (4/π³) · θ / sin θ` per steradian.
///
/// In (θ, φ) the density is `p(θ, φ) = sin θ · p(ω) = (4/π³) θ`, so θ has the marginal
/// `p(θ) = 8θ/π²` and CDF `P(θ) = 4θ²/π²`, and φ is uniform. Mapping: `θ = (π/2)√u₁`,
/// `φ = 2πu₂`, `ω = (sin θ cos φ, sin θ sin φ, cos θ)`. Inverse: `θ = atan2(√(x² + y²), z)`,
/// `u₁ = (2θ/π)²`. At the pole the pdf is its limit `4/π³`, never `0/0`; on the horizon it
/// is `2/π²`.
///
/// Citation: the quiz of the course notes (`docs/derivations.md` works it out), solved by the
/// inversion method as in M. Pharr, W. Jakob, G. Humphreys, 2016, "Physically Based
/// Rendering", 3rd ed., §13.6.
///
/// Directions passed to [`Warp::pdf`] and [`InvertibleWarp::invert`] are expected to be unit
/// length; since θ comes from `atan2`, any finite nonzero vector gives the pdf of its
/// direction.
///
/// ```
/// use mcrt::glam::{Vec2, Vec3};
/// use mcrt::sampling::warp::{ThetaOverSinHemisphere, Warp};
/// use std::f32::consts::PI;
///
/// let pole = ThetaOverSinHemisphere.sample(Vec2::new(0.0, 0.5));
/// assert_eq!(pole, Vec3::Z);
/// assert!((ThetaOverSinHemisphere.pdf(pole) - 4.0 / PI.powi(3)).abs() < 1e-7);
/// assert!((ThetaOverSinHemisphere.pdf(Vec3::X) - 2.0 / (PI * PI)).abs() < 1e-7);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ThetaOverSinHemisphere;

/// `θ / sin θ`, 1 at θ = 0 (its limit), never NaN for θ ∈ [0, π/2].
#[inline]
fn theta_over_sin(theta: f32) -> f32 {
    if theta < SMALL_THETA {
        1.0
    } else {
        theta / theta.sin()
    }
}

impl Warp for ThetaOverSinHemisphere {
    type Point = Vec3;

    #[inline]
    fn sample(&self, u: Vec2) -> Vec3 {
        let theta = FRAC_PI_2 * u.x.max(0.0).sqrt();
        let (s, c) = theta.sin_cos();
        direction(s, c, u.y)
    }

    /// `(4/π³) θ / sin θ` per steradian for z ≥ 0, 0 below or for non-finite input.
    #[inline]
    fn pdf(&self, w: Vec3) -> f32 {
        if w.z >= 0.0 && w.is_finite() {
            let theta = (w.x * w.x + w.y * w.y).sqrt().atan2(w.z);
            NORM * theta_over_sin(theta)
        } else {
            0.0
        }
    }

    #[inline]
    fn sample_with_pdf(&self, u: Vec2) -> (Vec3, f32) {
        let theta = FRAC_PI_2 * u.x.max(0.0).sqrt();
        let (s, c) = theta.sin_cos();
        (direction(s, c, u.y), NORM * theta_over_sin(theta))
    }
}

impl InvertibleWarp for ThetaOverSinHemisphere {
    #[inline]
    fn invert(&self, w: Vec3) -> Vec2 {
        let theta = (w.x * w.x + w.y * w.y).sqrt().atan2(w.z);
        let r = theta * FRAC_2_PI;
        clamp_unit2(r * r, azimuth_to_unit(w.x, w.y))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pdf_at_pole_and_horizon() {
        let t = ThetaOverSinHemisphere;
        assert_eq!(t.pdf(Vec3::Z), NORM);
        assert_eq!(t.pdf(Vec3::new(1e-30, 0.0, 1.0)), NORM);
        let h = t.pdf(Vec3::Y);
        assert!(h.is_finite() && (h - 2.0 / (PI * PI)).abs() < 1e-7);
        assert_eq!(t.pdf(Vec3::new(0.0, 1.0, -1e-6)), 0.0);
        assert_eq!(t.pdf(Vec3::new(0.0, f32::NAN, 1.0)), 0.0);
    }

    #[test]
    fn spot_value_and_round_trip() {
        let t = ThetaOverSinHemisphere;
        // u₁ = 1/4: θ = π/4.
        let w = t.sample(Vec2::new(0.25, 0.0));
        let d = std::f32::consts::FRAC_1_SQRT_2;
        assert!(w.is_finite() && (w - Vec3::new(d, 0.0, d)).length() < 1e-6);
        let p = t.pdf(w);
        let expect = NORM * (PI / 4.0) / d;
        assert!(p.is_finite() && (p - expect).abs() < 1e-6);
        for i in 1..20 {
            for j in 1..20 {
                let u = Vec2::new(i as f32 / 20.0, j as f32 / 20.0);
                let back = t.invert(t.sample(u));
                assert!(
                    back.is_finite() && (back - u).abs().max_element() < 1e-5,
                    "{u}"
                );
            }
        }
    }

    #[test]
    fn small_theta_ratio_is_continuous() {
        let below = theta_over_sin(SMALL_THETA * 0.999);
        let above = theta_over_sin(SMALL_THETA * 1.001);
        assert!(below.is_finite() && above.is_finite() && (below - above).abs() < 1e-6);
    }
}
