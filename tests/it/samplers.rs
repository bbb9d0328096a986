//! Properties of the samplers in `mcrt::sampling::sampler`: determinism, range, decorrelation,
//! stratification (strata, elementary intervals) and integration error.

use mcrt::glam::Vec2;
use mcrt::sampling::sampler::{
    CmjSampler, HaltonSampler, IndependentSampler, R2Sampler, SampleSource, Sampler,
    StratifiedSampler,
};
#[cfg(feature = "sobol")]
use mcrt::sampling::sampler::{Sobol4dSampler, SobolSampler};
use proptest::prelude::*;

/// A draw pattern close to a path tracer's: 2D, 2D, 1D, 2D, 1D, ...
#[derive(Debug, Clone, Copy, PartialEq)]
enum Value {
    One(f32),
    Two(Vec2),
}

fn draw_pattern<S: Sampler>(s: &mut S, pixel: [u32; 2], index: u32, n: usize) -> Vec<Value> {
    s.start_pixel_sample(pixel, index);
    (0..n)
        .map(|d| {
            if d % 3 == 2 {
                Value::One(s.next_1d())
            } else {
                Value::Two(s.next_2d())
            }
        })
        .collect()
}

fn in_unit(x: f32) -> bool {
    x.is_finite() && (0.0..1.0).contains(&x)
}

fn all_samplers(spp: u32, seed: u64) -> (IndependentSampler, StratifiedSampler) {
    (
        IndependentSampler::new(spp, seed).unwrap(),
        StratifiedSampler::new(spp, seed, true).unwrap(),
    )
}

/// Runs `check` on each sampler type, built for `spp` and `seed`.
macro_rules! for_each_sampler {
    ($spp:expr, $seed:expr, $check:expr) => {{
        let (a, b) = all_samplers($spp, $seed);
        $check(a, "independent");
        $check(b, "stratified");
        $check(
            StratifiedSampler::new($spp, $seed, false).unwrap(),
            "stratified, no jitter",
        );
        #[cfg(feature = "sobol")]
        $check(SobolSampler::new($spp, $seed).unwrap(), "sobol");
        #[cfg(feature = "sobol")]
        $check(Sobol4dSampler::new($spp, $seed).unwrap(), "sobol4d");
        $check(HaltonSampler::new($spp, $seed).unwrap(), "halton");
        $check(R2Sampler::new($spp, $seed).unwrap(), "r2");
        $check(CmjSampler::new($spp, $seed, true).unwrap(), "cmj");
        $check(
            CmjSampler::new($spp, $seed, false).unwrap(),
            "cmj, no jitter",
        );
    }};
}

fn check_deterministic<S: Sampler>(mut s: S, name: &str) {
    let mut other = s.clone();
    let first = draw_pattern(&mut s, [17, 5], 3, 20);
    draw_pattern(&mut other, [1, 1], 7, 5); // other history, same answer
    draw_pattern(&mut s, [0, 9], 2, 9);
    assert_eq!(first, draw_pattern(&mut other, [17, 5], 3, 20), "{name}");
    assert_eq!(first, draw_pattern(&mut s, [17, 5], 3, 20), "{name}");
}

#[test]
fn values_depend_only_on_seed_pixel_and_index() {
    for_each_sampler!(16, 42, check_deterministic);
}

fn check_inputs_matter<S: Sampler>(mut s: S, name: &str) {
    let base = draw_pattern(&mut s, [4, 4], 1, 6);
    assert_ne!(base, draw_pattern(&mut s, [5, 4], 1, 6), "{name}: pixel x");
    assert_ne!(base, draw_pattern(&mut s, [4, 5], 1, 6), "{name}: pixel y");
    assert_ne!(base, draw_pattern(&mut s, [4, 4], 2, 6), "{name}: index");
}

#[test]
fn pixel_and_index_change_the_values() {
    for_each_sampler!(16, 42, check_inputs_matter);
}

