//! The tent (triangle) density on `[−r, r]`.

use super::Warp1D;
use crate::sampling::error::check_param;
use crate::sampling::unit::clamp_unit;
use crate::sampling::SamplingError;

/// Points of `[−r, r]` with the tent density `(r − |x|)/r²` per unit length (peak `1/r` at 0).
///
/// Mapping (each half inverted on its own; the CDF is `(x + r)²/(2r²)` on the left half and
/// `1 − (r − x)²/(2r²)` on the right): `x = r(√(2u) − 1)` for `u < ½`,
/// `x = r(1 − √(2(1 − u)))` otherwise. Inverse: the CDF. The map is continuous and monotone
/// across `u = ½`, so strata of `u` stay strata of `x`.
///
/// Citation: the inversion method for the tent, as in M. Pharr, W. Jakob, G. Humphreys, 2023,
/// "Physically Based Rendering", 4th ed., §A.4.3 (`SampleTent`). Derivation:
/// `docs/derivations.md`.
///
/// ```
/// use mcrt::sampling::warp::{Tent, Warp1D};
///
/// let tent = Tent::new(1.0).unwrap();
/// assert!((tent.sample(0.125) + 0.5).abs() < 1e-6); // (x + 1)²/2 = 1/8
/// assert!((tent.pdf(-0.5) - 0.5).abs() < 1e-6);
/// assert!(Tent::new(0.0).is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tent {
    radius: f32,
}

impl Tent {
    /// The tent of half-width `radius`. Errors unless `radius` is finite and its peak density
    /// `1/radius` is too (`radius > ~2.9·10⁻³⁹`).
    pub fn new(radius: f32) -> Result<Self, SamplingError> {
        let radius = check_param("radius", radius, "finite, > 0, 1/radius finite", |r| {
            r > 0.0 && (1.0 / r).is_finite()
        })?;
        Ok(Self { radius })
    }

    /// The half-width `r`.
    #[must_use]
    pub fn radius(&self) -> f32 {
        self.radius
    }
}

impl Warp1D for Tent {
    #[inline]
    fn sample(&self, u: f32) -> f32 {
        let u = f64::from(clamp_unit(u));
        let r = f64::from(self.radius);
        let x = if u < 0.5 {
            r * ((2.0 * u).sqrt() - 1.0)
        } else {
            r * (1.0 - (2.0 * (1.0 - u)).sqrt())
        };
        x as f32
    }

    /// `(r − |x|)/r²` per unit length on `[−r, r]`, 0 outside.
    #[inline]
    fn pdf(&self, x: f32) -> f32 {
        let r = f64::from(self.radius);
        let d = r - f64::from(x).abs();
        if d >= 0.0 {
            (d / r / r) as f32
        } else {
            0.0
        }
    }

    #[inline]
    fn invert(&self, x: f32) -> f32 {
        let r = f64::from(self.radius);
        let x = f64::from(x).clamp(-r, r);
        let u = if x <= 0.0 {
            let t = (x + r) / r;
            0.5 * t * t
        } else {
            let t = (r - x) / r;
            1.0 - 0.5 * t * t
        };
        clamp_unit(u as f32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_and_edges() {
        for r in [1e-30f32, 0.5, 1.0, 1e30] {
            let t = Tent::new(r).unwrap();
            let lo = t.sample(0.0);
            let hi = t.sample(1.0 - 2f32.powi(-24));
            assert!(lo.is_finite() && hi.is_finite() && lo == -r && hi <= r && hi > 0.99 * r);
            for i in 1..40 {
                let u = i as f32 / 40.0;
                let x = t.sample(u);
                let back = t.invert(x);
                assert!(x.is_finite() && (back - u).abs() < 1e-5, "{r} {u} {back}");
                assert!(t.pdf(x) > 0.0);
            }
        }
        for bad in [0.0, -1.0, f32::NAN, f32::INFINITY, 1e-40] {
            assert!(Tent::new(bad).is_err(), "{bad}");
        }
    }
}
