//! The logistic density on the real line, and trimmed to an interval.

use super::Warp1D;
use crate::sampling::error::check_param;
use crate::sampling::unit::clamp_unit;
use crate::sampling::SamplingError;

/// The smallest `u` the logistic quantile is evaluated at (the smallest positive `f32`), so
/// that `u = 0` gives a finite sample (`μ − 103 s`).
const U_FLOOR: f64 = 1.401_298_464_324_817e-45;

/// The logistic density of `z = (x − μ)/s`, `e^{−|z|}/(1 + e^{−|z|})²` (per unit `z`).
#[inline]
fn std_logistic_pdf(z: f64) -> f64 {
    let t = (-z.abs()).exp();
    t / ((1.0 + t) * (1.0 + t))
}

/// The standard logistic CDF `1/(1 + e^{−z})`, relative-accurate for `z ≤ 0`.
#[inline]
fn std_logistic_cdf(z: f64) -> f64 {
    if z <= 0.0 {
        let e = z.exp();
        e / (1.0 + e)
    } else {
        1.0 / (1.0 + (-z).exp())
    }
}

/// `F(b) − F(a)` of the standard logistic for `a ≤ 0`, `a < b`, without cancellation:
/// `(1 − e^{a−b}) / ((1 + e^a)(1 + e^{−b}))`.
fn std_logistic_mass(a: f64, b: f64) -> f64 {
    -(a - b).exp_m1() / ((1.0 + a.exp()) * (1.0 + (-b).exp()))
}

/// The standard logistic quantile `ln(p/(1 − p))`, with `ln_1p` for the `1 − p`.
#[inline]
fn std_logistic_quantile(p: f64) -> f64 {
    p.ln() - (-p).ln_1p()
}

fn check_location_scale(mean: f32, scale: f32) -> Result<(f32, f32), SamplingError> {
    let mean = check_param("mean", mean, "finite", |_| true)?;
    let scale = check_param(
        "scale",
        scale,
        "finite, > 0, with the peak density 1/(4 scale) and mean ± 104 scale finite",
        |s| s > 0.0 && (0.25 / s).is_finite() && (mean.abs() + 104.0 * s).is_finite(),
    )?;
    Ok((mean, scale))
}

/// Points of the real line with the logistic density
/// `e^{−z}/(s (1 + e^{−z})²)`, `z = (x − μ)/s`, per unit length.
///
/// Mapping (inversion of the CDF `1/(1 + e^{−z})`): `x = μ + s ln(u/(1 − u))`, with `ln_1p`
/// for `ln(1 − u)`. Inverse: `u = 1/(1 + e^{−z})`. `u = 0` is taken as the smallest positive
/// `f32`, so samples reach `μ − 103s` below and `μ + 16.6s` above.
///
/// Citation: the inversion method, as in M. Pharr, W. Jakob, G. Humphreys, 2023, "Physically
/// Based Rendering", 4th ed., §A.4.6 (`SampleLogistic`). Derivation: `docs/derivations.md`.
///
/// ```
/// use mcrt::sampling::warp::{Logistic, Warp1D};
///
/// let l = Logistic::new(0.0, 2.0).unwrap();
/// let x = l.sample(0.75);
/// assert!((x - 2.0 * 3.0f32.ln()).abs() < 1e-5);
/// assert!((l.pdf(0.0) - 0.125).abs() < 1e-7 && (l.invert(x) - 0.75).abs() < 1e-6);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Logistic {
    mean: f32,
    scale: f32,
}

impl Logistic {
    /// The logistic density with location `mean` and scale `scale`. Errors unless both are
    /// finite, `scale > 0`, the peak `1/(4 scale)` is finite and `|mean| + 104 scale` fits in
    /// `f32`.
    pub fn new(mean: f32, scale: f32) -> Result<Self, SamplingError> {
        let (mean, scale) = check_location_scale(mean, scale)?;
        Ok(Self { mean, scale })
    }

    fn standardise(&self, x: f32) -> f64 {
        (f64::from(x) - f64::from(self.mean)) / f64::from(self.scale)
    }
}

impl Warp1D for Logistic {
    #[inline]
    fn sample(&self, u: f32) -> f32 {
        let z = std_logistic_quantile(f64::from(clamp_unit(u)).max(U_FLOOR));
        (f64::from(self.mean) + f64::from(self.scale) * z) as f32
    }

