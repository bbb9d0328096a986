//! Change of variables between measures, and numerical Jacobians of any warp.
//!
//! If `y = T(x)` maps a `k`-dimensional domain one-to-one onto a `k`-dimensional surface,
//! the densities are related by `p_Y(y) = p_X(x) / J(x)` with `J = sqrt(det(DᵀD))` and `D`
//! the (`m × k`) derivative of `T` (for a square `D`, `J = |det D|`). For a warp from the
//! unit square, `p_X = 1`, so `pdf(sample(u)) · J(u) = 1`: [`jacobian_identity_error`]
//! checks that identity for any [`Warp`] by central differences. Derivations are in
//! `docs/derivations.md`.
//!
//! The conversions below are the Jacobians a renderer meets. Each returns a finite value
//! `>= 0` for finite inputs `>= 0`: where the Jacobian is zero or infinite (a grazing light,
//! a sample at the pole or the centre) it returns 0, and a result beyond `f32` range is
//! clamped to `f32::MAX`. NaN inputs give 0.
//!
//! ```
//! use mcrt::glam::Vec2;
//! use mcrt::sampling::jacobian::{jacobian_identity_error, DEFAULT_JACOBIAN_STEP};
//! use mcrt::sampling::warp::Warp;
//!
//! /// A user's warp: the rectangle [0, 2] × [0, 3], pdf 1/6 per unit area.
//! struct Rect;
//! impl Warp for Rect {
//!     type Point = Vec2;
//!     fn sample(&self, u: Vec2) -> Vec2 {
//!         Vec2::new(2.0 * u.x, 3.0 * u.y)
//!     }
//!     fn pdf(&self, _: Vec2) -> f32 {
//!         1.0 / 6.0
//!     }
//! }
//!
//! let err = jacobian_identity_error(&Rect, Vec2::new(0.3, 0.6), DEFAULT_JACOBIAN_STEP).unwrap();
//! assert!(err < 1e-3);
//! // Too close to the square's edge for the central difference: no answer.
//! assert_eq!(jacobian_identity_error(&Rect, Vec2::new(0.0, 0.6), DEFAULT_JACOBIAN_STEP), None);
//! ```

use glam::{Vec2, Vec3};

use crate::sampling::warp::Warp;

/// Area → solid angle: `p_ω = p_A · d² / |cos θ'|`, where `d²` is the squared distance to
/// the point on the light and `θ'` the angle between the light's normal and the direction
/// back to the shading point. 0 when `cos θ' = 0` (the light is seen edge-on).
#[must_use]
pub fn solid_angle_pdf_from_area(pdf_area: f32, distance_sq: f32, cos_theta_light: f32) -> f32 {
    ratio(
        f64::from(pdf_area) * f64::from(distance_sq),
        f64::from(cos_theta_light).abs(),
    )
}

/// Solid angle → area: `p_A = p_ω · |cos θ'| / d²`, the inverse of
/// [`solid_angle_pdf_from_area`]. 0 when `d² = 0`.
#[must_use]
pub fn area_pdf_from_solid_angle(
    pdf_solid_angle: f32,
    distance_sq: f32,
    cos_theta_light: f32,
) -> f32 {
    ratio(
        f64::from(pdf_solid_angle) * f64::from(cos_theta_light).abs(),
        f64::from(distance_sq),
    )
}

/// Solid angle → spherical coordinates: `p(θ, φ) = sin θ · p(ω)`, a density per unit
/// `dθ dφ`, since `dω = sin θ dθ dφ`.
#[must_use]
pub fn spherical_pdf_from_solid_angle(pdf_solid_angle: f32, sin_theta: f32) -> f32 {
    ratio(f64::from(pdf_solid_angle) * f64::from(sin_theta).abs(), 1.0)
}

/// Spherical coordinates → solid angle: `p(ω) = p(θ, φ) / sin θ`. 0 at the poles
/// (`sin θ = 0`).
#[must_use]
pub fn solid_angle_pdf_from_spherical(pdf_theta_phi: f32, sin_theta: f32) -> f32 {
    ratio(f64::from(pdf_theta_phi), f64::from(sin_theta).abs())
}

