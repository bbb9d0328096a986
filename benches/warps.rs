//! ns per call of every warp's `sample`, `pdf` and `invert` (and `new` where a warp is built
//! per shading point), with `rand_distr`'s `UnitDisc` and `UnitSphere` side by side.
//!
//! Run: `cargo bench --features bench --bench warps`. Every timed iteration makes `BATCH` calls on pre-generated
//! inputs (sample values, or points drawn from the warp beforehand), so time per iteration /
//! `BATCH` is ns per call. `rand_distr` draws from an RNG, not from `u`, so the comparison group
//! runs ours on the same RNG (PCG32) and also times the RNG alone.

use std::hint::black_box;

use criterion::measurement::WallTime;
use criterion::{criterion_group, criterion_main, BenchmarkGroup, Criterion, Throughput};
use mcrt::glam::{Vec2, Vec3};
use mcrt::sampling::warp::{
    Beckmann, BeckmannVisible, Bilinear, BilinearPatch, CosineHemisphere, CosineSphericalTriangle,
    Exponential, Ggx, GgxVisible, HenyeyGreenstein, InvertibleWarp, Linear, Logistic,
    LowDistortionTriangle, Normal, Normal2D, PowerCosineHemisphere, Smoothstep, SphericalRectangle,
    SphericalTriangle, Tent, ThetaOverSinHemisphere, TrimmedLogistic, TruncatedExponential,
    UniformCone, UniformDisk, UniformDiskConcentric, UniformHemisphere, UniformSphere,
    UniformTriangle, VonMisesFisher, Warp, Warp1D,
};
use rand_core::{RngCore, SeedableRng};
use rand_distr::{Distribution, UnitDisc, UnitSphere};
use rand_pcg::Pcg32;

mod common;
use common::{config, uniforms_1d, uniforms_2d, BATCH};

type Group<'a> = BenchmarkGroup<'a, WallTime>;

/// Opens the group `warp/<name>`, counting `BATCH` calls per iteration.
fn group<'a>(c: &'a mut Criterion, name: &str) -> Group<'a> {
    let mut g = c.benchmark_group(format!("warp/{name}"));
    g.throughput(Throughput::Elements(BATCH as u64));
    g
}

/// Times `sample`, `sample_with_pdf` and `pdf`; returns the sampled points.
fn sample_and_pdf<W: Warp>(g: &mut Group, w: &W, us: &[Vec2]) -> Vec<W::Point> {
    g.bench_function("sample", |b| {
        b.iter(|| {
            for &u in us {
                black_box(w.sample(black_box(u)));
            }
        })
    });
    g.bench_function("sample_with_pdf", |b| {
        b.iter(|| {
            for &u in us {
                black_box(w.sample_with_pdf(black_box(u)));
            }
        })
    });
    let points: Vec<W::Point> = us.iter().map(|&u| w.sample(u)).collect();
    g.bench_function("pdf", |b| {
        b.iter(|| {
            for &p in &points {
                black_box(w.pdf(black_box(p)));
            }
        })
    });
    points
}

/// Times `invert` on points drawn from the warp.
fn invert<W: InvertibleWarp>(g: &mut Group, w: &W, points: &[W::Point]) {
    g.bench_function("invert", |b| {
        b.iter(|| {
            for &p in points {
                black_box(w.invert(black_box(p)));
            }
        })
    });
}

/// A warp with an inverse: sample, sample_with_pdf, pdf and invert.
fn invertible<W: InvertibleWarp>(c: &mut Criterion, name: &str, w: W, us: &[Vec2]) {
    let mut g = group(c, name);
    let points = sample_and_pdf(&mut g, &w, us);
    invert(&mut g, &w, &points);
    g.finish();
}

fn basic(c: &mut Criterion) {
    let us = uniforms_2d(BATCH, 11);
    invertible(c, "UniformDisk", UniformDisk, &us);
    invertible(c, "UniformDiskConcentric", UniformDiskConcentric, &us);
    invertible(c, "UniformTriangle", UniformTriangle, &us);
    invertible(c, "UniformHemisphere", UniformHemisphere, &us);
    invertible(c, "CosineHemisphere", CosineHemisphere, &us);
    invertible(c, "UniformSphere", UniformSphere, &us);
    let cone = UniformCone::from_angle(0.3).unwrap();
    invertible(c, "UniformCone(0.3 rad)", cone, &us);
    let power = PowerCosineHemisphere::new(20.0).unwrap();
    invertible(c, "PowerCosineHemisphere(n=20)", power, &us);
    invertible(c, "ThetaOverSinHemisphere", ThetaOverSinHemisphere, &us);
}

