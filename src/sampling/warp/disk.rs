//! Uniform points on the unit disk: the polar map and the concentric map.

use super::{InvertibleWarp, Warp};
use crate::sampling::unit::{clamp_unit, clamp_unit2};
use crate::sampling::warp::polar::{azimuth, azimuth_to_unit};
use glam::Vec2;
use std::f32::consts::{FRAC_1_PI, FRAC_PI_2, FRAC_PI_4};

/// Relative slack of the support test `x² + y² ≤ 1`, so that samples on the rim, whose
/// coordinates carry a few ulps of rounding, keep their density.
const RIM_SLACK: f32 = 4.0 * f32::EPSILON;

/// The density of both disk warps at `p`: `1/π` per unit area inside the unit disk, else 0.
#[inline]
fn disk_pdf(p: Vec2) -> f32 {
    if p.length_squared() <= 1.0 + RIM_SLACK {
        FRAC_1_PI
    } else {
        0.0
    }
}

/// Uniform points on the unit disk by the polar map; pdf `1/π` per unit area.
///
/// Mapping (inversion of the marginal CDF P(r) = r² and the conditional P(φ|r) = φ/(2π)):
/// `r = √u₁`, `φ = 2πu₂`, `p = r (cos φ, sin φ)`. Jacobian `|∂p/∂u| = π`. Inverse:
/// `u₁ = x² + y²`, `u₂ = atan2(y, x)/(2π)` mapped into `[0, 1)`. It squeezes strata near the
/// centre; [`UniformDiskConcentric`] keeps them compact.
///
/// Citation: the inversion method for the disk, as in M. Pharr, W. Jakob, G. Humphreys,
/// 2016, "Physically Based Rendering", 3rd ed., §13.6.2. Derivation: `docs/derivations.md`.
///
/// ```
/// use mcrt::glam::Vec2;
/// use mcrt::sampling::warp::{InvertibleWarp, UniformDisk, Warp};
///
/// let (p, pdf) = UniformDisk.sample_with_pdf(Vec2::new(0.25, 0.0));
/// assert!((p - Vec2::new(0.5, 0.0)).length() < 1e-6);
/// assert!((pdf - 1.0 / std::f32::consts::PI).abs() < 1e-7);
/// assert!((UniformDisk.invert(p) - Vec2::new(0.25, 0.0)).length() < 1e-6);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct UniformDisk;

impl Warp for UniformDisk {
    type Point = Vec2;

    #[inline]
    fn sample(&self, u: Vec2) -> Vec2 {
        let r = u.x.max(0.0).sqrt();
        let (c, s) = azimuth(u.y);
        Vec2::new(r * c, r * s)
    }

    /// `1/π` per unit area inside the unit disk (rim included), 0 outside.
    #[inline]
    fn pdf(&self, p: Vec2) -> f32 {
        disk_pdf(p)
    }

    #[inline]
    fn sample_with_pdf(&self, u: Vec2) -> (Vec2, f32) {
        (self.sample(u), FRAC_1_PI)
    }
}

impl InvertibleWarp for UniformDisk {
    #[inline]
    fn invert(&self, p: Vec2) -> Vec2 {
        clamp_unit2(p.length_squared(), azimuth_to_unit(p.x, p.y))
    }
}

/// Uniform points on the unit disk by the concentric map; pdf `1/π` per unit area.
///
/// Mapping: with `a = 2u₁ − 1`, `b = 2u₂ − 1`, concentric squares go to concentric circles:
/// if `|a| > |b|` then `r = a`, `φ = (π/4)(b/a)`, else `r = b`, `φ = π/2 − (π/4)(a/b)`;
/// `p = r (cos φ, sin φ)`. It is area-preserving up to the constant (Jacobian `π/4` per unit
/// of `(a, b)`, `π` per unit of `u`) and keeps strata compact. Inverse: the sector with the
/// larger of `|x|`, `|y|` gives `r = ±|p|` and the ratio from `atan(y/x)` or `atan(x/y)`.
///
/// Citation: P. Shirley, K. Chiu, 1997, "A Low Distortion Map Between Disk and Square",
/// Journal of Graphics Tools 2(3). Derivation: `docs/derivations.md`.
///
/// ```
/// use mcrt::glam::Vec2;
/// use mcrt::sampling::warp::{InvertibleWarp, UniformDiskConcentric, Warp};
///
/// let p = UniformDiskConcentric.sample(Vec2::new(1.0 - 2f32.powi(-24), 0.5));
/// assert!((p - Vec2::new(1.0, 0.0)).length() < 1e-6);
/// let u = Vec2::new(0.3, 0.8);
/// let back = UniformDiskConcentric.invert(UniformDiskConcentric.sample(u));
/// assert!((back - u).length() < 1e-6);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct UniformDiskConcentric;

