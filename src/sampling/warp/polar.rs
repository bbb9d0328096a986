//! Polar and spherical coordinates shared by the warps of the disk, the sphere, the
//! hemisphere, cones and lobes: the azimuth and its inverse, directions from (sin θ, cos θ),
//! a stable 1 − cos θ.

use crate::sampling::unit::clamp_unit;
use glam::Vec3;
use std::f32::consts::TAU;

/// (cos φ, sin φ) for φ = 2π u₂.
#[inline]
pub fn azimuth(u2: f32) -> (f32, f32) {
    let (s, c) = (TAU * u2).sin_cos();
    (c, s)
}

/// (cos φ, sin φ) for φ = 2π u₂, u₂ ∈ [0, 1], inline by polynomials (no call to the
/// library's `sin_cos`): the nearest quarter turn `q = round(4 u₂)`, the remainder
/// `x = 2π (u₂ − q/4) ∈ [−π/4, π/4]` (the subtraction is exact, by Sterbenz's lemma), the
/// Taylor polynomials of sin x to x⁹ and cos x to x¹⁰ (truncation errors below 2·10⁻⁹ on
/// that interval), then `q` quarter turns (Cody and Waite 1980, "Software Manual for the
/// Elementary Functions", Prentice-Hall, ch. 8). Within 2·10⁻⁷ of the exact values (test).
#[inline]
pub fn azimuth_polynomial(u2: f32) -> (f32, f32) {
    let q = (4.0 * u2 + 0.5) as i32;
    let x = TAU * (u2 - 0.25 * q as f32);
    let x2 = x * x;
    let sin = x
        * (1.0
            + x2 * (-1.0 / 6.0
                + x2 * (1.0 / 120.0 + x2 * (-1.0 / 5040.0 + x2 * (1.0 / 362_880.0)))));
    let cos = 1.0
        + x2 * (-0.5
            + x2 * (1.0 / 24.0
                + x2 * (-1.0 / 720.0 + x2 * (1.0 / 40_320.0 + x2 * (-1.0 / 3_628_800.0)))));
    // A quarter turn maps (cos, sin) to (−sin, cos); a half turn negates both.
    let (cos, sin) = if q & 1 == 1 { (-sin, cos) } else { (cos, sin) };
    if q & 2 == 2 {
        (-cos, -sin)
    } else {
        (cos, sin)
    }
}

/// The u₂ ∈ [0, 1) whose azimuth φ = 2π u₂ points along `(x, y)`; 0 at the origin.
#[inline]
pub fn azimuth_to_unit(x: f32, y: f32) -> f32 {
    let mut phi = y.atan2(x);
    if phi < 0.0 {
        phi += TAU;
    }
    clamp_unit(phi / TAU)
}

/// The unit direction with the given sin θ, cos θ and azimuth 2π u₂ about +z.
#[inline]
pub fn direction(sin_theta: f32, cos_theta: f32, u2: f32) -> Vec3 {
    let (c, s) = azimuth(u2);
    Vec3::new(sin_theta * c, sin_theta * s, cos_theta)
}

/// sin²θ = x² + y² of a direction (exact for unit vectors, accurate near the pole).
#[inline]
pub fn sin2_theta(w: Vec3) -> f32 {
    w.x * w.x + w.y * w.y
}

/// 1 − cos θ of a unit direction, computed as (x² + y²)/(1 + z) where z is near 1 (no
/// cancellation) and as 1 − z elsewhere.
#[inline]
pub fn one_minus_cos_theta(w: Vec3) -> f32 {
    if w.z > 0.5 {
        sin2_theta(w) / (1.0 + w.z)
    } else {
        1.0 - w.z
    }
}

/// sin θ from t = 1 − cos θ ∈ [0, 2]: √(t (2 − t)), never NaN.
#[inline]
pub fn sin_from_one_minus_cos(t: f32) -> f32 {
    (t * (2.0 - t)).max(0.0).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn azimuth_round_trip() {
        for &u in &[0.0, 0.1, 0.25, 0.5, 0.75, 0.9] {
            let (c, s) = azimuth(u);
            let back = azimuth_to_unit(c, s);
            assert!(back.is_finite() && (back - u).abs() < 1e-6, "{u} -> {back}");
        }
        assert_eq!(azimuth_to_unit(0.0, 0.0), 0.0);
        let near_one = azimuth_to_unit(1.0, -1e-30);
        assert!((0.0..1.0).contains(&near_one));
    }

    #[test]
    fn polynomial_azimuth_matches_the_library() {
        let n = 1 << 20;
        let mut worst = 0.0f64;
        for k in 0..=n {
            // The grid, its neighbours one ulp up and down (quadrant edges included), and 1.
            let u = (k as f32 / n as f32).min(1.0);
            for u in [
                u,
                f32::from_bits(u.to_bits().saturating_sub(1)),
                u.next_up(),
            ] {
                let (c, s) = azimuth_polynomial(u);
                let phi = std::f64::consts::TAU * f64::from(u);
                assert!(c.is_finite() && s.is_finite(), "{u}");
                let err = (f64::from(c) - phi.cos())
                    .abs()
                    .max((f64::from(s) - phi.sin()).abs());
                worst = worst.max(err);
            }
        }
        assert!(worst < 2e-7, "worst error {worst}");
    }

    #[test]
    fn stable_one_minus_cos_near_pole() {
        let theta = 1e-4f64;
        let w = Vec3::new(theta.sin() as f32, 0.0, theta.cos() as f32);
        let t = f64::from(one_minus_cos_theta(w));
        let exact = 2.0 * (theta / 2.0).sin().powi(2);
        assert!(t.is_finite() && ((t - exact) / exact).abs() < 1e-6);
    }
}