    /// `e^{−|z|}/(s (1 + e^{−|z|})²)` per unit length; 0 for NaN.
    #[inline]
    fn pdf(&self, x: f32) -> f32 {
        let z = self.standardise(x);
        if z.is_nan() {
            return 0.0;
        }
        (std_logistic_pdf(z) / f64::from(self.scale)) as f32
    }

    #[inline]
    fn invert(&self, x: f32) -> f32 {
        let z = self.standardise(x);
        clamp_unit(if z.is_nan() {
            0.0
        } else {
            std_logistic_cdf(z) as f32
        })
    }
}

/// Points of `[min, max]` with the logistic density restricted to it and renormalised:
/// `e^{−z}/(s (1 + e^{−z})² M)`, `z = (x − μ)/s`, `M = F(z_max) − F(z_min)` the logistic mass of
/// the interval.
///
/// Mapping: `x = μ + s F⁻¹(F(z_min) + u M)`, in `f64`, solved as an offset from `z_min`
/// (`logit(p + δ) − logit(p) = ln(1 + δ/p) − ln(1 − δ/(1 − p))`, so that an interval narrower
/// than the CDF's resolution is still sampled by its shape). `M` is formed without cancellation
/// (`(1 − e^{a−b}) / ((1 + e^a)(1 + e^{−b}))` for `a ≤ 0`), and an interval entirely above
/// the mean is handled as the mirror image of one below it (where the CDF keeps relative
/// accuracy), so an interval far in either tail is sampled accurately. Inverse: the mass of
/// `[z_min, z]` over `M`.
///
/// Citation: M. Pharr, W. Jakob, G. Humphreys, 2023, "Physically Based Rendering", 4th ed.,
/// §A.4.6 (`SampleTrimmedLogistic`). Derivation: `docs/derivations.md`.
///
/// ```
/// use mcrt::sampling::warp::{TrimmedLogistic, Warp1D};
///
/// let t = TrimmedLogistic::new(0.0, 1.0, -1.0, 1.0).unwrap();
/// assert!(t.sample(0.5).abs() < 1e-6);
/// let x = t.sample(0.9);
/// assert!(x > 0.0 && x <= 1.0 && (t.invert(x) - 0.9).abs() < 1e-6);
/// assert_eq!(t.pdf(1.5), 0.0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrimmedLogistic {
    mean: f32,
    scale: f32,
    min: f32,
    max: f32,
    /// The working interval in standardised units, `lo ≤ 0`, mirrored when `mirrored`.
    lo: f64,
    hi: f64,
    mirrored: bool,
    /// The logistic mass of the working interval.
    mass: f64,
    /// `F(lo)` and `1 − F(lo)`, or in the mirrored case `F(hi)` and `1 − F(hi)`: the CDF at
    /// the end the samples start from, and its complement, each without cancellation.
    f_start: f64,
    g_start: f64,
}

impl TrimmedLogistic {
    /// The logistic density with location `mean` and scale `scale` restricted to
    /// `[min, max]`. Errors as [`Logistic::new`], unless `min < max` are finite, or when the
    /// interval's mass underflows `f64` (an interval more than ~700 scales from the mean) or
    /// the renormalised peak density overflows `f32`.
    pub fn new(mean: f32, scale: f32, min: f32, max: f32) -> Result<Self, SamplingError> {
        let mean = check_param("mean", mean, "finite", |_| true)?;
        let scale = check_param("scale", scale, "finite, > 0, 1/scale finite", |s| {
            s > 0.0 && (1.0 / s).is_finite()
        })?;
        let min = check_param("min", min, "finite", |_| true)?;
        let max = check_param("max", max, "finite and > min", |m| m > min)?;
        let s = f64::from(scale);
        let za = (f64::from(min) - f64::from(mean)) / s;
        let zb = (f64::from(max) - f64::from(mean)) / s;
        let mirrored = za > 0.0;
        let (lo, hi) = if mirrored { (-zb, -za) } else { (za, zb) };
        let mass = std_logistic_mass(lo, hi);
        let start = if mirrored { hi } else { lo };
        let out = Self {
            mean,
            scale,
            min,
            max,
            lo,
            hi,
            mirrored,
            mass,
            f_start: std_logistic_cdf(start),
            g_start: std_logistic_cdf(-start),
        };
        // The density peaks at the point of the working interval nearest the mean.
        let peak = std_logistic_pdf(hi.min(0.0)) / (s * mass);
        if !(mass > 0.0 && (peak as f32).is_finite()) {
            return Err(SamplingError::Degenerate {
                what: "the interval's logistic mass underflows or its density overflows",
            });
        }
        Ok(out)
    }
}

