//! The latitude–longitude map between the unit square and the sphere: the coordinates of an
//! environment map image.

use super::{InvertibleWarp, Warp};
use crate::sampling::unit::clamp_unit;
use glam::{Vec2, Vec3};
use std::f32::consts::{PI, TAU};

/// The latitude–longitude (equirectangular) map of environment maps, in Mitsuba 3's
/// convention: `(u, v) ↦ (sin θ sin φ, cos θ, −sin θ cos φ)` with `φ = 2πu`, `θ = πv`, so
/// `+y` is up, `v = 0` is the north pole (`+y`), `v → 1` the south pole, `u = 0` looks
/// toward `−z` and `u = ¼` toward `+x`.
///
/// As a [`Warp`], uniform `(u, v)` gives directions with density
/// `p(ω) = 1 / (2π² sin θ)` per unit solid angle (the map's Jacobian is `2π² sin θ`). For a
/// density over the image, such as a
/// [`PiecewiseConstant2D`](crate::sampling::distribution::PiecewiseConstant2D) of an
/// environment map's luminance times `sin θ`, [`LatLong::solid_angle_pdf`] turns the
/// density per unit area of `[0,1)²` into one per steradian: sample `(uv, pdf_uv)` from the
/// table, then `dir = LatLong.sample(uv)` with density `solid_angle_pdf(pdf_uv,
/// LatLong::sin_theta(dir))`; for a direction from elsewhere, look the table up at
/// `LatLong.invert(dir)`.
///
/// **Edges.** [`InvertibleWarp::invert`] returns `(u, v)` in `[0,1)²`, so a table lookup
/// never falls off the image: the south pole (`v = 1`) maps to the last row
/// (`v = 1 − 2⁻²⁴`), the seam `φ → 2π` wraps to `u = 0`, a pole (where `φ` is undefined)
/// gets `u ∈ {0, ½}` whatever the signs of its zero components, and a NaN, infinite or zero
/// vector gives a finite `(u, v)` without panicking. [`LatLong::solid_angle_pdf`] floors
/// `sin θ` at `f32::EPSILON` (as Mitsuba 3's `envmap` does), so a direction on a pole, where
/// the map's density is positive, keeps a finite positive density instead of 0 (the poles
/// have no solid angle, so no integral changes); unlike
/// [`solid_angle_pdf_from_lat_long`](crate::sampling::jacobian::solid_angle_pdf_from_lat_long),
/// which returns 0 there.
///
/// Reference: Pharr, Jakob & Humphreys, 2016, *Physically Based Rendering* (3rd ed.),
/// section 14.2.4, "Infinite Area Lights" (the latitude–longitude map's `2π² sin θ`
/// Jacobian); derivation in `docs/derivations.md`, part III, "Latitude–longitude map".
///
/// ```
/// use mcrt::glam::{Vec2, Vec3};
/// use mcrt::sampling::distribution::PiecewiseConstant2D;
/// use mcrt::sampling::warp::{InvertibleWarp, LatLong, Warp};
///
/// // A 2 × 2 "image"; v = 1 (the south pole) would fall off the table, the inverse does not.
/// let table = PiecewiseConstant2D::new(&[1.0, 2.0, 3.0, 4.0], 2, 2).unwrap();
/// let uv = LatLong.invert(-Vec3::Y);
/// assert!(uv.y < 1.0 && table.pdf(uv) > 0.0);
///
/// // Sample a direction from the table and get its density per steradian.
/// let (uv, pdf_uv) = table.sample_with_pdf(Vec2::new(0.3, 0.8));
/// let dir = LatLong.sample(uv);
/// let pdf = LatLong::solid_angle_pdf(pdf_uv, LatLong::sin_theta(dir));
/// let again = LatLong::solid_angle_pdf(table.pdf(LatLong.invert(dir)), LatLong::sin_theta(dir));
/// assert!(pdf > 0.0 && (pdf - again).abs() <= 1e-5 * pdf);
/// ```
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct LatLong;

impl LatLong {
    /// `sin θ = √(x² + z²)` of a unit direction (θ measured from `+y`).
    #[inline]
    #[must_use]
    pub fn sin_theta(dir: Vec3) -> f32 {
        (dir.x * dir.x + dir.z * dir.z).sqrt()
    }