/// Incident directions for visible-normal warps, 0° to 85° from the normal.
fn incident(n: usize) -> Vec<Vec3> {
    (0..n)
        .map(|i| {
            let theta = 85f32.to_radians() * (i as f32 + 0.5) / n as f32;
            let phi = 2.4 * i as f32;
            let s = theta.sin();
            Vec3::new(s * phi.cos(), s * phi.sin(), theta.cos())
        })
        .collect()
}

/// Times `new` (one construction per call, as a BSDF does per shading point).
fn construction<T>(g: &mut Group, inputs: &[Vec3], build: impl Fn(Vec3) -> T) {
    g.bench_function("new", |b| {
        b.iter(|| {
            for &x in inputs {
                black_box(build(black_box(x)));
            }
        })
    });
}

fn microfacet(c: &mut Criterion) {
    let us = uniforms_2d(BATCH, 12);
    invertible(c, "Beckmann(0.3)", Beckmann::new(0.3).unwrap(), &us);
    invertible(c, "Ggx(0.3)", Ggx::new(0.3).unwrap(), &us);
    let wis = incident(BATCH);
    let wi = Vec3::new(0.6, 0.0, 0.8);

    let mut g = group(c, "GgxVisible(0.3, 37°)");
    sample_and_pdf(&mut g, &GgxVisible::new(0.3, wi).unwrap(), &us);
    construction(&mut g, &wis, |w| GgxVisible::new(0.3, w));
    g.finish();

    let mut g = group(c, "BeckmannVisible(0.3, 37°)");
    sample_and_pdf(&mut g, &BeckmannVisible::new(0.3, wi).unwrap(), &us);
    construction(&mut g, &wis, |w| BeckmannVisible::new(0.3, w));
    g.finish();
}

/// Shading points below a light that spans [-0.5, 0.5]² at height 2.
fn origins(n: usize) -> Vec<Vec3> {
    uniforms_2d(n, 13)
        .into_iter()
        .map(|u| Vec3::new(4.0 * u.x - 2.0, 4.0 * u.y - 2.0, 0.0))
        .collect()
}

fn spherical(c: &mut Criterion) {
    let us = uniforms_2d(BATCH, 14);
    let os = origins(BATCH);
    let (a, b, d) = (
        Vec3::new(-0.5, -0.5, 2.0),
        Vec3::new(0.5, -0.5, 2.0),
        Vec3::new(0.0, 0.5, 2.0),
    );
    let mut g = group(c, "SphericalTriangle");
    sample_and_pdf(
        &mut g,
        &SphericalTriangle::new(Vec3::ZERO, a, b, d).unwrap(),
        &us,
    );
    construction(&mut g, &os, |o| SphericalTriangle::new(o, a, b, d));
    g.finish();

    let (corner, ex, ey) = (a, Vec3::X, Vec3::Y);
    let mut g = group(c, "SphericalRectangle");
    let rect = SphericalRectangle::new(Vec3::ZERO, corner, ex, ey).unwrap();
    sample_and_pdf(&mut g, &rect, &us);
    construction(&mut g, &os, |o| SphericalRectangle::new(o, corner, ex, ey));
    g.finish();
}

/// `u` from PCG32 with 24-bit resolution, as our samplers make it.
fn next_u(rng: &mut Pcg32) -> Vec2 {
    let x = (rng.next_u32() >> 8) as f32 / 16_777_216.0;
    Vec2::new(x, (rng.next_u32() >> 8) as f32 / 16_777_216.0)
}

/// `BATCH` calls of `f`, each result passed through `black_box`.
fn batch<T>(mut f: impl FnMut() -> T) {
    for _ in 0..BATCH {
        black_box(f());
    }
}

fn versus_rand_distr(c: &mut Criterion) {
    let mut g = group(c, "vs_rand_distr");
    let mut rng = Pcg32::seed_from_u64(15);
    g.bench_function("pcg32 u only", |b| b.iter(|| batch(|| next_u(&mut rng))));
    g.bench_function("rand_distr UnitDisc", |b| {
        b.iter(|| batch(|| -> [f32; 2] { UnitDisc.sample(&mut rng) }))
    });
    g.bench_function("UniformDisk + pcg32", |b| {
        b.iter(|| batch(|| UniformDisk.sample(next_u(&mut rng))))
    });
    g.bench_function("UniformDiskConcentric + pcg32", |b| {
        b.iter(|| batch(|| UniformDiskConcentric.sample(next_u(&mut rng))))
    });
    g.bench_function("rand_distr UnitSphere", |b| {
        b.iter(|| batch(|| -> [f32; 3] { UnitSphere.sample(&mut rng) }))
    });
    g.bench_function("UniformSphere + pcg32", |b| {
        b.iter(|| batch(|| UniformSphere.sample(next_u(&mut rng))))
    });
    g.finish();
}

