//! The equal-area map between the unit square and the unit sphere that the directional
//! quadtrees live on (the cylindrical map of Müller et al. 2017): `cos θ = 2u − 1`,
//! `φ = 2πv`. Its Jacobian is constant, `|∂ω/∂(u, v)| = 4π`, so a density `p□` on the square
//! is the density `p□ / (4π)` per steradian on the sphere.

use crate::sampling::unit::clamp_unit;
use crate::sampling::warp::{InvertibleWarp, Warp};
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// The Jacobian `|∂ω/∂(u, v)|` of [`square_to_sphere`]: solid angle per unit area of the
/// square, `4π`.
pub const SQUARE_TO_SPHERE_JACOBIAN: f32 = 4.0 * PI;

/// The direction of the point `u` of the unit square: `z = cos θ = 2u.x − 1`, `φ = 2π u.y`.
#[inline]
pub fn square_to_sphere(u: Vec2) -> Vec3 {
    let z = (2.0 * u.x - 1.0).clamp(-1.0, 1.0);
    let r = (1.0 - z * z).max(0.0).sqrt();
    let (s, c) = (2.0 * PI * u.y).sin_cos();
    Vec3::new(r * c, r * s, z)
}

/// The point of the unit square of the direction `d` (need not be normalised; it is only read
/// through `d.z / |d|` and the angle of `(d.x, d.y)`), inside `[0, 1)²`. A zero, infinite or
/// NaN direction maps to a point of the square too (no NaN comes out).
#[inline]
pub fn sphere_to_square(d: Vec3) -> Vec2 {
    let len = d.length();
    let z = if len > 0.0 && len.is_finite() {
        d.z / len
    } else {
        0.0
    };
    let x = clamp_unit((z + 1.0) * 0.5);
    let mut phi = atan2(d.y, d.x);
    if phi < 0.0 {
        phi += 2.0 * PI;
    }
    let y = clamp_unit(phi * (0.5 / PI));
    Vec2::new(x, y)
}

/// `atan2(y, x)` in `[−π, π]` to a few ulp, inline and with selects instead of branches: the
/// guided path tracer maps two or three directions per vertex to the square, and the
/// library's `atan2f` is a call with branches on its argument that mispredict at random.
/// Octant reduction to `|t| ≤ tan(π/8)` and an odd minimax polynomial of degree 9 (the
/// reduction and degree of Cephes' `atanf`, Moshier 1989, "Methods and Programs for
/// Mathematical Functions"). A NaN in, or both arguments infinite, gives NaN.
#[inline]
pub(crate) fn atan2(y: f32, x: f32) -> f32 {
    use std::f32::consts::{FRAC_PI_2, FRAC_PI_4};
    const TAN_PI_8: f32 = 0.414_213_57;
    let (ax, ay) = (x.abs(), y.abs());
    let (lo, hi) = (ax.min(ay), ax.max(ay));
    // t = lo/hi ∈ [0, 1] (0 at the origin), then t' ∈ [−tan(π/8), tan(π/8)] with offset.
    let t = if hi > 0.0 { lo / hi } else { lo };
    let far = t > TAN_PI_8;
    let t = if far { (t - 1.0) / (t + 1.0) } else { t };
    let z = t * t;
    let p = ((8.053_744_5e-2 * z - 1.387_768_6e-1) * z + 1.997_771_1e-1) * z - 3.333_295e-1;
    let mut r = t + t * z * p + if far { FRAC_PI_4 } else { 0.0 };
    if ay > ax {
        r = FRAC_PI_2 - r;
    }
    if x.is_sign_negative() {
        r = PI - r;
    }
    if y.is_sign_negative() {
        r = -r;
    }
    if x.is_nan() || y.is_nan() {
        f32::NAN
    } else {
        r
    }
}

/// [`square_to_sphere`] as a [`Warp`]: the uniform sphere through the equal-area map, density
/// `1/(4π)`, so that the chi-square harness and the Jacobian check can test the map itself.
///
/// ```
/// use mcrt::glam::Vec2;
/// use mcrt::sampling::guiding::EqualAreaSphere;
/// use mcrt::sampling::warp::{InvertibleWarp, Warp};
///
/// let d = EqualAreaSphere.sample(Vec2::new(0.3, 0.7));
/// assert!((d.length() - 1.0).abs() < 1e-6);
/// assert!((EqualAreaSphere.invert(d) - Vec2::new(0.3, 0.7)).abs().max_element() < 1e-5);
/// ```
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct EqualAreaSphere;

impl Warp for EqualAreaSphere {
    type Point = Vec3;
    #[inline]
    fn sample(&self, u: Vec2) -> Vec3 {
        square_to_sphere(u)
    }
    #[inline]
    fn pdf(&self, _p: Vec3) -> f32 {
        1.0 / SQUARE_TO_SPHERE_JACOBIAN
    }
}

impl InvertibleWarp for EqualAreaSphere {
    #[inline]
    fn invert(&self, p: Vec3) -> Vec2 {
        sphere_to_square(p)
    }
}

#[cfg(test)]
mod tests {
    use super::atan2;

    /// The inline `atan2` agrees with the library's to a few ulp over every octant, the axes,
    /// signed zeros and the extremes; NaN stays NaN.
    #[test]
    fn atan2_agrees_with_the_library() {
        let mut worst = 0.0f32;
        let n = 4001;
        for i in 0..n {
            let a = -std::f32::consts::PI + 2.0 * std::f32::consts::PI * i as f32 / (n - 1) as f32;
            for r in [1e-30f32, 1e-3, 1.0, 7.5, 1e30] {
                let (y, x) = (r * a.sin(), r * a.cos());
                let (ours, lib) = (atan2(y, x), y.atan2(x));
                assert!(ours.is_finite(), "{y} {x}");
                worst = worst.max((ours - lib).abs());
            }
        }
        // Two ulp of an angle in [2, π].
        assert!(worst <= 4.0 * f32::EPSILON, "worst {worst}");
        for (y, x) in [
            (0.0f32, 0.0f32),
            (0.0, -0.0),
            (-0.0, -1.0),
            (1.0, 0.0),
            (-1.0, 0.0),
        ] {
            assert_eq!(atan2(y, x), y.atan2(x), "{y} {x}");
        }
        assert!(atan2(f32::NAN, 1.0).is_nan() && atan2(1.0, f32::NAN).is_nan());
    }
}
