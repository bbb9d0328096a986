//! Build time and ns per sample of the distributions in `mcrt::sampling::distribution`.
//!
//! Run: `cargo bench --features bench --bench distributions`. Sample benchmarks time `BATCH` calls per
//! iteration on pre-generated sample values (time per iteration / `BATCH` = ns per call); build
//! benchmarks time one construction per iteration. The alias table is timed at 10³ and 10⁶
//! entries to show that its cost per sample does not grow with the table (O(1)), while the
//! binary search of the 1D table grows as log n (plus cache misses on large tables). The light
//! BVH is timed on 10⁴ lights (`distribution/light_bvh`: build, and `sample` and `pmf` at
//! shading points, O(log n) each).

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use mcrt::sampling::distribution::{
    AliasTable, PiecewiseConstant1D, PiecewiseConstant2D, PiecewiseLinear2D,
    WindowedPiecewiseConstant2D,
};
use mcrt::sampling::warp::{InvertibleWarp, Warp};
use mcrt::sampling::{VarianceEstimator, WeightedReservoir};

mod common;
use common::{config, uniforms_1d, uniforms_2d, BATCH};

/// Positive weights with a wide dynamic range (like light powers or texel luminances).
fn weights(n: usize, seed: u64) -> Vec<f32> {
    uniforms_1d(n, seed)
        .into_iter()
        .map(|u| 0.01 + 10.0 * u * u * u)
        .collect()
}

fn piecewise_1d(c: &mut Criterion) {
    let us = uniforms_1d(BATCH, 1);
    let mut group = c.benchmark_group("distribution/piecewise_1d");
    for n in [1_000usize, 1_000_000] {
        let w = weights(n, 2);
        group.throughput(Throughput::Elements(1));
        group.bench_with_input(BenchmarkId::new("build", n), &w, |b, w| {
            b.iter(|| PiecewiseConstant1D::new(black_box(w)).unwrap())
        });
        let d = PiecewiseConstant1D::new(&w).unwrap();
        let xs: Vec<f32> = us.iter().map(|&u| d.sample(u).0).collect();
        group.throughput(Throughput::Elements(BATCH as u64));
        group.bench_with_input(BenchmarkId::new("sample", n), &us, |b, us| {
            b.iter(|| {
                us.iter()
                    .map(|&u| black_box(d.sample(black_box(u))).1)
                    .sum::<f32>()
            })
        });
        group.bench_with_input(BenchmarkId::new("pdf", n), &xs, |b, xs| {
            b.iter(|| {
                xs.iter()
                    .map(|&x| black_box(d.pdf(black_box(x))))
                    .sum::<f32>()
            })
        });
        group.bench_with_input(BenchmarkId::new("invert", n), &xs, |b, xs| {
            b.iter(|| {
                xs.iter()
                    .map(|&x| black_box(d.invert(black_box(x))))
                    .sum::<f32>()
            })
        });
    }
    group.finish();
}

fn alias(c: &mut Criterion) {
    let us = uniforms_1d(BATCH, 3);
    let mut group = c.benchmark_group("distribution/alias");
    for n in [1_000usize, 1_000_000] {
        let w = weights(n, 4);
        group.throughput(Throughput::Elements(1));
        group.bench_with_input(BenchmarkId::new("build", n), &w, |b, w| {
            b.iter(|| AliasTable::new(black_box(w)).unwrap())
        });
        let t = AliasTable::new(&w).unwrap();
        group.throughput(Throughput::Elements(BATCH as u64));
        group.bench_with_input(BenchmarkId::new("sample", n), &us, |b, us| {
            b.iter(|| {
                us.iter()
                    .map(|&u| black_box(t.sample(black_box(u))))
                    .sum::<usize>()
            })
        });
        let idx: Vec<usize> = us.iter().map(|&u| t.sample(u)).collect();
        group.bench_with_input(BenchmarkId::new("pmf", n), &idx, |b, idx| {
            b.iter(|| {
                idx.iter()
                    .map(|&i| black_box(t.pmf(black_box(i))))
                    .sum::<f32>()
            })
        });
    }
    group.finish();
}

