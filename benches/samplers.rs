//! ns per 2D and per 1D sample value for each sampler of `mcrt::sampling::sampler`.
//!
//! Run: `cargo bench --features bench --bench samplers`. Each timed iteration starts `BATCH / 8` pixel samples
//! and draws 8 2D (or 1D) values from each, so time per iteration / `BATCH` is the cost of one
//! value including its share of `start_pixel_sample`; `start_pixel_sample` is also timed alone.
//! On a shared machine only the ratios between samplers within one run mean anything; the
//! instruction counts of docs/performance-profile.md are the stable figures.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use mcrt::glam::Vec2;
use mcrt::sampling::sampler::{
    AnySampler, CmjSampler, HaltonSampler, IndependentSampler, R2Sampler, Sampler,
    StratifiedSampler,
};
#[cfg(feature = "sobol")]
use mcrt::sampling::sampler::{Sobol4dSampler, SobolSampler};
use std::hint::black_box;

mod common;
use common::{config, BATCH};

/// 2D values drawn per pixel sample in the timed loop (a short path's worth).
const DIMS: usize = 8;

/// Pixel `i` of a 64-pixel-wide tile, so nothing per pixel can be hoisted out of the loop.
fn pixel(i: u32) -> [u32; 2] {
    [i & 63, i >> 6]
}

fn draw_2d<S: Sampler>(s: &mut S, index: u32) -> Vec2 {
    let mut acc = Vec2::ZERO;
    for i in 0..(BATCH / DIMS) as u32 {
        s.start_pixel_sample(pixel(i), index);
        for _ in 0..DIMS {
            acc += black_box(s.next_2d());
        }
    }
    acc
}

fn draw_1d<S: Sampler>(s: &mut S, index: u32) -> f32 {
    let mut acc = 0.0;
    for i in 0..(BATCH / DIMS) as u32 {
        s.start_pixel_sample(pixel(i), index);
        for _ in 0..DIMS {
            acc += black_box(s.next_1d());
        }
    }
    acc
}

fn starts_only<S: Sampler>(s: &mut S, index: u32) {
    for i in 0..BATCH as u32 {
        s.start_pixel_sample(pixel(i), index);
        black_box(&mut *s);
    }
}

fn bench_one<S: Sampler>(c: &mut Criterion, name: &str, mut s: S) {
    let mut group = c.benchmark_group(format!("sampler/{name}"));
    group.throughput(Throughput::Elements(BATCH as u64));
    group.bench_function("next_2d", |b| b.iter(|| draw_2d(&mut s, black_box(5))));
    group.bench_function("next_1d", |b| b.iter(|| draw_1d(&mut s, black_box(5))));
    group.bench_function("start_pixel_sample", |b| {
        b.iter(|| starts_only(&mut s, black_box(5)))
    });
    group.finish();
}

fn samplers(c: &mut Criterion) {
    bench_one(c, "independent", IndependentSampler::new(128, 1).unwrap());
    bench_one(
        c,
        "stratified",
        StratifiedSampler::new(128, 1, true).unwrap(),
    );
    #[cfg(feature = "sobol")]
    bench_one(c, "sobol", SobolSampler::new(128, 1).unwrap());
    #[cfg(feature = "sobol")]
    bench_one(c, "sobol4d", Sobol4dSampler::new(128, 1).unwrap());
    bench_one(c, "cmj", CmjSampler::new(128, 1, true).unwrap());
    bench_one(c, "halton", HaltonSampler::new(144, 1).unwrap());
    bench_one(c, "r2", R2Sampler::new(128, 1).unwrap());
    #[cfg(feature = "sobol")]
    raw_sobol(c);
    // The cost of choosing at run time: the same independent sampler behind `AnySampler`.
    let any: AnySampler = IndependentSampler::new(128, 1).unwrap().into();
    bench_one(c, "any(independent)", any);
}

/// The `sobol_burley` calls alone (two dimensions via `sample_4d` or two `sample` calls, a new
/// seed per call as our padding uses): what `SobolSampler` cost before its scalar path, which
/// returns the same values.
#[cfg(feature = "sobol")]
fn raw_sobol(c: &mut Criterion) {
    let mut group = c.benchmark_group("sampler/sobol_burley_raw");
    group.throughput(Throughput::Elements(BATCH as u64));
    group.bench_function("sample_4d", |b| {
        b.iter(|| {
            for i in 0..BATCH as u32 {
                black_box(sobol_burley::sample_4d(
                    black_box(i & 127),
                    0,
                    i.wrapping_mul(0x9e37_79b9),
                ));
            }
        })
    });
    group.bench_function("sample x2", |b| {
        b.iter(|| {
            for i in 0..BATCH as u32 {
                let seed = i.wrapping_mul(0x9e37_79b9);
                let index = black_box(i & 127);
                black_box(sobol_burley::sample(index, 0, seed));
                black_box(sobol_burley::sample(index, 1, seed));
            }
        })
    });
    group.finish();
}

criterion_group! {
    name = benches;
    config = config();
    targets = samplers
}
criterion_main!(benches);
