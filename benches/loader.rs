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
//! `tests/hostile_input.rs` bounds the same loads at a few seconds, so that a return to
//! quadratic time fails the tests too.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use mcrt::scene::loader::parse_scene;

/// `n` spheres, one per line.
fn spheres(n: usize) -> String {
    let mut xml = String::from("<scene version=\"3.0.0\">\n");
    for i in 0..n {
        xml.push_str(&format!(
            "<shape type=\"sphere\"><float name=\"radius\" value=\"0.01\"/>\
             <transform name=\"to_world\"><translate x=\"{i}\"/></transform>\
             <bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.5\"/></bsdf></shape>\n"
        ));
    }
    xml.push_str("</scene>");
    xml
}

/// `n` defaults, each used once.
fn defaults(n: usize) -> String {
    let mut xml = String::from("<scene version=\"3.0.0\">\n");
    for i in 0..n {
        xml.push_str(&format!("<default name=\"r{i}\" value=\"0.{i}1\"/>\n"));
    }
    for i in 0..n {
        xml.push_str(&format!(
            "<shape type=\"sphere\"><float name=\"radius\" value=\"$r{i}\"/></shape>\n"
        ));
    }
    xml.push_str("</scene>");
    xml
}

/// `n` top-level BSDFs.
fn bsdfs(n: usize) -> String {
    let mut xml = String::from("<scene version=\"3.0.0\">\n");
    xml.push_str(&"<bsdf type=\"diffuse\"/>\n".repeat(n));
    xml.push_str("</scene>");
    xml
}

fn bench_loader(c: &mut Criterion) {
    let mut g = c.benchmark_group("loader");
    g.warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3))
        .sample_size(10);
    for (name, xml) in [
        ("spheres_20k", spheres(20_000)),
        ("defaults_20k", defaults(20_000)),
        ("spheres_80k", spheres(80_000)),
        ("bsdfs_1m", bsdfs(1_000_000)),
    ] {
        g.throughput(Throughput::Bytes(xml.len() as u64));
        g.bench_function(name, |b| {
            b.iter(|| parse_scene(black_box(&xml), None, &[]).expect("loads"))
        });
    }
    g.finish();
}

criterion_group!(benches, bench_loader);
criterion_main!(benches);
