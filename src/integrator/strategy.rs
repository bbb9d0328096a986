//! Which sampling strategies an estimator uses at every path vertex, and their MIS weights.

use crate::sampling::mis::{balance_heuristic, power_heuristic};

/// The power (`POWER`, β = 2) or balance heuristic weight of strategy `f` against `g`, in
/// `[0, 1]`: `1 / (1 + (g/f)^β)` with `f = n_f·pdf_f`, `g = n_g·pdf_g`. Computed inline in
/// `f32` in the usual case (both products finite, `f > 0`, `n_g, pdf_g ≥ 0`), where it agrees with
/// [`power_heuristic`] / [`balance_heuristic`] to `f32` rounding; every other input (zero,
/// infinite, NaN, negative) goes to those functions and their documented edge cases.
#[inline(always)]
fn two<const POWER: bool>(n_f: f32, pdf_f: f32, n_g: f32, pdf_g: f32) -> f32 {
    let (f, g) = (n_f * pdf_f, n_g * pdf_g);
    // `n_g, pdf_g ≥ 0` separately: a negative input times 0 would pass as `g = −0`.
    let valid_g = n_g >= 0.0 && pdf_g >= 0.0 && g < f32::INFINITY;
    // `f > 0` with `pdf_f > 0` also means `n_f > 0` (two negatives would multiply to f > 0).
    if pdf_f > 0.0 && f > 0.0 && f < f32::INFINITY && valid_g {
        let r = g / f;
        // r = ∞ (f underflowing against g) gives 0, as the f64 formula does to f32 precision.
        return 1.0 / (1.0 + if POWER { r * r } else { r });
    }
    if POWER {
        power_heuristic(n_f, pdf_f, n_g, pdf_g)
    } else {
        balance_heuristic(n_f, pdf_f, n_g, pdf_g)
    }
}

/// How light arriving at a vertex is estimated.
///
/// Delta BSDFs are always handled by BSDF sampling and delta lights always by light
/// sampling (each is the only strategy that can find them), so every strategy converges to
/// the same image on every scene; the switch changes only how the non-delta parts are
/// found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Strategy {
    /// BSDF sampling only: emitters count when a sampled ray hits them.
    BsdfOnly,
    /// Light sampling only: emitters hit by BSDF sampling count only from the camera or
    /// after a delta bounce.
    LightOnly,
    /// Both, combined with the balance heuristic.
    MisBalance,
    /// Both, combined with the power heuristic (β = 2), as Mitsuba 3 does.
    #[default]
    MisPower,
}

impl Strategy {
    /// Whether next-event estimation of non-delta lights is used.
    #[inline]
    pub fn samples_lights(self) -> bool {
        !matches!(self, Strategy::BsdfOnly)
    }

    /// Weight of a light sample of solid-angle density `pdf_light` (with `n_light` such
    /// samples per vertex) against BSDF sampling of density `pdf_bsdf` (`n_bsdf` samples).
    /// In `[0, 1]`.
    #[inline]
    pub fn light_weight(self, n_light: f32, pdf_light: f32, n_bsdf: f32, pdf_bsdf: f32) -> f32 {
        match self {
            Strategy::BsdfOnly => 0.0,
            Strategy::LightOnly => 1.0,
            Strategy::MisBalance => two::<false>(n_light, pdf_light, n_bsdf, pdf_bsdf),
            Strategy::MisPower => two::<true>(n_light, pdf_light, n_bsdf, pdf_bsdf),
        }
    }

    /// Weight of an emitter hit by a (non-delta) BSDF sample of density `pdf_bsdf`, against
    /// light sampling of density `pdf_light`. In `[0, 1]`.
    #[inline]
    pub fn bsdf_weight(self, n_bsdf: f32, pdf_bsdf: f32, n_light: f32, pdf_light: f32) -> f32 {
        match self {
            Strategy::BsdfOnly => 1.0,
            Strategy::LightOnly => 0.0,
            Strategy::MisBalance => two::<false>(n_bsdf, pdf_bsdf, n_light, pdf_light),
            Strategy::MisPower => two::<true>(n_bsdf, pdf_bsdf, n_light, pdf_light),
        }
    }

    /// Parses `bsdf`, `light`, `balance` or `power`.
    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "bsdf" => Some(Strategy::BsdfOnly),
            "light" => Some(Strategy::LightOnly),
            "balance" => Some(Strategy::MisBalance),
            "power" => Some(Strategy::MisPower),
            _ => None,
        }
    }

    /// The name [`Strategy::parse`] accepts.
    pub fn name(self) -> &'static str {
        match self {
            Strategy::BsdfOnly => "bsdf",
            Strategy::LightOnly => "light",
            Strategy::MisBalance => "balance",
            Strategy::MisPower => "power",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_sum_to_one_for_mis() {
        for s in [Strategy::MisBalance, Strategy::MisPower] {
            for (a, b) in [(1.0, 1.0), (0.1, 7.0), (3.0, 0.0), (1e30, 2.0)] {
                let w = s.light_weight(1.0, a, 1.0, b) + s.bsdf_weight(1.0, b, 1.0, a);
                assert!(w.is_finite() && (w - 1.0).abs() < 1e-5, "{s:?} {a} {b} {w}");
            }
        }
        for s in [Strategy::BsdfOnly, Strategy::LightOnly] {
            let w = s.light_weight(1.0, 0.3, 1.0, 0.7) + s.bsdf_weight(1.0, 0.7, 1.0, 0.3);
            assert_eq!(w, 1.0);
        }
    }

    /// The inline `f32` weights agree with `sampling::mis` on ordinary, tiny, huge and
    /// degenerate inputs (the latter are handed to `sampling::mis`).
    #[test]
    fn inline_weights_match_sampling_mis() {
        let values = [
            0.0,
            1e-38,
            1e-20,
            0.25,
            1.0,
            3.0,
            1e20,
            3e38,
            f32::INFINITY,
            f32::NAN,
            -1.0,
        ];
        for n in [0.0, 1.0, 2.0, -1.0] {
            for &a in &values {
                for &b in &values {
                    let pairs = [
                        (two::<true>(n, a, 1.0, b), power_heuristic(n, a, 1.0, b)),
                        (two::<false>(n, a, 1.0, b), balance_heuristic(n, a, 1.0, b)),
                        (two::<true>(1.0, a, n, b), power_heuristic(1.0, a, n, b)),
                        (two::<true>(n, a, n, b), power_heuristic(n, a, n, b)),
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

    #[test]
    fn names_round_trip() {
        for s in [
            Strategy::BsdfOnly,
            Strategy::LightOnly,
            Strategy::MisBalance,
            Strategy::MisPower,
        ] {
            assert_eq!(Strategy::parse(s.name()), Some(s));
        }
        assert_eq!(Strategy::parse("mis"), None);
    }
}