#[test]
fn the_seed_changes_the_values() {
    let mut a = IndependentSampler::new(4, 1).unwrap();
    let mut b = IndependentSampler::new(4, 2).unwrap();
    assert_ne!(
        draw_pattern(&mut a, [0, 0], 0, 4),
        draw_pattern(&mut b, [0, 0], 0, 4)
    );
    let mut a = StratifiedSampler::new(4, 1, true).unwrap();
    let mut b = StratifiedSampler::new(4, 2, true).unwrap();
    assert_ne!(
        draw_pattern(&mut a, [0, 0], 0, 4),
        draw_pattern(&mut b, [0, 0], 0, 4)
    );
    #[cfg(feature = "sobol")]
    {
        let mut a = SobolSampler::new(4, 1).unwrap();
        let mut b = SobolSampler::new(4, 2).unwrap();
        assert_ne!(
            draw_pattern(&mut a, [0, 0], 0, 4),
            draw_pattern(&mut b, [0, 0], 0, 4)
        );
    }
}

fn check_range<S: Sampler>(mut s: S, name: &str) {
    let spp = s.samples_per_pixel();
    for p in 0..64 {
        for i in 0..spp * 2 {
            for v in draw_pattern(&mut s, [p, p / 8], i, 12) {
                let ok = match v {
                    Value::One(x) => in_unit(x),
                    Value::Two(u) => in_unit(u.x) && in_unit(u.y),
                };
                assert!(ok, "{name}: {v:?} at pixel {p}, index {i}");
            }
        }
    }
}

#[test]
fn values_lie_in_the_half_open_unit_interval() {
    for_each_sampler!(16, 3, check_range);
    for_each_sampler!(7, 3, check_range);
}

/// Pearson correlation of two equally long series, in f64.
fn correlation(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len() as f64;
    let (ma, mb) = (a.iter().sum::<f64>() / n, b.iter().sum::<f64>() / n);
    let cov: f64 = a.iter().zip(b).map(|(x, y)| (x - ma) * (y - mb)).sum();
    let va: f64 = a.iter().map(|x| (x - ma).powi(2)).sum();
    let vb: f64 = b.iter().map(|y| (y - mb).powi(2)).sum();
    cov / (va * vb).sqrt()
}

/// Correlation between neighbouring pixels' values at the same (index, dimension). With 8192
/// pairs the correlation of independent values has a standard deviation of about 0.011.
fn pixel_correlation<S: Sampler>(mut s: S) -> f64 {
    let (mut a, mut b) = (Vec::new(), Vec::new());
    for p in 0..256u32 {
        for i in 0..16 {
            s.start_pixel_sample([p, 7], i);
            let u = s.next_2d();
            s.start_pixel_sample([p + 1, 7], i);
            let v = s.next_2d();
            a.extend([f64::from(u.x), f64::from(u.y)]);
            b.extend([f64::from(v.x), f64::from(v.y)]);
        }
    }
    correlation(&a, &b)
}

fn check_pixels_decorrelated<S: Sampler>(s: S, name: &str) {
    let r = pixel_correlation(s);
    assert!(r.is_finite() && r.abs() < 0.05, "{name}: correlation {r}");
}

#[test]
fn neighbouring_pixels_are_decorrelated() {
    for_each_sampler!(16, 11, check_pixels_decorrelated);
}

/// A broken sampler that gives every pixel the values of pixel (0, 0).
#[derive(Clone)]
struct SamePixel<S>(S);

impl<S: Sampler> Sampler for SamePixel<S> {
    fn start_pixel_sample(&mut self, _pixel: [u32; 2], sample_index: u32) {
        self.0.start_pixel_sample([0, 0], sample_index);
    }
    fn samples_per_pixel(&self) -> u32 {
        self.0.samples_per_pixel()
    }
}

impl<S: Sampler> SampleSource for SamePixel<S> {
    fn next_1d(&mut self) -> f32 {
        self.0.next_1d()
    }
    fn next_2d(&mut self) -> Vec2 {
        self.0.next_2d()
    }
}

#[test]
fn decorrelation_check_rejects_a_sampler_that_ignores_the_pixel() {
    let r = pixel_correlation(SamePixel(IndependentSampler::new(16, 11).unwrap()));
    assert!(r.is_finite() && r > 0.99, "correlation {r}");
}

