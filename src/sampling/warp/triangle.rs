//! Uniform barycentric coordinates on a triangle, and their placement on a triangle in 3D.

use super::{InvertibleWarp, Warp};
use crate::sampling::unit::clamp_unit2;
use glam::{DVec3, Vec2, Vec3};

/// Absolute slack of the support test, so that samples on the edges, which carry a rounding
/// of an ulp or two, keep their density.
const EDGE_SLACK: f32 = 2.0 * f32::EPSILON;

/// Uniform barycentric coordinates `(b₁, b₂)` on the reference triangle
/// `{b₁ ≥ 0, b₂ ≥ 0, b₁ + b₂ ≤ 1}`; pdf `2` per unit barycentric area.
///
/// Mapping (marginal p(b₁) = 2(1 − b₁), conditional p(b₂|b₁) = 1/(1 − b₁), both inverted):
/// `b₁ = 1 − √u₁`, `b₂ = u₂ √u₁`. Jacobian `|∂b/∂u| = 1/2`. Inverse: `u₁ = (1 − b₁)²`,
/// `u₂ = b₂ / (1 − b₁)` (0 at the vertex `b₁ = 1`, where `u₂` is not unique).
/// Use [`triangle_point`] and [`triangle_area_pdf`] to place the sample on a triangle in 3D.
///
/// Citation: G. Turk, 1990, "Generating Random Points in Triangles", Graphics Gems, Academic
/// Press. Derivation: `docs/derivations.md`.
///
/// ```
/// use mcrt::glam::{Vec2, Vec3};
/// use mcrt::sampling::warp::{triangle_area_pdf, triangle_point, UniformTriangle, Warp};
///
/// let (bary, pdf) = UniformTriangle.sample_with_pdf(Vec2::new(0.25, 0.5));
/// assert!((bary - Vec2::new(0.5, 0.25)).length() < 1e-6 && pdf == 2.0);
/// let (a, b, c) = (Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0));
/// assert!((triangle_point(a, b, c, bary) - Vec3::new(1.0, 0.5, 0.0)).length() < 1e-6);
/// assert!((triangle_area_pdf(a, b, c) - 0.5).abs() < 1e-7); // area 2
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct UniformTriangle;

impl Warp for UniformTriangle {
    type Point = Vec2;

    #[inline]
    fn sample(&self, u: Vec2) -> Vec2 {
        let s = u.x.max(0.0).sqrt();
        // b₁ = 1 − √u₁ written as (1 − u₁)/(1 + √u₁): no cancellation as u₁ → 1.
        Vec2::new((1.0 - u.x) / (1.0 + s), u.y * s)
    }

    /// `2` per unit barycentric area inside the reference triangle (edges included), else 0.
    #[inline]
    fn pdf(&self, b: Vec2) -> f32 {
        if b.x >= -EDGE_SLACK && b.y >= -EDGE_SLACK && b.x + b.y <= 1.0 + EDGE_SLACK {
            2.0
        } else {
            0.0
        }
    }

    #[inline]
    fn sample_with_pdf(&self, u: Vec2) -> (Vec2, f32) {
        (self.sample(u), 2.0)
    }
}

impl InvertibleWarp for UniformTriangle {
    #[inline]
    fn invert(&self, b: Vec2) -> Vec2 {
        let s = 1.0 - b.x;
        let u2 = if s > 0.0 { b.y / s } else { 0.0 };
        clamp_unit2(s * s, u2)
    }
}