/// Latitude–longitude image coordinates → solid angle: with `u = φ / 2π` and `v = θ / π`,
/// `p(ω) = p(u, v) / (2π² sin θ)`. 0 at the poles. (The environment-map case of
/// [`PiecewiseConstant2D`](crate::sampling::distribution::PiecewiseConstant2D); the map
/// itself, direction ↔ `(u, v)`, and a conversion that stays positive at the poles are
/// [`LatLong`](crate::sampling::warp::LatLong).)
#[must_use]
pub fn solid_angle_pdf_from_lat_long(pdf_uv: f32, sin_theta: f32) -> f32 {
    let two_pi_sq = 2.0 * std::f64::consts::PI * std::f64::consts::PI;
    ratio(f64::from(pdf_uv), two_pi_sq * f64::from(sin_theta).abs())
}

/// Cartesian → polar: `p(r, φ) = r · p(x, y)`, since `dx dy = r dr dφ`.
#[must_use]
pub fn polar_pdf_from_cartesian(pdf_xy: f32, r: f32) -> f32 {
    ratio(f64::from(pdf_xy) * f64::from(r).abs(), 1.0)
}

/// Polar → Cartesian: `p(x, y) = p(r, φ) / r`. 0 at the centre (`r = 0`).
#[must_use]
pub fn cartesian_pdf_from_polar(pdf_r_phi: f32, r: f32) -> f32 {
    ratio(f64::from(pdf_r_phi), f64::from(r).abs())
}

/// `num / den` as a finite `f32 >= 0`: 0 for a zero denominator, NaN or negative input;
/// clamped to `f32::MAX`.
fn ratio(num: f64, den: f64) -> f32 {
    let q = num / den;
    if den > 0.0 && q >= 0.0 {
        q.min(f64::from(f32::MAX)) as f32
    } else {
        0.0
    }
}

/// A point type a warp or sampler can produce, seen as a point of `R³` for numerical
/// differentiation (and, in `mcrt::stats`, for binning).
///
/// Implemented for `f32` (a line), [`Vec2`] (the plane), [`Vec3`] (directions and surfaces)
/// and `usize` (categories, which have no derivative). [`WarpPoint::DIM`] picks the Jacobian
/// of [`numerical_jacobian_of`]: `|dx/du₁|`, `|det D|` or `‖∂p/∂u₁ × ∂p/∂u₂‖`.
pub trait WarpPoint: Copy {
    /// The number of meaningful coordinates (1, 2 or 3; 0 for categories).
    const DIM: usize;
    /// The coordinates in `f64`, padded with zeros.
    fn to_f64(self) -> [f64; 3];
    /// Whether every coordinate is finite.
    fn is_finite_point(self) -> bool {
        self.to_f64().iter().all(|c| c.is_finite())
    }
}

impl WarpPoint for f32 {
    const DIM: usize = 1;
    fn to_f64(self) -> [f64; 3] {
        [f64::from(self), 0.0, 0.0]
    }
}

impl WarpPoint for Vec2 {
    const DIM: usize = 2;
    fn to_f64(self) -> [f64; 3] {
        [f64::from(self.x), f64::from(self.y), 0.0]
    }
}

impl WarpPoint for Vec3 {
    const DIM: usize = 3;
    fn to_f64(self) -> [f64; 3] {
        [f64::from(self.x), f64::from(self.y), f64::from(self.z)]
    }
}

impl WarpPoint for usize {
    const DIM: usize = 0;
    fn to_f64(self) -> [f64; 3] {
        [self as f64, 0.0, 0.0]
    }
}