fn piecewise_2d(c: &mut Criterion) {
    let (width, height) = (1024usize, 512usize);
    // An environment-map-like table: a smooth sky plus a small bright sun.
    let mut values = weights(width * height, 5);
    for y in 40..44 {
        for x in 700..704 {
            values[y * width + x] = 1.0e5;
        }
    }
    let us = uniforms_2d(BATCH, 6);
    let mut group = c.benchmark_group("distribution/piecewise_2d");
    group.throughput(Throughput::Elements(1));
    group.bench_function(BenchmarkId::new("build", "1024x512"), |b| {
        b.iter(|| PiecewiseConstant2D::new(black_box(&values), width, height).unwrap())
    });
    let d = PiecewiseConstant2D::new(&values, width, height).unwrap();
    let ps: Vec<_> = us.iter().map(|&u| d.sample_cell(u).0).collect();
    group.throughput(Throughput::Elements(BATCH as u64));
    group.bench_function(BenchmarkId::new("sample", "1024x512"), |b| {
        b.iter(|| {
            us.iter()
                .map(|&u| black_box(d.sample_cell(black_box(u))).1)
                .sum::<f32>()
        })
    });
    group.bench_function(BenchmarkId::new("pdf", "1024x512"), |b| {
        b.iter(|| {
            ps.iter()
                .map(|&p| black_box(d.pdf(black_box(p))))
                .sum::<f32>()
        })
    });
    group.bench_function(BenchmarkId::new("invert", "1024x512"), |b| {
        b.iter(|| {
            ps.iter()
                .map(|&p| black_box(d.invert(black_box(p))).x)
                .sum::<f32>()
        })
    });
    group.finish();
}

/// `PiecewiseLinear2D` on a 1025 × 513 vertex grid (an environment map's texel centres).
fn piecewise_linear_2d(c: &mut Criterion) {
    let (width, height) = (1025usize, 513usize);
    let values = weights(width * height, 9);
    let us = uniforms_2d(BATCH, 10);
    let mut group = c.benchmark_group("distribution/piecewise_linear_2d");
    group.throughput(Throughput::Elements(1));
    group.bench_function(BenchmarkId::new("build", "1025x513"), |b| {
        b.iter(|| PiecewiseLinear2D::new(black_box(&values), width, height).unwrap())
    });
    let d = PiecewiseLinear2D::new(&values, width, height).unwrap();
    let ps: Vec<_> = us.iter().map(|&u| d.sample(u)).collect();
    group.throughput(Throughput::Elements(BATCH as u64));
    group.bench_function(BenchmarkId::new("sample", "1025x513"), |b| {
        b.iter(|| {
            us.iter()
                .map(|&u| black_box(d.sample(black_box(u))).x)
                .sum::<f32>()
        })
    });
    group.bench_function(BenchmarkId::new("pdf", "1025x513"), |b| {
        b.iter(|| {
            ps.iter()
                .map(|&p| black_box(d.pdf(black_box(p))))
                .sum::<f32>()
        })
    });
    group.bench_function(BenchmarkId::new("invert", "1025x513"), |b| {
        b.iter(|| {
            ps.iter()
                .map(|&p| black_box(d.invert(black_box(p))).x)
                .sum::<f32>()
        })
    });
    group.finish();
}

/// `WindowedPiecewiseConstant2D` on a 1024 × 512 table through a window of a tenth of each
/// side (a portal), and the summed-area table's build.
fn windowed_2d(c: &mut Criterion) {
    let (width, height) = (1024usize, 512usize);
    let values = weights(width * height, 11);
    let us = uniforms_2d(BATCH, 12);
    let mut group = c.benchmark_group("distribution/windowed_2d");
    group.throughput(Throughput::Elements(1));
    group.bench_function(BenchmarkId::new("build", "1024x512"), |b| {
        b.iter(|| WindowedPiecewiseConstant2D::new(black_box(&values), width, height).unwrap())
    });
    let d = WindowedPiecewiseConstant2D::new(&values, width, height).unwrap();
    let win = d
        .window(
            mcrt::glam::Vec2::new(0.3, 0.4),
            mcrt::glam::Vec2::new(0.4, 0.5),
        )
        .unwrap();
    let ps: Vec<_> = us.iter().map(|&u| win.sample(u)).collect();
    group.throughput(Throughput::Elements(BATCH as u64));
    group.bench_function(BenchmarkId::new("sample", "window 0.1x0.1"), |b| {
        b.iter(|| {
            us.iter()
                .map(|&u| black_box(win.sample(black_box(u))).x)
                .sum::<f32>()
        })
    });
    group.bench_function(BenchmarkId::new("invert", "window 0.1x0.1"), |b| {
        b.iter(|| {
            ps.iter()
                .map(|&p| black_box(win.invert(black_box(p))).x)
                .sum::<f32>()
        })
    });
    group.finish();
}

