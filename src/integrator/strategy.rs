//! Which sampling strategies an estimator uses at every path vertex, and their MIS weights.

use crate::sampling::mis::{balance_heuristic, power_heuristic};

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
            Strategy::MisBalance => balance_heuristic(n_light, pdf_light, n_bsdf, pdf_bsdf),
            Strategy::MisPower => power_heuristic(n_light, pdf_light, n_bsdf, pdf_bsdf),
        }
    }

    /// Weight of an emitter hit by a (non-delta) BSDF sample of density `pdf_bsdf`, against
    /// light sampling of density `pdf_light`. In `[0, 1]`.
    #[inline]
    pub fn bsdf_weight(self, n_bsdf: f32, pdf_bsdf: f32, n_light: f32, pdf_light: f32) -> f32 {
        match self {
            Strategy::BsdfOnly => 1.0,
            Strategy::LightOnly => 0.0,
            Strategy::MisBalance => balance_heuristic(n_bsdf, pdf_bsdf, n_light, pdf_light),
            Strategy::MisPower => power_heuristic(n_bsdf, pdf_bsdf, n_light, pdf_light),
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
