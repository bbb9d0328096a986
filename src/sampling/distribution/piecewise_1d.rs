//! A piecewise-constant density on an interval, sampled by inverting its CDF.

pub(crate) use crate::sampling::unit::clamp_unit;
use crate::sampling::unit::ONE_MINUS_EPSILON;
use crate::sampling::SamplingError;

/// A piecewise-constant density on `[min, max)`, proportional to a table of non-negative
/// values, one per equal-width bin.
///
/// The density is `p(x) = f[i] / I` for `x` in bin `i`, per unit length of `x`, where
/// `I = Σ f · width` is the table's [`integral`](Self::integral). Sampling inverts the CDF
/// (the inversion method; see `docs/derivations.md`), accumulated in `f64`, by
/// binary search. A bin whose value is zero is never sampled, for any `u ∈ [0,1)`, and a
/// sample always lies inside the bin reported with it and strictly below `max`.
///
/// Entries so small against the total that their density underflows `f32` (below about
/// 10⁻⁴⁵) count as zero: they are never sampled and their pdf is 0.
///
/// Every bin must be at least one `f32` step wide, so that it holds a sample: at most 2²⁴
/// bins on `[0, 1)`, fewer on intervals far from 0 (the constructors check).
///
/// Reference: Pharr, Jakob & Humphreys, 2023, *Physically Based Rendering* (4th ed.),
/// section A.5, "Sampling piecewise-constant functions".
///
/// ```
/// use mcrt::sampling::distribution::PiecewiseConstant1D;
///
/// let d = PiecewiseConstant1D::new(&[1.0, 0.0, 3.0]).unwrap();
/// let (x, pdf, bin) = d.sample(0.5);
/// assert_eq!(bin, 2); // the zero bin is skipped
/// assert!((2.0 / 3.0..1.0).contains(&x));
/// assert!((pdf - 3.0 / d.integral()).abs() < 1e-6);
/// assert!((d.invert(x) - 0.5).abs() < 1e-6);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct PiecewiseConstant1D {
    /// The table, as given (in `f64`).
    func: Vec<f64>,
    /// Unnormalised running sums of `func`: `cdf[0] = 0`, `cdf[i + 1] = cdf[i] + func[i]`.
    cdf: Vec<f64>,
    /// Lower end of the interval.
    min: f32,
    /// Upper end of the interval.
    max: f32,
    /// `n / (total · (max − min))`: multiplies a value into a density.
    pdf_scale: f64,
    /// Index of the last bin with a nonzero value.
    last_nonzero: usize,
    /// `n / (max − min)`: maps `x − min` to the bin coordinate.
    bins_per_unit: f64,
}

impl PiecewiseConstant1D {
    /// A distribution on `[0, 1)` proportional to `values`.
    ///
    /// # Errors
    /// [`SamplingError::EmptyTable`] for no values, [`SamplingError::InvalidEntry`] for a
    /// negative, NaN or infinite value, [`SamplingError::ZeroTable`] when every value is 0.
    pub fn new(values: &[f32]) -> Result<Self, SamplingError> {
        Self::new_on(values, 0.0, 1.0)
    }

    /// A distribution on `[min, max)` proportional to `values`.
    ///
    /// # Errors
    /// As [`new`](Self::new), and [`SamplingError::InvalidParameter`] when `min` or `max` is
    /// not finite, `max <= min`, a bin would be narrower than the `f32` spacing on the
    /// interval, or the density would overflow `f32`.
    pub fn new_on(values: &[f32], min: f32, max: f32) -> Result<Self, SamplingError> {
        validate_table(values)?;
        let func = values.iter().map(|&v| f64::from(v)).collect();
        Self::from_validated(func, min, max)
    }

