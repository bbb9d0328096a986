//! The Henyey–Greenstein phase function as a warp onto the sphere.

use super::{InvertibleWarp, Warp};
use crate::sampling::error::check_param;
use crate::sampling::unit::{clamp_unit, clamp_unit2};
use crate::sampling::warp::polar::{azimuth_to_unit, direction, sin2_theta};
use crate::sampling::SamplingError;
use glam::{Vec2, Vec3};
use std::f64::consts::PI;

/// `(1 − cos θ, 1 + cos θ)` of a unit direction, each without cancellation.
#[inline]
pub(crate) fn one_minus_and_plus_cos(w: Vec3) -> (f64, f64) {
    let s2 = f64::from(sin2_theta(w));
    let z = f64::from(w.z);
    if z > 0.0 {
        (s2 / (1.0 + z), 1.0 + z)
    } else {
        (1.0 - z, s2 / (1.0 - z))
    }
}

/// Directions on the sphere with the Henyey–Greenstein density about +z,
/// `(1 − g²) / (4π (1 + g² − 2g cos θ)^{3/2})` per steradian; `g > 0` concentrates them about
/// +z (forward scattering along +z), `g < 0` about −z, `g = 0` is uniform.
///
/// Mapping (inversion of the CDF in `cos θ`, rewritten so that `g` never divides and nothing
/// cancels): with `d = (1 + g)(1 − u₁) + (1 − g) u₁`,
/// `1 − cos θ = u₁ (1 − g)² (1 + g + d)/d²` and `1 + cos θ = (1 − u₁)(1 + g)² (1 − g + d)/d²`,
/// `sin θ = √((1 − cos θ)(1 + cos θ))`, `φ = 2πu₂`. The formulas hold at `g = 0` (uniform) and
/// keep the lobe's shape as `|g| → 1`, where `cos θ` itself rounds to ±1 in `f32`.
/// Inverse: `u₁ = (1 + g)(1 − cos θ)/(D (D + 1 − g))` with
/// `D = √(1 + g² − 2g cos θ)`, `u₂ = φ/(2π)`.
///
/// Citation: L. G. Henyey, J. L. Greenstein, 1941, "Diffuse radiation in the Galaxy",
/// Astrophysical Journal 93. Derivation: `docs/derivations.md`.
///
/// To use it as a phase function `p(ω_o, ω_i)` with `cos θ = ω_o · ω_i`, rotate the sample
/// into a frame about `ω_o` ([`Frame`](crate::sampling::Frame)) (pbrt's convention, where `g > 0` scatters forward, takes the frame
/// about `−ω_o`).
///
/// ```
/// use mcrt::glam::Vec2;
/// use mcrt::sampling::warp::{HenyeyGreenstein, InvertibleWarp, Warp};
///
/// let hg = HenyeyGreenstein::new(0.9).unwrap();
/// let (w, pdf) = hg.sample_with_pdf(Vec2::new(0.5, 0.3));
/// assert!(w.z > 0.9 && (pdf - hg.pdf(w)).abs() < 1e-3 * pdf);
/// assert!((hg.invert(w) - Vec2::new(0.5, 0.3)).length() < 1e-5);
/// assert!(HenyeyGreenstein::new(1.0).is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HenyeyGreenstein {
    g: f64,
}

impl HenyeyGreenstein {
    /// The density with asymmetry `g ∈ (−1, 1)` (the mean cosine). Errors outside that range.
    pub fn new(g: f32) -> Result<Self, SamplingError> {
        let g = check_param("g", g, "finite, in (-1, 1)", |g| g > -1.0 && g < 1.0)?;
        Ok(Self { g: f64::from(g) })
    }

    /// The asymmetry `g`.
    #[must_use]
    pub fn g(&self) -> f32 {
        self.g as f32
    }

    /// `1 + g² − 2g cos θ` from `(1 − cos θ, 1 + cos θ)`, as a sum of non-negative terms.
    fn denominator(&self, omc: f64, opc: f64) -> f64 {
        let g = self.g;
        if g >= 0.0 {
            (1.0 - g) * (1.0 - g) + 2.0 * g * omc
        } else {
            (1.0 + g) * (1.0 + g) - 2.0 * g * opc
        }
    }
}

impl Warp for HenyeyGreenstein {
    type Point = Vec3;

    #[inline]
    fn sample(&self, u: Vec2) -> Vec3 {
        let g = self.g;
        let u1 = f64::from(clamp_unit(u.x));
        let d = (1.0 + g) * (1.0 - u1) + (1.0 - g) * u1;
        let omc = u1 * (1.0 - g) * (1.0 - g) * (1.0 + g + d) / (d * d);
        let opc = (1.0 - u1) * (1.0 + g) * (1.0 + g) * (1.0 - g + d) / (d * d);
        let cos = if omc < opc { 1.0 - omc } else { opc - 1.0 };
        let sin = (omc * opc).max(0.0).sqrt();
        direction(sin as f32, cos as f32, u.y)
    }

    /// `(1 − g²)/(4π (1 + g² − 2g cos θ)^{3/2})` per steradian for unit `w`; 0 for NaN.
    #[inline]
    fn pdf(&self, w: Vec3) -> f32 {
        if !w.is_finite() {
            return 0.0;
        }
        let (omc, opc) = one_minus_and_plus_cos(w);
        let den = self.denominator(omc, opc);
        ((1.0 - self.g * self.g) / (4.0 * PI * den * den.sqrt())) as f32
    }
}

impl InvertibleWarp for HenyeyGreenstein {
    #[inline]
    fn invert(&self, w: Vec3) -> Vec2 {
        let (omc, opc) = one_minus_and_plus_cos(w);
        let big_d = self.denominator(omc, opc).sqrt();
        let u1 = (1.0 + self.g) * omc / (big_d * (big_d + 1.0 - self.g));
        clamp_unit2(
            if u1.is_nan() { 0.0 } else { u1 as f32 },
            azimuth_to_unit(w.x, w.y),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_the_textbook_form_and_round_trips() {
        for g in [-0.999_999f32, -0.9, -0.3, 0.0, 1e-8, 0.5, 0.99, 0.999_999] {
            let hg = HenyeyGreenstein::new(g).unwrap();
            for i in 1..20 {
                for j in [1, 7] {
                    let u = Vec2::new(i as f32 / 20.0, j as f32 / 10.0);
                    let w = hg.sample(u);
                    assert!(w.is_finite() && (w.length() - 1.0).abs() < 1e-6, "{g} {u}");
                    let g64 = f64::from(g);
                    let c = f64::from(w.z);
                    let textbook = (1.0 - g64 * g64)
                        / (4.0 * PI * (1.0 + g64 * g64 - 2.0 * g64 * c).powf(1.5));
                    let pdf = f64::from(hg.pdf(w));
                    if g.abs() < 0.99 {
                        assert!(pdf.is_finite() && ((pdf - textbook) / textbook).abs() < 1e-4);
                    }
                    let back = hg.invert(w);
                    assert!(
                        back.is_finite() && (back - u).abs().max_element() < 1e-4,
                        "{g} {u} {back}"
                    );
                }
            }
        }
    }
}
