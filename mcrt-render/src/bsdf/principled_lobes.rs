//! The pieces of the principled BSDF: Schlick's Fresnel, the anisotropic GGX of the main
//! specular lobe, and the GTR1 distribution of the clearcoat. Derivations:
//! `docs/bsdf-models.md`, section "Principled".

use glam::{Vec2, Vec3};
use mcrt::sampling::warp::{Ggx, GgxVisible, Warp};
use std::f32::consts::PI;

/// Schlick's weight `(1 − cos θ)⁵` (Schlick 1994, "An Inexpensive BRDF Model for
/// Physically-based Rendering", Computer Graphics Forum 13(3), eq. 15).
#[inline]
pub(super) fn schlick_weight(cos: f32) -> f32 {
    let m = (1.0 - cos).clamp(0.0, 1.0);
    let m2 = m * m;
    m2 * m2 * m
}

/// Schlick's Fresnel `R0 + (1 − R0)(1 − cos)⁵` for a direction with cosine `cos_i` (signed:
/// negative from inside) at an interface of relative index `eta`; when the far side is the
/// less dense one the cosine is the refracted direction's, so the curve reaches 1 at total
/// internal reflection (Schlick 1994, as above; Burley 2012, "Physically Based Shading at
/// Disney", SIGGRAPH course notes, §5.4).
#[inline]
pub(super) fn schlick(r0: f32, cos_i: f32, eta: f32) -> f32 {
    let eta_it = if cos_i >= 0.0 { eta } else { 1.0 / eta };
    let w = if eta_it > 1.0 {
        schlick_weight(cos_i.abs())
    } else {
        let sin2_t = (1.0 - cos_i * cos_i) * eta_it.recip().powi(2);
        schlick_weight((1.0 - sin2_t).max(0.0).sqrt())
    };
    r0 + (1.0 - r0) * w
}

/// Normal-incidence reflectance `((η − 1)/(η + 1))²` of an interface of index `eta`.
#[inline]
pub(super) fn r0_of_eta(eta: f32) -> f32 {
    let r = (eta - 1.0) / (eta + 1.0);
    r * r
}

/// Smallest roughness α of the main lobe on either axis, as in Mitsuba 3.
const MIN_ALPHA: f32 = 0.001;

/// Anisotropic GGX (Trowbridge–Reitz) with roughnesses `ax` along x and `ay` along y, Smith
/// masking, and visible-normal sampling by stretching to α = 1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct AnisoGgx {
    pub ax: f32,
    pub ay: f32,
}

impl AnisoGgx {
    /// `α = roughness²` stretched by `aspect = √(1 − 0.9 · anisotropic)`: `αx = α/aspect`,
    /// `αy = α · aspect`, both at least 0.001 (Burley 2012, §B.2, eq. 16 and the text under
    /// it).
    pub fn new(roughness: f32, anisotropic: f32) -> Self {
        let aspect = (1.0 - 0.9 * anisotropic).sqrt();
        let a = roughness * roughness;
        Self {
            ax: (a / aspect).max(MIN_ALPHA),
            ay: (a * aspect).max(MIN_ALPHA),
        }
    }

    /// D(m) per steradian of m, 0 for m.z ≤ 0 (Burley 2012, §B.2, eq. 13).
    #[inline]
    pub fn d(&self, m: Vec3) -> f32 {
        if m.z <= 0.0 {
            return 0.0;
        }
        let t = (m.x / self.ax).powi(2) + (m.y / self.ay).powi(2) + m.z * m.z;
        1.0 / (PI * self.ax * self.ay * t * t)
    }

    /// Smith G₁(v, m) = 2 / (1 + √(1 + (αx² vx² + αy² vy²)/vz²)); 0 when v sees m's back
    /// (Heitz 2014, "Understanding the Masking-Shadowing Function in Microfacet-Based
    /// BRDFs", JCGT 3(2), eq. 86 with the anisotropic α of §5.3).
    #[inline]
    pub fn g1(&self, v: Vec3, m: Vec3) -> f32 {
        if v.dot(m) * v.z <= 0.0 {
            return 0.0;
        }
        let t2 = ((v.x * self.ax).powi(2) + (v.y * self.ay).powi(2)) / (v.z * v.z);
        2.0 / (1.0 + (1.0 + t2).sqrt())
    }

    /// Density of visible normals seen from `wo` (wo.z > 0), per steradian of m:
    /// G₁(wo, m) max(0, wo·m) D(m) / cos θ_o (Heitz 2014, as above, eq. 38).
    #[inline]
    pub fn pdf_visible(&self, wo: Vec3, m: Vec3) -> f32 {
        let dot = wo.dot(m);
        if dot <= 0.0 || wo.z <= 0.0 {
            return 0.0;
        }
        self.g1(wo, m) * dot * self.d(m) / wo.z
    }