    /// Builds from entries already known to be finite and `>= 0`, not all zero.
    pub(crate) fn from_validated(
        mut func: Vec<f64>,
        min: f32,
        max: f32,
    ) -> Result<Self, SamplingError> {
        crate::sampling::error::check_param("min", min, "finite", |_| true)?;
        crate::sampling::error::check_param("max", max, "finite and > min", |m| m > min)?;
        let range = f64::from(max) - f64::from(min);
        check_bin_width(func.len(), min, max)?;
        let sum: f64 = func.iter().sum();
        if sum <= 0.0 {
            return Err(SamplingError::ZeroTable);
        }
        let n = func.len() as f64;
        drop_underflowing(&mut func, n / (sum * range));
        let cdf = running_sums(&func);
        let total = cdf[func.len()];
        let last_nonzero = func
            .iter()
            .rposition(|&v| v > 0.0)
            .ok_or(SamplingError::ZeroTable)?;
        let pdf_scale = func.len() as f64 / (total * range);
        let peak = func.iter().fold(0.0_f64, |m, &v| m.max(v)) * pdf_scale;
        if !((peak as f32).is_finite() && total.is_finite()) {
            return Err(SamplingError::InvalidParameter {
                name: "max - min",
                value: range,
                expected: "wide enough that the density fits in f32",
            });
        }
        Ok(Self {
            func,
            cdf,
            min,
            max,
            pdf_scale,
            last_nonzero,
            bins_per_unit: n / range,
        })
    }

    /// Draws `x` by inverting the CDF at `u ∈ [0,1)`: returns `(x, pdf(x), bin of x)`, the
    /// pdf per unit length. Never returns a bin whose value is zero; `u` outside `[0,1)`
    /// (or NaN) is clamped into it.
    #[must_use]
    #[inline]
    pub fn sample(&self, u: f32) -> (f32, f32, usize) {
        let u = clamp_unit(u);
        let target = f64::from(u) * self.total();
        // First bin whose upper CDF end exceeds the target: never a zero bin, since a zero
        // bin's upper end equals its lower end, which is <= target.
        let i = self.cdf[1..]
            .partition_point(|&c| c <= target)
            .min(self.last_nonzero);
        let (lo, hi) = (self.cdf[i], self.cdf[i + 1]);
        let d = (target - lo) / (hi - lo);
        let d = if d >= 0.0 { d.min(1.0) } else { 0.0 }; // NaN when hi == lo after rounding
        let x = self.point_in_bin(i, d);
        (x, self.pdf_of_bin(i), i)
    }

    /// The density of [`sample`](Self::sample) at `x`, per unit length; 0 outside
    /// `[min, max)`.
    #[must_use]
    #[inline]
    pub fn pdf(&self, x: f32) -> f32 {
        match self.bin_of(x) {
            Some(i) => self.pdf_of_bin(i),
            None => 0.0,
        }
    }

    /// The `u` that [`sample`](Self::sample) maps to `x` (the CDF at `x`), in `[0, 1)`.
    /// Points below `min` give 0, points at or above `max` give `1 − 2⁻²⁴`. Inside a zero
    /// bin, where no `u` maps, the CDF (constant there) is returned.
    #[must_use]
    #[inline]
    pub fn invert(&self, x: f32) -> f32 {
        let n = self.func.len() as f64;
        let t = self.bin_coordinate(x);
        if t.is_nan() || t <= 0.0 {
            return 0.0;
        }
        if t >= n {
            return ONE_MINUS_EPSILON;
        }
        let i = (t as usize).min(self.func.len() - 1);
        let d = (t - i as f64).clamp(0.0, 1.0);
        let c = self.cdf[i] + d * (self.cdf[i + 1] - self.cdf[i]);
        ((c / self.total()) as f32).clamp(0.0, ONE_MINUS_EPSILON)
    }

    /// `∫ f(x) dx` over `[min, max)`: the mean value times the interval's width.
    #[must_use]
    pub fn integral(&self) -> f32 {
        (self.total() / self.func.len() as f64 * self.range()) as f32
    }

    /// The probability of bin `i` (its value over the sum of values); 0 past the end.
    #[must_use]
    pub fn pmf(&self, i: usize) -> f32 {
        self.pmf_f64(i) as f32
    }

    /// [`pmf`](Self::pmf) in `f64`, for statistics (exact bin masses of the chi-square test).
    #[must_use]
    pub fn pmf_f64(&self, i: usize) -> f64 {
        self.func.get(i).map_or(0.0, |&v| v / self.total())
    }

