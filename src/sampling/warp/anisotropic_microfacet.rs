//! Anisotropic microfacet distributions (GGX, Beckmann) with roughness αᵤ along the local x
//! axis and αᵥ along y: the NDF, Smith masking, and sampling of all normals (pdf
//! D(m) cos θ_m) and of the normals visible from a direction.
//!
//! Every warp here is the isotropic α = 1 warp in the *stretched* configuration: a slope
//! (x̃, ỹ) of the α = 1 surface is the slope (αᵤ x̃, αᵥ ỹ) of the anisotropic one, so a
//! normal m₁ maps to m = normalize(αᵤ m₁.x, αᵥ m₁.y, m₁.z), and a direction w to
//! normalize(αᵤ w.x, αᵥ w.y, w.z) (`docs/derivations.md`, Part II, "4b. Anisotropic microfacets").
//! With αᵤ = αᵥ they are the distributions of [`Ggx`] and [`Beckmann`] (those keep their
//! own, cheaper, isotropic code).
//!
//! Heitz 2014, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs",
//! JCGT 3(2) (the stretch invariance).

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::microfacet::special::beckmann_lambda_exact;
use super::microfacet::{check_alpha, clamp_alpha};
use super::visible_normals::check_wi;
use super::{Beckmann, BeckmannVisible, Ggx, GgxVisible, Warp};
use crate::sampling::SamplingError;

/// The roughness pair of an anisotropic distribution, each checked as [`Ggx::new`] checks α.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Alphas {
    u: f32,
    v: f32,
}

impl Alphas {
    fn new(alpha_u: f32, alpha_v: f32) -> Result<Self, SamplingError> {
        Ok(Self {
            u: check_alpha(alpha_u)?,
            v: check_alpha(alpha_v)?,
        })
    }

    /// Both clamped into [1e-4, 1e4] (NaN to 1e-4), without a check.
    #[inline]
    fn clamped(alpha_u: f32, alpha_v: f32) -> Self {
        Self {
            u: clamp_alpha(alpha_u),
            v: clamp_alpha(alpha_v),
        }
    }

    /// `w` in the α = 1 configuration (not normalised).
    #[inline]
    fn stretch(self, w: Vec3) -> Vec3 {
        Vec3::new(self.u * w.x, self.v * w.y, w.z)
    }

    /// A normal of the α = 1 configuration mapped back (unit length).
    #[inline]
    fn unstretch(self, m1: Vec3) -> Vec3 {
        Vec3::new(self.u * m1.x, self.v * m1.y, m1.z).normalize()
    }

    /// (x²/αᵤ² + y²/αᵥ², z², |m|²) of `m`: the squared slope numerator, scaled.
    #[inline]
    fn scaled_radial(self, m: Vec3) -> (f32, f32, f32) {
        let (x, y) = (m.x / self.u, m.y / self.v);
        (x * x + y * y, m.z * m.z, m.length_squared())
    }

    /// α² tan² θ_w along the azimuth of `w`: (αᵤ² w.x² + αᵥ² w.y²)/w.z².
    #[inline]
    fn projected_tan2(self, w: Vec3) -> f32 {
        let (x, y) = (self.u * w.x, self.v * w.y);
        (x * x + y * y) / (w.z * w.z)
    }
}

/// cos θ of a possibly non-unit `m`, 0 for the zero vector.
fn cos_theta(m: Vec3) -> f32 {
    let len = m.length();
    if len > 0.0 {
        m.z / len
    } else {
        0.0
    }
}

/// Smith G₁(w, m) from Λ(w): 1/(1 + Λ), 0 on a facet seen from its back.
fn g1_from(lambda: f32, w: Vec3, m: Vec3) -> f32 {
    if w.dot(m) * w.z <= 0.0 {
        return 0.0;
    }
    1.0 / (1.0 + lambda)
}

