//! The inversion method for a 1D density given by its CDF: safeguarded Newton iteration with
//! a bisection fallback.

use crate::sampling::SamplingError;

/// Samples a 1D density on `[a, b]` by numerically inverting its CDF.
///
/// Given a monotone non-decreasing `cdf` and its derivative `pdf` (both unnormalised is
/// fine: the target is `cdf(a) + u · (cdf(b) − cdf(a))`), [`sample`](Self::sample) solves
/// `cdf(x) = target` by Newton's method inside a bracket `[lo, hi]` that always contains the
/// root. A Newton step is taken only when the pdf is positive and finite and the step lands
/// strictly inside the bracket; otherwise the bracket is bisected. The iteration stops when
/// the last step or the bracket is shorter than the tolerance, or after the iteration cap.
///
/// Accuracy: when the bracket stops the iteration, the result is within `tolerance` of the
/// root; when a Newton step shorter than `tolerance` stops it, the error is of the order of
/// the next step, far smaller near a simple root (quadratic convergence). Newton usually
/// needs a handful of steps; bisection alone would need `log₂((b − a) / tolerance)`.
/// Defaults: tolerance `1e-12 · (b − a)` (about 2¹² times the `f64` resolution at the ends
/// of the interval), cap 100 iterations (enough for bisection alone to shrink the
/// bracket by 2⁻¹⁰⁰).
///
/// Reference: Press, Teukolsky, Vetterling & Flannery, 2007, *Numerical Recipes* (3rd ed.),
/// section 9.4, "Newton–Raphson method using derivative" (routine `rtsafe`).
///
/// ```
/// use mcrt::sampling::distribution::Inversion1D;
///
/// // p(x) = 3x² on [0, 1]: CDF x³, exact inverse ∛u.
/// let inv = Inversion1D::new(0.0, 1.0).unwrap();
/// let x = inv.sample(|x| x * x * x, |x| 3.0 * x * x, 0.3);
/// assert!((x - 0.3_f64.cbrt()).abs() < 1e-10);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inversion1D {
    a: f64,
    b: f64,
    tolerance: f64,
    max_iterations: u32,
}

impl Inversion1D {
    /// Inversion on `[a, b]` with the default tolerance `1e-12 · (b − a)` and cap of 100
    /// iterations.
    ///
    /// # Errors
    /// [`SamplingError::InvalidParameter`] unless `a` and `b` are finite and `a < b`.
    pub fn new(a: f64, b: f64) -> Result<Self, SamplingError> {
        check("a", a, "finite", a.is_finite())?;
        check("b", b, "finite and > a", b.is_finite() && b > a)?;
        Ok(Self {
            a,
            b,
            tolerance: 1e-12 * (b - a),
            max_iterations: 100,
        })
    }

    /// The same with an absolute tolerance on `x`.
    ///
    /// # Errors
    /// [`SamplingError::InvalidParameter`] unless `tolerance` is finite and `> 0`.
    pub fn with_tolerance(self, tolerance: f64) -> Result<Self, SamplingError> {
        check(
            "tolerance",
            tolerance,
            "finite and > 0",
            tolerance.is_finite() && tolerance > 0.0,
        )?;
        Ok(Self { tolerance, ..self })
    }

    /// The same with another iteration cap (at least 1).
    #[must_use]
    pub fn with_max_iterations(self, max_iterations: u32) -> Self {
        Self {
            max_iterations: max_iterations.max(1),
            ..self
        }
    }

    /// The `x ∈ [a, b]` with `cdf(x) = cdf(a) + u · (cdf(b) − cdf(a))`, for `u ∈ [0, 1]`
    /// (clamped into it; NaN acts as 0). Returns `a` when `cdf(b) − cdf(a)` is not a
    /// positive finite number (use [`sample_by_inversion`] to get an error instead).
    #[must_use]
    #[inline]
    pub fn sample(&self, cdf: impl Fn(f64) -> f64, pdf: impl Fn(f64) -> f64, u: f64) -> f64 {
        let u = if u >= 0.0 { u.min(1.0) } else { 0.0 };
        let (c_a, c_b) = (cdf(self.a), cdf(self.b));
        let mass = c_b - c_a;
        if !(mass.is_finite() && mass > 0.0) {
            return self.a;
        }
        let target = c_a + u * mass;
        let (mut lo, mut hi) = (self.a, self.b);
        // Start where a uniform density would put the root.
        let mut x = self.a + u * (self.b - self.a);
        for _ in 0..self.max_iterations {
            let f = cdf(x) - target;
            if f == 0.0 {
                return x;
            }
            if f < 0.0 {
                lo = x;
            } else {
                hi = x;
            }
            let slope = pdf(x);
            let newton = x - f / slope;
            let next = if slope > 0.0 && newton > lo && newton < hi {
                newton
            } else {
                0.5 * (lo + hi)
            };
            let step = (next - x).abs();
            x = next;
            if step <= self.tolerance || hi - lo <= self.tolerance {
                break;
            }
        }
        x.clamp(self.a, self.b)
    }

    /// The interval `(a, b)`.
    #[must_use]
    pub fn interval(&self) -> (f64, f64) {
        (self.a, self.b)
    }

    /// The absolute tolerance on `x`.
    #[must_use]
    pub fn tolerance(&self) -> f64 {
        self.tolerance
    }
}