/// Uniform barycentric coordinates `(b₁, b₂)` on the reference triangle by Heitz's
/// low-distortion map; pdf `2` per unit barycentric area, as [`UniformTriangle`].
///
/// Mapping (the square cut along its diagonal, each half sheared onto the triangle): if
/// `u₁ < u₂`, `b₁ = u₁/2` and `b₂ = u₂ − u₁/2`; otherwise `b₂ = u₂/2` and `b₁ = u₁ − u₂/2`.
/// Jacobian `|∂b/∂u| = 1/2` on both halves. Inverse: if `b₂ > b₁`, `u = (2b₁, b₂ + b₁)`, else
/// `u = (b₁ + b₂, 2b₂)`. The map is piecewise linear with no square root, so a stratified or
/// low-discrepancy set of `u` stays evenly spread on the triangle (the √u₁ of
/// [`UniformTriangle`] squeezes strata toward one vertex).
///
/// Citation: E. Heitz, 2019, "A Low-Distortion Map Between Triangle and Square", technical
/// report. Derivation: `docs/derivations.md`.
///
/// ```
/// use mcrt::glam::Vec2;
/// use mcrt::sampling::warp::{InvertibleWarp, LowDistortionTriangle, Warp};
///
/// let b = LowDistortionTriangle.sample(Vec2::new(0.2, 0.6));
/// assert!((b - Vec2::new(0.1, 0.5)).length() < 1e-7);
/// assert!((LowDistortionTriangle.invert(b) - Vec2::new(0.2, 0.6)).length() < 1e-7);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LowDistortionTriangle;

impl Warp for LowDistortionTriangle {
    type Point = Vec2;

    #[inline]
    fn sample(&self, u: Vec2) -> Vec2 {
        if u.x < u.y {
            let b1 = 0.5 * u.x;
            Vec2::new(b1, u.y - b1)
        } else {
            let b2 = 0.5 * u.y;
            Vec2::new(u.x - b2, b2)
        }
    }

    /// `2` per unit barycentric area inside the reference triangle (edges included), else 0.
    #[inline]
    fn pdf(&self, b: Vec2) -> f32 {
        UniformTriangle.pdf(b)
    }

    #[inline]
    fn sample_with_pdf(&self, u: Vec2) -> (Vec2, f32) {
        (self.sample(u), 2.0)
    }
}

impl InvertibleWarp for LowDistortionTriangle {
    #[inline]
    fn invert(&self, b: Vec2) -> Vec2 {
        if b.y > b.x {
            clamp_unit2(2.0 * b.x, b.y + b.x)
        } else {
            clamp_unit2(b.x + b.y, 2.0 * b.y)
        }
    }
}

/// The point with barycentric coordinates `bary = (b₁, b₂)` on the triangle `(a, b, c)`:
/// `a + b₁ (b − a) + b₂ (c − a)`, i.e. weights `(1 − b₁ − b₂, b₁, b₂)` on `(a, b, c)`.
///
/// Written from the edge vectors so the point stays on the triangle's plane without the
/// cancellation of `1 − b₁ − b₂`. With [`UniformTriangle`], the density of the point is
/// [`triangle_area_pdf`] per unit area (the barycentric pdf 2 divided by twice the area).
#[must_use]
#[inline]
pub fn triangle_point(a: Vec3, b: Vec3, c: Vec3, bary: Vec2) -> Vec3 {
    a + bary.x * (b - a) + bary.y * (c - a)
}

/// The area of the triangle `(a, b, c)`, `|(b − a) × (c − a)| / 2`, computed in f64 so that
/// slivers keep their (tiny) area; never NaN for finite input.
#[must_use]
pub fn triangle_area(a: Vec3, b: Vec3, c: Vec3) -> f32 {
    let (a, b, c) = (a.as_dvec3(), b.as_dvec3(), c.as_dvec3());
    let cross: DVec3 = (b - a).cross(c - a);
    (0.5 * cross.length()) as f32
}

