//! Inversion of the Beckmann visible-slope CDF (α = 1, incidence rotated into the xz plane).
//!
//! The slope x̃ of a visible Beckmann normal seen from (sin θ, 0, cos θ) has density
//! ∝ e^{−x²} (cos θ − x sin θ) on x < cot θ, with the unnormalised CDF
//! F(x) = cos θ (√π/2) erfc(−x) + sin θ e^{−x²}/2. With (cos θ, sin θ) = (1, 0) this is the
//! CDF of the other slope, e^{−y²}/√π. F is solved by Newton's method safeguarded by
//! bisection, in `f64`, to a relative tolerance of 1e-12.

use super::super::microfacet::special::erfc_given_gaussian;

const SQRT_PI: f64 = 1.772_453_850_905_516;

/// The visible-slope CDF of one incidence, F(x) as above.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SlopeCdf {
    cos: f64,
    sin: f64,
    /// Upper end of the support, cot θ (+∞ at normal incidence).
    x_max: f64,
    /// F(x_max).
    total: f64,
}

impl SlopeCdf {
    /// The CDF for incidence (sin θ, 0, cos θ); `cos > 0`, `sin ≥ 0`, cos² + sin² = 1.
    pub(crate) fn new(cos: f64, sin: f64) -> Self {
        let x_max = if sin > 0.0 { cos / sin } else { f64::INFINITY };
        let mut cdf = Self {
            cos,
            sin,
            x_max,
            total: 1.0,
        };
        cdf.total = cdf.eval(x_max).0;
        cdf
    }

    /// Unnormalised F(x) and F'(x) = e^{−x²}(cos θ − x sin θ), sharing one `exp`.
    fn eval(&self, x: f64) -> (f64, f64) {
        let gaussian = if x.is_finite() { (-x * x).exp() } else { 0.0 };
        let cdf = self.cos * 0.5 * SQRT_PI * erfc_given_gaussian(-x, gaussian)
            + self.sin * 0.5 * gaussian;
        (cdf, gaussian * (self.cos - x * self.sin))
    }

    /// The slope x with F(x) = u F(x_max); u is clamped to [2⁻⁴⁰, 1 − 2⁻⁴⁰].
    pub(crate) fn invert(&self, u: f64) -> f64 {
        let eps = 2f64.powi(-40);
        let u = u.clamp(eps, 1.0 - eps);
        let target = u * self.total;
        let (mut lo, mut hi) = self.bracket(u, target);
        let guess = gaussian_quantile_guess(u);
        let mut x = if guess > lo && guess < hi {
            guess
        } else {
            0.5 * (lo + hi)
        };
        for _ in 0..100 {
            let (cdf, density) = self.eval(x);
            let f = cdf - target;
            if f > 0.0 {
                hi = x;
            } else {
                lo = x;
            }
            if hi - lo <= 1e-12 * (1.0 + x.abs()) || f == 0.0 {
                break;
            }
            let step = x - f / density;
            let next = if step > lo && step < hi && step.is_finite() {
                step
            } else {
                0.5 * (lo + hi)
            };
            let converged = (next - x).abs() <= 1e-12 * (1.0 + x.abs());
            x = next;
            if converged {
                break;
            }
        }
        x.clamp(lo, hi)
    }

    /// An interval containing the solution, from erfc(t) ≤ e^{−t²} for t ≥ 0.
    fn bracket(&self, u: f64, target: f64) -> (f64, f64) {
        // Left: for x ≤ 0, F(x) ≤ k e^{−x²} with k = cos√π/2 + sin/2.
        let k = 0.5 * (self.cos * SQRT_PI + self.sin);
        let lo = -(k / target).ln().max(0.0).sqrt() - 1e-3;
        // Right: for x ≥ 0, F(x_max) − F(x) ≤ cos (√π/2) e^{−x²}.
        let rest = (1.0 - u) * self.total;
        let hi = (0.5 * self.cos * SQRT_PI / rest).ln().max(0.0).sqrt() + 1e-3;
        (lo, hi.min(self.x_max))
    }
}

/// A starting point for Newton's method: the quantile of the density e^{−y²}/√π, i.e.
/// erf⁻¹(2u − 1), by Winitzki's closed-form approximation (relative error ~2e-3).
/// Winitzki 2008, "A handy approximation for the error function and its inverse".
fn gaussian_quantile_guess(u: f64) -> f64 {
    const A: f64 = 0.147;
    let z = 2.0 * u - 1.0;
    let ln = ((1.0 - z) * (1.0 + z)).ln();
    let b = 2.0 / (std::f64::consts::PI * A) + 0.5 * ln;
    ((b * b - ln / A).sqrt() - b).max(0.0).sqrt().copysign(z)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverts_the_cdf_at_several_incidences() {
        for theta in [0.0f64, 0.5, 1.2, 1.55, 1.5690] {
            let cdf = SlopeCdf::new(theta.cos(), theta.sin());
            assert!(cdf.total.is_finite() && cdf.total > 0.0);
            let mut last = f64::NEG_INFINITY;
            for i in 0..=20 {
                let u = i as f64 / 20.0;
                let x = cdf.invert(u);
                assert!(
                    x.is_finite() && x <= cdf.x_max && x >= last,
                    "θ {theta} u {u}: {x}"
                );
                last = x;
                let back = cdf.eval(x).0 / cdf.total;
                let want = u.clamp(2f64.powi(-40), 1.0 - 2f64.powi(-40));
                assert!((back - want).abs() < 1e-9, "θ {theta} u {u}: F = {back}");
            }
        }
    }

    #[test]
    fn normal_incidence_is_a_gaussian() {
        let cdf = SlopeCdf::new(1.0, 0.0);
        let x = cdf.invert(0.5);
        assert!(x.is_finite() && x.abs() < 1e-9);
        // P(X ≤ 1) for density e^{−x²}/√π is (1 + erf 1)/2.
        let x = cdf.invert(0.5 * (1.0 + 0.842_700_792_949_714_9));
        assert!(x.is_finite() && (x - 1.0).abs() < 1e-9, "{x}");
    }
}
