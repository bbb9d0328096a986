//! Normal (Gaussian) densities: one-dimensional by the inverse CDF, two-dimensional by the
//! Box–Muller map.

use super::{InvertibleWarp, Warp, Warp1D};
use crate::sampling::error::check_param;
use crate::sampling::unit::{clamp_unit, clamp_unit2};
use crate::sampling::warp::polar::{azimuth, azimuth_to_unit};
use crate::sampling::SamplingError;
use glam::Vec2;
use std::f64::consts::{PI, TAU};

pub(crate) mod phi;

use phi::{std_normal_cdf, std_normal_quantile};

/// The smallest `u` the normal quantile is evaluated at: `u = 0` maps to Φ⁻¹ of the smallest
/// positive `f32` (about −14.1σ), so that no sample is infinite.
const U_FLOOR: f64 = 1.401_298_464_324_817e-45;

fn check_mean_sigma(mean: f32, sigma: f32, reach: f32) -> Result<(f32, f32), SamplingError> {
    let mean = check_param("mean", mean, "finite", |_| true)?;
    let sigma = check_param(
        "sigma",
        sigma,
        "finite, > 0, with the peak density and mean ± 15 sigma finite",
        |s| s > 0.0 && (1.0 / s).is_finite() && (mean.abs() + reach * s).is_finite(),
    )?;
    Ok((mean, sigma))
}

/// Points of the real line with the normal density `exp(−(x − μ)²/(2σ²))/(σ√(2π))` per unit
/// length.
///
/// Mapping: `x = μ + σ Φ⁻¹(u)`, the inversion method; Φ⁻¹ is computed in `f64` from a rational
/// first guess refined by Halley steps on an accurate erfc, so it keeps relative accuracy
/// deep in the lower tail. Inverse: `u = Φ((x − μ)/σ)`. Since `u ≤ 1 − 2⁻²⁴`, samples reach
/// `+5.3σ` above the mean; below it they reach `−14.1σ` (`u = 0` is taken as the smallest
/// positive `f32`). For pairs of normals at a lower cost, use [`Normal2D`].
///
/// Citation: the inversion method with M. Abramowitz, I. Stegun, 1964, "Handbook of
/// Mathematical Functions", 26.2.23 as the first guess. Derivation: `docs/derivations.md`.
///
/// ```
/// use mcrt::sampling::warp::{Normal, Warp1D};
///
/// let n = Normal::new(1.0, 2.0).unwrap();
/// assert!((n.sample(0.5) - 1.0).abs() < 1e-6);
/// let x = n.sample(0.975); // Φ⁻¹(0.975) = 1.959964
/// assert!((x - (1.0 + 2.0 * 1.959964)).abs() < 1e-4);
/// assert!((n.invert(x) - 0.975).abs() < 1e-6);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Normal {
    mean: f32,
    sigma: f32,
}

impl Normal {
    /// The normal density with mean `mean` and standard deviation `sigma`. Errors unless both
    /// are finite, `sigma > 0`, `1/sigma` is finite and `|mean| + 15 sigma` fits in `f32`.
    pub fn new(mean: f32, sigma: f32) -> Result<Self, SamplingError> {
        let (mean, sigma) = check_mean_sigma(mean, sigma, 15.0)?;
        Ok(Self { mean, sigma })
    }

    /// The standard normal, mean 0 and standard deviation 1.
    #[must_use]
    pub fn standard() -> Self {
        Self {
            mean: 0.0,
            sigma: 1.0,
        }
    }

    fn standardise(&self, x: f32) -> f64 {
        (f64::from(x) - f64::from(self.mean)) / f64::from(self.sigma)
    }
}

impl Warp1D for Normal {
    #[inline]
    fn sample(&self, u: f32) -> f32 {
        let z = std_normal_quantile(f64::from(clamp_unit(u)).max(U_FLOOR));
        (f64::from(self.mean) + f64::from(self.sigma) * z) as f32
    }

    /// `exp(−z²/2)/(σ√(2π))` per unit length with `z = (x − μ)/σ`; 0 for NaN.
    #[inline]
    fn pdf(&self, x: f32) -> f32 {
        let z = self.standardise(x);
        if z.is_nan() {
            return 0.0;
        }
        ((-0.5 * z * z).exp() / (f64::from(self.sigma) * TAU.sqrt())) as f32
    }

    #[inline]
    fn invert(&self, x: f32) -> f32 {
        clamp_unit(std_normal_cdf(self.standardise(x)) as f32)
    }
}

/// Points of the plane with the isotropic two-dimensional normal density
/// `exp(−|p − μ|²/(2σ²))/(2πσ²)` per unit area, by the Box–Muller map.
///
/// Mapping: radius `r = σ √(−2 ln(1 − u₁))` (inversion of the Rayleigh CDF `1 − e^{−r²/2σ²}`,
/// with `ln_1p` so that `u₁ = 0` gives `r = 0`), angle `φ = 2πu₂`, `p = μ + r (cos φ, sin φ)`.
/// Inverse: `u₁ = −expm1(−|p − μ|²/(2σ²))`, `u₂ = atan2/(2π)` in `[0, 1)`. Jacobian
/// `|∂p/∂u| = 2πσ² e^{r²/2σ²}`. The largest radius (at `u₁ = 1 − 2⁻²⁴`) is `5.77σ`.
///
/// Citation: G. E. P. Box, M. E. Muller, 1958, "A Note on the Generation of Random Normal
/// Deviates", Annals of Mathematical Statistics 29(2). Derivation: `docs/derivations.md`.
///
/// ```
/// use mcrt::glam::Vec2;
/// use mcrt::sampling::warp::{InvertibleWarp, Normal2D, Warp};
///
/// let n = Normal2D::new(Vec2::ZERO, 1.0).unwrap();
/// let (p, pdf) = n.sample_with_pdf(Vec2::new(0.5, 0.25));
/// assert!((p.length_squared() - 2.0 * std::f32::consts::LN_2).abs() < 1e-5); // r² = 2 ln 2
/// assert!((pdf - 0.25 / std::f32::consts::PI).abs() < 1e-6);
/// assert!((n.invert(p) - Vec2::new(0.5, 0.25)).length() < 1e-5);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Normal2D {
    mean: Vec2,
    sigma: f32,
}