/// The density per unit area of uniform points on the triangle `(a, b, c)`: `1 / area`.
///
/// Returns 0 for a degenerate triangle (zero, subnormal or non-finite area, or an area so
/// small that `1/area` overflows f32): such a triangle has no area density and should not be
/// sampled. Never NaN.
#[must_use]
pub fn triangle_area_pdf(a: Vec3, b: Vec3, c: Vec3) -> f32 {
    let (da, db, dc) = (a.as_dvec3(), b.as_dvec3(), c.as_dvec3());
    let area = 0.5 * (db - da).cross(dc - da).length();
    let pdf = (1.0 / area) as f32;
    if area > 0.0 && pdf.is_finite() {
        pdf
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn first_barycentric_keeps_its_digits_near_u1_one() {
        // Found by the f32/f64 study (mcrt-render/examples/convergence): 1 − √u₁ lost every digit.
        for k in [1, 3, 10, 20, 24] {
            let u1 = 1.0 - (2f32).powi(-k);
            let b = UniformTriangle.sample(Vec2::new(u1, 0.3));
            let exact = 1.0 - f64::from(u1).sqrt();
            let rel = (f64::from(b.x) - exact).abs() / exact;
            assert!(
                b.x.is_finite() && rel < 4.0 * f64::from(f32::EPSILON),
                "k {k}: {rel}"
            );
        }
    }
    use crate::sampling::unit::ONE_MINUS_EPSILON;

    #[test]
    fn vertices_and_spot_values() {
        let t = UniformTriangle;
        assert_eq!(t.sample(Vec2::new(0.0, 0.3)), Vec2::new(1.0, 0.0));
        let near_b = t.sample(Vec2::new(ONE_MINUS_EPSILON, 0.0));
        assert!(near_b.is_finite() && near_b.x >= 0.0 && near_b.x < 1e-7 && near_b.y == 0.0);
        let near_c = t.sample(Vec2::new(ONE_MINUS_EPSILON, ONE_MINUS_EPSILON));
        assert!(near_c.is_finite() && near_c.x + near_c.y <= 1.0 && t.pdf(near_c) == 2.0);
    }

    #[test]
    fn pdf_support() {
        let t = UniformTriangle;
        assert_eq!(t.pdf(Vec2::new(0.2, 0.2)), 2.0);
        assert_eq!(t.pdf(Vec2::new(0.0, 1.0)), 2.0);
        for b in [
            Vec2::new(-0.01, 0.5),
            Vec2::new(0.6, 0.6),
            Vec2::new(f32::NAN, 0.0),
        ] {
            assert_eq!(t.pdf(b), 0.0);
        }
    }

    #[test]
    fn round_trip() {
        for i in 1..20 {
            for j in 1..20 {
                let u = Vec2::new(i as f32 / 20.0, j as f32 / 20.0);
                let back = UniformTriangle.invert(UniformTriangle.sample(u));
                assert!(
                    back.is_finite() && (back - u).abs().max_element() < 1e-6,
                    "{u}"
                );
            }
        }
        let v = UniformTriangle.invert(Vec2::new(1.0, 0.0));
        assert_eq!(v, Vec2::ZERO);
    }

    #[test]
    fn low_distortion_round_trip_and_edges() {
        let t = LowDistortionTriangle;
        for i in 0..=20 {
            for j in 0..=20 {
                let u =
                    Vec2::new(i as f32 / 20.0, j as f32 / 20.0).min(Vec2::splat(ONE_MINUS_EPSILON));
                let b = t.sample(u);
                assert!(b.is_finite() && t.pdf(b) == 2.0, "{u}: {b}");
                let back = t.invert(b);
                assert!(
                    back.is_finite() && (back - u).abs().max_element() < 1e-6,
                    "{u}"
                );
            }
        }
    }

    #[test]
    fn slivers_and_degenerate_triangles() {
        let a = Vec3::ZERO;
        let b = Vec3::new(1.0, 0.0, 0.0);
        let sliver = Vec3::new(0.5, 1e-20, 0.0);
        let pdf = triangle_area_pdf(a, b, sliver);
        assert!(pdf.is_finite() && (pdf - 2e20).abs() / 2e20 < 1e-6);
        let p = triangle_point(a, b, sliver, UniformTriangle.sample(Vec2::new(0.3, 0.6)));
        assert!(p.is_finite());
        assert_eq!(triangle_area_pdf(a, b, Vec3::new(2.0, 0.0, 0.0)), 0.0);
        assert_eq!(triangle_area_pdf(a, a, a), 0.0);
        assert_eq!(triangle_area_pdf(a, b, Vec3::new(0.5, 1e-40, 0.0)), 0.0);
        assert_eq!(triangle_area_pdf(a, b, Vec3::new(f32::NAN, 0.0, 0.0)), 0.0);
        let area = triangle_area(a, Vec3::new(3.0, 0.0, 0.0), Vec3::new(0.0, 4.0, 0.0));
        assert!(area.is_finite() && (area - 6.0).abs() < 1e-6);
    }
}