/// Within a pixel, successive dimensions are uncorrelated (the padding works).
fn check_dimensions_decorrelated<S: Sampler>(mut s: S, name: &str) {
    let (mut a, mut b) = (Vec::new(), Vec::new());
    let spp = s.samples_per_pixel();
    for p in 0..128u32 {
        for i in 0..spp {
            s.start_pixel_sample([p, 0], i);
            let (u, v) = (s.next_2d(), s.next_2d());
            a.extend([f64::from(u.x), f64::from(u.y)]);
            b.extend([f64::from(v.x), f64::from(v.y)]);
        }
    }
    let r = correlation(&a, &b);
    assert!(r.is_finite() && r.abs() < 0.06, "{name}: correlation {r}");
}

#[test]
fn dimensions_are_decorrelated() {
    for_each_sampler!(16, 12, check_dimensions_decorrelated);
}

/// Counts, for several pixels and the first 6 2D dimensions, how many of `count` samples
/// starting at `first` fall in each cell of an `nx × ny` grid; returns every (pixel, dimension)
/// whose cells do not all hold `count / (nx · ny)`.
fn cell_violations<S: Sampler>(s: &mut S, first: u32, count: u32, grid: (u32, u32)) -> Vec<String> {
    let (nx, ny) = grid;
    let mut bad = Vec::new();
    for pixel in [[0, 0], [1, 0], [13, 99], [4000, 3]] {
        for dim in 0..6usize {
            let mut cells = vec![0u32; (nx * ny) as usize];
            for i in first..first + count {
                s.start_pixel_sample(pixel, i);
                for _ in 0..dim {
                    s.next_2d();
                }
                let u = s.next_2d();
                assert!(in_unit(u.x) && in_unit(u.y), "{u:?}");
                let (cx, cy) = ((u.x * nx as f32) as u32, (u.y * ny as f32) as u32);
                cells[(cy.min(ny - 1) * nx + cx.min(nx - 1)) as usize] += 1;
            }
            let per_cell = count / (nx * ny);
            if !cells.iter().all(|&c| c == per_cell) {
                bad.push(format!(
                    "pixel {pixel:?} dim {dim} grid {nx}x{ny}: {cells:?}"
                ));
            }
        }
    }
    bad
}

/// Asserts that [`cell_violations`] finds none.
fn assert_cells<S: Sampler>(s: &mut S, first: u32, count: u32, grid: (u32, u32), name: &str) {
    let bad = cell_violations(s, first, count, grid);
    assert!(bad.is_empty(), "{name}: {bad:?}");
}

/// Same as [`cell_violations`] for 1D values in `n` intervals (drawn after `dim` other 1D
/// values).
fn interval_violations<S: Sampler>(s: &mut S, first: u32, count: u32, n: u32) -> Vec<String> {
    let mut bad = Vec::new();
    for pixel in [[0, 0], [2, 5], [640, 480]] {
        for dim in 0..6usize {
            let mut cells = vec![0u32; n as usize];
            for i in first..first + count {
                s.start_pixel_sample(pixel, i);
                for _ in 0..dim {
                    s.next_1d();
                }
                let x = s.next_1d();
                assert!(in_unit(x), "{x}");
                cells[((x * n as f32) as u32).min(n - 1) as usize] += 1;
            }
            if !cells.iter().all(|&c| c == count / n) {
                bad.push(format!(
                    "pixel {pixel:?} dim {dim} {n} intervals: {cells:?}"
                ));
            }
        }
    }
    bad
}

/// Asserts that [`interval_violations`] finds none.
fn assert_intervals<S: Sampler>(s: &mut S, first: u32, count: u32, n: u32, name: &str) {
    let bad = interval_violations(s, first, count, n);
    assert!(bad.is_empty(), "{name}: {bad:?}");
}

