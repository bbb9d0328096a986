//! Warps: maps from the unit square `u ∈ [0,1)²` to a domain, each with its pdf and, where it
//! exists, its inverse.
//!
//! Every warp implements [`Warp`]; the invertible ones also implement [`InvertibleWarp`], so
//! generic code (the chi-square harness in `mcrt::stats`, property tests, your own code) can
//! take any of them. The derivation of each mapping (pdf, CDF, inverse, Jacobian) is in
//! `docs/derivations.md`.
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
//! `tests/warp_edge_inputs.rs` checks this for every warp.
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

mod cone;
mod disk;
mod hemisphere;
mod microfacet;
mod power_cosine;
mod sphere;
mod spherical_rectangle;
mod spherical_triangle;
mod theta_over_sin;
mod triangle;
mod visible_normals;

pub use cone::*;
pub use disk::*;
pub use hemisphere::*;
pub use microfacet::*;
pub use power_cosine::*;
pub use sphere::*;
pub use spherical_rectangle::*;
pub use spherical_triangle::*;
pub use theta_over_sin::*;
pub use triangle::*;
pub use visible_normals::*;

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