impl Normal2D {
    /// The isotropic normal density about `mean` with standard deviation `sigma` per
    /// coordinate. Errors unless both are finite, `sigma > 0`, the peak density `1/(2πσ²)`
    /// is a finite normal `f32` (`2.2·10⁻²⁰ ≲ sigma ≲ 3.6·10¹⁸`) and every coordinate of
    /// `mean` plus 6 sigma fits in `f32`.
    pub fn new(mean: Vec2, sigma: f32) -> Result<Self, SamplingError> {
        let m = mean.abs().max_element();
        let sigma = check_mean_sigma(m, sigma, 6.0)?.1;
        let s = f64::from(sigma);
        let peak = (1.0 / (2.0 * PI * s * s)) as f32;
        if !(peak.is_finite() && peak >= f32::MIN_POSITIVE) {
            return Err(SamplingError::InvalidParameter {
                name: "sigma",
                value: s,
                expected:
                    "a peak density 1/(2 pi sigma^2) that is a normal f32 (2.2e-20 to 3.6e18)",
            });
        }
        if !mean.is_finite() {
            return Err(SamplingError::InvalidParameter {
                name: "mean",
                value: f64::NAN,
                expected: "finite",
            });
        }
        Ok(Self { mean, sigma })
    }

    /// `(p − μ)/σ` in `f64`.
    fn standardise(&self, p: Vec2) -> (f64, f64) {
        let s = f64::from(self.sigma);
        (
            (f64::from(p.x) - f64::from(self.mean.x)) / s,
            (f64::from(p.y) - f64::from(self.mean.y)) / s,
        )
    }
}

impl Warp for Normal2D {
    type Point = Vec2;

    #[inline]
    fn sample(&self, u: Vec2) -> Vec2 {
        let r = (-2.0 * (-f64::from(clamp_unit(u.x))).ln_1p()).sqrt() * f64::from(self.sigma);
        let (c, s) = azimuth(u.y);
        Vec2::new(
            (f64::from(self.mean.x) + r * f64::from(c)) as f32,
            (f64::from(self.mean.y) + r * f64::from(s)) as f32,
        )
    }

    /// `exp(−|p − μ|²/(2σ²))/(2πσ²)` per unit area; 0 for NaN.
    #[inline]
    fn pdf(&self, p: Vec2) -> f32 {
        let (x, y) = self.standardise(p);
        let r2 = x * x + y * y;
        if r2.is_nan() {
            return 0.0;
        }
        let s = f64::from(self.sigma);
        ((-0.5 * r2).exp() / (2.0 * PI * s * s)) as f32
    }
}

impl InvertibleWarp for Normal2D {
    #[inline]
    fn invert(&self, p: Vec2) -> Vec2 {
        let (x, y) = self.standardise(p);
        let u1 = -(-0.5 * (x * x + y * y)).exp_m1();
        clamp_unit2(u1 as f32, azimuth_to_unit(x as f32, y as f32))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normal_edges_are_finite() {
        for (mean, sigma) in [(0.0f32, 1.0f32), (1e30, 1e-30), (-3.0, 1e30), (0.0, 1e-38)] {
            let n = Normal::new(mean, sigma).unwrap();
            for u in [0.0, 2f32.powi(-24), 0.5, 1.0 - 2f32.powi(-24)] {
                let x = n.sample(u);
                let p = n.pdf(x);
                assert!(
                    x.is_finite() && p.is_finite(),
                    "{mean} {sigma} {u}: {x} {p}"
                );
            }
        }
        let n = Normal::standard();
        let lo = n.sample(0.0);
        assert!(lo.is_finite() && (-14.2..-14.0).contains(&lo), "{lo}");
        for bad in [
            (0.0, 0.0),
            (0.0, -1.0),
            (f32::NAN, 1.0),
            (f32::MAX, 1e37),
            (0.0, 1e-40),
        ] {
            assert!(Normal::new(bad.0, bad.1).is_err(), "{bad:?}");
        }
    }

    #[test]
    fn normal_round_trip() {
        let n = Normal::new(-2.0, 0.5).unwrap();
        for i in 1..100 {
            let u = i as f32 / 100.0;
            let back = n.invert(n.sample(u));
            assert!(back.is_finite() && (back - u).abs() < 1e-6, "{u} {back}");
        }
    }

    #[test]
    fn box_muller_edges() {
        let n = Normal2D::new(Vec2::new(1.0, -1.0), 2.0).unwrap();
        let centre = n.sample(Vec2::ZERO);
        assert_eq!(centre, Vec2::new(1.0, -1.0));
        let far = n.sample(Vec2::splat(1.0 - 2f32.powi(-24)));
        let r = (far - Vec2::new(1.0, -1.0)).length();
        assert!(far.is_finite() && (r - 2.0 * 5.7686).abs() < 1e-2, "{r}");
        assert!(n.pdf(far) > 0.0);
        assert!(Normal2D::new(Vec2::new(f32::NAN, 0.0), 1.0).is_err());
        assert!(Normal2D::new(Vec2::ZERO, 0.0).is_err());
        assert!(
            Normal2D::new(Vec2::ZERO, 1e-21).is_err() && Normal2D::new(Vec2::ZERO, 3e-20).is_ok()
        );
    }
}
