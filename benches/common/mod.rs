//! Helpers shared by the benchmarks: a short criterion configuration and pre-generated inputs.
// Each bench file uses a different subset of these helpers.
#![allow(dead_code)]

use std::time::Duration;

use criterion::Criterion;
use mcrt::glam::Vec2;

/// Inputs per timed iteration: criterion's time per iteration divided by this is ns per call.
pub const BATCH: usize = 1024;

/// A short configuration so that every bench file runs in well under a minute.
pub fn config() -> Criterion {
    Criterion::default()
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_millis(1500))
        .sample_size(20)
        .without_plots()
}

/// SplitMix64 step: deterministic input generation outside the timed loops.
fn splitmix(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// `n` values in `[0, 1)` with 24-bit resolution, from a fixed seed.
pub fn uniforms_1d(n: usize, seed: u64) -> Vec<f32> {
    let mut s = seed;
    (0..n)
        .map(|_| (splitmix(&mut s) >> 40) as f32 / 16_777_216.0)
        .collect()
}

/// `n` points in `[0, 1)²`, from a fixed seed.
pub fn uniforms_2d(n: usize, seed: u64) -> Vec<Vec2> {
    let v = uniforms_1d(2 * n, seed);
    v.chunks_exact(2).map(|c| Vec2::new(c[0], c[1])).collect()
}