    /// The number of bins.
    #[must_use]
    pub fn len(&self) -> usize {
        self.func.len()
    }

    /// Always `false`: a distribution has at least one bin.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.func.is_empty()
    }

    /// The interval `(min, max)` the density lives on.
    #[must_use]
    pub fn domain(&self) -> (f32, f32) {
        (self.min, self.max)
    }

    /// The bin holding `x`, or `None` outside `[min, max)`. Monotone in `x`.
    #[must_use]
    pub fn bin_of(&self, x: f32) -> Option<usize> {
        let t = self.bin_coordinate(x);
        if t >= 0.0 && t < self.func.len() as f64 {
            Some(t as usize)
        } else {
            None
        }
    }

    /// The sum of the values (the unnormalised CDF at `max`).
    pub(crate) fn total(&self) -> f64 {
        self.cdf[self.func.len()]
    }

    /// The density (per unit length) in bin `i`.
    fn pdf_of_bin(&self, i: usize) -> f32 {
        (self.func[i] * self.pdf_scale) as f32
    }

    fn range(&self) -> f64 {
        f64::from(self.max) - f64::from(self.min)
    }

    /// `(x − min) · n / (max − min)`, whose integer part is the bin index; NaN for NaN.
    /// Monotone in `x`; exact on `[0, 1)` (then `n / (max − min) = n`).
    fn bin_coordinate(&self, x: f32) -> f64 {
        (f64::from(x) - f64::from(self.min)) * self.bins_per_unit
    }

    /// The `f32` at fraction `d ∈ [0,1]` of bin `i`, nudged by whole `f32` steps so that
    /// [`bin_of`](Self::bin_of) agrees it lies in bin `i` (rounding to `f32` can carry it
    /// onto a neighbour, or onto `max`).
    fn point_in_bin(&self, i: usize, d: f64) -> f32 {
        let mut x = (f64::from(self.min) + (i as f64 + d) / self.bins_per_unit) as f32;
        for _ in 0..4 {
            let t = self.bin_coordinate(x);
            if t >= (i + 1) as f64 {
                x = x.next_down();
            } else if t < i as f64 {
                x = x.next_up();
            } else {
                break;
            }
        }
        x.clamp(self.min, self.max.next_down())
    }
}

/// Rejects an empty table or one with a negative, NaN or infinite entry. (An all-zero table
/// is rejected later, where the caller decides whether that is an error.)
pub(crate) fn validate_table(values: &[f32]) -> Result<(), SamplingError> {
    if values.is_empty() {
        return Err(SamplingError::EmptyTable);
    }
    match values.iter().position(|v| !(v.is_finite() && *v >= 0.0)) {
        Some(index) => Err(SamplingError::InvalidEntry {
            index,
            value: f64::from(values[index]),
        }),
        None => Ok(()),
    }
}

/// Checks a row-major grid table: `width · height` values ([`SamplingError::ShapeMismatch`]
/// otherwise), then as [`validate_table`]. Returns the number of values.
pub(crate) fn validate_grid(
    values: &[f32],
    width: usize,
    height: usize,
) -> Result<usize, SamplingError> {
    let expected = width.saturating_mul(height);
    if values.len() != expected {
        return Err(SamplingError::ShapeMismatch {
            expected,
            got: values.len(),
        });
    }
    validate_table(values)?;
    Ok(expected)
}

/// Rejects bins narrower than the `f32` spacing on `[min, max)`: such a bin may hold no
/// `f32` at all, so a sample could not be placed inside it.
fn check_bin_width(n: usize, min: f32, max: f32) -> Result<(), SamplingError> {
    let m = min.abs().max(max.abs());
    let spacing = f64::from(m) - f64::from(m.next_down());
    if (f64::from(max) - f64::from(min)) / n as f64 >= spacing {
        Ok(())
    } else {
        Err(SamplingError::InvalidParameter {
            name: "values.len()",
            value: n as f64,
            expected: "at most (max - min) / (f32 spacing at max(|min|, |max|)) bins",
        })
    }
}