/// What the anisotropic GGX and Beckmann distributions share around their own `d` and
/// `lambda`: the checked and the clamped constructors, the roughness pair, Smith's G₁ and G,
/// and the warp (the isotropic α = 1 sample `$unit::UNIT`, stretched; pdf D(m) cos θ_m).
macro_rules! anisotropic_common {
    ($ty:ident, $unit:ident) => {
        impl $ty {
            /// Roughness `alpha_u` along x and `alpha_v` along y, each in [1e-4, 1e4].
            #[inline]
            pub fn new(alpha_u: f32, alpha_v: f32) -> Result<Self, SamplingError> {
                Ok(Self {
                    a: Alphas::new(alpha_u, alpha_v)?,
                })
            }

            /// Roughness `alpha_u` along x and `alpha_v` along y, each clamped into
            /// [1e-4, 1e4] (NaN to 1e-4), without a check: for a roughness that varies per
            /// shading point.
            #[inline]
            pub fn clamped(alpha_u: f32, alpha_v: f32) -> Self {
                Self {
                    a: Alphas::clamped(alpha_u, alpha_v),
                }
            }

            /// (αᵤ, αᵥ).
            pub fn alphas(&self) -> (f32, f32) {
                (self.a.u, self.a.v)
            }

            /// Smith masking 1/(1 + Λ(w)), 0 when w sees the back of m.
            pub fn g1(&self, w: Vec3, m: Vec3) -> f32 {
                g1_from(self.lambda(w), w, m)
            }

            /// Separable Smith shadowing-masking G₁(wi, m) G₁(wo, m) (Mitsuba 3's `G`).
            pub fn g(&self, wi: Vec3, wo: Vec3, m: Vec3) -> f32 {
                self.g1(wi, m) * self.g1(wo, m)
            }
        }

        impl Warp for $ty {
            type Point = Vec3;

            #[inline]
            fn sample(&self, u: Vec2) -> Vec3 {
                self.a.unstretch($unit::UNIT.sample(u))
            }

            /// D(m) cos θ_m per steradian; 0 for m.z ≤ 0.
            #[inline]
            fn pdf(&self, m: Vec3) -> f32 {
                self.d(m) * cos_theta(m).max(0.0)
            }
        }
    };
}

/// The anisotropic GGX distribution
/// D(m) = 1/(π αᵤ αᵥ cos⁴θ (1 + tan²θ (cos²φ/αᵤ² + sin²φ/αᵥ²))²), sampled with pdf
/// D(m) cos θ_m per steradian (the α = 1 GGX sample, stretched).
///
/// Walter, Marschner, Li, Torrance 2007, "Microfacet Models for Refraction through Rough
/// Surfaces", EGSR; Heitz 2014, JCGT 3(2) (anisotropic form and Λ).
///
/// ```
/// use mcrt::glam::{Vec2, Vec3};
/// use mcrt::sampling::warp::{GgxAnisotropic, Warp};
///
/// let g = GgxAnisotropic::new(0.05, 0.4).unwrap();
/// let (m, pdf) = g.sample_with_pdf(Vec2::new(0.3, 0.6));
/// assert!(m.z > 0.0 && (pdf - g.d(m) * m.z).abs() <= 1e-4 * pdf);
/// assert_eq!(g.g1(Vec3::Z, m), 1.0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GgxAnisotropic {
    a: Alphas,
}

anisotropic_common!(GgxAnisotropic, Ggx);

impl GgxAnisotropic {
    /// D(m) per steradian of m, normalised in projected area; 0 for m.z ≤ 0. `m` need not
    /// be unit length.
    pub fn d(&self, m: Vec3) -> f32 {
        if m.z <= 0.0 || !m.is_finite() {
            return 0.0;
        }
        let (r2, z2, n2) = self.a.scaled_radial(m);
        let q = (r2 + z2) / n2; // x̂²/αᵤ² + ŷ²/αᵥ² + ẑ² of the unit normal
        1.0 / (PI * self.a.u * self.a.v * q * q)
    }

    /// Smith Λ(w) = (√(1 + α_w² tan²θ_w) − 1)/2 with α_w the roughness along w's azimuth.
    pub fn lambda(&self, w: Vec3) -> f32 {
        if w.x == 0.0 && w.y == 0.0 {
            return 0.0;
        }
        let t = self.a.projected_tan2(w);
        if !t.is_finite() {
            return f32::INFINITY;
        }
        t / (2.0 * (1.0 + (1.0 + t).sqrt()))
    }
}

/// The anisotropic Beckmann distribution
/// D(m) = exp(−tan²θ (cos²φ/αᵤ² + sin²φ/αᵥ²))/(π αᵤ αᵥ cos⁴θ), sampled with pdf
/// D(m) cos θ_m per steradian (the α = 1 Beckmann sample, stretched). Its Λ is the rational
/// fit of Walter et al. at the roughness along w's azimuth, as Mitsuba 3's;
/// [`BeckmannAnisotropic::lambda_exact`] is the erf form.
///
/// Walter, Marschner, Li, Torrance 2007, "Microfacet Models for Refraction through Rough
/// Surfaces", EGSR.
///
/// ```
/// use mcrt::glam::Vec2;
/// use mcrt::sampling::warp::{BeckmannAnisotropic, Warp};
///
/// let b = BeckmannAnisotropic::new(0.3, 0.1).unwrap();
/// let (m, pdf) = b.sample_with_pdf(Vec2::new(0.5, 0.5));
/// assert!((pdf - b.d(m) * m.z).abs() <= 1e-4 * pdf);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BeckmannAnisotropic {
    a: Alphas,
}

