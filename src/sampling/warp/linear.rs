//! Linear densities: on `[0, 1]` between two end values, and bilinear on `[0, 1]²` between
//! four corner values.

use super::{InvertibleWarp, Warp, Warp1D};
use crate::sampling::unit::{clamp_unit, clamp_unit2};
use crate::sampling::SamplingError;
use glam::Vec2;

/// `t ∈ [0, 1]` with density `(1 − t) a + t b` for end values normalised to `a + b = 2`.
///
/// The root of the CDF `a t + (b − a) t²/2 = u`, rationalised so that nothing cancels:
/// `t = 2u / (a + √((1 − u) a² + u b²))`. The denominator is 0 only for `a = 0, u = 0`.
#[inline]
pub(crate) fn sample_linear_normalised(u: f64, a: f64, b: f64) -> f64 {
    let den = a + ((1.0 - u) * a * a + u * b * b).sqrt();
    if den > 0.0 {
        (2.0 * u / den).clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// The CDF of [`sample_linear_normalised`]: `t (a (2 − t) + b t) / 2`.
#[inline]
pub(crate) fn linear_cdf_normalised(t: f64, a: f64, b: f64) -> f64 {
    0.5 * t * (a * (2.0 - t) + b * t)
}

/// End values `(a, b) ≥ 0` scaled to `a + b = 2`; a pair summing to 0 (or not finite)
/// becomes the uniform `(1, 1)`.
#[inline]
pub(crate) fn normalise_ends(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    if s > 0.0 && s.is_finite() {
        (2.0 * a / s, 2.0 * b / s)
    } else {
        (1.0, 1.0)
    }
}

fn check_weight(name: &'static str, v: f32) -> Result<f64, SamplingError> {
    if v.is_finite() && v >= 0.0 {
        Ok(f64::from(v))
    } else {
        Err(SamplingError::InvalidParameter {
            name,
            value: f64::from(v),
            expected: "finite and >= 0",
        })
    }
}

/// Points of `[0, 1]` with density proportional to the linear function from `a` at 0 to `b`
/// at 1; pdf `((1 − x) a + x b) · 2/(a + b)` per unit length.
///
/// Mapping (inversion of the quadratic CDF, in the rationalised form that stays accurate
/// when `a` or `b` is 0 and when `a = b`): `x = 2u / (a' + √((1 − u) a'² + u b'²))` with
/// `a' = 2a/(a + b)`, `b' = 2b/(a + b)`. Inverse: `u = x (a' (2 − x) + b' x)/2`.
///
/// Citation: the inversion method for a linear density, as in M. Pharr, W. Jakob,
/// G. Humphreys, 2023, "Physically Based Rendering", 4th ed., §A.4.2 (`SampleLinear`).
/// Derivation: `docs/derivations.md`.
///
/// ```
/// use mcrt::sampling::warp::{Linear, Warp1D};
///
/// let ramp = Linear::new(0.0, 1.0).unwrap(); // density 2x
/// let x = ramp.sample(0.25);
/// assert!((x - 0.5).abs() < 1e-6 && (ramp.pdf(x) - 1.0).abs() < 1e-6);
/// assert!((ramp.invert(x) - 0.25).abs() < 1e-6);
/// assert!(Linear::new(0.0, 0.0).is_err() && Linear::new(-1.0, 1.0).is_err());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Linear {
    a: f64,
    b: f64,
}

impl Linear {
    /// The density from `a` at 0 to `b` at 1 (scaled to integrate to 1). Errors unless both
    /// are finite and `≥ 0` and not both 0.
    pub fn new(a: f32, b: f32) -> Result<Self, SamplingError> {
        let (a, b) = (check_weight("a", a)?, check_weight("b", b)?);
        if a + b <= 0.0 {
            return Err(SamplingError::Degenerate {
                what: "both end values are 0",
            });
        }
        let (a, b) = normalise_ends(a, b);
        Ok(Self { a, b })
    }
}

impl Warp1D for Linear {
    #[inline]
    fn sample(&self, u: f32) -> f32 {
        sample_linear_normalised(f64::from(clamp_unit(u)), self.a, self.b) as f32
    }

    /// `(1 − x) a' + x b'` per unit length on `[0, 1]`, 0 outside.
    #[inline]
    fn pdf(&self, x: f32) -> f32 {
        if (0.0..=1.0).contains(&x) {
            let x = f64::from(x);
            ((1.0 - x) * self.a + x * self.b) as f32
        } else {
            0.0
        }
    }

    #[inline]
    fn invert(&self, x: f32) -> f32 {
        let x = f64::from(x.clamp(0.0, 1.0));
        clamp_unit(linear_cdf_normalised(x, self.a, self.b) as f32)
    }
}

/// Points of `[0, 1]²` with density proportional to the bilinear interpolation of four corner
/// values; pdf `bilerp(x, y) · 4/Σv` per unit area.
///
/// Mapping (marginal and conditional, both linear): `y` from the linear density between the
/// row sums `v₀₀ + v₁₀` and `v₀₁ + v₁₁` with `u₂`, then `x` from the linear density between
/// `lerp(y, v₀₀, v₀₁)` and `lerp(y, v₁₀, v₁₁)` with `u₁` (each by [`Linear`]'s map). Inverse:
/// the two linear CDFs in the other order. Corners are given as `[v₀₀, v₁₀, v₀₁, v₁₁]`, the
/// values at `(0, 0)`, `(1, 0)`, `(0, 1)`, `(1, 1)`.
///
/// Citation: M. Pharr, W. Jakob, G. Humphreys, 2023, "Physically Based Rendering", 4th ed.,
/// §A.5.3 (`SampleBilinear`). Derivation: `docs/derivations.md`.
///
/// ```
/// use mcrt::glam::Vec2;
/// use mcrt::sampling::warp::{Bilinear, InvertibleWarp, Warp};
///
/// let b = Bilinear::new([0.0, 1.0, 1.0, 2.0]).unwrap(); // density (x + y)
/// let (p, pdf) = b.sample_with_pdf(Vec2::new(0.3, 0.8));
/// assert!((pdf - (p.x + p.y)).abs() < 1e-5);
/// assert!((b.invert(p) - Vec2::new(0.3, 0.8)).length() < 1e-5);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bilinear {
    /// Corner values scaled to mean 1 (so the density is their bilinear interpolation).
    v: [f64; 4],
}