impl Warp1D for TrimmedLogistic {
    #[inline]
    fn sample(&self, u: f32) -> f32 {
        // F(w) = F(start) ± δ with δ = u M, solved as an offset from the start so that a
        // narrow interval keeps its digits: logit(p + δ) − logit(p) =
        // ln(1 + δ/p) − ln(1 − δ/(1 − p)).
        let d = f64::from(clamp_unit(u)) * self.mass;
        let w = if self.mirrored {
            // w = −z runs down as u runs up: start from the top of the working interval.
            self.hi + (-d / self.f_start).ln_1p() - (d / self.g_start).ln_1p()
        } else {
            let offset = self.lo + (d / self.f_start).ln_1p() - (-d / self.g_start).ln_1p();
            if offset.is_finite() {
                offset
            } else {
                // F(lo) underflowed (lo far below the mean): invert F directly.
                std_logistic_quantile(self.f_start + d)
            }
        };
        let w = if w.is_nan() {
            self.lo
        } else {
            w.clamp(self.lo, self.hi)
        };
        let z = if self.mirrored { -w } else { w };
        let x = f64::from(self.mean) + f64::from(self.scale) * z;
        (x as f32).clamp(self.min, self.max)
    }

    /// The logistic density over `M` per unit length on `[min, max]`, 0 outside.
    #[inline]
    fn pdf(&self, x: f32) -> f32 {
        if !(x >= self.min && x <= self.max) {
            return 0.0;
        }
        let z = (f64::from(x) - f64::from(self.mean)) / f64::from(self.scale);
        (std_logistic_pdf(z) / (f64::from(self.scale) * self.mass)) as f32
    }

    #[inline]
    fn invert(&self, x: f32) -> f32 {
        let x = x.clamp(self.min, self.max);
        let z = (f64::from(x) - f64::from(self.mean)) / f64::from(self.scale);
        let u = if self.mirrored {
            let w = (-z).clamp(self.lo, self.hi);
            if w < self.hi {
                std_logistic_mass(w, self.hi) / self.mass
            } else {
                0.0
            }
        } else {
            let w = z.clamp(self.lo, self.hi);
            if w > self.lo {
                std_logistic_mass(self.lo, w) / self.mass
            } else {
                0.0
            }
        };
        clamp_unit(u as f32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn logistic_edges() {
        let l = Logistic::new(0.0, 1.0).unwrap();
        let lo = l.sample(0.0);
        let hi = l.sample(1.0 - 2f32.powi(-24));
        assert!(lo.is_finite() && (-104.0..-102.0).contains(&lo), "{lo}");
        assert!(hi.is_finite() && (16.0..17.0).contains(&hi), "{hi}");
        for i in 1..50 {
            let u = i as f32 / 50.0;
            let back = l.invert(l.sample(u));
            assert!(back.is_finite() && (back - u).abs() < 1e-6);
        }
    }

    #[test]
    fn trimmed_in_the_tails() {
        for (min, max) in [
            (-1.0f32, 1.0f32),
            (30.0, 31.0),
            (-31.0, -30.0),
            (-500.0, 600.0),
            (0.0, 1e-3),
        ] {
            let t = TrimmedLogistic::new(0.0, 1.0, min, max).unwrap();
            let mut prev = f32::NEG_INFINITY;
            for i in 0..=40 {
                let u = (i as f32 / 40.0).min(1.0 - 2f32.powi(-24));
                let x = t.sample(u);
                assert!(
                    x.is_finite() && x >= min && x <= max && x >= prev,
                    "{min} {max} {u}: {x}"
                );
                prev = x;
                if i > 0 && i < 40 {
                    let back = t.invert(x);
                    assert!(
                        back.is_finite() && (back - u).abs() < 1e-4,
                        "{min} {u} {back}"
                    );
                    assert!(t.pdf(x) > 0.0);
                }
            }
        }
        assert!(TrimmedLogistic::new(0.0, 1.0, 800.0, 900.0).is_err());
        assert!(TrimmedLogistic::new(0.0, 1.0, 1.0, 1.0).is_err());
    }
}
