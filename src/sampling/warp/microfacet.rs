//! Microfacet normal distributions (Beckmann, GGX): the NDF, Smith masking, and sampling of
//! microfacet normals with pdf D(m) cos θ_m.
//!
//! Conventions (derivations in `docs/derivations.md`):
//! - D is normalised in projected area: ∫ D(m) cos θ_m dω_m = 1 over the upper hemisphere.
//! - [`Beckmann`] and [`Ggx`] sample m with pdf D(m) cos θ_m per steradian (Mitsuba 3's
//!   convention for `square_to_beckmann_pdf`). A renderer turns this half-vector pdf into a
//!   reflected-direction pdf by the Jacobian 1/(4 |wo·m|).
//! - Roughness α is accepted in [1e-4, 1e4] and tested from 1e-4 to 1. Mitsuba 3 clamps
//!   smaller α to 1e-4; callers reading scene files should do the same before calling `new`.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::{InvertibleWarp, Warp};
use crate::sampling::error::check_param;
use crate::sampling::SamplingError;

mod distribution;
pub(crate) mod special;

pub use distribution::MicrofacetDistribution;

// `u` is clamped to the largest `f32` below 1, so that `1 − u` is never 0.
use crate::sampling::unit::ONE_MINUS_EPSILON;

/// Validates a roughness: finite, in [1e-4, 1e4].
pub(crate) fn check_alpha(alpha: f32) -> Result<f32, SamplingError> {
    check_param(
        "alpha",
        alpha,
        "finite, in [1e-4, 1e4] (clamp smaller values to 1e-4 like Mitsuba 3)",
        |a| (1e-4..=1e4).contains(&a),
    )
}

/// `alpha` clamped into [1e-4, 1e4] (NaN to 1e-4): a roughness [`check_alpha`] accepts,
/// for a value that varies per shading point (a textured roughness), made without a check.
#[inline]
pub(crate) fn clamp_alpha(alpha: f32) -> f32 {
    if alpha >= 1e-4 {
        alpha.min(1e4)
    } else {
        1e-4
    }
}

/// (sin² θ, cos² θ)·|m|² split: returns (x² + y², z²) of `m`.
fn radial_axial(m: Vec3) -> (f32, f32) {
    (m.x * m.x + m.y * m.y, m.z * m.z)
}

/// The normal with tan² θ = `tan2` and azimuth 2π u₂, computed without 1 − cos² cancellation.
fn normal_from_tan2(tan2: f32, u2: f32) -> Vec3 {
    let cos_theta = 1.0 / (1.0 + tan2).sqrt();
    let sin_theta = tan2.sqrt() * cos_theta;
    let (sin_phi, cos_phi) = (2.0 * PI * u2).sin_cos();
    Vec3::new(sin_theta * cos_phi, sin_theta * sin_phi, cos_theta)
}

/// u₂ ∈ [0, 1) from the azimuth of m.
fn azimuth_to_unit(m: Vec3) -> f32 {
    let mut u = m.y.atan2(m.x) / (2.0 * PI);
    if u < 0.0 {
        u += 1.0;
    }
    if u >= 1.0 {
        0.0
    } else {
        u
    }
}

/// cos θ of a possibly non-unit `m`.
fn cos_theta(m: Vec3) -> f32 {
    let len = m.length();
    if len > 0.0 {
        m.z / len
    } else {
        0.0
    }
}

/// The Beckmann distribution D(m) = exp(−tan²θ/α²) / (π α² cos⁴θ), sampled with pdf
/// D(m) cos θ_m per steradian.
///
/// Mapping: tan² θ = −α² ln(1 − u₁), φ = 2π u₂; inverse u₁ = 1 − exp(−tan²θ/α²).
/// Smith Λ ([`MicrofacetDistribution::lambda`]) uses the rational approximation of
/// Walter et al. (< 0.35 % error in G₁), exactly like Mitsuba 3; the exact erf form is
/// [`Beckmann::lambda_exact`].
///
/// Walter, Marschner, Li, Torrance 2007, "Microfacet Models for Refraction through Rough
/// Surfaces", EGSR.
///
/// ```
/// use mcrt::glam::Vec2;
/// use mcrt::sampling::warp::{Beckmann, InvertibleWarp, MicrofacetDistribution, Warp};
///
/// let b = Beckmann::new(0.3).unwrap();
/// let (m, pdf) = b.sample_with_pdf(Vec2::new(0.5, 0.5)); // Mitsuba 3.9.1 gives NaN here
/// assert!(m.is_finite() && (m.length() - 1.0).abs() < 1e-6);
/// assert!((pdf - b.d(m) * m.z).abs() <= 1e-5 * pdf);
/// assert!((b.invert(m) - Vec2::new(0.5, 0.5)).abs().max_element() < 1e-5);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Beckmann {
    alpha: f32,
}

