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
    let mut phi = d.y.atan2(d.x);
    if phi < 0.0 {
        phi += 2.0 * PI;
    }
    let y = clamp_unit(phi * (0.5 / PI));
    Vec2::new(x, y)
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
