//! Exponential densities: on `[0, ∞)`, and truncated to an interval (either direction of
//! decay).

use super::Warp1D;
use crate::sampling::error::check_param;
use crate::sampling::unit::clamp_unit;
use crate::sampling::SamplingError;

/// Points of `[0, ∞)` with the exponential density `λ e^{−λx}` per unit length.
///
/// Mapping (inversion of `P(x) = 1 − e^{−λx}`): `x = −ln(1 − u)/λ`, written with `ln_1p` so
/// that small `u` keep their digits. Inverse: `u = −expm1(−λx)`. The largest sample, at
/// `u = 1 − 2⁻²⁴`, is `24 ln 2 / λ ≈ 16.6/λ`.
///
/// Citation: the inversion method, as in M. Pharr, W. Jakob, G. Humphreys, 2023, "Physically
/// Based Rendering", 4th ed., §A.4.5 (`SampleExponential`). Derivation: `docs/derivations.md`.
///
/// ```
/// use mcrt::sampling::warp::{Exponential, Warp1D};
///
/// let e = Exponential::new(2.0).unwrap();
/// let x = e.sample(0.5);
/// assert!((x - std::f32::consts::LN_2 / 2.0).abs() < 1e-6);
/// assert!((e.pdf(x) - 1.0).abs() < 1e-6 && (e.invert(x) - 0.5).abs() < 1e-6);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Exponential {
    rate: f32,
}

impl Exponential {
    /// The density with rate `λ = rate`. Errors unless `rate` is finite and large enough that
    /// the largest sample `16.6/λ` fits in `f32` (`rate ≥ ~5·10⁻³⁸`).
    pub fn new(rate: f32) -> Result<Self, SamplingError> {
        let rate = check_param("rate", rate, "finite and >= 5e-38", |r| r >= 5e-38)?;
        Ok(Self { rate })
    }

    /// The rate `λ`.
    #[must_use]
    pub fn rate(&self) -> f32 {
        self.rate
    }
}

impl Warp1D for Exponential {
    #[inline]
    fn sample(&self, u: f32) -> f32 {
        let u = f64::from(clamp_unit(u));
        (-(-u).ln_1p() / f64::from(self.rate)) as f32
    }

    /// `λ e^{−λx}` per unit length for `x ≥ 0`, 0 for `x < 0`.
    #[inline]
    fn pdf(&self, x: f32) -> f32 {
        if x >= 0.0 {
            let l = f64::from(self.rate);
            (l * (-l * f64::from(x)).exp()) as f32
        } else {
            0.0
        }
    }

    #[inline]
    fn invert(&self, x: f32) -> f32 {
        let t = f64::from(x.max(0.0)) * f64::from(self.rate);
        clamp_unit((-(-t).exp_m1()) as f32)
    }
}

/// Points of `[min, max]` with density proportional to `e^{−λ(x − min)}`; pdf
/// `λ e^{−λ(x − min)} / (1 − e^{−λ(max − min)})` per unit length. `λ` may have either sign (a
/// negative rate grows toward `max`) or be 0 (uniform).
///
/// Mapping, with `L = max − min` and for `λ > 0`: `x = min − ln(1 + u·expm1(−λL))/λ`
/// (inversion of `P(x) = expm1(−λ(x − min))/expm1(−λL)`), with `ln_1p` and `expm1` so that
/// neither a tiny `λL` (nearly uniform) nor a huge one (nearly the untruncated exponential)
/// loses digits. A negative rate is the mirror image: `x = max − t` where `t` is drawn with
/// `|λ|`. Inverse: `P(x)`, mirrored likewise. Computed in `f64`.
///
/// Citation: the inversion method, as in M. Pharr, W. Jakob, G. Humphreys, 2023, "Physically
/// Based Rendering", 4th ed., §A.4.5. Derivation: `docs/derivations.md`.
///
/// ```
/// use mcrt::sampling::warp::{TruncatedExponential, Warp1D};
///
/// let e = TruncatedExponential::new(1.0, 0.0, 1.0).unwrap();
/// let x = e.sample(0.7);
/// assert!((0.0..=1.0).contains(&x) && (e.invert(x) - 0.7).abs() < 1e-6);
/// let total = (1.0 - (-1.0f32).exp()); // ∫₀¹ e^{−x} dx
/// assert!((e.pdf(0.0) - 1.0 / total).abs() < 1e-5);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TruncatedExponential {
    min: f32,
    max: f32,
    /// `|λ|` in f64.
    rate: f64,
    /// Whether `λ < 0`: distances are measured from `max`.
    mirrored: bool,
    /// `L = max − min` in f64.
    len: f64,
    /// `expm1(−|λ| L)` (−1 < it ≤ 0; 0 only when `λ = 0`).
    expm1_len: f64,
}