/// A good default step for [`numerical_jacobian`]: 2⁻⁹ ≈ 1.95·10⁻³.
///
/// Central differences of an `f32` warp have truncation error `O(h²)` and rounding error
/// about `ε₃₂ / h ≈ 6·10⁻⁸ / h` relative to the output's scale; 2⁻⁹ balances them for
/// derivatives of order 1. Measured on a 400 × 400 grid of cell centres with
/// `u₁ ∈ (0.05, 0.95)`: `max |pdf · J − 1|` is 1.6·10⁻⁴ for the polar disk map and
/// 1.5·10⁻⁴ for the uniform sphere map, so tests can allow 10⁻³. Near a singular point of
/// square-root type at distance `s` (in `u`), the truncation error grows like
/// `0.1 · (h / s)²`: 2·10⁻² at `s = 2.5 h`, 10⁻³ at `s = 10 h`. Warps with steep
/// derivatives (narrow lobes, high exponents) need a smaller step and a looser tolerance.
///
/// What to skip, measured with this step over a 300 × 300 grid of cell centres for the
/// crate's basic warps (max `|pdf · J − 1|` ≤ 1.0·10⁻³ once skipped, 2·10⁻² to 10⁻¹
/// otherwise; cone from 10⁻³ to 0.1 rad, power cosine up to exponent 1000):
///
/// | warp | skip (the singular points: poles, centres, rims) |
/// |---|---|
/// | polar disk (`r = √u₁`), triangle (`√u₁`), hemisphere, cone, θ/sin θ | `u₁ < 10 h` |
/// | sphere | `u₁ < 10 h` or `u₁ > 1 − 10 h` |
/// | power cosine | `u₁ > 1 − 10 h` (the pole, `cos θ = u₁^(1/(n+1)) → 1`) |
/// | concentric disk | `|u₁ − u₂| < 2h` or `|u₁ + u₂ − 1| < 2h` (the diagonals), `|u − (½, ½)| < 20 h` (the centre) |
/// | cosine hemisphere (Malley) | as the concentric disk, and within `10 h` of any edge of the square (the horizon, `z = √(1 − r²)`) |
pub const DEFAULT_JACOBIAN_STEP: f64 = 1.0 / 512.0;

/// `J(u) = sqrt(det(DᵀD))` of `w.sample` at `u`, by central differences with step `h`:
/// [`numerical_jacobian_of`] for a [`Warp`].
#[must_use]
pub fn numerical_jacobian<W>(w: &W, u: Vec2, h: f64) -> Option<f64>
where
    W: Warp + ?Sized,
    W::Point: WarpPoint,
{
    numerical_jacobian_of(|v| w.sample(v), u, h)
}

/// `J(u) = sqrt(det(DᵀD))` of the map `sample` at `u`, by central differences with step
/// `h`, evaluated in `f64` from the `f32` outputs (the step actually used is the difference
/// of the `f32`-rounded arguments): `|dx/du₁|` for `f32` points (only `u.x` moves),
/// `|det D|` for [`Vec2`], `‖∂p/∂u₁ × ∂p/∂u₂‖` for [`Vec3`].
///
/// Returns `None` when `h` is not finite and positive, when a stencil point `u ± h·eᵢ`
/// (rounded to `f32`) leaves `[0,1)²` (so `u` within `h` of the square's edges), when an
/// output is not finite, when `J` is not finite, and for categories (`usize` points).
///
/// Seams and singular points are the caller's to skip: the stencil must not straddle a
/// seam where the map's derivative jumps (the concentric disk's diagonals `u.x = u.y` and
/// `u.x = 1 − u.y`, and its centre; the `φ = 0` cut of polar maps lies on the square's edge
/// `u₂ = 0`, which the edge rule already skips), and near a singular point (`√u₁` at
/// `u₁ = 0`, the poles of sphere maps) the truncation error grows like `(h / s)²` at
/// distance `s`. Filter `u` beforehand, or use [`numerical_jacobian_excluding`]. See
/// [`DEFAULT_JACOBIAN_STEP`] for the accuracy.
///
/// ```
/// use mcrt::glam::Vec2;
/// use mcrt::sampling::jacobian::numerical_jacobian_of;
///
/// // (r, φ) = (√u₁, 2πu₂) maps the square onto the unit disk with J = π everywhere.
/// let disk = |u: Vec2| {
///     let (r, phi) = (u.x.sqrt(), std::f32::consts::TAU * u.y);
///     Vec2::new(r * phi.cos(), r * phi.sin())
/// };
/// let j = numerical_jacobian_of(disk, Vec2::new(0.4, 0.3), 1e-3).unwrap();
/// assert!(j.is_finite() && (j - std::f64::consts::PI).abs() < 1e-3);
/// assert_eq!(numerical_jacobian_of(disk, Vec2::new(0.0, 0.3), 1e-3), None);
/// ```
#[must_use]
pub fn numerical_jacobian_of<P: WarpPoint>(
    sample: impl Fn(Vec2) -> P,
    u: Vec2,
    h: f64,
) -> Option<f64> {
    if !(h.is_finite() && h > 0.0) || P::DIM == 0 {
        return None;
    }
    let du = partial(&sample, u, Vec2::X, h)?;
    let j = if P::DIM == 1 {
        du[0].abs()
    } else {
        let dv = partial(&sample, u, Vec2::Y, h)?;
        // det(DᵀD) = |∂x|²|∂y|² − (∂x·∂y)² = |∂x × ∂y|², formed without cancellation.
        let cross = [
            du[1] * dv[2] - du[2] * dv[1],
            du[2] * dv[0] - du[0] * dv[2],
            du[0] * dv[1] - du[1] * dv[0],
        ];
        if P::DIM == 2 {
            cross[2].abs()
        } else {
            cross.iter().map(|c| c * c).sum::<f64>().sqrt()
        }
    };
    j.is_finite().then_some(j)
}