/// A 1D warp: sample, sample_with_pdf, pdf and invert.
fn one_d<W: Warp1D>(c: &mut Criterion, name: &str, w: W, us: &[f32]) {
    let mut g = group(c, name);
    g.bench_function("sample", |b| {
        b.iter(|| {
            for &u in us {
                black_box(w.sample(black_box(u)));
            }
        })
    });
    g.bench_function("sample_with_pdf", |b| {
        b.iter(|| {
            for &u in us {
                black_box(w.sample_with_pdf(black_box(u)));
            }
        })
    });
    let xs: Vec<f32> = us.iter().map(|&u| w.sample(u)).collect();
    g.bench_function("pdf", |b| {
        b.iter(|| {
            for &x in &xs {
                black_box(w.pdf(black_box(x)));
            }
        })
    });
    g.bench_function("invert", |b| {
        b.iter(|| {
            for &x in &xs {
                black_box(w.invert(black_box(x)));
            }
        })
    });
    g.finish();
}

/// The toolbox of issue 15: 1D densities, bilinear, Box–Muller, phase-function lobes, the
/// low-distortion triangle.
fn toolbox(c: &mut Criterion) {
    let u1 = uniforms_1d(BATCH, 16);
    one_d(c, "Linear(1,3)", Linear::new(1.0, 3.0).unwrap(), &u1);
    one_d(c, "Tent(1)", Tent::new(1.0).unwrap(), &u1);
    one_d(c, "Exponential(2)", Exponential::new(2.0).unwrap(), &u1);
    let te = TruncatedExponential::new(2.0, 0.0, 1.0).unwrap();
    one_d(c, "TruncatedExponential(2,[0,1])", te, &u1);
    one_d(c, "Normal(0,1)", Normal::standard(), &u1);
    one_d(c, "Logistic(0,1)", Logistic::new(0.0, 1.0).unwrap(), &u1);
    let tl = TrimmedLogistic::new(0.0, 1.0, -3.0, 3.0).unwrap();
    one_d(c, "TrimmedLogistic(0,1,[-3,3])", tl, &u1);
    one_d(
        c,
        "Smoothstep([0,1])",
        Smoothstep::new(0.0, 1.0).unwrap(),
        &u1,
    );
    let us = uniforms_2d(BATCH, 17);
    let bilinear = Bilinear::new([1.0, 2.0, 3.0, 4.0]).unwrap();
    invertible(c, "Bilinear([1,2,3,4])", bilinear, &us);
    let n2 = Normal2D::new(Vec2::ZERO, 1.0).unwrap();
    invertible(c, "Normal2D(Box-Muller)", n2, &us);
    invertible(c, "LowDistortionTriangle", LowDistortionTriangle, &us);
    let hg = HenyeyGreenstein::new(0.7).unwrap();
    invertible(c, "HenyeyGreenstein(0.7)", hg, &us);
    let vmf = VonMisesFisher::new(100.0).unwrap();
    invertible(c, "VonMisesFisher(100)", vmf, &us);
    let twisted = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(1.3, 0.9, 0.8)];
    invertible(
        c,
        "BilinearPatch(twisted)",
        BilinearPatch::new(twisted).unwrap(),
        &us,
    );
    let (a, b, d) = (
        Vec3::new(-0.5, -0.5, 2.0),
        Vec3::new(0.5, -0.5, 2.0),
        Vec3::new(0.0, 0.5, 2.0),
    );
    let tri = SphericalTriangle::new(Vec3::ZERO, a, b, d).unwrap();
    invertible(c, "SphericalTriangle", tri, &us);
    let rect = SphericalRectangle::new(Vec3::ZERO, a, Vec3::X, Vec3::Y).unwrap();
    invertible(c, "SphericalRectangle", rect, &us);
    let cosine = CosineSphericalTriangle::new(Vec3::ZERO, a, b, d, Vec3::new(0.3, 0.0, 1.0));
    invertible(c, "CosineSphericalTriangle", cosine.unwrap(), &us);
}

criterion_group! {
    name = benches;
    config = config();
    targets = basic, microfacet, spherical, versus_rand_distr, toolbox
}
criterion_main!(benches);