/// The stratification checks have power: independent values are not stratified (a 4 × 4 grid
/// filled one per cell by chance has probability 16!/16¹⁶ ≈ 10⁻⁶ per pixel and dimension).
#[test]
fn stratification_checks_reject_independent_values() {
    let mut s = IndependentSampler::new(16, 5).unwrap();
    assert_eq!(cell_violations(&mut s, 0, 16, (4, 4)).len(), 24);
    assert_eq!(interval_violations(&mut s, 0, 16, 16).len(), 18);
}

#[test]
fn stratified_square_counts_put_one_sample_in_each_stratum() {
    for n in [1u32, 2, 3, 4, 5, 8, 11] {
        for jitter in [true, false] {
            let mut s = StratifiedSampler::new(n * n, 5, jitter).unwrap();
            let name = format!("stratified n={n} jitter={jitter}");
            assert_cells(&mut s, 0, n * n, (n, n), &name);
            assert_intervals(&mut s, 0, n * n, n * n, &name);
            // A second round of indices is stratified on its own.
            assert_cells(&mut s, n * n, n * n, (n, n), &name);
        }
    }
}

#[test]
fn stratified_non_square_counts_round_up_and_stay_stratified() {
    for spp in [2u32, 3, 5, 10, 50] {
        let mut s = StratifiedSampler::new(spp, 8, true).unwrap();
        let total = s.samples_per_pixel();
        let n = s.resolution();
        assert_eq!(total, n * n);
        assert!(
            total >= spp && (n - 1) * (n - 1) < spp,
            "spp {spp} -> {total}"
        );
        assert_cells(&mut s, 0, total, (n, n), "stratified, rounded");
        assert_intervals(&mut s, 0, total, total, "stratified, rounded");
    }
}

/// Correlated multi-jittering: for `N = m × n` samples (square or not), each full round puts
/// one point in every cell of the `m × n` grid, one in every `1/N` column and one in every
/// `1/N` row of each 2D dimension, and one in every `1/N` interval of each 1D dimension.
#[test]
fn cmj_rounds_are_multi_jittered() {
    for spp in [1u32, 2, 4, 6, 12, 16, 20, 64, 100] {
        for jitter in [true, false] {
            let mut s = CmjSampler::new(spp, 13, jitter).unwrap();
            let (m, n) = s.grid();
            assert_eq!(m * n, spp, "{spp} is already m × n");
            let name = format!("cmj {m} x {n} jitter={jitter}");
            assert_cells(&mut s, 0, spp, (m, n), &name);
            assert_cells(&mut s, 0, spp, (spp, 1), &format!("{name}, columns"));
            assert_cells(&mut s, 0, spp, (1, spp), &format!("{name}, rows"));
            assert_intervals(&mut s, 0, spp, spp, &name);
            // A later round of indices is multi-jittered on its own.
            assert_cells(
                &mut s,
                2 * spp,
                spp,
                (m, n),
                &format!("{name}, third round"),
            );
            assert_cells(
                &mut s,
                2 * spp,
                spp,
                (spp, 1),
                &format!("{name}, third round"),
            );
        }
    }
}

/// The multi-jitter checks have power: a stratified sampler's 16 points fill the 4 × 4
/// cells but not the 16 fine columns (its jitter is free within each cell).
#[test]
fn multi_jitter_check_rejects_plain_jittering() {
    let mut s = StratifiedSampler::new(16, 13, true).unwrap();
    assert!(cell_violations(&mut s, 0, 16, (4, 4)).is_empty());
    assert_eq!(cell_violations(&mut s, 0, 16, (16, 1)).len(), 24);
}

/// For `2^k` points: every elementary interval of shape `2^-a × 2^-(k-a)` holds one point.
#[cfg(feature = "sobol")]
#[test]
fn sobol_first_power_of_two_samples_form_a_0_k_2_net() {
    let mut s = SobolSampler::new(1024, 77).unwrap();
    for k in 0..=10u32 {
        for a in 0..=k {
            let name = format!("sobol k={k} shape 2^{a} x 2^{}", k - a);
            assert_cells(&mut s, 0, 1 << k, (1 << a, 1 << (k - a)), &name);
        }
        assert_intervals(&mut s, 0, 1 << k, 1 << k, &format!("sobol 1D k={k}"));
    }
    // Later aligned blocks of 2^k indices are nets too (the sequence is progressive).
    assert_cells(&mut s, 256, 256, (16, 16), "sobol second block of 256");
    assert_cells(&mut s, 1 << 16, 64, (8, 8), "sobol past 2^16");
}