impl Beckmann {
    /// Beckmann of roughness 1: the configuration that the anisotropic Beckmann
    /// distribution stretches (Heitz 2014, JCGT 3(2)), made without a check.
    pub const UNIT: Beckmann = Beckmann { alpha: 1.0 };

    /// A Beckmann distribution of roughness `alpha` ∈ [1e-4, 1e4] (tested 1e-4 to 1).
    #[inline]
    pub fn new(alpha: f32) -> Result<Self, SamplingError> {
        Ok(Self {
            alpha: check_alpha(alpha)?,
        })
    }

    /// The distribution of roughness `alpha` clamped into [1e-4, 1e4] (NaN to 1e-4), without
    /// a check: for a roughness that varies per shading point (a textured roughness), where
    /// Mitsuba 3 clamps the same way.
    #[inline]
    pub fn clamped(alpha: f32) -> Self {
        Self {
            alpha: clamp_alpha(alpha),
        }
    }

    /// The exact Smith Λ(w) = (e^{−a²}/(a√π) − erfc(a))/2 with a = 1/(α tan θ_w), computed
    /// in `f64`. [`BeckmannVisible`](super::BeckmannVisible) uses it so its pdf integrates to 1.
    pub fn lambda_exact(&self, w: Vec3) -> f32 {
        let (r2, z2) = radial_axial(w);
        if r2 == 0.0 {
            return 0.0;
        }
        let a = (f64::from(z2) / f64::from(r2)).sqrt() / f64::from(self.alpha);
        special::beckmann_lambda_exact(a) as f32
    }
}

impl MicrofacetDistribution for Beckmann {
    fn alpha(&self) -> f32 {
        self.alpha
    }

    fn d(&self, m: Vec3) -> f32 {
        let (r2, z2) = radial_axial(m);
        // The finiteness test also sends NaN and infinite normals to 0.
        if m.z <= 0.0 || !m.is_finite() {
            return 0.0;
        }
        let e = r2 / (z2 * self.alpha * self.alpha);
        if e.is_nan() || e > 100.0 {
            return 0.0; // exp(−e) is below f32's range; also avoids 0·∞
        }
        let cos2 = z2 / (r2 + z2);
        (-e).exp() / (PI * self.alpha * self.alpha * cos2 * cos2)
    }

    fn lambda(&self, w: Vec3) -> f32 {
        let (r2, z2) = radial_axial(w);
        if r2 == 0.0 {
            return 0.0;
        }
        let a = (z2 / r2).sqrt() / self.alpha;
        if a >= 1.6 {
            return 0.0;
        }
        // Rational fit of Walter et al. 2007 (the one Mitsuba 3 uses); +∞ at a = 0.
        (1.0 - 1.259 * a + 0.396 * a * a) / (3.535 * a + 2.181 * a * a)
    }
}

impl Warp for Beckmann {
    type Point = Vec3;

    #[inline]
    fn sample(&self, u: Vec2) -> Vec3 {
        let u1 = u.x.clamp(0.0, ONE_MINUS_EPSILON);
        let tan2 = -self.alpha * self.alpha * (-u1).ln_1p();
        normal_from_tan2(tan2.max(0.0), u.y)
    }

    /// D(m) cos θ_m per steradian; 0 for m.z ≤ 0.
    #[inline]
    fn pdf(&self, m: Vec3) -> f32 {
        self.d(m) * cos_theta(m).max(0.0)
    }
}

impl InvertibleWarp for Beckmann {
    #[inline]
    fn invert(&self, m: Vec3) -> Vec2 {
        let (r2, z2) = radial_axial(m);
        let e = r2 / (z2 * self.alpha * self.alpha);
        // 1 − exp(−e), rounded once whichever side of 1/2 it falls.
        let u1 = if e.is_nan() {
            0.0
        } else if e > std::f32::consts::LN_2 {
            1.0 - (-e).exp()
        } else {
            -(-e).exp_m1()
        };
        Vec2::new(u1.min(ONE_MINUS_EPSILON), azimuth_to_unit(m))
    }
}

