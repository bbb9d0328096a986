//! Deterministic parallel helpers on `std::thread::scope`: work is cut into fixed chunks
//! whose results do not depend on which thread ran them.

use glam::Vec2;
use rand_core::RngCore;
use rand_pcg::Pcg64;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Samples per chunk; chunk `c` always draws from RNG stream `c`.
pub(crate) const CHUNK: usize = 1 << 15;

/// The thread count to use when none is given.
pub(crate) fn default_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// The RNG of chunk `chunk` for run seed `seed`.
pub(crate) fn chunk_rng(seed: u64, chunk: usize) -> Pcg64 {
    let state = (u128::from(seed) << 64) | u128::from(seed ^ 0x9E37_79B9_7F4A_7C15);
    Pcg64::new(state, chunk as u128)
}

/// A uniform `u ∈ [0,1)²` with 24-bit coordinates (so `1 − 2⁻²⁴` is the largest value).
pub(crate) fn next_u(rng: &mut Pcg64) -> Vec2 {
    let f = |x: u32| (x >> 8) as f32 * (1.0 / (1u32 << 24) as f32);
    Vec2::new(f(rng.next_u32()), f(rng.next_u32()))
}

/// Runs `work(chunk, &mut acc)` for every chunk in `0..chunks` on up to `threads` threads,
/// each with its own accumulator from `init`, and returns the accumulators. Callers merge
/// them with an order-independent operation (integer sums).
pub(crate) fn for_chunks<A: Send>(
    chunks: usize,
    threads: usize,
    init: &(dyn Fn() -> A + Sync),
    work: &(dyn Fn(usize, &mut A) + Sync),
) -> Vec<A> {
    let next = AtomicUsize::new(0);
    let threads = threads.clamp(1, chunks.max(1));
    std::thread::scope(|s| {
        let handles: Vec<_> = (0..threads)
            .map(|_| {
                s.spawn(|| {
                    let mut acc = init();
                    loop {
                        let c = next.fetch_add(1, Ordering::Relaxed);
                        if c >= chunks {
                            break acc;
                        }
                        work(c, &mut acc);
                    }
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().expect("a worker thread panicked"))
            .collect()
    })
}

/// `f(i)` for `i in 0..n`, computed in parallel, returned in index order.
pub(crate) fn map_indexed<T: Send + Default + Clone>(
    n: usize,
    threads: usize,
    f: &(dyn Fn(usize) -> T + Sync),
) -> Vec<T> {
    const BLOCK: usize = 64;
    let blocks = n.div_ceil(BLOCK);
    let parts = for_chunks(blocks, threads, &Vec::new, &|b,
                                                         acc: &mut Vec<(
        usize,
        Vec<T>,
    )>| {
        let range = b * BLOCK..((b + 1) * BLOCK).min(n);
        acc.push((b, range.map(f).collect()));
    });
    let mut out = vec![T::default(); n];
    for (b, values) in parts.into_iter().flatten() {
        for (k, v) in values.into_iter().enumerate() {
            out[b * BLOCK + k] = v;
        }
    }
    out
}
