//! Uniform directions in a cone about +z, accurate down to tiny cones (the sun, 4.7·10⁻³ rad,
//! and smaller).

use super::{InvertibleWarp, Warp};
use crate::sampling::error::check_param;
use crate::sampling::unit::clamp_unit2;
use crate::sampling::warp::polar::{
    azimuth_to_unit, direction, one_minus_cos_theta, sin_from_one_minus_cos,
};
use crate::sampling::SamplingError;
use glam::{Vec2, Vec3};
use std::f64::consts::TAU;

/// The smallest accepted `1 − cos θ_max`: below it, `x² + y²` of the samples (≈ θ²) would
/// underflow f32 and the support test could no longer see them.
const MIN_ONE_MINUS_COS: f64 = 1e-30;

/// Relative slack of the support test `1 − cos θ ≤ 1 − cos θ_max`, so that samples on the
/// rim, whose recomputed `1 − cos θ` carries a few ulps of rounding, keep their density.
const RIM_SLACK: f32 = 1e-6;

/// Uniform directions in the cone `θ ≤ θ_max` about +z; pdf `1/(2π(1 − cos θ_max))` per
/// steradian inside, 0 outside.
///
/// Mapping (inversion of P(θ) = (1 − cos θ)/(1 − cos θ_max)): `1 − cos θ = u₁ (1 − cos θ_max)`,
/// `sin θ = √((1 − cos θ)(1 + cos θ))`, `φ = 2πu₂`. The type stores `1 − cos θ_max` (from
/// [`UniformCone::from_angle`] as `2 sin²(θ_max/2)`, exact for tiny cones) and never forms
/// `1 − z` near the axis: `sample` builds `sin θ` from `1 − cos θ`, and `pdf` and `invert`
/// take `1 − cos θ = (x² + y²)/(1 + z)`. A cone of half-angle 10⁻⁴ rad is sampled to f32
/// accuracy although every sample's z rounds to 1.
///
/// Citation: the inversion method on the spherical cap, as in M. Pharr, W. Jakob,
/// G. Humphreys, 2016, "Physically Based Rendering", 3rd ed., §13.6.4. Derivation:
/// `docs/derivations.md`.
///
/// Directions passed to [`Warp::pdf`] and [`InvertibleWarp::invert`] are expected to be unit
/// length; other finite vectors give finite, meaningless values. To sample a cone about
/// another axis, rotate the samples into a frame built around that axis
/// ([`Frame::to_world`](crate::sampling::Frame::to_world)).
///
/// ```
/// use mcrt::glam::Vec2;
/// use mcrt::sampling::warp::{InvertibleWarp, UniformCone, Warp};
///
/// let cone = UniformCone::from_angle(1e-4).unwrap();
/// let (w, pdf) = cone.sample_with_pdf(Vec2::new(0.999, 0.25));
/// assert!(w.y > 0.99e-4 && w.y < 1e-4 && w.z == 1.0); // z rounds to 1, y does not
/// assert!((pdf * cone.solid_angle() - 1.0).abs() < 1e-6);
/// assert!((cone.invert(w) - Vec2::new(0.999, 0.25)).length() < 1e-5);
/// assert!(UniformCone::new(1.0).is_err() && UniformCone::from_angle(f32::NAN).is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UniformCone {
    one_minus_cos_max: f32,
    cos_max: f32,
    pdf: f32,
}

impl UniformCone {
    /// The cone with `cos θ_max = cos_theta_max ∈ [−1, 1)`; −1 is the whole sphere.
    ///
    /// `1 − cos θ_max` is then exact in f32 for the given value, but a cosine cannot describe
    /// a cone narrower than about 3·10⁻⁴ rad (f32's spacing below 1): use
    /// [`UniformCone::from_angle`] for those. Errors on NaN, infinities, values outside
    /// `[−1, 1)`, or a cone too narrow for f32.
    #[inline]
    pub fn new(cos_theta_max: f32) -> Result<Self, SamplingError> {
        let c = check_param("cos_theta_max", cos_theta_max, "finite, in [-1, 1)", |c| {
            (-1.0..1.0).contains(&c)
        })?;
        Self::from_one_minus_cos(1.0 - f64::from(c), "cos_theta_max", f64::from(c))
    }

