//! Where the f32 formulations lose digits: the relative error of θ against u₁ for the
//! smallest cone and the sharpest lobe, stable against naive.

use crate::measure::ulps;
use crate::naive::{NaiveCone, NaivePowerCosine};
use crate::plot::{Look, Plot, Series};
use crate::reference::{theta, RefCone, RefPowerCosine, Reference};
use crate::warps::AsF64;
use mcrt::glam::{DVec2, Vec2};
use mcrt::sampling::warp::{PowerCosineHemisphere, UniformCone, Warp};

/// Errors of θ (in ulps of θ) drawn at this floor when exact, so log axes can show them.
pub const FLOOR: f64 = 0.1;

/// u₁ from 2⁻²⁴ to 1 − 2⁻²⁴, `n` + 1 points evenly spaced in log₂ u₁.
fn u1s(n: usize) -> Vec<f32> {
    (0..=n)
        .map(|i| {
            (2f64.powf(-24.0 + 24.0 * i as f64 / n as f64) as f32).min(1.0 - f32::EPSILON / 2.0)
        })
        .collect()
}

/// Max over 16 azimuths of the θ error, for each u₁.
fn curve<W: Warp>(label: &str, w: &W, rf: &impl Reference, n: usize) -> Series
where
    W::Point: AsF64,
{
    let points = u1s(n)
        .into_iter()
        .map(|u1| {
            let worst = (0..16)
                .map(|j| {
                    let u2 = (j as f32 + 0.5) / 16.0;
                    let got = theta(w.sample(Vec2::new(u1, u2)).as_f64());
                    let want = theta(rf.sample(DVec2::new(f64::from(u1), f64::from(u2))).0);
                    ulps(got, want, want)
                })
                .fold(0.0, f64::max);
            (f64::from(u1), worst.max(FLOOR))
        })
        .collect();
    Series {
        label: label.into(),
        points,
        guide: false,
        look: Look::default(),
    }
}

/// The plot (errors of 0 drawn at [`FLOOR`]); `None` if a warp rejects its parameter.
pub fn plot(n: usize) -> Option<Plot> {
    let cone = UniformCone::from_angle(1e-4).ok()?;
    let lobe = PowerCosineHemisphere::new(1e6).ok()?;
    let rc = RefCone::from_angle(f64::from(1e-4f32));
    let rl = RefPowerCosine { n: 1e6 };
    Some(Plot {
        title: "Relative error of θ against u₁ (max over 16 azimuths)".into(),
        x_label: "u₁".into(),
        y_label: "error of θ (ulps of θ)".into(),
        series: vec![
            curve("UniformCone, θmax = 1e-4", &cone, &rc, n),
            curve(
                "naive cone, θmax = 1e-4",
                &NaiveCone::from_angle(1e-4),
                &rc,
                n,
            ),
            curve("PowerCosineHemisphere, n = 1e6", &lobe, &rl, n),
            curve(
                "naive power cosine, n = 1e6",
                &NaivePowerCosine { n: 1e6 },
                &rl,
                n,
            ),
        ],
        headroom: 1e3,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stable_formulas_keep_theta_naive_ones_lose_it() {
        let p = plot(24).expect("valid parameters");
        let worst = |s: &Series| s.points.iter().map(|p| p.1).fold(0.0, f64::max);
        assert!(worst(&p.series[0]).is_finite() && worst(&p.series[0]) < 8.0);
        assert!(worst(&p.series[2]).is_finite() && worst(&p.series[2]) < 8.0);
        assert!(worst(&p.series[1]) > 1e5 && worst(&p.series[3]) > 1e5);
        assert_eq!(p.series[0].points.len(), 25);
    }
}