/// The concentric map as (signed radius r, φ): `p = r (cos φ, sin φ)`.
#[inline]
pub(in crate::sampling::warp) fn concentric_polar(u: Vec2) -> (f32, f32) {
    let a = 2.0 * u.x - 1.0;
    let b = 2.0 * u.y - 1.0;
    if a == 0.0 && b == 0.0 {
        (0.0, 0.0)
    } else if a.abs() > b.abs() {
        (a, FRAC_PI_4 * (b / a))
    } else {
        (b, FRAC_PI_2 - FRAC_PI_4 * (a / b))
    }
}

/// The inverse of [`concentric_polar`] applied to a point of the disk: `u` in `[0, 1)²`.
#[inline]
pub(in crate::sampling::warp) fn concentric_invert(p: Vec2) -> Vec2 {
    let r = p.length();
    let (a, b) = if r == 0.0 {
        (0.0, 0.0)
    } else if p.x.abs() >= p.y.abs() {
        let a = r.copysign(p.x);
        (a, a * (4.0 * FRAC_1_PI) * (p.y / p.x).atan())
    } else {
        let b = r.copysign(p.y);
        (b * (4.0 * FRAC_1_PI) * (p.x / p.y).atan(), b)
    };
    Vec2::new(clamp_unit(0.5 * (a + 1.0)), clamp_unit(0.5 * (b + 1.0)))
}

impl Warp for UniformDiskConcentric {
    type Point = Vec2;

    #[inline]
    fn sample(&self, u: Vec2) -> Vec2 {
        let (r, phi) = concentric_polar(u);
        let (s, c) = phi.sin_cos();
        Vec2::new(r * c, r * s)
    }

    /// `1/π` per unit area inside the unit disk (rim included), 0 outside.
    #[inline]
    fn pdf(&self, p: Vec2) -> f32 {
        disk_pdf(p)
    }

    #[inline]
    fn sample_with_pdf(&self, u: Vec2) -> (Vec2, f32) {
        (self.sample(u), FRAC_1_PI)
    }
}

impl InvertibleWarp for UniformDiskConcentric {
    #[inline]
    fn invert(&self, p: Vec2) -> Vec2 {
        concentric_invert(p)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec2, b: Vec2, tol: f32) -> bool {
        a.is_finite() && b.is_finite() && (a - b).abs().max_element() <= tol
    }

    #[test]
    fn polar_spot_values() {
        assert!(close(UniformDisk.sample(Vec2::ZERO), Vec2::ZERO, 0.0));
        assert!(close(
            UniformDisk.sample(Vec2::new(0.25, 0.25)),
            Vec2::new(0.0, 0.5),
            1e-6
        ));
        let rim = UniformDisk.sample(Vec2::new(crate::sampling::ONE_MINUS_EPSILON, 0.5));
        assert!(close(rim, Vec2::new(-1.0, 0.0), 1e-6));
        assert!(UniformDisk.pdf(rim) > 0.0);
    }

    #[test]
    fn concentric_spot_values() {
        let c = UniformDiskConcentric;
        assert!(close(c.sample(Vec2::splat(0.5)), Vec2::ZERO, 0.0));
        assert!(close(
            c.sample(Vec2::new(0.75, 0.5)),
            Vec2::new(0.5, 0.0),
            1e-6
        ));
        assert!(close(
            c.sample(Vec2::new(0.5, 0.0)),
            Vec2::new(0.0, -1.0),
            1e-6
        ));
        let d = std::f32::consts::FRAC_1_SQRT_2;
        assert!(close(c.sample(Vec2::new(1.0, 1.0)), Vec2::new(d, d), 1e-6));
        assert!(close(
            c.sample(Vec2::new(0.0, 0.0)),
            Vec2::new(-d, -d),
            1e-6
        ));
    }

    #[test]
    fn pdf_inside_and_outside() {
        for p in [Vec2::ZERO, Vec2::new(0.6, -0.8), Vec2::new(-0.1, 0.2)] {
            assert_eq!(UniformDisk.pdf(p), FRAC_1_PI);
            assert_eq!(UniformDiskConcentric.pdf(p), FRAC_1_PI);
        }
        for p in [
            Vec2::new(1.0, 0.01),
            Vec2::new(f32::NAN, 0.0),
            Vec2::splat(1e30),
        ] {
            assert_eq!(UniformDisk.pdf(p), 0.0);
            assert_eq!(UniformDiskConcentric.pdf(p), 0.0);
        }
    }

    #[test]
    fn round_trips() {
        for i in 1..20 {
            for j in 1..20 {
                let u = Vec2::new(i as f32 / 20.0, j as f32 / 20.0);
                assert!(
                    close(UniformDisk.invert(UniformDisk.sample(u)), u, 1e-6),
                    "{u}"
                );
                let c = UniformDiskConcentric;
                assert!(close(c.invert(c.sample(u)), u, 1e-6), "{u}");
            }
        }
    }

    #[test]
    fn invert_outside_is_clamped() {
        for p in [
            Vec2::new(3.0, 0.0),
            Vec2::new(f32::NAN, 1.0),
            Vec2::new(0.0, -5.0),
        ] {
            for u in [UniformDisk.invert(p), UniformDiskConcentric.invert(p)] {
                assert!(u.is_finite() && u.min_element() >= 0.0 && u.max_element() < 1.0);
            }
        }
    }
}
