//! Warps: maps from the unit square `u ∈ [0,1)²` to a domain, each with its pdf and, where it
//! exists, its inverse.
//!
//! Every warp implements [`Warp`]; the invertible ones also implement [`InvertibleWarp`], so
//! generic code (the chi-square harness in `mcrt::stats`, property tests, your own code) can
//! take any of them. Densities on the real line (linear, tent, exponential, normal, logistic,
//! smoothstep) take a single `u ∈ [0,1)` and implement [`Warp1D`], so a sampler's 1D
//! dimensions drive them without wasting a second coordinate. The derivation of each mapping (pdf, CDF, inverse, Jacobian) is in
//! `docs/derivations.md`.
//!
//! # Directions about another axis
//!
//! Directional warps sample about `+z` (a z-up local frame, `cos θ = z`). For a lobe about
//! another unit axis `n`, build a [`Frame`](crate::sampling::Frame) with
//! [`Frame::from_normal(n)`](crate::sampling::Frame::from_normal), map samples out with
//! [`Frame::to_world`](crate::sampling::Frame::to_world), and take a world direction back with
//! [`Frame::to_local`](crate::sampling::Frame::to_local) before calling `pdf` or `invert`
//! (a rotation: the densities per solid angle are unchanged).
//!
//! # Inputs outside the unit square
//!
//! Every warp is defined for `u ∈ [0,1)^d`; the property tests pin the edges `u = 0` and
//! `u = 1 − 2⁻²⁴`. For `u` outside it (negative, ≥ 1, NaN or infinite) all warps agree:
//!
//! - `sample` and `sample_with_pdf` do not panic and return *some* point (and density),
//!   which may lie off the support or be NaN or infinite; nothing more is promised
//!   (clamping would hide the caller's bug and cost every sample a branch);
//! - `pdf` of any point, NaN and infinite points included, is finite and ≥ 0, and 0 for a
//!   non-finite point or a point off the support; so `pdf(sample(u))` is never NaN, and an
//!   estimator that checks `pdf > 0` drops such a sample.
//!
//! `tests/it/warp_edge_inputs.rs` checks this for every warp.
//!
//! ```
//! use mcrt::glam::Vec2;
//! use mcrt::sampling::warp::{CosineHemisphere, Warp};
//!
//! let (w, pdf) = CosineHemisphere.sample_with_pdf(Vec2::new(0.3, 0.7));
//! assert!((w.length() - 1.0).abs() < 1e-5);
//! assert!((pdf - w.z / std::f32::consts::PI).abs() < 1e-5);
//! ```

use glam::Vec2;

mod anisotropic_microfacet;
mod bilinear_patch;
mod cone;
mod disk;
mod exponential;
mod hemisphere;
mod henyey_greenstein;
mod lat_long;
pub(crate) mod linear;
mod logistic;
mod microfacet;
mod normal;
pub mod polar;
mod power_cosine;
mod smoothstep;
mod sphere;
mod spherical_rectangle;
mod spherical_triangle;
mod tent;
mod theta_over_sin;
mod triangle;
mod visible_normals;
mod von_mises_fisher;

pub use anisotropic_microfacet::*;
pub use bilinear_patch::*;
pub use cone::*;
pub use disk::*;
pub use exponential::*;
pub use hemisphere::*;
pub use henyey_greenstein::*;
pub use lat_long::LatLong;
pub use linear::*;
pub use logistic::*;
pub use microfacet::*;
pub use normal::*;
pub use power_cosine::*;
pub use smoothstep::*;
pub use sphere::*;
pub use spherical_rectangle::*;
pub use spherical_triangle::*;
pub use tent::*;
pub use theta_over_sin::*;
pub use triangle::*;
pub use visible_normals::*;
pub use von_mises_fisher::*;

/// A map from the unit square to a domain, with the density of its image.
pub trait Warp {
    /// A point of the domain: [`glam::Vec2`] for planar domains, [`glam::Vec3`] for
    /// directions.
    type Point: Copy;

    /// Maps `u ∈ [0,1)²` to a point of the domain.
    fn sample(&self, u: Vec2) -> Self::Point;

    /// The density of [`Warp::sample`] at `p`, in the measure the type documents; 0 outside
    /// the support.
    fn pdf(&self, p: Self::Point) -> f32;

    /// [`Warp::sample`] and [`Warp::pdf`] at once; override when that is cheaper.
    #[inline]
    fn sample_with_pdf(&self, u: Vec2) -> (Self::Point, f32) {
        let p = self.sample(u);
        (p, self.pdf(p))
    }
}

/// A warp with an inverse: [`InvertibleWarp::invert`] maps a point of the domain back to the
/// unit square.
pub trait InvertibleWarp: Warp {
    /// The `u` such that `sample(u) == p` (one of them, where the map is not one-to-one).
    fn invert(&self, p: Self::Point) -> Vec2;
}

/// A map from `u ∈ [0,1)` to the real line, with the density of its image and its inverse:
/// the one-dimensional counterpart of [`Warp`] and [`InvertibleWarp`].
///
/// ```
/// use mcrt::sampling::warp::{Tent, Warp1D};
///
/// let tent = Tent::new(2.0).unwrap();
/// let (x, pdf) = tent.sample_with_pdf(0.5);
/// assert!(x.abs() < 1e-6 && (pdf - 0.5).abs() < 1e-6);
/// assert!((tent.invert(x) - 0.5).abs() < 1e-6);
/// ```
pub trait Warp1D {
    /// Maps `u ∈ [0,1)` to a point of the support.
    fn sample(&self, u: f32) -> f32;

    /// The density of [`Warp1D::sample`] at `x`, per unit length; 0 outside the support.
    fn pdf(&self, x: f32) -> f32;

    /// The `u ∈ [0,1)` with `sample(u) == x` (clamped into `[0, 1 − 2⁻²⁴]`).
    fn invert(&self, x: f32) -> f32;

    /// [`Warp1D::sample`] and [`Warp1D::pdf`] at once; override when that is cheaper.
    #[inline]
    fn sample_with_pdf(&self, u: f32) -> (f32, f32) {
        let x = self.sample(u);
        (x, self.pdf(x))
    }
}
