//! What simulating only the effects a scene needs buys: the Cornell box (diffuse only, one
//! area light) rendered by the loop the renderer specialises to it (`Sided<Diffuse>`, no
//! point-light or environment code; the same machine code a diffuse-only renderer would
//! have) against the general loop (every material through `AnyBsdf`, lights checked at run
//! time). 64×64 pixels, 4 spp, one thread, fixed seed.
//!
//! `cargo bench --features bench --bench render_effects`

use criterion::{criterion_group, criterion_main, Criterion};
use mcrt_render::render::{RenderOptions, Renderer};
use std::sync::atomic::AtomicBool;

fn bench(c: &mut Criterion) {
    let desc = mcrt_render::cornell_box::cornell_box_with(4, 64, -1);
    let mut group = c.benchmark_group("cornell_box_64x64_4spp");
    group.sample_size(20);
    for (name, specialize) in [
        ("specialised (diffuse only)", true),
        ("general loop", false),
    ] {
        let opts = RenderOptions {
            threads: 1,
            seed: Some(1),
            specialize,
            ..RenderOptions::default()
        };
        let r = Renderer::new(&desc, &opts).expect("scene builds");
        let cancel = AtomicBool::new(false);
        group.bench_function(name, |b| b.iter(|| r.render(&|_, _| {}, &cancel).samples));
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
