//! Small measuring tools: f32 ulps, order statistics, a timing loop and the unit-square point
//! set the warp study evaluates.

use std::hint::black_box;
use std::time::Instant;

/// The spacing of f32 numbers at `|x|` (the gap to the next larger f32), never below the
/// smallest normal spacing so that a zero reference does not make every error infinite.
pub fn ulp_f32(x: f64) -> f64 {
    let a = (x.abs() as f32).max(f32::MIN_POSITIVE);
    if !a.is_finite() {
        return f64::INFINITY;
    }
    f64::from(a.next_up()) - f64::from(a)
}

/// `|got − reference|` in f32 ulps of `scale`. Infinite when either value is not finite
/// (unless both are the same infinity) or when the scale is zero and `got` is not (a value
/// outside the reference's support).
pub fn ulps(got: f64, reference: f64, scale: f64) -> f64 {
    if !got.is_finite() || !reference.is_finite() {
        return if got == reference { 0.0 } else { f64::INFINITY };
    }
    if scale == 0.0 {
        return if got == reference { 0.0 } else { f64::INFINITY };
    }
    (got - reference).abs() / ulp_f32(scale)
}

/// Maximum and 99th percentile of a set of errors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ErrorStats {
    /// The largest error.
    pub max: f64,
    /// The 99th percentile (nearest rank).
    pub p99: f64,
}

impl ErrorStats {
    /// Summarises `errors` (NaN counts as infinite); an empty set gives zeros.
    pub fn of(errors: &mut [f64]) -> Self {
        if errors.is_empty() {
            return Self { max: 0.0, p99: 0.0 };
        }
        for e in errors.iter_mut() {
            if e.is_nan() {
                *e = f64::INFINITY;
            }
        }
        errors.sort_by(f64::total_cmp);
        let rank = ((0.99 * errors.len() as f64).ceil() as usize).clamp(1, errors.len());
        Self {
            max: errors[errors.len() - 1],
            p99: errors[rank - 1],
        }
    }
}

/// The median of `xs` (the mean of the two middle values for an even count); 0 if empty.
pub fn median(xs: &mut [f64]) -> f64 {
    if xs.is_empty() {
        return 0.0;
    }
    xs.sort_by(f64::total_cmp);
    let n = xs.len();
    if n % 2 == 1 {
        xs[n / 2]
    } else {
        0.5 * (xs[n / 2 - 1] + xs[n / 2])
    }
}

/// Nanoseconds per call of `f` over `inputs`: one warm-up pass, then the median over `runs`
/// timed runs of `reps` sweeps each. Every result goes through [`black_box`]. Keep runs
/// short on a shared machine: a run that is preempted counts as one outlier.
pub fn ns_per_call<I: Copy, O>(inputs: &[I], runs: usize, reps: usize, f: impl Fn(I) -> O) -> f64 {
    let sweep = || {
        for &x in inputs {
            black_box(f(black_box(x)));
        }
    };
    sweep();
    let mut times: Vec<f64> = (0..runs)
        .map(|_| {
            let t = Instant::now();
            for _ in 0..reps {
                sweep();
            }
            t.elapsed().as_secs_f64() * 1e9 / (reps * inputs.len()).max(1) as f64
        })
        .collect();
    median(&mut times)
}

/// Values of one coordinate close to the ends of `[0, 1)`, where f32 formulas lose digits.
pub const EDGES: [f32; 12] = [
    0.0,
    1.0 / 16_777_216.0,
    1.0 / 1_048_576.0,
    1.0 / 65_536.0,
    1.0 / 4096.0,
    1e-3,
    0.5,
    1.0 - 1e-3,
    1.0 - 1.0 / 4096.0,
    1.0 - 1.0 / 65_536.0,
    1.0 - 1.0 / 1_048_576.0,
    1.0 - 1.0 / 16_777_216.0,
];

/// The point set of the warp study: `n` points of the R2 low-discrepancy sequence (Roberts'
/// additive recurrence with the plastic number), then the edge values crossed with each other
/// and with 32 evenly spaced values of the other coordinate.
pub fn unit_square_points(n: usize) -> Vec<[f32; 2]> {
    const G: f64 = 1.324_717_957_244_746; // plastic number
    let (a1, a2) = (1.0 / G, 1.0 / (G * G));
    let mut pts: Vec<[f32; 2]> = (0..n)
        .map(|i| {
            let k = i as f64 + 0.5;
            [((k * a1).fract()) as f32, ((k * a2).fract()) as f32]
        })
        .map(|[x, y]| [x.min(EDGES[11]), y.min(EDGES[11])])
        .collect();
    for &a in &EDGES {
        for &b in &EDGES {
            pts.push([a, b]);
        }
        for j in 0..32 {
            let t = (j as f32 + 0.5) / 32.0;
            pts.push([a, t]);
            pts.push([t, a]);
        }
    }
    pts
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ulp_of_one_and_zero() {
        assert_eq!(ulp_f32(1.0), f64::from(f32::EPSILON));
        assert_eq!(ulp_f32(-1.0), f64::from(f32::EPSILON));
        let tiny = ulp_f32(0.0);
        assert!(tiny > 0.0 && tiny < 1e-40);
    }

    #[test]
    fn ulps_count_spacing_and_flag_non_finite() {
        let e = ulps(1.0 + 3.0 * f64::from(f32::EPSILON), 1.0, 1.0);
        assert!(e.is_finite() && (e - 3.0).abs() < 1e-9);
        assert_eq!(ulps(f64::NAN, 1.0, 1.0), f64::INFINITY);
        assert_eq!(ulps(f64::INFINITY, 1.0, 1.0), f64::INFINITY);
        assert_eq!(ulps(2.0, 2.0, 2.0), 0.0);
        assert_eq!(ulps(1e-30, 0.0, 0.0), f64::INFINITY);
        assert_eq!(ulps(0.0, 0.0, 0.0), 0.0);
    }

    #[test]
    fn stats_max_and_p99() {
        let mut v: Vec<f64> = (1..=200).map(f64::from).collect();
        let s = ErrorStats::of(&mut v);
        assert_eq!((s.max, s.p99), (200.0, 198.0));
        let mut with_nan = vec![1.0, f64::NAN];
        assert_eq!(ErrorStats::of(&mut with_nan).max, f64::INFINITY);
        assert_eq!(ErrorStats::of(&mut []).max, 0.0);
    }

    #[test]
    fn median_odd_and_even() {
        assert_eq!(median(&mut [3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&mut [4.0, 1.0, 2.0, 3.0]), 2.5);
    }

    #[test]
    fn points_lie_in_the_unit_square_and_reach_the_edges() {
        let pts = unit_square_points(1000);
        assert!(pts
            .iter()
            .all(|p| p.iter().all(|&x| (0.0..1.0).contains(&x))));
        assert!(pts.iter().any(|p| p[0] == 0.0));
        assert!(pts.iter().any(|p| p[0] == 1.0 - 2f32.powi(-24)));
        assert_eq!(pts.len(), 1000 + 12 * (12 + 64));
    }
}
