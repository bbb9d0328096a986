//! The smoothstep density on an interval.

use super::Warp1D;
use crate::sampling::error::check_param;
use crate::sampling::unit::clamp_unit;
use crate::sampling::SamplingError;

/// The CDF of the smoothstep density in `t ∈ [0, 1]`: `t³ (2 − t)`.
#[inline]
fn cdf(t: f64) -> f64 {
    t * t * t * (2.0 - t)
}

/// Solves `t³ (2 − t) = u` for `t ∈ [0, 1]` by Newton's method inside a shrinking bracket
/// (bisection when a step would leave it). The first guess is the root of the dominant term at
/// either end (`2t³ = u` near 0, `2(1 − t) = 1 − u` near 1), so a few steps suffice.
fn invert_cdf(u: f64) -> f64 {
    if u <= 0.0 {
        return 0.0;
    }
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    let mut t = if u < 0.5 {
        (0.5 * u).cbrt()
    } else {
        1.0 - 0.5 * (1.0 - u)
    };
    for _ in 0..60 {
        let f = cdf(t) - u;
        if f == 0.0 {
            break;
        }
        if f < 0.0 {
            lo = t;
        } else {
            hi = t;
        }
        let slope = 2.0 * t * t * (3.0 - 2.0 * t);
        let newton = t - f / slope;
        let next = if slope > 0.0 && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        let step = (next - t).abs();
        t = next;
        if step <= 1e-15 * t || hi - lo <= 1e-15 * t {
            break;
        }
    }
    t.clamp(0.0, 1.0)
}

/// Points of `[min, max]` with density proportional to the smoothstep `3t² − 2t³`,
/// `t = (x − min)/(max − min)`: pdf `2 (3t² − 2t³)/(max − min)` per unit length.
///
/// Mapping: `t` is the root in `[0, 1]` of the quartic CDF `t³ (2 − t) = u`, found by
/// safeguarded Newton iteration in `f64` (relative accuracy 10⁻¹⁵, also near `t = 0` where the
/// CDF is cubic); `x = min + t (max − min)`. Inverse: `u = t³ (2 − t)`.
///
/// Citation: M. Pharr, W. Jakob, G. Humphreys, 2023, "Physically Based Rendering", 4th ed.,
/// §A.4.7 (`SampleSmoothStep`). Derivation: `docs/derivations.md`.
///
/// ```
/// use mcrt::sampling::warp::{Smoothstep, Warp1D};
///
/// let s = Smoothstep::new(0.0, 1.0).unwrap();
/// let x = s.sample(0.5);
/// assert!((x.powi(3) * (2.0 - x) - 0.5).abs() < 1e-6);
/// assert!((s.pdf(1.0) - 2.0).abs() < 1e-6 && s.pdf(0.0) == 0.0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Smoothstep {
    min: f32,
    max: f32,
}

impl Smoothstep {
    /// The smoothstep density on `[min, max]`. Errors unless both are finite, `min < max`,
    /// and the peak density `2/(max − min)` fits in `f32`.
    pub fn new(min: f32, max: f32) -> Result<Self, SamplingError> {
        let min = check_param("min", min, "finite", |_| true)?;
        let max = check_param("max", max, "finite, > min, 2/(max - min) finite", |m| {
            m > min && ((2.0 / (f64::from(m) - f64::from(min))) as f32).is_finite()
        })?;
        Ok(Self { min, max })
    }

    fn len(&self) -> f64 {
        f64::from(self.max) - f64::from(self.min)
    }
}

impl Warp1D for Smoothstep {
    #[inline]
    fn sample(&self, u: f32) -> f32 {
        let t = invert_cdf(f64::from(clamp_unit(u)));
        ((f64::from(self.min) + t * self.len()) as f32).clamp(self.min, self.max)
    }

    /// `2 (3t² − 2t³)/(max − min)` per unit length on `[min, max]`, 0 outside.
    #[inline]
    fn pdf(&self, x: f32) -> f32 {
        if !(x >= self.min && x <= self.max) {
            return 0.0;
        }
        let t = ((f64::from(x) - f64::from(self.min)) / self.len()).clamp(0.0, 1.0);
        (2.0 * t * t * (3.0 - 2.0 * t) / self.len()) as f32
    }

    #[inline]
    fn invert(&self, x: f32) -> f32 {
        let t = ((f64::from(x) - f64::from(self.min)) / self.len()).clamp(0.0, 1.0);
        clamp_unit(if t.is_nan() { 0.0 } else { cdf(t) as f32 })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverts_the_quartic_everywhere() {
        for u in [
            1e-300,
            1e-30,
            1e-8,
            0.01,
            0.3,
            0.5,
            0.9,
            0.999_999,
            1.0 - 2f64.powi(-24),
        ] {
            let t = invert_cdf(u);
            let back = cdf(t);
            assert!(
                t.is_finite() && ((back - u) / u).abs() < 1e-13,
                "{u}: {t} {back}"
            );
        }
        assert_eq!(invert_cdf(0.0), 0.0);
    }

    #[test]
    fn round_trip_and_parameters() {
        let s = Smoothstep::new(-1.0, 3.0).unwrap();
        for i in 1..50 {
            let u = i as f32 / 50.0;
            let x = s.sample(u);
            assert!(x.is_finite() && s.pdf(x) > 0.0 && (s.invert(x) - u).abs() < 1e-6);
        }
        assert!(Smoothstep::new(1.0, 1.0).is_err() && Smoothstep::new(0.0, 1e-45).is_err());
        assert!(Smoothstep::new(-f32::MAX, f32::MAX).is_ok());
    }
}