    /// A density per unit area of the `(u, v)` square turned into one per steradian:
    /// `p(ω) = p(u, v) / (2π² max(sin θ, ε))`, `ε = f32::EPSILON`; 0 for `pdf_uv ≤ 0` or NaN.
    #[inline]
    #[must_use]
    pub fn solid_angle_pdf(pdf_uv: f32, sin_theta: f32) -> f32 {
        let p = pdf_uv / (2.0 * PI * PI * sin_theta.abs().max(f32::EPSILON));
        if p > 0.0 {
            p
        } else {
            0.0
        }
    }

    /// `(u, v, sin θ)` of a direction (any length; the zero vector is the north pole), with
    /// `u, v ∈ [0, 1)` and `sin θ` of the direction as given.
    #[inline]
    pub fn uv_sin_theta(dir: Vec3) -> (Vec2, f32) {
        let u = wrap_unit(dir.x.atan2(-dir.z) / TAU);
        let sin_theta = Self::sin_theta(dir);
        let v = clamp_unit(sin_theta.atan2(dir.y) / PI);
        (Vec2::new(u, v), sin_theta)
    }

    /// The direction of `(u, v)` and its `sin θ = sin πv` (as [`Warp::sample`] computes it).
    #[inline]
    pub fn direction_sin_theta(uv: Vec2) -> (Vec3, f32) {
        let (sin_theta, cos_theta) = (PI * uv.y).sin_cos();
        let (sin_phi, cos_phi) = (TAU * uv.x).sin_cos();
        let dir = Vec3::new(sin_theta * sin_phi, cos_theta, -sin_theta * cos_phi);
        (dir, sin_theta)
    }
}

/// `x` modulo 1, in `[0, 1)`: a result that rounds up to 1 wraps to 0, `−0` becomes `+0`,
/// NaN becomes 0.
#[inline]
fn wrap_unit(x: f32) -> f32 {
    let y = x - x.floor();
    if y < 1.0 {
        y + 0.0
    } else {
        0.0
    }
}

impl Warp for LatLong {
    type Point = Vec3;

    /// The direction of image coordinates `u = (u, v)`.
    #[inline]
    fn sample(&self, u: Vec2) -> Vec3 {
        Self::direction_sin_theta(u).0
    }

    /// `1 / (2π² max(sin θ, ε))` per steradian for a finite direction, 0 otherwise.
    #[inline]
    fn pdf(&self, dir: Vec3) -> f32 {
        if dir.is_finite() {
            Self::solid_angle_pdf(1.0, Self::sin_theta(dir))
        } else {
            0.0
        }
    }
}

impl InvertibleWarp for LatLong {
    /// The image coordinates `(u, v) ∈ [0,1)²` of a direction (see [`LatLong`]'s edges).
    #[inline]
    fn invert(&self, dir: Vec3) -> Vec2 {
        Self::uv_sin_theta(dir).0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axes() {
        let close = |a: Vec3, b: Vec3| (a - b).length() < 1e-6;
        assert!(close(LatLong.sample(Vec2::new(0.0, 0.0)), Vec3::Y));
        assert!(close(LatLong.sample(Vec2::new(0.0, 0.5)), -Vec3::Z));
        assert!(close(LatLong.sample(Vec2::new(0.25, 0.5)), Vec3::X));
        assert!(close(LatLong.sample(Vec2::new(0.5, 0.5)), Vec3::Z));
        assert_eq!(LatLong.invert(-Vec3::Z), Vec2::new(0.0, 0.5));
        assert_eq!(LatLong.invert(Vec3::X), Vec2::new(0.25, 0.5));
    }

    #[test]
    fn wrap_edges() {
        assert_eq!(wrap_unit(-0.0).to_bits(), 0.0f32.to_bits());
        assert_eq!(wrap_unit(1.0), 0.0);
        assert_eq!(wrap_unit(-1e-9), 0.0); // 1 − 10⁻⁹ rounds to 1
        assert_eq!(wrap_unit(f32::NAN), 0.0);
        assert_eq!(wrap_unit(f32::INFINITY), 0.0);
        assert_eq!(wrap_unit(-0.25), 0.75);
    }
}