/// Sets to zero the entries whose density `v · scale` underflows `f32` (below about
/// 10⁻⁴⁵): they could never be reported with a positive pdf, so they are never sampled.
pub(crate) fn drop_underflowing(func: &mut [f64], scale: f64) {
    for v in func.iter_mut() {
        if (*v * scale) as f32 == 0.0 {
            *v = 0.0;
        }
    }
}

/// `[0, f₀, f₀ + f₁, …]`: the unnormalised CDF at the bin edges.
fn running_sums(func: &[f64]) -> Vec<f64> {
    let mut cdf = Vec::with_capacity(func.len() + 1);
    let mut sum = 0.0_f64;
    cdf.push(sum);
    for &v in func {
        sum += v;
        cdf.push(sum);
    }
    cdf
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_bad_tables() {
        assert_eq!(
            PiecewiseConstant1D::new(&[]),
            Err(SamplingError::EmptyTable)
        );
        assert_eq!(
            PiecewiseConstant1D::new(&[0.0, 0.0]),
            Err(SamplingError::ZeroTable)
        );
        for bad in [-1.0, f32::NAN, f32::INFINITY] {
            let err = PiecewiseConstant1D::new(&[1.0, bad]).unwrap_err();
            assert!(matches!(err, SamplingError::InvalidEntry { index: 1, .. }));
        }
        assert!(PiecewiseConstant1D::new_on(&[1.0], 1.0, 1.0).is_err());
        assert!(PiecewiseConstant1D::new_on(&[1.0], 0.0, f32::NAN).is_err());
        // Bins of 10⁻³ near 10⁶, where f32 steps are 0.0625: rejected.
        assert!(PiecewiseConstant1D::new_on(&[1.0; 1000], 1e6, 1e6 + 1.0).is_err());
        assert!(PiecewiseConstant1D::new_on(&[1.0; 16], 1e6, 1e6 + 1.0).is_ok());
    }

    #[test]
    fn skips_zero_bins_at_the_edges_of_u() {
        let d = PiecewiseConstant1D::new(&[0.0, 2.0, 0.0, 0.0, 1.0, 0.0]).unwrap();
        for u in [0.0, 1e-9, 0.5, 2.0 / 3.0, ONE_MINUS_EPSILON] {
            let (x, pdf, i) = d.sample(u);
            assert!(x.is_finite() && pdf.is_finite());
            assert!(i == 1 || i == 4, "u = {u} gave bin {i}");
            assert_eq!(d.bin_of(x), Some(i));
            assert!(pdf > 0.0);
        }
        assert_eq!(d.sample(0.0).2, 1);
        assert_eq!(d.sample(ONE_MINUS_EPSILON).2, 4);
    }

    #[test]
    fn pdf_integral_and_invert() {
        let d = PiecewiseConstant1D::new_on(&[1.0, 3.0], 2.0, 4.0).unwrap();
        let integral = d.integral();
        assert!(integral.is_finite() && (integral - 4.0).abs() < 1e-6);
        assert!((d.pdf(2.5) - 0.25).abs() < 1e-7 && (d.pdf(3.5) - 0.75).abs() < 1e-7);
        assert_eq!(d.pdf(4.0), 0.0);
        assert_eq!(d.pdf(1.9), 0.0);
        let (x, _, i) = d.sample(0.25);
        assert_eq!(i, 1);
        assert!(x.is_finite() && (x - 3.0).abs() < 1e-6);
        let u = d.invert(3.5);
        assert!(u.is_finite() && (u - 0.625).abs() < 1e-7);
        assert_eq!(d.invert(10.0), ONE_MINUS_EPSILON);
        assert_eq!(d.invert(-10.0), 0.0);
    }

    #[test]
    fn the_last_sample_stays_below_max() {
        let d = PiecewiseConstant1D::new(&[1.0; 3]).unwrap();
        let (x, _, i) = d.sample(ONE_MINUS_EPSILON);
        assert_eq!(i, 2);
        assert!(x < 1.0);
    }
}
