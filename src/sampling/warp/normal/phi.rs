//! The standard normal CDF Φ, its complement and its inverse, in `f64`, accurate to about
//! 10⁻¹⁴ relative in both tails (far beyond what the `f32` warps need). Written from the
//! series and continued fraction of erfc; see `docs/derivations.md`.

use std::f64::consts::{FRAC_1_SQRT_2, PI};

/// Where erfc switches from the series to the continued fraction.
const SWITCH: f64 = 2.5;

/// `1/√π`.
const FRAC_1_SQRT_PI: f64 = 0.564_189_583_547_756_3;

/// erfc(x) for `x ≥ 0`.
///
/// For `x < 2.5`: `erf x = (2/√π) e^{−x²} Σ 2ⁿ x^{2n+1} / (1·3···(2n+1))`, a series of
/// positive terms (no cancellation), and erfc = 1 − erf. Beyond: the continued fraction
/// `erfc x = e^{−x²}/√π · 1/(x + (1/2)/(x + 1/(x + (3/2)/(x + …))))`, evaluated backward
/// from a fixed depth.
pub(crate) fn erfc_nonneg(x: f64) -> f64 {
    if x < SWITCH {
        let two_x2 = 2.0 * x * x;
        let (mut term, mut sum) = (x, x);
        let mut n = 0.0;
        while term > 1e-17 * sum {
            n += 1.0;
            term *= two_x2 / (2.0 * n + 1.0);
            sum += term;
        }
        1.0 - 2.0 * FRAC_1_SQRT_PI * (-x * x).exp() * sum
    } else {
        let mut f = x;
        for k in (1..=60).rev() {
            f = x + 0.5 * f64::from(k) / f;
        }
        (-x * x).exp() * FRAC_1_SQRT_PI / f
    }
}

/// The upper tail `Q(z) = 1 − Φ(z) = erfc(z/√2)/2`, accurate for `z ≥ 0`.
#[inline]
pub(crate) fn upper_tail(z: f64) -> f64 {
    0.5 * erfc_nonneg(z * FRAC_1_SQRT_2)
}

/// Φ(z), accurate in relative terms in the lower tail.
pub(crate) fn std_normal_cdf(z: f64) -> f64 {
    if z.is_nan() {
        return 0.5;
    }
    if z < 0.0 {
        upper_tail(-z)
    } else {
        1.0 - upper_tail(z)
    }
}

/// The standard normal density φ(z).
#[inline]
pub(crate) fn std_normal_pdf(z: f64) -> f64 {
    (-0.5 * z * z).exp() / (2.0 * PI).sqrt()
}

/// Φ⁻¹(p) for `p ∈ (0, 1)` (`p` is clamped into `[f64::MIN_POSITIVE, 1 − 2⁻⁵³]`).
///
/// Starts from the rational approximation of Abramowitz & Stegun 26.2.23 in the tail of
/// `q = min(p, 1 − p)` (absolute error below 4.5·10⁻⁴), then takes two Halley steps on
/// `Q(z) = q` (cubic convergence: 4.5·10⁻⁴ → ~10⁻¹⁰ → below `f64` resolution).
pub(crate) fn std_normal_quantile(p: f64) -> f64 {
    let p = p.clamp(f64::MIN_POSITIVE, 1.0 - f64::EPSILON / 2.0);
    let q = p.min(1.0 - p);
    let t = (-2.0 * q.ln()).sqrt();
    let num = 2.515_517 + t * (0.802_853 + t * 0.010_328);
    let den = 1.0 + t * (1.432_788 + t * (0.189_269 + t * 0.001_308));
    let mut z = (t - num / den).max(0.0);
    for _ in 0..2 {
        let e = (upper_tail(z) - q) / std_normal_pdf(z);
        if !e.is_finite() {
            break;
        }
        z += e / (1.0 - 0.5 * z * e);
    }
    if p < 0.5 {
        -z
    } else {
        z
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(got: f64, want: f64, rel: f64) -> bool {
        got.is_finite() && ((got - want) / want).abs() <= rel
    }

    #[test]
    fn erfc_reference_values() {
        // Reference values of erfc to 16 digits.
        let cases = [
            (0.0, 1.0),
            (0.5, 0.479_500_122_186_953_5),
            (1.0, 0.157_299_207_050_285_1),
            (2.0, 4.677_734_981_047_266e-3),
            (3.0, 2.209_049_699_858_544e-5),
            (5.0, 1.537_459_794_428_035e-12),
        ];
        for (x, want) in cases {
            let got = erfc_nonneg(x);
            assert!(close(got, want, 1e-12), "erfc({x}) = {got}, want {want}");
        }
        let (below, above) = (erfc_nonneg(SWITCH - 1e-12), erfc_nonneg(SWITCH));
        assert!(close(below, above, 1e-10), "{below} {above}");
    }

    #[test]
    fn quantile_inverts_the_cdf() {
        for p in [
            1e-300,
            1e-45,
            1e-10,
            0.01,
            0.3,
            0.5,
            0.7,
            0.999,
            1.0 - 2f64.powi(-24),
        ] {
            let z = std_normal_quantile(p);
            let back = std_normal_cdf(z);
            assert!(close(back, p, 1e-12), "p {p}: z {z}, Φ(z) {back}");
        }
        // A dense sweep: the grid of (0, 1) and every decade of the lower tail.
        let grid = (1..1000).map(|k| f64::from(k) / 1000.0);
        let decades = (1..300).map(|k| 10f64.powi(-k));
        for p in grid.chain(decades) {
            let back = std_normal_cdf(std_normal_quantile(p));
            assert!(close(back, p, 1e-12), "p {p}: Φ(Φ⁻¹(p)) = {back}");
        }
        let mid = std_normal_quantile(0.5);
        assert!(mid.is_finite() && mid.abs() < 1e-15, "{mid}");
    }
}
