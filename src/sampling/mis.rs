//! Multiple importance sampling weights: the balance and power heuristics.
//!
//! Every function returns a weight in `[0, 1]`, never the weighted estimate. With
//! `f = n_f · pdf_f` and `g = n_g · pdf_g` (sample counts times densities, all in the same
//! measure):
//!
//! - balance heuristic `w = f / (f + g)`, power heuristic (β = 2) `w = f² / (f² + g²)`,
//!   both computed as `1 / (1 + (g / f)^β)`: in `f32` when `f` and `g` are finite, `f` is
//!   normal (≥ `f32::MIN_POSITIVE`) and `g ≥ 0` (the estimators' case, a few instructions),
//!   otherwise in `f64`, so no finite input overflows; the two agree to `f32` rounding;
//! - `f = 0` gives 0 (including 0/0): a strategy that cannot produce the sample gets no
//!   weight;
//! - `f = ∞` gives 1 and `g = ∞` gives 0 (a delta strategy takes all the weight); both
//!   infinite give ½ (with n strategies, `1/k` among the `k` infinite ones);
//! - a NaN or negative count or pdf anywhere gives 0: the caller's bug is not spread into
//!   the image.
//!
//! For two strategies the weights of `f` and `g` sum to 1 whenever the pdfs are valid and
//! not both zero.
//!
//! Reference: Veach & Guibas, 1995, "Optimally Combining Sampling Techniques for Monte
//! Carlo Rendering", SIGGRAPH '95, DOI 10.1145/218380.218498.
//!
//! ```
//! use mcrt::sampling::mis::{balance_heuristic, power_heuristic};
//!
//! assert_eq!(balance_heuristic(1.0, 3.0, 1.0, 1.0), 0.75);
//! assert_eq!(power_heuristic(1.0, 3.0, 1.0, 1.0), 0.9);
//! assert_eq!(power_heuristic(1.0, f32::INFINITY, 1.0, 5.0), 1.0);
//! assert_eq!(power_heuristic(1.0, 0.0, 1.0, 0.0), 0.0);
//! ```

/// The balance heuristic weight `n_f·pdf_f / (n_f·pdf_f + n_g·pdf_g)` of strategy `f`, in
/// `[0, 1]`; edge cases as in the [module docs](self).
#[inline]
#[must_use]
pub fn balance_heuristic(n_f: f32, pdf_f: f32, n_g: f32, pdf_g: f32) -> f32 {
    two_strategies::<false>(n_f, pdf_f, n_g, pdf_g)
}

/// The power heuristic weight (β = 2) `(n_f·pdf_f)² / ((n_f·pdf_f)² + (n_g·pdf_g)²)` of
/// strategy `f`, computed as `1 / (1 + (n_g·pdf_g / n_f·pdf_f)²)`, in `[0, 1]`; edge cases
/// as in the [module docs](self).
#[inline]
#[must_use]
pub fn power_heuristic(n_f: f32, pdf_f: f32, n_g: f32, pdf_g: f32) -> f32 {
    two_strategies::<true>(n_f, pdf_f, n_g, pdf_g)
}

/// The balance heuristic weight of strategy `i` among `(count, pdf)` pairs:
/// `f_i / Σ_j f_j` with `f_j = count_j · pdf_j`, in `[0, 1]`. 0 when `i` is out of range;
/// edge cases as in the [module docs](self).
#[must_use]
pub fn balance_heuristic_n(i: usize, counts_and_pdfs: &[(f32, f32)]) -> f32 {
    n_strategies(i, counts_and_pdfs, |f| f)
}

/// The power heuristic weight (β = 2) of strategy `i` among `(count, pdf)` pairs:
/// `f_i² / Σ_j f_j²`, in `[0, 1]`. 0 when `i` is out of range; edge cases as in the
/// [module docs](self).
#[must_use]
pub fn power_heuristic_n(i: usize, counts_and_pdfs: &[(f32, f32)]) -> f32 {
    n_strategies(i, counts_and_pdfs, |f| f * f)
}

