//! Scene loading time on large ordinary files: the loader must be linear in the file size.
//!
//! Run: `cargo bench --features bench --bench loader`.
//!
//! - `loader/spheres_20k`: 20 000 spheres, each with a radius, a translation and a diffuse
//!   BSDF (3.6 MB of XML, one shape per line), parsed from memory.
//! - `loader/defaults_20k`: 20 000 `<default>` parameters and 20 000 shapes using them.
//! - `loader/spheres_80k`: four times the spheres; linear loading takes about four times as
//!   long (the old loader's quadratic position lookups took sixteen).
//! - `loader/bsdfs_1m`: a million top-level `<bsdf type="diffuse"/>` (24 MB).
//!
//! - `mesh_1m/read_ply`: reading a binary little-endian PLY file of 10⁶ triangles (a torus,
//!   500 000 vertices with normals, 23 MB; written once to `target/bench-data/`).
//! - `mesh_1m/geometry`: the same mesh, already read, turned into world-space geometry
//!   with the BVH (the acceleration structure's build dominates).
//! - `mesh_1m/scene`: a scene file naming the PLY, loaded and built (`Geometry::new` from
//!   the description: reading plus building).
//!
//! Mitsuba 3's own load of the same file: `python3 scripts/time_mitsuba_load.py` (after
//! this bench has written the file) times `mi.load_dict` of the `ply` shape alone and of a
//! scene holding it (which builds Mitsuba's BVH).
//!
//! `tests/hostile_input.rs` bounds the XML loads at a few seconds, so that a return to
//! quadratic time fails the tests too.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use mcrt::glam::Vec3;
use mcrt_render::description::{ShapeDesc, ShapeKind};
use mcrt_render::geometry::{AccelKind, Geometry};
use mcrt_render::loader::parse_scene;
use mcrt_render::mesh_file::ply::read_ply;
use std::path::PathBuf;

#[path = "../tests/common/large_scenes.rs"]
mod large_scenes;
use large_scenes::{bsdfs, defaults, spheres};

/// Writes (once) a binary little-endian PLY torus of `2 nu nv` triangles with vertex
/// normals, and returns its path.
fn torus_ply(nu: usize, nv: usize) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/bench-data");
    let path = dir.join(format!("torus-{}.ply", 2 * nu * nv));
    if path.exists() {
        return path;
    }
    std::fs::create_dir_all(&dir).expect("bench-data folder");
    let mut out = format!(
        "ply\nformat binary_little_endian 1.0\ncomment mcrt loader bench: a torus\n\
         element vertex {}\nproperty float x\nproperty float y\nproperty float z\n\
         property float nx\nproperty float ny\nproperty float nz\n\
         element face {}\nproperty list uchar int vertex_indices\nend_header\n",
        nu * nv,
        2 * nu * nv
    )
    .into_bytes();
    let (major, minor) = (1.0f32, 0.35f32);
    for i in 0..nu {
        for j in 0..nv {
            let u = std::f32::consts::TAU * i as f32 / nu as f32;
            let w = std::f32::consts::TAU * j as f32 / nv as f32;
            let n = Vec3::new(w.cos() * u.cos(), w.cos() * u.sin(), w.sin());
            let p = Vec3::new(major * u.cos(), major * u.sin(), 0.0) + minor * n;
            for x in p.to_array().into_iter().chain(n.to_array()) {
                out.extend(x.to_le_bytes());
            }
        }
    }
    for i in 0..nu {
        for j in 0..nv {
            let id = |a: usize, b: usize| ((a % nu) * nv + b % nv) as i32;
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            for t in [[a, b, c], [a, c, d]] {
                out.push(3);
                for k in t {
                    out.extend(k.to_le_bytes());
                }
            }
        }
    }
    std::fs::write(&path, out).expect("bench PLY written");
    path
}

fn bench_loader(c: &mut Criterion) {
    let mut g = c.benchmark_group("loader");
    g.warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3))
        .sample_size(10);
    for (name, xml) in [
        ("spheres_20k", spheres(20_000, false)),
        ("defaults_20k", defaults(20_000)),
        ("spheres_80k", spheres(80_000, false)),
        ("bsdfs_1m", bsdfs(1_000_000)),
    ] {
        g.throughput(Throughput::Bytes(xml.len() as u64));
        g.bench_function(name, |b| {
            b.iter(|| parse_scene(black_box(&xml), None, &[]).expect("loads"))
        });
    }
    g.finish();
}

fn bench_mesh(c: &mut Criterion) {
    let path = torus_ply(1000, 500);
    eprintln!("mesh_1m: {}", path.display());
    let mut g = c.benchmark_group("mesh_1m");
    g.warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(10))
        .sample_size(10);
    g.throughput(Throughput::Elements(1_000_000));
    g.bench_function("read_ply", |b| {
        b.iter(|| read_ply(black_box(&path)).expect("reads"))
    });
    let mesh = read_ply(&path).expect("reads");
    let shape = ShapeDesc::new(ShapeKind::Mesh {
        positions: mesh.positions,
        normals: mesh.normals,
        indices: mesh.indices,
    });
    g.bench_function("geometry", |b| {
        b.iter(|| {
            Geometry::new(
                black_box(std::slice::from_ref(&shape)),
                None,
                AccelKind::Bvh,
            )
        })
    });
    let xml = format!(
        "<scene version=\"3.0.0\"><shape type=\"ply\">\
         <string name=\"filename\" value=\"{}\"/></shape></scene>",
        path.display()
    );
    g.bench_function("scene", |b| {
        b.iter(|| {
            let d = parse_scene(black_box(&xml), None, &[]).expect("loads");
            Geometry::new(&d.shapes, None, AccelKind::Bvh).expect("builds")
        })
    });
    g.finish();
}

criterion_group!(benches, bench_loader, bench_mesh);
criterion_main!(benches);
