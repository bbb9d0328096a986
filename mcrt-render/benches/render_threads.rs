//! The renderer's throughput and how it scales with threads: the built-in Cornell box
//! (128×128, 4 spp, unlimited depth, the default options of the `render` example) rendered
//! with 1, 2 and 4 worker threads. Criterion's throughput is set to the samples (group
//! `render/samples`) or to the rays (group `render/rays`) one render makes, so
//! `scripts/bench_table.py --rate render/` prints M samples/s and M rays/s and the speed-up over
//! one thread.
//!
//! `cargo bench --features bench --bench render_threads`

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use mcrt_render::render::{RenderOptions, Renderer};
use std::sync::atomic::AtomicBool;
use std::time::Duration;

/// Worker threads to measure; the CI machine has 2 cores, so 4 shows oversubscription.
const THREADS: [usize; 3] = [1, 2, 4];

fn bench(c: &mut Criterion) {
    let desc = mcrt_render::cornell_box::cornell_box_with(4, 128, -1);
    let cancel = AtomicBool::new(false);
    let renderer = |threads| {
        let opts = RenderOptions {
            threads,
            seed: Some(1),
            ..RenderOptions::default()
        };
        Renderer::new(&desc, &opts).expect("the built-in Cornell box builds")
    };
    // One render gives the counts: the same seed makes the same paths on any thread count.
    let once = renderer(1).render(&|_, _| {}, &cancel);
    for (unit, count) in [("samples", once.samples), ("rays", once.rays)] {
        let mut group = c.benchmark_group(format!("render/{unit}"));
        group.sample_size(10);
        group.measurement_time(Duration::from_secs(4));
        group.throughput(Throughput::Elements(count));
        for threads in THREADS {
            let r = renderer(threads);
            group.bench_function(format!("threads={threads}"), |b| {
                b.iter(|| r.render(&|_, _| {}, &cancel).samples)
            });
        }
        group.finish();
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
