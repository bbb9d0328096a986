//! Ray-query throughput of the acceleration structures (`mcrt::scene::geometry::AccelKind`),
//! single thread, on pre-generated rays (fixed seeds) so criterion reports rays per second.
//!
//! Run: `cargo bench --bench accel`.
//!
//! - `accel/cornell_box`: closest-hit and occlusion (`t_max = 1`) queries for the BVH, the
//!   grid and brute force on the shapes of `tests/data/cornell-box.xml`, random rays from
//!   inside the box.
//! - `accel/soup_100k`, `accel/sphere_130k`: build time and closest-hit queries for the BVH
//!   and the grid on a 100 000-triangle soup (every point of space lies in the boxes of
//!   hundreds of triangles: a hard case) and a closed 130 560-triangle tessellated sphere (256 × 256),
//!   random rays from inside. Build throughput is reported in triangles per second.
//!
//! Correctness of the same structures is checked in `tests/accel.rs`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion, SamplingMode, Throughput};
use mcrt::glam::{Mat4, Vec3};
use mcrt::scene::description::{ShapeDesc, ShapeKind};
use mcrt::scene::geometry::{AccelKind, Geometry, Ray};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

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

fn unit_vec(r: &mut Pcg64) -> Vec3 {
    let z = r.random_range(-1.0f32..1.0);
    let phi = r.random_range(0.0f32..std::f32::consts::TAU);
    let s = (1.0 - z * z).max(0.0).sqrt();
    Vec3::new(s * phi.cos(), s * phi.sin(), z)
}

fn point(r: &mut Pcg64, h: f32) -> Vec3 {
    Vec3::new(
        r.random_range(-h..h),
        r.random_range(-h..h),
        r.random_range(-h..h),
    )
}

fn random_rays(r: &mut Pcg64, n: usize, h: f32) -> Vec<Ray> {
    (0..n)
        .map(|_| Ray {
            origin: point(r, h),
            dir: unit_vec(r),
        })
        .collect()
}

fn mesh(positions: Vec<Vec3>, indices: Vec<[u32; 3]>) -> ShapeDesc {
    ShapeDesc::new(ShapeKind::Mesh {
        positions,
        normals: vec![],
        indices,
    })
}

/// A triangle soup with every tenth triangle degenerate (collinear or repeated vertices).
fn soup(r: &mut Pcg64, n: usize) -> ShapeDesc {
    let mut pos = Vec::new();
    for k in 0..n {
        let c = point(r, 1.0);
        let a = c + point(r, 0.15);
        let (b, d) = match k % 10 {
            0 => (a, c),
            5 => (c + (a - c) * 2.0, a + a - c),
            _ => (c + point(r, 0.15), c + point(r, 0.15)),
        };
        pos.extend([a, b, d]);
    }
    let idx = (0..n as u32)
        .map(|k| [3 * k, 3 * k + 1, 3 * k + 2])
        .collect();
    mesh(pos, idx)
}

/// A closed latitude–longitude sphere mesh of radius 1 with shared vertices
/// (`2 · n_theta · n_phi − 2 · n_phi` triangles).
fn tessellated_sphere(n_theta: u32, n_phi: u32) -> ShapeDesc {
    let mut pos = vec![Vec3::Z, -Vec3::Z];
    for i in 1..n_theta {
        let th = std::f32::consts::PI * i as f32 / n_theta as f32;
        for j in 0..n_phi {
            let ph = std::f32::consts::TAU * j as f32 / n_phi as f32;
            pos.push(Vec3::new(
                th.sin() * ph.cos(),
                th.sin() * ph.sin(),
                th.cos(),
            ));
        }
    }
    let v = |i: u32, j: u32| 2 + (i - 1) * n_phi + j % n_phi;
    let mut idx = Vec::new();
    for j in 0..n_phi {
        idx.push([0, v(1, j), v(1, j + 1)]);
        idx.push([1, v(n_theta - 1, j + 1), v(n_theta - 1, j)]);
        for i in 1..n_theta - 1 {
            idx.push([v(i, j), v(i + 1, j), v(i + 1, j + 1)]);
            idx.push([v(i, j), v(i + 1, j + 1), v(i, j + 1)]);
        }
    }
    mesh(pos, idx)
}

fn row_major(m: [f32; 16]) -> Mat4 {
    Mat4::from_cols_array(&m).transpose()
}

/// The Cornell box shapes of `tests/data/cornell-box.xml`, in file order.
fn cornell_box() -> Vec<ShapeDesc> {
    let with = |kind, m| {
        let mut s = ShapeDesc::new(kind);
        s.to_world = row_major(m);
        s
    };
    let rect = |m| with(ShapeKind::Rectangle, m);
    let cube = |m| with(ShapeKind::Cube, m);
    vec![
        rect([
            0.23, 0., 0., 0., 0., 0., -0.19, 0.99, 0., 0.19, 0., 0.01, 0., 0., 0., 1.,
        ]),
        rect([
            1., 0., 0., 0., 0., 0., 1., -1., 0., -1., 0., 0., 0., 0., 0., 1.,
        ]),
        rect([
            1., 0., 0., 0., 0., 0., -1., 1., 0., 1., 0., 0., 0., 0., 0., 1.,
        ]),
        rect([
            1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., -1., 0., 0., 0., 1.,
        ]),
        rect([
            0., 0., -1., 1., 0., 1., 0., 0., 1., 0., 0., 0., 0., 0., 0., 1.,
        ]),
        rect([
            0., 0., 1., -1., 0., 1., 0., 0., -1., 0., 0., 0., 0., 0., 0., 1.,
        ]),
        cube([
            0.286891, 0., -0.0877115, 0.335, 0., 0.3, 0., -0.7, 0.0877115, 0., 0.286891, 0.38, 0.,
            0., 0., 1.,
        ]),
        cube([
            0.28491, 0., 0.0939491, -0.33, 0., 0.61, 0., -0.4, -0.0939491, 0., 0.28491, -0.28, 0.,
            0., 0., 1.,
        ]),
    ]
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
    for kind in [AccelKind::Bvh, AccelKind::Grid, AccelKind::BruteForce] {
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
        for kind in [AccelKind::Bvh, AccelKind::Grid] {
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

criterion_group! {
    name = benches;
    config = config();
    targets = cornell, large_meshes
}
criterion_main!(benches);