/// Samples a density on `[a, b]` given its CDF and pdf by inversion, to absolute tolerance
/// `tol` on `x` (see [`Inversion1D`] for the method, the stopping rule and the cap).
///
/// # Errors
/// [`SamplingError::InvalidParameter`] for an invalid interval, tolerance or `u` outside
/// `[0, 1]` (or NaN); [`SamplingError::Degenerate`] when `cdf(b) − cdf(a)` is not a positive
/// finite number.
///
/// ```
/// use mcrt::sampling::distribution::sample_by_inversion;
///
/// // The quiz's P(θ) = 4θ²/π² on [0, π/2]: inverse θ = (π/2)√u.
/// let pi = std::f64::consts::PI;
/// let cdf = |t: f64| 4.0 * t * t / (pi * pi);
/// let pdf = |t: f64| 8.0 * t / (pi * pi);
/// let theta = sample_by_inversion(cdf, pdf, 0.0, pi / 2.0, 0.25, 1e-12).unwrap();
/// assert!((theta - pi / 4.0).abs() < 1e-10);
/// ```
pub fn sample_by_inversion(
    cdf: impl Fn(f64) -> f64,
    pdf: impl Fn(f64) -> f64,
    a: f64,
    b: f64,
    u: f64,
    tol: f64,
) -> Result<f64, SamplingError> {
    let inv = Inversion1D::new(a, b)?.with_tolerance(tol)?;
    check("u", u, "in [0, 1]", (0.0..=1.0).contains(&u))?;
    let mass = cdf(b) - cdf(a);
    if !(mass.is_finite() && mass > 0.0) {
        return Err(SamplingError::Degenerate {
            what: "cdf(b) - cdf(a) is not positive and finite",
        });
    }
    Ok(inv.sample(cdf, pdf, u))
}

fn check(
    name: &'static str,
    value: f64,
    expected: &'static str,
    ok: bool,
) -> Result<(), SamplingError> {
    if ok {
        Ok(())
    } else {
        Err(SamplingError::InvalidParameter {
            name,
            value,
            expected,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn assert_close(x: f64, want: f64, tol: f64) {
        assert!(x.is_finite() && (x - want).abs() <= tol, "{x} vs {want}");
    }

    #[test]
    fn quiz_theta_density() {
        let cdf = |t: f64| 4.0 * t * t / (PI * PI);
        let pdf = |t: f64| 8.0 * t / (PI * PI);
        for u in [0.0, 1e-9, 0.3, 0.5, 0.999, 1.0] {
            let t = sample_by_inversion(cdf, pdf, 0.0, PI / 2.0, u, 1e-13).unwrap();
            assert_close(t, PI / 2.0 * u.sqrt(), 1e-12);
        }
    }

    #[test]
    fn beckmann_theta_density() {
        // CDF(θ) = 1 − exp(−tan²θ / α²), inverse tan²θ = −α² ln(1 − u).
        for alpha in [1e-3, 0.1, 0.5, 1.0] {
            let cdf = |t: f64| -(-(t.tan() / alpha).powi(2)).exp_m1();
            let pdf = |t: f64| {
                let c = t.cos();
                2.0 * t.tan() / (alpha * alpha * c * c) * (-(t.tan() / alpha).powi(2)).exp()
            };
            for u in [0.01, 0.3, 0.5, 0.9, 0.999] {
                let t = sample_by_inversion(cdf, pdf, 0.0, PI / 2.0 - 1e-9, u, 1e-13).unwrap();
                let want = (alpha * (-(-u).ln_1p()).sqrt()).atan();
                assert_close(t, want, 1e-9 * want.max(1e-3));
            }
        }
    }

    #[test]
    fn polynomial_on_an_offset_interval() {
        // p(x) ∝ x² on [1, 2]: x = ∛(1 + 7u).
        let inv = Inversion1D::new(1.0, 2.0).unwrap();
        for u in [0.0, 0.2, 0.7, 1.0] {
            let x = inv.sample(|x| x * x * x, |x| 3.0 * x * x, u);
            assert_close(x, (1.0 + 7.0 * u).cbrt(), 1e-11);
        }
    }

    #[test]
    fn a_useless_pdf_falls_back_to_bisection() {
        let inv = Inversion1D::new(0.0, 1.0)
            .unwrap()
            .with_tolerance(1e-14)
            .unwrap();
        let x = inv.sample(|x| x * x, |_| f64::NAN, 0.49);
        assert_close(x, 0.7, 1e-13);
        let x = inv.sample(|x| x * x, |_| 0.0, 0.49);
        assert_close(x, 0.7, 1e-13);
        let x = inv.sample(|x| x * x, |_| -1.0, 0.49);
        assert_close(x, 0.7, 1e-13);
    }

    #[test]
    fn rejects_bad_input() {
        let (c, p) = (|x: f64| x, |_: f64| 1.0);
        assert!(sample_by_inversion(c, p, 1.0, 1.0, 0.5, 1e-9).is_err());
        assert!(sample_by_inversion(c, p, 0.0, f64::INFINITY, 0.5, 1e-9).is_err());
        assert!(sample_by_inversion(c, p, 0.0, 1.0, 0.5, 0.0).is_err());
        assert!(sample_by_inversion(c, p, 0.0, 1.0, f64::NAN, 1e-9).is_err());
        let flat = sample_by_inversion(|_| 1.0, p, 0.0, 1.0, 0.5, 1e-9);
        assert!(matches!(flat, Err(SamplingError::Degenerate { .. })));
    }
}