/// The GGX (Trowbridge–Reitz) distribution D(m) = α² / (π cos⁴θ (α² + tan²θ)²), sampled
/// with pdf D(m) cos θ_m per steradian.
///
/// Mapping: tan² θ = α² u₁/(1 − u₁), φ = 2π u₂; inverse u₁ = tan²θ/(α² + tan²θ).
/// Smith Λ(w) = (√(1 + α² tan²θ_w) − 1)/2, exact.
///
/// Walter, Marschner, Li, Torrance 2007, "Microfacet Models for Refraction through Rough
/// Surfaces", EGSR.
///
/// ```
/// use mcrt::glam::{Vec2, Vec3};
/// use mcrt::sampling::warp::{Ggx, MicrofacetDistribution, Warp};
///
/// let g = Ggx::new(0.2).unwrap();
/// let m = g.sample(Vec2::new(0.7, 0.1));
/// assert!(m.z > 0.0 && (g.pdf(m) - g.d(m) * m.z).abs() <= 1e-5 * g.pdf(m));
/// assert_eq!(g.g1(Vec3::Z, m), 1.0); // no masking at normal incidence
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ggx {
    alpha: f32,
}

impl Ggx {
    /// GGX of roughness 1: the stretched configuration in which visible normals of any
    /// roughness are drawn (Heitz 2018, "Sampling the GGX Distribution of Visible Normals",
    /// JCGT 7(4), §2), made without a check.
    pub const UNIT: Ggx = Ggx { alpha: 1.0 };

    /// A GGX distribution of roughness `alpha` ∈ [1e-4, 1e4] (tested 1e-4 to 1).
    #[inline]
    pub fn new(alpha: f32) -> Result<Self, SamplingError> {
        Ok(Self {
            alpha: check_alpha(alpha)?,
        })
    }

    /// The distribution of roughness `alpha` clamped into [1e-4, 1e4] (NaN to 1e-4), without
    /// a check: for a roughness that varies per shading point (a textured roughness), where
    /// Mitsuba 3 clamps the same way.
    #[inline]
    pub fn clamped(alpha: f32) -> Self {
        Self {
            alpha: clamp_alpha(alpha),
        }
    }
}

impl MicrofacetDistribution for Ggx {
    fn alpha(&self) -> f32 {
        self.alpha
    }

    fn d(&self, m: Vec3) -> f32 {
        let (r2, z2) = radial_axial(m);
        // The finiteness test also sends NaN and infinite normals to 0.
        if m.z <= 0.0 || !m.is_finite() {
            return 0.0;
        }
        let a2 = self.alpha * self.alpha;
        let n2 = r2 + z2;
        let den = a2 * z2 + r2; // = |m|² cos²θ (α² + tan²θ)
        a2 * (n2 / den) * (n2 / den) / PI
    }

    fn lambda(&self, w: Vec3) -> f32 {
        let (r2, z2) = radial_axial(w);
        if r2 == 0.0 {
            return 0.0;
        }
        let t = self.alpha * self.alpha * r2 / z2; // α² tan²θ
        if !t.is_finite() {
            return f32::INFINITY;
        }
        // (√(1+t) − 1)/2 without cancellation.
        t / (2.0 * (1.0 + (1.0 + t).sqrt()))
    }
}

impl Warp for Ggx {
    type Point = Vec3;

    #[inline]
    fn sample(&self, u: Vec2) -> Vec3 {
        let u1 = u.x.clamp(0.0, ONE_MINUS_EPSILON);
        let tan2 = self.alpha * self.alpha * (u1 / (1.0 - u1));
        normal_from_tan2(tan2, u.y)
    }

    /// D(m) cos θ_m per steradian; 0 for m.z ≤ 0.
    #[inline]
    fn pdf(&self, m: Vec3) -> f32 {
        self.d(m) * cos_theta(m).max(0.0)
    }
}