/// `n · pdf` in `f64` (exact range: no overflow or underflow for finite `f32` inputs), or
/// `None` for a NaN or negative input.
fn product(n: f32, pdf: f32) -> Option<f64> {
    let ok = |x: f32| x >= 0.0; // false for NaN
    if !(ok(n) && ok(pdf)) {
        return None;
    }
    if n == 0.0 || pdf == 0.0 {
        return Some(0.0); // 0 · ∞ counts as 0: no samples, or a density that is 0 here
    }
    Some(f64::from(n) * f64::from(pdf))
}

/// The weight of `f` against `g`, `1 / (1 + (g/f)^β)` with β = 2 (`POWER`) or 1: inline in
/// `f32` in the usual case (both products finite, `f` normal, `n_g, pdf_g ≥ 0`), where
/// it agrees with [`two_strategies_f64`] to `f32` rounding; every other input (zero,
/// subnormal, infinite, NaN, negative) goes to that function and its edge cases.
#[inline(always)]
fn two_strategies<const POWER: bool>(n_f: f32, pdf_f: f32, n_g: f32, pdf_g: f32) -> f32 {
    let (f, g) = (n_f * pdf_f, n_g * pdf_g);
    // `n_g, pdf_g ≥ 0` separately: a negative input times 0 would pass as `g = −0`.
    let valid_g = n_g >= 0.0 && pdf_g >= 0.0 && g < f32::INFINITY;
    // `f > 0` with `pdf_f > 0` also means `n_f > 0` (two negatives would multiply to f > 0).
    if pdf_f > 0.0 && (f32::MIN_POSITIVE..f32::INFINITY).contains(&f) && valid_g {
        let r = g / f;
        // r = ∞ (f underflowing against g) gives 0, as the f64 formula does to f32 precision.
        return 1.0 / (1.0 + if POWER { r * r } else { r });
    }
    two_strategies_f64(
        n_f,
        pdf_f,
        n_g,
        pdf_g,
        if POWER { |r| r * r } else { |r| r },
    )
}

/// [`two_strategies`] in `f64`, with the edge cases of the [module docs](self).
fn two_strategies_f64(n_f: f32, pdf_f: f32, n_g: f32, pdf_g: f32, power: fn(f64) -> f64) -> f32 {
    let (Some(f), Some(g)) = (product(n_f, pdf_f), product(n_g, pdf_g)) else {
        return 0.0;
    };
    if f == 0.0 {
        return 0.0;
    }
    match (f.is_infinite(), g.is_infinite()) {
        (true, true) => 0.5,
        (true, false) => 1.0,
        (false, true) => 0.0,
        (false, false) => (1.0 / (1.0 + power(g / f))) as f32,
    }
}