anisotropic_common!(BeckmannAnisotropic, Beckmann);

impl BeckmannAnisotropic {
    /// D(m) per steradian of m, normalised in projected area; 0 for m.z ≤ 0. `m` need not
    /// be unit length.
    pub fn d(&self, m: Vec3) -> f32 {
        if m.z <= 0.0 || !m.is_finite() {
            return 0.0;
        }
        let (r2, z2, n2) = self.a.scaled_radial(m);
        let e = r2 / z2;
        if e.is_nan() || e > 100.0 {
            return 0.0;
        }
        let cos2 = z2 / n2;
        (-e).exp() / (PI * self.a.u * self.a.v * cos2 * cos2)
    }

    /// Smith Λ(w) by the rational fit of Walter et al. (Mitsuba 3's), at a = 1/(α_w tan θ_w).
    pub fn lambda(&self, w: Vec3) -> f32 {
        if w.x == 0.0 && w.y == 0.0 {
            return 0.0;
        }
        let a = 1.0 / self.a.projected_tan2(w).sqrt();
        if a >= 1.6 {
            return 0.0;
        }
        (1.0 - 1.259 * a + 0.396 * a * a) / (3.535 * a + 2.181 * a * a)
    }

    /// The exact Smith Λ(w) (erf form, in `f64`), as [`Beckmann::lambda_exact`].
    pub fn lambda_exact(&self, w: Vec3) -> f32 {
        if w.x == 0.0 && w.y == 0.0 {
            return 0.0;
        }
        let a = 1.0 / f64::from(self.a.projected_tan2(w)).sqrt();
        beckmann_lambda_exact(a) as f32
    }
}

/// G₁(wi) D(m) max(0, wi·m)/cos θ_i given the precomputed 1/((1 + Λ(wi)) cos θ_i).
fn visible_pdf(d: f32, wi: Vec3, m: Vec3, scale: f32) -> f32 {
    let dot = wi.dot(m);
    if m.z > 0.0 && dot > 0.0 && m.is_finite() {
        d * dot * scale
    } else {
        0.0
    }
}

/// Visible normals of [`GgxAnisotropic`] seen from `wi`: the α = 1 [`GgxVisible`] sample
/// seen from the stretched wi, stretched back. pdf per steradian
/// G₁(wi) max(0, wi·m) D(m)/cos θ_i.
///
/// Dupuy, Benyoub 2023, "Sampling Visible GGX Normals with Spherical Caps", CGF (HPG).
///
/// ```
/// use mcrt::glam::{Vec2, Vec3};
/// use mcrt::sampling::warp::{GgxAnisotropic, GgxAnisotropicVisible, Warp};
///
/// let wi = Vec3::new(0.6, 0.0, 0.8);
/// let v = GgxAnisotropicVisible::new(GgxAnisotropic::new(0.1, 0.5).unwrap(), wi).unwrap();
/// let (m, pdf) = v.sample_with_pdf(Vec2::new(0.2, 0.9));
/// assert!(m.dot(wi) > 0.0 && pdf > 0.0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GgxAnisotropicVisible {
    ggx: GgxAnisotropic,
    wi: Vec3,
    unit: GgxVisible,
    /// 1/((1 + Λ(wi)) cos θ_i).
    scale: f32,
}

impl GgxAnisotropicVisible {
    /// The visible normals of `ggx` seen from `wi` (unit length within 1e-3, renormalised;
    /// wi.z > 0).
    pub fn new(ggx: GgxAnisotropic, wi: Vec3) -> Result<Self, SamplingError> {
        let wi = check_wi(wi)?;
        let unit = GgxVisible::from_distribution(Ggx::UNIT, ggx.a.stretch(wi).normalize())?;
        let scale = 1.0 / ((1.0 + ggx.lambda(wi)) * wi.z);
        Ok(Self {
            ggx,
            wi,
            unit,
            scale,
        })
    }
}

impl Warp for GgxAnisotropicVisible {
    type Point = Vec3;

    #[inline]
    fn sample(&self, u: Vec2) -> Vec3 {
        self.ggx.a.unstretch(self.unit.sample(u))
    }

    /// G₁(wi) max(0, wi·m) D(m)/cos θ_i per steradian; 0 for m.z ≤ 0 or wi·m ≤ 0.
    #[inline]
    fn pdf(&self, m: Vec3) -> f32 {
        visible_pdf(self.ggx.d(m), self.wi, m, self.scale)
    }
}