    /// The cone of half-angle `theta_max ∈ (0, π]` radians, storing `1 − cos θ_max` as
    /// `2 sin²(θ_max/2)` (computed in f64). Errors on NaN, infinities, values outside
    /// `(0, π]`, or a cone narrower than about 1.4·10⁻¹⁵ rad (where `x² + y²` of its samples
    /// underflows f32).
    pub fn from_angle(theta_max: f32) -> Result<Self, SamplingError> {
        let t = check_param("theta_max", theta_max, "finite, in (0, pi]", |t| {
            t > 0.0 && t <= std::f32::consts::PI
        })?;
        let half_sin = (0.5 * f64::from(t)).sin();
        Self::from_one_minus_cos(2.0 * half_sin * half_sin, "theta_max", f64::from(t))
    }

    /// The cone whose half-angle has sine `sin_theta_max ∈ (0, 1]`, for example the cone a
    /// sphere of radius r subtends from distance d > r (sin θ_max = r / d), which then
    /// needs no trigonometry: `1 − cos θ_max = s² / (1 + √(1 − s²))`, computed in f64 (the
    /// product form avoids the cancellation of `1 − √(1 − s²)`). Only cones up to a
    /// hemisphere can be given this way. Errors on NaN, infinities, values outside `(0, 1]`,
    /// or a cone too narrow (as [`UniformCone::from_angle`]).
    ///
    /// ```
    /// use mcrt::sampling::warp::UniformCone;
    ///
    /// // A sphere of radius 1 seen from distance 2: θ_max = 30°.
    /// let cone = UniformCone::from_sin_theta_max(0.5).unwrap();
    /// assert!((cone.cos_theta_max() - 0.75f32.sqrt()).abs() < 1e-6);
    /// ```
    pub fn from_sin_theta_max(sin_theta_max: f32) -> Result<Self, SamplingError> {
        let s = check_param("sin_theta_max", sin_theta_max, "finite, in (0, 1]", |s| {
            s > 0.0 && s <= 1.0
        })?;
        let s2 = f64::from(s) * f64::from(s);
        Self::from_one_minus_cos(
            s2 / (1.0 + (1.0 - s2).sqrt()),
            "sin_theta_max",
            f64::from(s),
        )
    }

    fn from_one_minus_cos(omc: f64, name: &'static str, value: f64) -> Result<Self, SamplingError> {
        if !(MIN_ONE_MINUS_COS..=2.0).contains(&omc) {
            return Err(SamplingError::InvalidParameter {
                name,
                value,
                expected: "a cone with 1 - cos(theta_max) >= 1e-30 (theta_max >= ~1.4e-15 rad)",
            });
        }
        Ok(Self {
            one_minus_cos_max: omc as f32,
            cos_max: (1.0 - omc) as f32,
            pdf: (1.0 / (TAU * omc)) as f32,
        })
    }

    /// `1 − cos θ_max`, accurate to f32 relative precision even for tiny cones.
    #[must_use]
    pub fn one_minus_cos_theta_max(&self) -> f32 {
        self.one_minus_cos_max
    }

    /// `cos θ_max` (rounds to 1 for cones narrower than about 3·10⁻⁴ rad; prefer
    /// [`UniformCone::one_minus_cos_theta_max`]).
    #[must_use]
    pub fn cos_theta_max(&self) -> f32 {
        self.cos_max
    }

    /// The cone's solid angle `2π (1 − cos θ_max)` in steradians.
    #[must_use]
    pub fn solid_angle(&self) -> f32 {
        (TAU * f64::from(self.one_minus_cos_max)) as f32
    }

    /// Whether the unit direction `w` lies in the cone (rim included, with a relative slack
    /// of 10⁻⁶ on `1 − cos θ` for rounding).
    #[must_use]
    pub fn contains(&self, w: Vec3) -> bool {
        w.is_finite() && one_minus_cos_theta(w) <= self.one_minus_cos_max * (1.0 + RIM_SLACK)
    }
}

impl Warp for UniformCone {
    type Point = Vec3;

    #[inline]
    fn sample(&self, u: Vec2) -> Vec3 {
        let t = u.x * self.one_minus_cos_max;
        direction(sin_from_one_minus_cos(t), 1.0 - t, u.y)
    }