impl Bilinear {
    /// The density through the corner values `[v₀₀, v₁₀, v₀₁, v₁₁]`. Errors unless all are
    /// finite and `≥ 0` and not all 0.
    pub fn new(corners: [f32; 4]) -> Result<Self, SamplingError> {
        let names = ["v00", "v10", "v01", "v11"];
        let mut v = [0.0; 4];
        for i in 0..4 {
            v[i] = check_weight(names[i], corners[i])?;
        }
        let sum: f64 = v.iter().sum();
        if sum <= 0.0 {
            return Err(SamplingError::Degenerate {
                what: "every corner value is 0",
            });
        }
        Ok(Self {
            v: v.map(|c| 4.0 * c / sum),
        })
    }

    /// The end values of the marginal in `y`, and of the conditional in `x` at `y`.
    fn ends(&self, y: f64) -> [(f64, f64); 2] {
        let [v00, v10, v01, v11] = self.v;
        let marginal = normalise_ends(v00 + v10, v01 + v11);
        let conditional = normalise_ends(v00 + y * (v01 - v00), v10 + y * (v11 - v10));
        [marginal, conditional]
    }
}

impl Warp for Bilinear {
    type Point = Vec2;

    #[inline]
    fn sample(&self, u: Vec2) -> Vec2 {
        let [(ma, mb), _] = self.ends(0.0);
        let y = sample_linear_normalised(f64::from(clamp_unit(u.y)), ma, mb);
        let [_, (ca, cb)] = self.ends(y);
        let x = sample_linear_normalised(f64::from(clamp_unit(u.x)), ca, cb);
        Vec2::new(x as f32, y as f32)
    }

    /// The bilinear interpolation of the normalised corners per unit area on `[0, 1]²`, 0
    /// outside.
    #[inline]
    fn pdf(&self, p: Vec2) -> f32 {
        if !((0.0..=1.0).contains(&p.x) && (0.0..=1.0).contains(&p.y)) {
            return 0.0;
        }
        let (x, y) = (f64::from(p.x), f64::from(p.y));
        let [v00, v10, v01, v11] = self.v;
        let bottom = v00 + x * (v10 - v00);
        let top = v01 + x * (v11 - v01);
        (bottom + y * (top - bottom)).max(0.0) as f32
    }
}

impl InvertibleWarp for Bilinear {
    #[inline]
    fn invert(&self, p: Vec2) -> Vec2 {
        let (x, y) = (
            f64::from(p.x.clamp(0.0, 1.0)),
            f64::from(p.y.clamp(0.0, 1.0)),
        );
        let [(ma, mb), (ca, cb)] = self.ends(y);
        clamp_unit2(
            linear_cdf_normalised(x, ca, cb) as f32,
            linear_cdf_normalised(y, ma, mb) as f32,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_spot_values_and_edges() {
        for (a, b) in [
            (0.0, 1.0),
            (1.0, 0.0),
            (1.0, 1.0),
            (1e-30, 1e30),
            (3.0, 1.0),
        ] {
            let l = Linear::new(a, b).unwrap();
            assert_eq!(l.sample(0.0), 0.0);
            let top = l.sample(1.0 - 2f32.powi(-24));
            assert!(
                top.is_finite() && top <= 1.0 && top > 0.99,
                "{a} {b}: {top}"
            );
            for i in 1..20 {
                let u = i as f32 / 20.0;
                let x = l.sample(u);
                let back = l.invert(x);
                assert!(x.is_finite() && (back - u).abs() < 1e-5, "{a} {b} {u}");
            }
        }
        let ramp = Linear::new(0.0, 2.0).unwrap();
        let x = ramp.sample(0.25);
        assert!(x.is_finite() && (x - 0.5).abs() < 1e-6);
    }

    #[test]
    fn linear_rejects_bad_input() {
        for (a, b) in [
            (0.0, 0.0),
            (-1.0, 1.0),
            (f32::NAN, 1.0),
            (1.0, f32::INFINITY),
        ] {
            assert!(Linear::new(a, b).is_err(), "{a} {b}");
        }
    }

    #[test]
    fn bilinear_round_trip_and_zero_corners() {
        for corners in [
            [1.0, 1.0, 1.0, 1.0],
            [0.0, 0.0, 0.0, 1.0],
            [5.0, 0.0, 0.0, 0.0],
        ] {
            let b = Bilinear::new(corners).unwrap();
            for i in 1..10 {
                for j in 1..10 {
                    let u = Vec2::new(i as f32 / 10.0, j as f32 / 10.0);
                    let p = b.sample(u);
                    let back = b.invert(p);
                    assert!(
                        p.is_finite() && (back - u).abs().max_element() < 1e-5,
                        "{u}"
                    );
                    assert!(b.pdf(p) > 0.0);
                }
            }
        }
        assert!(Bilinear::new([0.0; 4]).is_err());
        assert!(Bilinear::new([1.0, f32::NAN, 0.0, 0.0]).is_err());
    }
}