/// A smooth integrand on the unit square with a known integral.
fn smooth(u: Vec2) -> f64 {
    let (x, y) = (f64::from(u.x), f64::from(u.y));
    (x * y).exp() + (3.0 * x).sin() * y * y
}

/// The exact integral of [`smooth`]: Σₙ 1/(n!·(n+1)²) + (1 − cos 3)/9.
fn smooth_integral() -> f64 {
    let mut sum = 0.0;
    let mut factorial = 1.0;
    for n in 0..20 {
        if n > 0 {
            factorial *= f64::from(n);
        }
        sum += 1.0 / (factorial * f64::from(n + 1).powi(2));
    }
    sum + (1.0 - 3f64.cos()) / 9.0
}

/// Root mean square error over 128 pixels of the `spp`-sample estimate in dimension 2.
fn rms_error<S: Sampler>(mut s: S) -> f64 {
    let exact = smooth_integral();
    let spp = s.samples_per_pixel();
    let mut sq = 0.0;
    for p in 0..128u32 {
        let mut est = 0.0;
        for i in 0..spp {
            s.start_pixel_sample([p, 1], i);
            s.next_2d();
            s.next_1d();
            est += smooth(s.next_2d());
        }
        sq += (est / f64::from(spp) - exact).powi(2);
    }
    (sq / 128.0).sqrt()
}

#[test]
fn smooth_integrand_error_is_lower_than_independent() {
    let independent = rms_error(IndependentSampler::new(256, 1).unwrap());
    let stratified = rms_error(StratifiedSampler::new(256, 1, true).unwrap());
    println!("rms error at 256 spp: independent {independent:e}, stratified {stratified:e}");
    assert!(independent.is_finite() && stratified.is_finite());
    // Independent: about σ/16 (measured 3.1e-2); stratified on a smooth integrand: O(N^-1)
    // (measured 2.3e-3); Owen-scrambled Sobol: O(N^-1.5) (measured 3.6e-4).
    assert!(
        stratified < independent / 4.0,
        "stratified {stratified:e} vs independent {independent:e}"
    );
    let cmj = rms_error(CmjSampler::new(256, 1, true).unwrap());
    println!("rms error at 256 spp: cmj {cmj:e}");
    assert!(
        cmj.is_finite() && cmj < independent / 4.0,
        "cmj {cmj:e} vs independent {independent:e}"
    );
    #[cfg(feature = "sobol")]
    {
        let sobol = rms_error(SobolSampler::new(256, 1).unwrap());
        println!("rms error at 256 spp: sobol {sobol:e}");
        assert!(
            sobol.is_finite() && sobol < independent / 20.0 && sobol < stratified / 2.0,
            "sobol {sobol:e} vs independent {independent:e}, stratified {stratified:e}"
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 256,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x5a3b),
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn any_seed_pixel_and_index_give_values_in_range(
        seed in any::<u64>(), x in any::<u32>(), y in any::<u32>(), index in any::<u32>(),
        spp in 1u32..5000,
    ) {
        let mut failures = Vec::new();
        for_each_sampler!(spp, seed, |mut s: _, name: &str| {
            for v in draw_pattern(&mut s, [x, y], index, 9) {
                let ok = match v {
                    Value::One(t) => in_unit(t),
                    Value::Two(u) => in_unit(u.x) && in_unit(u.y),
                };
                if !ok {
                    failures.push(format!("{name}: {v:?}"));
                }
            }
        });
        prop_assert!(failures.is_empty(), "{:?}", failures);
    }
}

// A crate root resolves child modules beside itself, so the path names the subdirectory.
#[path = "samplers/dimensions.rs"]
mod dimensions;
#[path = "samplers/low_discrepancy.rs"]
mod low_discrepancy;
#[cfg(feature = "sobol")]
#[path = "samplers/sobol_4d.rs"]
mod sobol_4d;