fn n_strategies(i: usize, items: &[(f32, f32)], power: fn(f64) -> f64) -> f32 {
    let Some(&(n_i, pdf_i)) = items.get(i) else {
        return 0.0;
    };
    let Some(f) = product(n_i, pdf_i) else {
        return 0.0;
    };
    let mut infinite = 0usize;
    for &(n, pdf) in items {
        match product(n, pdf) {
            None => return 0.0,
            Some(g) if g.is_infinite() => infinite += 1,
            Some(_) => {}
        }
    }
    if f == 0.0 {
        return 0.0;
    }
    if infinite > 0 {
        return if f.is_infinite() {
            1.0 / infinite as f32
        } else {
            0.0
        };
    }
    // Ratios to f keep every term finite or +∞ in f64 (never NaN), and the own term is 1.
    let sum: f64 = items
        .iter()
        .filter_map(|&(n, pdf)| product(n, pdf))
        .map(|g| power(g / f))
        .sum();
    (1.0 / sum) as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    const INF: f32 = f32::INFINITY;

    #[test]
    fn spot_values() {
        assert_eq!(balance_heuristic(1.0, 1.0, 1.0, 1.0), 0.5);
        assert_eq!(balance_heuristic(2.0, 1.0, 1.0, 2.0), 0.5);
        assert_eq!(power_heuristic(1.0, 1.0, 1.0, 2.0), 0.2);
        assert!(
            (power_heuristic_n(0, &[(1.0, 1.0), (1.0, 2.0), (2.0, 1.0)]) - 1.0 / 9.0).abs() < 1e-7
        );
        assert!((balance_heuristic_n(2, &[(1.0, 1.0), (1.0, 2.0), (2.0, 1.0)]) - 0.4).abs() < 1e-7);
    }

    #[test]
    fn edge_cases() {
        for h in [balance_heuristic, power_heuristic] {
            assert_eq!(h(1.0, 0.0, 1.0, 0.0), 0.0);
            assert_eq!(h(1.0, INF, 1.0, 1e30), 1.0);
            assert_eq!(h(1.0, 1e30, 1.0, INF), 0.0);
            assert_eq!(h(1.0, INF, 1.0, INF), 0.5);
            assert_eq!(h(1.0, f32::NAN, 1.0, 1.0), 0.0);
            assert_eq!(h(1.0, 1.0, 1.0, f32::NAN), 0.0);
            assert_eq!(h(1.0, -1.0, 1.0, 1.0), 0.0);
            assert_eq!(h(0.0, 1.0, 1.0, 1.0), 0.0);
            assert_eq!(h(1.0, 1.0, 0.0, INF), 1.0);
            let w = h(1.0, f32::MAX, 1.0, f32::MAX);
            assert!(w.is_finite() && (w - 0.5).abs() < 1e-7);
            let w = h(1.0, f32::MAX, 1.0, f32::MIN_POSITIVE * 1e-3);
            assert_eq!(w, 1.0);
            let w = h(1.0, f32::MIN_POSITIVE * 1e-3, 1.0, f32::MAX);
            assert_eq!(w, 0.0);
        }
        assert_eq!(balance_heuristic_n(3, &[(1.0, 1.0)]), 0.0);
        assert_eq!(
            power_heuristic_n(0, &[(1.0, INF), (1.0, INF), (1.0, 1.0)]),
            0.5
        );
        assert_eq!(
            power_heuristic_n(2, &[(1.0, INF), (1.0, INF), (1.0, 1.0)]),
            0.0
        );
        assert_eq!(balance_heuristic_n(0, &[(1.0, 2.0), (1.0, f32::NAN)]), 0.0);
    }

    /// The inline `f32` weights agree with the `f64` formula on ordinary, tiny (subnormal
    /// included), huge and degenerate inputs (the latter are handed to the `f64` formula).
    #[test]
    fn f32_path_matches_the_f64_formula() {
        let values = [
            0.0,
            1e-44,
            1e-38,
            1e-20,
            0.25,
            1.0,
            3.0,
            1e20,
            3e38,
            INF,
            f32::NAN,
            -1.0,
        ];
        let square: fn(f64) -> f64 = |r| r * r;
        let identity: fn(f64) -> f64 = |r| r;
        for n in [0.0, 1.0, 2.0, -1.0] {
            for &a in &values {
                for &b in &values {
                    let pairs = [
                        (
                            power_heuristic(n, a, 1.0, b),
                            two_strategies_f64(n, a, 1.0, b, square),
                        ),
                        (
                            balance_heuristic(n, a, 1.0, b),
                            two_strategies_f64(n, a, 1.0, b, identity),
                        ),
                        (
                            power_heuristic(1.0, a, n, b),
                            two_strategies_f64(1.0, a, n, b, square),
                        ),
                        (
                            power_heuristic(n, a, n, b),
                            two_strategies_f64(n, a, n, b, square),
                        ),
                    ];
                    for (got, want) in pairs {
                        assert!(got.is_finite() && want.is_finite(), "{n} {a} {b}");
                        assert!((0.0..=1.0).contains(&got), "{n} {a} {b} {got}");
                        assert!((got - want).abs() <= 1e-6, "{n} {a} {b}: {got} vs {want}");
                    }
                }
            }
        }
    }
}