impl TruncatedExponential {
    /// The density `∝ e^{−rate (x − min)}` on `[min, max]`. Errors unless all three are
    /// finite, `min < max`, and the peak density fits in `f32`.
    pub fn new(rate: f32, min: f32, max: f32) -> Result<Self, SamplingError> {
        let rate = check_param("rate", rate, "finite", |_| true)?;
        let min = check_param("min", min, "finite", |_| true)?;
        let max = check_param("max", max, "finite and > min", |m| m > min)?;
        let len = f64::from(max) - f64::from(min);
        let l = f64::from(rate).abs();
        let out = Self {
            min,
            max,
            rate: l,
            mirrored: rate < 0.0,
            len,
            expm1_len: (-l * len).exp_m1(),
        };
        let peak = out.density_at_distance(0.0);
        if !(peak as f32).is_finite() {
            return Err(SamplingError::InvalidParameter {
                name: "rate",
                value: f64::from(rate),
                expected: "a peak density |rate| / (1 - exp(-|rate| (max - min))) that fits in f32",
            });
        }
        Ok(out)
    }

    /// The density at distance `t ∈ [0, L]` from the end where it peaks.
    fn density_at_distance(&self, t: f64) -> f64 {
        if self.expm1_len == 0.0 {
            1.0 / self.len
        } else {
            self.rate * (-self.rate * t).exp() / -self.expm1_len
        }
    }

    /// The distance of `x` from the end where the density peaks.
    fn distance(&self, x: f64) -> f64 {
        if self.mirrored {
            f64::from(self.max) - x
        } else {
            x - f64::from(self.min)
        }
    }
}

impl Warp1D for TruncatedExponential {
    #[inline]
    fn sample(&self, u: f32) -> f32 {
        let u = f64::from(clamp_unit(u));
        // The mirrored density is sampled from its own peak with 1 − u, so x grows with u.
        let v = if self.mirrored { 1.0 - u } else { u };
        let t = if self.expm1_len == 0.0 {
            v * self.len
        } else {
            (-(v * self.expm1_len).ln_1p() / self.rate).min(self.len)
        };
        let x = if self.mirrored {
            f64::from(self.max) - t
        } else {
            f64::from(self.min) + t
        };
        (x as f32).clamp(self.min, self.max)
    }

    /// `|λ| e^{−|λ| t} / (1 − e^{−|λ| L})` per unit length, `t` the distance from the peak
    /// end, on `[min, max]`; 0 outside.
    #[inline]
    fn pdf(&self, x: f32) -> f32 {
        if x >= self.min && x <= self.max {
            self.density_at_distance(self.distance(f64::from(x)).max(0.0)) as f32
        } else {
            0.0
        }
    }

    #[inline]
    fn invert(&self, x: f32) -> f32 {
        let t = self.distance(f64::from(x.clamp(self.min, self.max)));
        let p = if self.expm1_len == 0.0 {
            t / self.len
        } else {
            (-self.rate * t).exp_m1() / self.expm1_len
        };
        clamp_unit((if self.mirrored { 1.0 - p } else { p }) as f32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exponential_extremes() {
        for rate in [5e-38f32, 1e-3, 1.0, 1e30, f32::MAX] {
            let e = Exponential::new(rate).unwrap();
            for u in [0.0, 1e-7, 0.5, 1.0 - 2f32.powi(-24)] {
                let x = e.sample(u);
                let p = e.pdf(x);
                assert!(
                    x.is_finite() && x >= 0.0 && p.is_finite(),
                    "{rate} {u}: {x}"
                );
                let back = e.invert(x);
                assert!(
                    back.is_finite() && (back - u).abs() <= 1e-6 * u.max(1e-1),
                    "{rate} {u}"
                );
            }
        }
        assert!(Exponential::new(0.0).is_err() && Exponential::new(f32::NAN).is_err());
    }

    #[test]
    fn truncated_matches_in_both_directions() {
        for (rate, min, max) in [
            (1.0f32, 0.0f32, 1.0f32),
            (-1.0, 0.0, 1.0),
            (0.0, -2.0, 3.0),
            (1e-30, 0.0, 1.0),
            (1e4, 1.0, 2.0),
            (-1e4, 1.0, 2.0),
        ] {
            let e = TruncatedExponential::new(rate, min, max).unwrap();
            for i in 1..20 {
                let u = i as f32 / 20.0;
                let x = e.sample(u);
                assert!(x.is_finite() && x >= min && x <= max, "{rate}: {x}");
                let pdf = e.pdf(x);
                assert!(pdf.is_finite() && pdf > 0.0);
                // One f32 step of x moves u by pdf · ulp(x).
                let tol = 1e-5 + 2.0 * pdf * x.abs().max(1.0) * f32::EPSILON;
                let back = e.invert(x);
                assert!(
                    back.is_finite() && (back - u).abs() < tol,
                    "{rate} {u} {back}"
                );
            }
        }
        // Mirror symmetry: λ < 0 on [0, 1] is λ > 0 reflected.
        let (pos, neg) = (
            TruncatedExponential::new(3.0, 0.0, 1.0).unwrap(),
            TruncatedExponential::new(-3.0, 0.0, 1.0).unwrap(),
        );
        let (a, b) = (pos.pdf(0.2), neg.pdf(0.8));
        assert!(a.is_finite() && (a - b).abs() < 1e-5);
        assert!(TruncatedExponential::new(1.0, 1.0, 1.0).is_err());
        assert!(TruncatedExponential::new(f32::MAX, 0.0, 1.0).is_ok());
    }
}