    /// A normal visible from `wo` (wo.z > 0): `wo` stretched by (αx, αy), a visible normal of
    /// the α = 1 distribution drawn there, stretched back (Heitz 2018, "Sampling the GGX
    /// Distribution of Visible Normals", JCGT 7(4), §2 and listing 1).
    #[inline]
    pub fn sample_visible(&self, wo: Vec3, u: Vec2) -> Option<Vec3> {
        let w = Vec3::new(wo.x * self.ax, wo.y * self.ay, wo.z).try_normalize()?;
        let n = GgxVisible::from_distribution(Ggx::UNIT, w).ok()?.sample(u);
        Vec3::new(n.x * self.ax, n.y * self.ay, n.z.max(0.0)).try_normalize()
    }
}

/// The clearcoat's roughness `α = lerp(0.1, 0.001, gloss)` (Burley 2012, §5.6).
#[inline]
pub(super) fn clearcoat_alpha(gloss: f32) -> f32 {
    0.1 * (1.0 - gloss) + 0.001 * gloss
}

/// GTR1 (Berry) D(h) = (α² − 1) / (π ln(α²) (1 + (α² − 1) cos²θ_h)), per steradian of h,
/// 0 for cos θ_h ≤ 0 (Burley 2012, §B.1, eq. 4), for α in (0, 1).
#[inline]
pub(super) fn gtr1_d(cos_h: f32, alpha: f32) -> f32 {
    if cos_h <= 0.0 {
        return 0.0;
    }
    let a2 = alpha * alpha;
    (a2 - 1.0) / (PI * a2.ln() * (1.0 + (a2 - 1.0) * cos_h * cos_h))
}

/// A normal drawn with density `D(h) cos θ_h` of [`gtr1_d`]:
/// `cos²θ_h = (1 − α^(2(1 − u.x))) / (1 − α²)`, `φ = 2π u.y` (Burley 2012, §B.2, eq. 5).
#[inline]
pub(super) fn gtr1_sample(u: Vec2, alpha: f32) -> Vec3 {
    let a2 = alpha * alpha;
    let cos2 = ((1.0 - a2.powf(1.0 - u.x)) / (1.0 - a2)).clamp(0.0, 1.0);
    let sin = (1.0 - cos2).sqrt();
    let (s, c) = (2.0 * PI * u.y).sin_cos();
    Vec3::new(sin * c, sin * s, cos2.sqrt())
}

/// Isotropic Smith G₁ of GGX with roughness `alpha` for a direction above the surface
/// (Walter, Marschner, Li, Torrance 2007, "Microfacet Models for Refraction through Rough
/// Surfaces", EGSR, eq. 34).
#[inline]
pub(super) fn smith_g1_isotropic(v: Vec3, alpha: f32) -> f32 {
    let cos2 = v.z * v.z;
    let tan2 = (1.0 - cos2).max(0.0) / cos2;
    2.0 / (1.0 + (1.0 + alpha * alpha * tan2).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// D(m) cos θ_m integrates to 1 over the hemisphere, for GTR1 and anisotropic GGX
    /// (midpoint rule in (cos θ, φ)).
    #[test]
    fn distributions_are_normalised() {
        let ggx = AnisoGgx::new(0.6, 0.8);
        let (n_t, n_p) = (4000, 256);
        let (mut s_ggx, mut s_gtr1) = (0.0f64, 0.0f64);
        for i in 0..n_t {
            let c = (i as f32 + 0.5) / n_t as f32;
            let s = (1.0 - c * c).sqrt();
            s_gtr1 += f64::from(gtr1_d(c, 0.05) * c) * 2.0 * std::f64::consts::PI;
            for j in 0..n_p {
                let p = (j as f32 + 0.5) / n_p as f32 * 2.0 * PI;
                let m = Vec3::new(s * p.cos(), s * p.sin(), c);
                s_ggx += f64::from(ggx.d(m) * c) * 2.0 * std::f64::consts::PI / n_p as f64;
            }
        }
        let (s_ggx, s_gtr1) = (s_ggx / n_t as f64, s_gtr1 / n_t as f64);
        assert!(
            s_ggx.is_finite() && (s_ggx - 1.0).abs() < 2e-3,
            "GGX {s_ggx}"
        );
        assert!(
            s_gtr1.is_finite() && (s_gtr1 - 1.0).abs() < 2e-3,
            "GTR1 {s_gtr1}"
        );
    }

    /// Schlick's curve is R0 at normal incidence and 1 at grazing incidence.
    #[test]
    fn schlick_end_points() {
        let r0 = r0_of_eta(1.5);
        assert!((r0 - 0.04).abs() < 1e-6);
        assert!((schlick(r0, 1.0, 1.5) - r0).abs() < 1e-6);
        assert!((schlick(r0, 0.0, 1.5) - 1.0).abs() < 1e-6);
    }
}