    /// `1/(2π(1 − cos θ_max))` per steradian inside the cone (see
    /// [`UniformCone::contains`]), 0 outside or for non-finite input.
    #[inline]
    fn pdf(&self, w: Vec3) -> f32 {
        if self.contains(w) {
            self.pdf
        } else {
            0.0
        }
    }

    #[inline]
    fn sample_with_pdf(&self, u: Vec2) -> (Vec3, f32) {
        (self.sample(u), self.pdf)
    }
}

impl InvertibleWarp for UniformCone {
    #[inline]
    fn invert(&self, w: Vec3) -> Vec2 {
        let u1 = one_minus_cos_theta(w) / self.one_minus_cos_max;
        clamp_unit2(u1, azimuth_to_unit(w.x, w.y))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::unit::ONE_MINUS_EPSILON;

    #[test]
    fn rejects_bad_parameters() {
        for c in [1.0, 1.5, -1.01, f32::NAN, f32::INFINITY] {
            assert!(UniformCone::new(c).is_err(), "{c}");
        }
        for t in [0.0, -0.1, 3.2, f32::NAN, f32::NEG_INFINITY, 1e-20] {
            assert!(UniformCone::from_angle(t).is_err(), "{t}");
        }
        assert!(UniformCone::new(-1.0).is_ok());
        assert!(UniformCone::from_angle(std::f32::consts::PI).is_ok());
    }

    #[test]
    fn from_sine_matches_from_angle() {
        for s in [1.0f32, 0.999, 0.5, 0.1, 1e-3, 1e-6, 1e-12, 1e-14] {
            let a = UniformCone::from_sin_theta_max(s).unwrap();
            let b = UniformCone::from_angle(f64::from(s).asin() as f32).unwrap();
            let (x, y) = (a.one_minus_cos_theta_max(), b.one_minus_cos_theta_max());
            assert!(x.is_finite() && y.is_finite() && x > 0.0, "s {s}: {x} {y}");
            assert!((x / y - 1.0).abs() < 1e-6, "s {s}: {x} against {y}");
        }
        for bad in [0.0, -0.5, 1.5, f32::NAN, f32::INFINITY, 1e-15] {
            assert!(UniformCone::from_sin_theta_max(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn tiny_cone_is_exact() {
        let cone = UniformCone::from_angle(1e-4).unwrap();
        let theta = f64::from(1e-4f32);
        let exact = 2.0 * (theta / 2.0).sin().powi(2);
        let got = f64::from(cone.one_minus_cos_theta_max());
        assert!(got.is_finite() && ((got - exact) / exact).abs() < 1e-7);
        let rim = cone.sample(Vec2::new(ONE_MINUS_EPSILON, 0.0));
        assert!(rim.is_finite() && ((f64::from(rim.x) - theta) / theta).abs() < 1e-6);
        assert!(cone.pdf(rim) > 0.0);
        let outside = Vec3::new(1.01e-4, 0.0, 1.0);
        assert_eq!(cone.pdf(outside), 0.0);
    }

    #[test]
    fn whole_sphere_and_hemisphere() {
        let sphere = UniformCone::new(-1.0).unwrap();
        let p = sphere.pdf(-Vec3::Z);
        assert!(p.is_finite() && (p - 0.25 / std::f32::consts::PI).abs() < 1e-8);
        let hemi = UniformCone::from_angle(std::f32::consts::FRAC_PI_2).unwrap();
        assert!((hemi.solid_angle() - std::f32::consts::TAU).abs() < 1e-5);
        assert_eq!(hemi.pdf(Vec3::new(0.0, 0.6, -0.8)), 0.0);
    }

    #[test]
    fn round_trip() {
        for angle in [1e-4, 1e-2, 1.0, 3.0] {
            let cone = UniformCone::from_angle(angle).unwrap();
            for i in 1..20 {
                for j in 1..20 {
                    let u = Vec2::new(i as f32 / 20.0, j as f32 / 20.0);
                    let back = cone.invert(cone.sample(u));
                    assert!(back.is_finite() && (back - u).abs().max_element() < 1e-5);
                }
            }
        }
    }
}
