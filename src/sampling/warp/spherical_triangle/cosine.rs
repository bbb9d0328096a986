//! Spherical-triangle sampling weighted by the cosine at the shading point, by a bilinear warp
//! of the unit square before Arvo's map.

use glam::{Vec2, Vec3};

use super::super::linear::Bilinear;
use super::super::{InvertibleWarp, Warp};
use super::SphericalTriangle;
use crate::sampling::unit::ONE_MINUS_EPSILON;
use crate::sampling::SamplingError;

/// The smallest corner weight, relative to the largest: a corner whose cosine is 0 keeps a
/// little density, so every direction of the triangle can still be sampled (as pbrt-v4 does
/// with its floor of 0.01).
const MIN_CORNER_WEIGHT: f32 = 0.01;

/// Directions toward a triangle with density approximately proportional to `|cos θ|` at the
/// shading point: a [`Bilinear`] warp of `u` whose corner values are the cosines of the
/// directions that the corners of the square map to, followed by [`SphericalTriangle`]'s
/// uniform map. pdf `bilinear(invert(ω))/Ω` per steradian on the triangle, 0 elsewhere
/// (exact for this sampler; the cosine is matched exactly at the three vertex directions and
/// approximately between them).
///
/// Mapping: `ω = T(B(u))`, `T` the spherical triangle's map, `B` the bilinear warp. Since `T`
/// has density `1/Ω` and `B` density `b(u′)` on the square, the composition has density
/// `b(T⁻¹(ω))/Ω` per steradian. Inverse: `B⁻¹(T⁻¹(ω))`. Corner weights are
/// `max(|n · T(corner)|, 0.01 · max)` so that no part of the triangle gets density 0.
///
/// Citation: M. Pharr, W. Jakob, G. Humphreys, 2023, "Physically Based Rendering", 4th ed.,
/// §6.5.4 (triangle sampling warped by the corner cosines). Derivation:
/// `docs/derivations.md`.
///
/// ```
/// use mcrt::glam::{Vec2, Vec3};
/// use mcrt::sampling::warp::{CosineSphericalTriangle, InvertibleWarp, Warp};
///
/// let (a, b, c) = (Vec3::new(-1.0, -1.0, 1.0), Vec3::new(3.0, -1.0, 0.2), Vec3::new(0.0, 1.0, 1.0));
/// let t = CosineSphericalTriangle::new(Vec3::ZERO, a, b, c, Vec3::Z).unwrap();
/// let (w, pdf) = t.sample_with_pdf(Vec2::new(0.3, 0.6));
/// assert!(pdf > 0.0 && (pdf - t.pdf(w)).abs() < 1e-3 * pdf);
/// assert!((t.invert(w) - Vec2::new(0.3, 0.6)).length() < 1e-3);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CosineSphericalTriangle {
    triangle: SphericalTriangle,
    bilinear: Bilinear,
}

impl CosineSphericalTriangle {
    /// The triangle `a`, `b`, `c` seen from `origin`, weighted by the cosine to `normal` (any
    /// length; its sign does not matter). Errors as [`SphericalTriangle::new`], or for a
    /// `normal` that is zero or not finite.
    pub fn new(
        origin: Vec3,
        a: Vec3,
        b: Vec3,
        c: Vec3,
        normal: Vec3,
    ) -> Result<Self, SamplingError> {
        let n = normal
            .try_normalize()
            .ok_or(SamplingError::InvalidDirection {
                name: "normal",
                expected: "finite and nonzero",
            })?;
        let triangle = SphericalTriangle::new(origin, a, b, c)?;
        let e = ONE_MINUS_EPSILON;
        let corners = [
            Vec2::ZERO,
            Vec2::new(e, 0.0),
            Vec2::new(0.0, e),
            Vec2::new(e, e),
        ]
        .map(|u| n.dot(triangle.sample(u)).abs());
        let top = corners.iter().fold(0.0f32, |m, &c| m.max(c));
        // All four cosines 0 (a triangle seen edge-on from the normal's plane): uniform.
        let floor = if top > 0.0 {
            MIN_CORNER_WEIGHT * top
        } else {
            1.0
        };
        let bilinear = Bilinear::new(corners.map(|c| c.max(floor)))?;
        Ok(Self { triangle, bilinear })
    }

    /// The underlying uniform spherical triangle.
    #[must_use]
    pub fn triangle(&self) -> &SphericalTriangle {
        &self.triangle
    }
}

impl Warp for CosineSphericalTriangle {
    type Point = Vec3;

    #[inline]
    fn sample(&self, u: Vec2) -> Vec3 {
        self.triangle.sample(self.bilinear.sample(u))
    }

    /// `bilinear(T⁻¹(ω))/Ω` per steradian on directions hitting the triangle (the area
    /// fallback's density in place of `1/Ω` when [`SphericalTriangle::is_area_sampled`]), 0
    /// elsewhere.
    #[inline]
    fn pdf(&self, w: Vec3) -> f32 {
        let base = self.triangle.pdf(w);
        if base > 0.0 {
            base * self.bilinear.pdf(self.triangle.invert(w))
        } else {
            0.0
        }
    }

    #[inline]
    fn sample_with_pdf(&self, u: Vec2) -> (Vec3, f32) {
        let (v, b) = self.bilinear.sample_with_pdf(u);
        let (w, base) = self.triangle.sample_with_pdf(v);
        (w, base * b)
    }
}

impl InvertibleWarp for CosineSphericalTriangle {
    #[inline]
    fn invert(&self, w: Vec3) -> Vec2 {
        self.bilinear.invert(self.triangle.invert(w))
    }
}