/// ns per offered item of a weighted reservoir (a stream of `BATCH` items), and per value of
/// the Welford estimator.
fn streaming(c: &mut Criterion) {
    let w = weights(BATCH, 7);
    let us = uniforms_1d(BATCH, 8);
    let mut group = c.benchmark_group("distribution/streaming");
    group.throughput(Throughput::Elements(BATCH as u64));
    group.bench_function("WeightedReservoir::add", |b| {
        b.iter(|| {
            let mut r = WeightedReservoir::new();
            for (i, (&wi, &u)) in w.iter().zip(&us).enumerate() {
                r.add(i, black_box(wi), black_box(u));
            }
            black_box(r.into_item())
        })
    });
    group.bench_function("VarianceEstimator::add", |b| {
        b.iter(|| {
            let mut v = VarianceEstimator::new();
            for &x in &w {
                v.add(f64::from(black_box(x)));
            }
            black_box(v.variance())
        })
    });
    group.finish();
}

/// `LightBvh` over 10⁴ lights (points and one-sided panels in `[-10, 10]³`, powers from
/// [`weights`]): build, then `sample` and `pmf` at `BATCH` shading points with normals.
fn light_bvh(c: &mut Criterion) {
    use mcrt::glam::Vec3;
    use mcrt::sampling::light_bvh::{LightBounds, LightBvh};
    let n = 10_000usize;
    let power = weights(n, 11);
    let pos = uniforms_1d(6 * n, 12);
    let lights: Vec<LightBounds> = (0..n)
        .map(|i| {
            let r = &pos[6 * i..6 * i + 6];
            let c = Vec3::new(r[0], r[1], r[2]) * 20.0 - 10.0;
            let normal = Vec3::new(r[3] - 0.5, r[4] - 0.5, r[5] - 0.5);
            if i % 2 == 0 {
                LightBounds::point(c, power[i])
            } else {
                LightBounds::planar(
                    c,
                    c + 0.3 * Vec3::new(r[3], r[4], 0.0),
                    normal,
                    false,
                    power[i],
                )
            }
        })
        .collect();
    let qs = uniforms_1d(7 * BATCH, 13);
    let queries: Vec<(Vec3, Vec3, f32)> = qs
        .chunks_exact(7)
        .map(|q| {
            let p = Vec3::new(q[0], q[1], q[2]) * 24.0 - 12.0;
            let n = Vec3::new(q[3] - 0.5, q[4] - 0.5, q[5] - 0.5);
            (p, n, q[6])
        })
        .collect();
    let mut group = c.benchmark_group("distribution/light_bvh");
    group.throughput(Throughput::Elements(1));
    group.bench_with_input(BenchmarkId::new("build", n), &lights, |b, l| {
        b.iter(|| LightBvh::new(black_box(l)).unwrap())
    });
    let bvh = LightBvh::new(&lights).unwrap();
    let picks: Vec<(Vec3, Vec3, usize)> = queries
        .iter()
        .map(|&(p, nrm, u)| (p, nrm, bvh.sample(p, nrm, u).map_or(0, |s| s.0)))
        .collect();
    group.throughput(Throughput::Elements(BATCH as u64));
    group.bench_with_input(BenchmarkId::new("sample", n), &queries, |b, qs| {
        b.iter(|| {
            qs.iter()
                .map(|&(p, nrm, u)| {
                    black_box(bvh.sample(black_box(p), nrm, u)).map_or(0.0, |s| s.1)
                })
                .sum::<f32>()
        })
    });
    group.bench_with_input(BenchmarkId::new("pmf", n), &picks, |b, ps| {
        b.iter(|| {
            ps.iter()
                .map(|&(p, nrm, i)| black_box(bvh.pmf(black_box(p), nrm, i)))
                .sum::<f32>()
        })
    });
    group.finish();
}

criterion_group! {
    name = benches;
    config = config();
    targets = piecewise_1d, alias, piecewise_2d, piecewise_linear_2d, windowed_2d, streaming, light_bvh
}
criterion_main!(benches);
