//! Table resolution against error and time: importance sampling the environment map × lobe
//! integrand of [`crate::environment`] from piecewise-constant 2D tables of the map,
//! box-filtered to increasing resolutions.

use crate::environment::EnvMap;
use crate::measure::{median, ns_per_call};
use mcrt::glam::Vec2;
use mcrt::sampling::distribution::PiecewiseConstant2D;
use rand_core::{RngCore, SeedableRng};
use rand_pcg::Pcg32;
use std::time::Instant;

/// How much work the study does.
#[derive(Debug, Clone, Copy)]
pub struct DistEffort {
    /// Width of the environment map (height is half); tables are box-filtered from it.
    pub base_width: usize,
    /// Widest table (tables are 2:1, from 16×8 up, plus a 1×1 uniform baseline).
    pub max_width: usize,
    /// Samples per estimate.
    pub n: usize,
    /// Independent estimates for the measured RMSE.
    pub m: usize,
    /// Timed builds (median reported); sampling is timed over 4 × runs + 1 short runs.
    pub runs: usize,
}

/// One table resolution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DistRow {
    /// Columns.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// Time to build the table from the cell values, ms.
    pub build_ms: f64,
    /// ns per `sample` call.
    pub ns_sample: f64,
    /// Measured relative RMSE of an `n`-sample estimate (over `m` estimates).
    pub rel_rmse: f64,
    /// Relative variance of one sample, Var[g/p]/I², by quadrature at the map's pixel
    /// centres (so the RMSE at `n` samples is √(rel_var / n)).
    pub rel_var: f64,
}

impl DistRow {
    /// Samples needed for a relative RMSE of `target`.
    pub fn samples_for(&self, target: f64) -> f64 {
        self.rel_var / (target * target)
    }
}

/// A uniform random point of `[0,1)²`.
fn next_u(rng: &mut Pcg32) -> Vec2 {
    let f = |r: &mut Pcg32| (r.next_u32() >> 8) as f32 * (1.0 / 16_777_216.0);
    Vec2::new(f(rng), f(rng))
}

/// Relative RMSE of `m` estimates of `n` samples each, against `truth`.
fn measured_rmse(
    map: &EnvMap,
    d: &PiecewiseConstant2D,
    truth: f64,
    (n, m): (usize, usize),
    seed: u64,
) -> f64 {
    let mut rng = Pcg32::seed_from_u64(seed);
    let mut sq = 0.0;
    for _ in 0..m {
        let mut sum = 0.0;
        for _ in 0..n {
            let (p, pdf, _) = d.sample_cell(next_u(&mut rng));
            if pdf > 0.0 {
                sum += map.integrand(f64::from(p.x), f64::from(p.y)) / f64::from(pdf);
            }
        }
        let e = sum / n as f64 - truth;
        sq += e * e;
    }
    (sq / m as f64).sqrt() / truth
}

/// Var[g/p]/I² by quadrature at the map's pixel centres: ∫ g²/p dA / I² − 1.
fn predicted_rel_var(map: &EnvMap, d: &PiecewiseConstant2D, truth: f64) -> f64 {
    let (w, h) = (map.width, map.height);
    let mut second = 0.0;
    for j in 0..h {
        let y = (j as f64 + 0.5) / h as f64;
        for i in 0..w {
            let x = (i as f64 + 0.5) / w as f64;
            let g = map.integrand(x, y);
            let p = f64::from(d.pdf(Vec2::new(x as f32, y as f32)));
            if g > 0.0 && p > 0.0 {
                second += g * g / p;
            }
        }
    }
    second / (w * h) as f64 / (truth * truth) - 1.0
}

/// The table sizes studied: 1×1, then 16×8 doubling up to `max_width` (at most the map's).
pub fn resolutions(max_width: usize) -> Vec<(usize, usize)> {
    let mut v = vec![(1, 1)];
    let mut w = 16;
    while w <= max_width {
        v.push((w, w / 2));
        w *= 2;
    }
    v
}

/// Runs the study; returns the rows and the reference integral.
pub fn run(e: DistEffort) -> Result<(Vec<DistRow>, f64), String> {
    let map = EnvMap::new(e.base_width, e.base_width / 2);
    let truth = map.reference_integral(4);
    let us: Vec<Vec2> = {
        let mut rng = Pcg32::seed_from_u64(7);
        (0..crate::warps::TIMING_POINTS)
            .map(|_| next_u(&mut rng))
            .collect()
    };
    let mut rows = Vec::new();
    for (w, h) in resolutions(e.max_width) {
        let cells = map.downsample(w, h);
        let mut builds = Vec::new();
        let mut table = None;
        for _ in 0..e.runs {
            let t = Instant::now();
            let d = PiecewiseConstant2D::new(&cells, w, h).map_err(|err| err.to_string())?;
            builds.push(t.elapsed().as_secs_f64() * 1e3);
            table = Some(d);
        }
        let d = table.ok_or("no timed runs")?;
        rows.push(DistRow {
            width: w,
            height: h,
            build_ms: median(&mut builds),
            ns_sample: ns_per_call(&us, 4 * e.runs + 1, 1, |u| d.sample_cell(u)),
            rel_rmse: measured_rmse(&map, &d, truth, (e.n, e.m), 1 + w as u64),
            rel_var: predicted_rel_var(&map, &d, truth),
        });
    }
    Ok((rows, truth))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finer_tables_reduce_the_error_and_prediction_matches() {
        let e = DistEffort {
            base_width: 256,
            max_width: 64,
            n: 64,
            m: 400,
            runs: 1,
        };
        let (rows, truth) = run(e).expect("tables build");
        assert!(truth.is_finite() && truth > 0.0);
        assert_eq!(rows.len(), 4);
        let (first, last) = (rows[0], rows[rows.len() - 1]);
        assert!(
            last.rel_var.is_finite() && last.rel_var < 0.1 * first.rel_var,
            "{rows:?}"
        );
        for r in &rows {
            let predicted = (r.rel_var / e.n as f64).sqrt();
            assert!(r.rel_rmse.is_finite() && predicted.is_finite());
            // 400 estimates give the RMSE to about ±10% (heavier tails at coarse tables).
            assert!(
                (r.rel_rmse / predicted - 1.0).abs() < 0.35,
                "{r:?} {predicted}"
            );
        }
    }

    #[test]
    fn resolutions_double() {
        assert_eq!(resolutions(64), vec![(1, 1), (16, 8), (32, 16), (64, 32)]);
    }
}