impl InvertibleWarp for Ggx {
    #[inline]
    fn invert(&self, m: Vec3) -> Vec2 {
        let (r2, z2) = radial_axial(m);
        let den = self.alpha * self.alpha * z2 + r2;
        // r²/(α²z² + r²), or 1 − α²z²/(α²z² + r²) near 1 so it is rounded once.
        let a2z2 = self.alpha * self.alpha * z2;
        let u1 = if den <= 0.0 || den.is_nan() {
            0.0
        } else if r2 > a2z2 {
            1.0 - a2z2 / den
        } else {
            r2 / den
        };
        Vec2::new(u1.min(ONE_MINUS_EPSILON), azimuth_to_unit(m))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clamped_equals_new_in_range_and_clamps_outside() {
        for a in [1e-4f32, 0.05, 0.3, 1.0, 7.5, 1e4] {
            assert_eq!(Ggx::clamped(a), Ggx::new(a).unwrap());
            assert_eq!(Beckmann::clamped(a), Beckmann::new(a).unwrap());
        }
        for (a, want) in [
            (0.0f32, 1e-4f32),
            (-3.0, 1e-4),
            (f32::NAN, 1e-4),
            (1e9, 1e4),
        ] {
            assert_eq!(Ggx::clamped(a).alpha(), want, "{a}");
            assert_eq!(Beckmann::clamped(a).alpha(), want, "{a}");
        }
        let g = super::super::GgxAnisotropic::clamped(f32::NAN, 0.5);
        assert_eq!(g.alphas(), (1e-4, 0.5));
        let b = super::super::BeckmannAnisotropic::clamped(0.2, f32::INFINITY);
        assert_eq!(b.alphas(), (0.2, 1e4));
    }

    const EDGES: [f32; 3] = [0.0, 0.5, ONE_MINUS_EPSILON];

    #[test]
    fn rejects_bad_alpha() {
        for a in [0.0, -1.0, f32::NAN, f32::INFINITY, 1e-5, 2e4] {
            assert!(Beckmann::new(a).is_err(), "Beckmann alpha {a}");
            assert!(Ggx::new(a).is_err(), "Ggx alpha {a}");
        }
    }

    /// Unit, finite normals with finite positive pdf at every pair of edge values of u.
    fn assert_edges_are_finite(name: &str, warp: &dyn Warp<Point = Vec3>) {
        for u1 in EDGES {
            for u2 in EDGES {
                let (m, pdf) = warp.sample_with_pdf(Vec2::new(u1, u2));
                assert!(
                    m.is_finite() && (m.length() - 1.0).abs() < 1e-6,
                    "{name} {m}"
                );
                assert!(pdf.is_finite() && pdf > 0.0, "{name} u ({u1},{u2})");
            }
        }
    }

    #[test]
    fn beckmann_mitsuba_nan_input_and_edges() {
        for alpha in [1e-4, 1e-3, 0.01, 0.1, 0.5, 1.0] {
            let b = Beckmann::new(alpha).unwrap();
            assert_edges_are_finite(&format!("Beckmann {alpha}"), &b);
        }
    }

    #[test]
    fn ggx_edges() {
        for alpha in [1e-4, 1e-3, 0.01, 0.1, 0.5, 1.0] {
            let g = Ggx::new(alpha).unwrap();
            assert_edges_are_finite(&format!("Ggx {alpha}"), &g);
        }
    }

    #[test]
    fn round_trips() {
        let u = Vec2::new(0.37, 0.81);
        let b = Beckmann::new(0.2).unwrap();
        let g = Ggx::new(0.2).unwrap();
        let ub = b.invert(b.sample(u));
        let ug = g.invert(g.sample(u));
        assert!(
            ub.is_finite() && (ub - u).abs().max_element() < 1e-5,
            "{ub}"
        );
        assert!(
            ug.is_finite() && (ug - u).abs().max_element() < 1e-5,
            "{ug}"
        );
    }

    #[test]
    fn masking_limits_and_signs() {
        let b = Beckmann::new(0.3).unwrap();
        let g = Ggx::new(0.3).unwrap();
        let grazing = Vec3::X;
        assert_eq!(b.lambda(Vec3::Z), 0.0);
        assert_eq!(g.lambda(Vec3::Z), 0.0);
        assert_eq!(b.g1(grazing, Vec3::Z), 0.0);
        assert_eq!(g.lambda(grazing), f32::INFINITY);
        let w = Vec3::new(0.6, 0.0, 0.8);
        let back = Vec3::new(-0.9, 0.0, 0.1).normalize();
        assert_eq!(g.g1(w, back), 0.0);
        assert_eq!(b.g(w, w, back), 0.0);
        let m = Vec3::Z;
        let sep = g.g(w, w, m);
        let cor = g.g_height_correlated(w, w, m); // 1/(1+2Λ) ≥ 1/(1+Λ)²
        assert!(sep.is_finite() && cor.is_finite() && sep <= cor && sep > 0.0 && sep < 1.0);
        // Rational and exact Beckmann Λ agree to the fit's accuracy in G₁.
        for z in [0.1f32, 0.3, 0.6, 0.9] {
            let w = Vec3::new((1.0 - z * z).sqrt(), 0.0, z);
            let (fit, exact) = (b.lambda(w), b.lambda_exact(w));
            let rel = ((1.0 + fit) / (1.0 + exact) - 1.0).abs();
            assert!(rel.is_finite() && rel < 4e-3, "z {z}: {fit} vs {exact}");
        }
    }

    #[test]
    fn d_is_finite_at_extremes() {
        for alpha in [1e-4f32, 1.0, 1e4] {
            let b = Beckmann::new(alpha).unwrap();
            let g = Ggx::new(alpha).unwrap();
            for m in [Vec3::Z, Vec3::X, Vec3::new(1.0, 0.0, 1e-20), -Vec3::Z] {
                for v in [b.d(m), g.d(m), b.pdf(m), g.pdf(m)] {
                    assert!(v.is_finite() && v >= 0.0, "alpha {alpha} m {m}: {v}");
                }
            }
        }
    }
}