/// Visible normals of [`BeckmannAnisotropic`] seen from `wi`: the α = 1
/// [`BeckmannVisible`] sample seen from the stretched wi, stretched back. pdf per steradian
/// G₁(wi) max(0, wi·m) D(m)/cos θ_i with the exact (erf) Λ, so that it integrates to 1.
///
/// Jakob 2014, "An Improved Visible Normal Sampling Routine for the Beckmann Distribution",
/// technical note.
///
/// ```
/// use mcrt::glam::{Vec2, Vec3};
/// use mcrt::sampling::warp::{BeckmannAnisotropic, BeckmannAnisotropicVisible, Warp};
///
/// let wi = Vec3::new(0.0, 0.6, 0.8);
/// let b = BeckmannAnisotropic::new(0.4, 0.05).unwrap();
/// let v = BeckmannAnisotropicVisible::new(b, wi).unwrap();
/// let (m, pdf) = v.sample_with_pdf(Vec2::new(0.5, 0.5));
/// assert!(m.dot(wi) > 0.0 && pdf.is_finite() && pdf > 0.0);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct BeckmannAnisotropicVisible {
    beckmann: BeckmannAnisotropic,
    wi: Vec3,
    unit: BeckmannVisible,
    /// 1/((1 + Λ(wi)) cos θ_i), exact Λ.
    scale: f32,
}

impl BeckmannAnisotropicVisible {
    /// The visible normals of `beckmann` seen from `wi` (unit length within 1e-3,
    /// renormalised; wi.z > 0).
    pub fn new(beckmann: BeckmannAnisotropic, wi: Vec3) -> Result<Self, SamplingError> {
        let wi = check_wi(wi)?;
        let unit = BeckmannVisible::new(1.0, beckmann.a.stretch(wi).normalize())?;
        let lambda = f64::from(beckmann.lambda_exact(wi));
        let scale = (1.0 / ((1.0 + lambda) * f64::from(wi.z))) as f32;
        Ok(Self {
            beckmann,
            wi,
            unit,
            scale,
        })
    }
}

impl Warp for BeckmannAnisotropicVisible {
    type Point = Vec3;

    #[inline]
    fn sample(&self, u: Vec2) -> Vec3 {
        self.beckmann.a.unstretch(self.unit.sample(u))
    }

    /// G₁(wi) max(0, wi·m) D(m)/cos θ_i per steradian (exact Λ); 0 for m.z ≤ 0 or wi·m ≤ 0.
    #[inline]
    fn pdf(&self, m: Vec3) -> f32 {
        visible_pdf(self.beckmann.d(m), self.wi, m, self.scale)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::warp::MicrofacetDistribution;

    const NORMALS: [Vec3; 3] = [
        Vec3::Z,
        Vec3::new(0.2, 0.1, 0.97),
        Vec3::new(-0.5, 0.3, 0.8),
    ];

    /// With αᵤ = αᵥ the anisotropic distributions are the isotropic ones.
    #[test]
    fn equal_alphas_are_the_isotropic_distributions() {
        let (ga, ba) = (
            GgxAnisotropic::new(0.3, 0.3).unwrap(),
            BeckmannAnisotropic::new(0.3, 0.3).unwrap(),
        );
        let (g, b) = (Ggx::new(0.3).unwrap(), Beckmann::new(0.3).unwrap());
        let close = |x: f32, y: f32| x.is_finite() && (x - y).abs() <= 1e-5 * y.abs().max(1.0);
        for m in NORMALS {
            let m = m.normalize();
            assert!(close(ga.d(m), g.d(m)), "{m}");
            assert!(close(ba.d(m), b.d(m)), "{m}");
            assert!(close(ga.lambda(m), g.lambda(m)), "{m}");
            assert!(close(ba.lambda(m), b.lambda(m)), "{m}");
            assert!(close(ba.lambda_exact(m), b.lambda_exact(m)), "{m}");
        }
    }

    /// Roughness along x only: a normal tilted along x is far likelier than one tilted as
    /// much along y.
    #[test]
    fn roughness_follows_its_axis() {
        let g = GgxAnisotropic::new(0.5, 0.05).unwrap();
        let (along_u, along_v) = (
            Vec3::new(0.3, 0.0, 1.0).normalize(),
            Vec3::new(0.0, 0.3, 1.0).normalize(),
        );
        assert!(g.d(along_u) > 10.0 * g.d(along_v));
        assert!(g.lambda(along_u) > g.lambda(along_v));
    }

    #[test]
    fn rejects_bad_alphas_and_directions() {
        assert!(GgxAnisotropic::new(0.0, 0.1).is_err());
        assert!(BeckmannAnisotropic::new(0.1, f32::NAN).is_err());
        let g = GgxAnisotropic::new(0.1, 0.2).unwrap();
        assert!(GgxAnisotropicVisible::new(g, -Vec3::Z).is_err());
        let b = BeckmannAnisotropic::new(0.1, 0.2).unwrap();
        assert!(BeckmannAnisotropicVisible::new(b, Vec3::X).is_err());
    }
}
