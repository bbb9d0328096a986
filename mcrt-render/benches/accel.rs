//! Ray-query throughput of the acceleration structures (`mcrt_render::geometry::AccelKind`),
//! single thread, on pre-generated rays (fixed seeds) so criterion reports rays per second.
//!
//! Run: `cargo bench --features bench --bench accel`.
//!
//! - `accel/cornell_box`: closest-hit and occlusion (`t_max = 1`) queries for the BVH
//!   (4-wide `Bvh` and 8-wide `Bvh8`), the grid, the kd-tree and brute force on the shapes
//!   of `tests/data/cornell-box.xml`, random rays from inside the box.
//! - `accel/soup_100k`, `accel/sphere_130k`: build time and closest-hit queries for the BVH
//!   (4-wide and 8-wide), the grid and the kd-tree on a 100 000-triangle soup (every point of space lies in the boxes of
//!   hundreds of triangles: a hard case) and a closed 130 560-triangle tessellated sphere (256 × 256),
//!   random rays from inside. Build throughput is reported in triangles per second.
//! - `accel/degenerate_20k`: build time of the BVH, the grid and the kd-tree on the
//!   degenerate 20 000-triangle soups of issue 26 (`tests/it/common/degenerate.rs`: copies of
//!   one triangle on shared or separate vertices, shifted overlapping copies in one plane, a
//!   fan on one edge, zero-area triangles) beside a random soup of the same size.
//!
//! Correctness of the same structures is checked in `tests/it/accel.rs`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion, SamplingMode, Throughput};
use mcrt_render::geometry::{AccelKind, Geometry, Ray};
use rand::SeedableRng;
use rand_pcg::Pcg64;

#[path = "../tests/it/common/degenerate.rs"]
mod degenerate;
#[path = "../tests/it/common/scenes.rs"]
mod scenes;
use scenes::{cornell_box, random_rays, soup, tessellated_sphere};

/// Rays per timed iteration on the Cornell box.
const CORNELL_RAYS: usize = 16_384;
/// Rays per timed iteration on the large meshes (the soup runs at well under 1 M rays/s).
const MESH_RAYS: usize = 4096;

/// A short configuration: the whole file runs in about a minute on an idle machine.
fn config() -> Criterion {
    Criterion::default()
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_millis(1500))
        .sample_size(10)
        .without_plots()
}

/// Number of rays with a closest hit (kept so the queries cannot be optimised away).
fn closest_hits(g: &Geometry, rays: &[Ray]) -> usize {
    rays.iter()
        .filter(|ray| black_box(g).intersect(ray, f32::INFINITY).is_some())
        .count()
}

fn cornell(c: &mut Criterion) {
    let shapes = cornell_box();
    let rays = random_rays(&mut Pcg64::seed_from_u64(11), CORNELL_RAYS, 0.95);
    let mut group = c.benchmark_group("accel/cornell_box");
    group.sampling_mode(SamplingMode::Flat);
    group.throughput(Throughput::Elements(rays.len() as u64));
    for kind in [
        AccelKind::Bvh,
        AccelKind::Bvh8,
        AccelKind::Grid,
        AccelKind::KdTree,
        AccelKind::BruteForce,
    ] {
        let g = Geometry::new(&shapes, None, kind).expect("the Cornell box builds");
        group.bench_function(format!("closest_hit/{kind:?}"), |b| {
            b.iter(|| closest_hits(&g, black_box(&rays)))
        });
        group.bench_function(format!("occlusion/{kind:?}"), |b| {
            b.iter(|| {
                black_box(&rays)
                    .iter()
                    .filter(|ray| black_box(&g).occluded(ray, 1.0))
                    .count()
            })
        });
    }
    group.finish();
}

fn large_meshes(c: &mut Criterion) {
    let mut r = Pcg64::seed_from_u64(15);
    let rays = random_rays(&mut r, MESH_RAYS, 0.5);
    for (name, triangles, shapes) in [
        ("soup_100k", 100_000, vec![soup(&mut r, 100_000)]),
        ("sphere_130k", 130_560, vec![tessellated_sphere(256, 256)]),
    ] {
        let mut group = c.benchmark_group(format!("accel/{name}"));
        group.sampling_mode(SamplingMode::Flat);
        for kind in [
            AccelKind::Bvh,
            AccelKind::Bvh8,
            AccelKind::Grid,
            AccelKind::KdTree,
        ] {
            // Build throughput in triangles per second.
            group.throughput(Throughput::Elements(triangles));
            group.bench_function(format!("build/{kind:?}"), |b| {
                b.iter(|| Geometry::new(black_box(&shapes), None, kind).expect("mesh builds"))
            });
            let g = Geometry::new(&shapes, None, kind).expect("mesh builds");
            group.throughput(Throughput::Elements(rays.len() as u64));
            group.bench_function(format!("closest_hit/{kind:?}"), |b| {
                b.iter(|| closest_hits(&g, black_box(&rays)))
            });
        }
        group.finish();
    }
}

fn degenerate_soups(c: &mut Criterion) {
    const N: usize = 20_000;
    let mut group = c.benchmark_group("accel/degenerate_20k");
    group.sampling_mode(SamplingMode::Flat);
    group.throughput(Throughput::Elements(N as u64));
    for (name, shape) in degenerate::all(N) {
        let shapes = [shape];
        for kind in [AccelKind::Bvh, AccelKind::Grid, AccelKind::KdTree] {
            group.bench_function(format!("build/{name}/{kind:?}"), |b| {
                b.iter(|| Geometry::new(black_box(&shapes), None, kind).expect("soup builds"))
            });
        }
    }
    group.finish();
}

criterion_group! {
    name = benches;
    config = config();
    targets = cornell, large_meshes, degenerate_soups
}
criterion_main!(benches);