/// [`numerical_jacobian`], but `None` also when `exclude` holds at `u` or at any of the
/// four stencil points `u ± h·e₁`, `u ± h·e₂`. Make `exclude` describe a neighbourhood of
/// each seam or singular point (e.g. `|u.x − u.y| < 2h` for a diagonal seam).
#[must_use]
pub fn numerical_jacobian_excluding<W>(
    w: &W,
    u: Vec2,
    h: f64,
    exclude: impl Fn(Vec2) -> bool,
) -> Option<f64>
where
    W: Warp + ?Sized,
    W::Point: WarpPoint,
{
    let hf = h as f32;
    let stencil = [
        u,
        u + Vec2::X * hf,
        u - Vec2::X * hf,
        u + Vec2::Y * hf,
        u - Vec2::Y * hf,
    ];
    if stencil.iter().any(|&p| exclude(p)) {
        return None;
    }
    numerical_jacobian(w, u, h)
}

/// `|pdf(sample(u)) · J(u) − 1|`, in `f64`: 0 for a warp whose pdf is right at `u`.
/// `None` where [`numerical_jacobian`] is; `Some(∞)` when the pdf is NaN or infinite.
#[must_use]
pub fn jacobian_identity_error<W>(w: &W, u: Vec2, h: f64) -> Option<f64>
where
    W: Warp + ?Sized,
    W::Point: WarpPoint,
{
    let j = numerical_jacobian(w, u, h)?;
    let (_, pdf) = w.sample_with_pdf(u);
    let err = (f64::from(pdf) * j - 1.0).abs();
    Some(if err.is_finite() { err } else { f64::INFINITY })
}

/// `∂ sample / ∂ u` along `axis`, by a central difference over the realised `f32` step;
/// `None` when a stencil point leaves `[0,1)²` or an output is not finite.
fn partial<P: WarpPoint>(
    sample: &impl Fn(Vec2) -> P,
    u: Vec2,
    axis: Vec2,
    h: f64,
) -> Option<[f64; 3]> {
    let along = |s: f64| {
        let v = Vec2::new(
            (f64::from(u.x) + s * f64::from(axis.x)) as f32,
            (f64::from(u.y) + s * f64::from(axis.y)) as f32,
        );
        let inside = (0.0..1.0).contains(&v.x) && (0.0..1.0).contains(&v.y);
        inside.then_some(v)
    };
    let (plus, minus) = (along(h)?, along(-h)?);
    let step = (f64::from(plus.x) - f64::from(minus.x)) * f64::from(axis.x)
        + (f64::from(plus.y) - f64::from(minus.y)) * f64::from(axis.y);
    let (a, b) = (sample(plus), sample(minus));
    if !(a.is_finite_point() && b.is_finite_point()) {
        return None;
    }
    let (a, b) = (a.to_f64(), b.to_f64());
    Some([0, 1, 2].map(|k| (a[k] - b[k]) / step))
}

#[cfg(test)]
mod tests;
