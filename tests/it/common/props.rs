//! Settings and value strategies shared by the property tests: fixed seeds, so every run
//! draws the same cases, and `u` values that hit the edges of [0, 1) often. Included with
//! `#[path = "common/props.rs"] mod props;` (it needs no crate feature, unlike
//! `common/mod.rs`).
#![allow(dead_code)] // each test file uses a different subset

use mcrt::glam::Vec2;
use mcrt::sampling::ONE_MINUS_EPSILON;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};

/// The warp and streaming property tests' seed ("mcrt").
pub const SEED: u64 = 0x6d63_7274;

/// The distribution property tests' seed.
pub const DISTRIBUTION_SEED: u64 = 0x5eed_d157;

/// `cases` cases drawn from the fixed `seed`, without failure files.
pub fn config_seeded(cases: u32, seed: u64) -> Config {
    Config {
        cases,
        rng_seed: RngSeed::Fixed(seed),
        failure_persistence: None,
        ..Config::default()
    }
}

/// `cases` cases drawn from [`SEED`].
pub fn config(cases: u32) -> Config {
    config_seeded(cases, SEED)
}

/// `cases` cases drawn from [`DISTRIBUTION_SEED`].
pub fn distribution_config(cases: u32) -> Config {
    config_seeded(cases, DISTRIBUTION_SEED)
}

/// One coordinate of u: free (any float in [0, 1)), or pinned to an edge.
pub fn coord() -> impl Strategy<Value = f32> {
    prop_oneof![
        1 => Just(0.0f32),
        1 => Just(0.5f32),
        1 => Just(ONE_MINUS_EPSILON),
        5 => 0.0f32..1.0,
    ]
}

/// A point of the unit square from [`coord`]s.
pub fn u_any() -> impl Strategy<Value = Vec2> {
    (coord(), coord()).prop_map(|(a, b)| Vec2::new(a, b))
}

/// A sample value in [0,1): free (24-bit grid, as samplers produce) or pinned to an edge.
pub fn unit() -> impl Strategy<Value = f32> {
    prop_oneof![
        6 => (0u32..1 << 24).prop_map(|k| k as f32 / (1u32 << 24) as f32),
        1 => Just(0.0f32),
        1 => Just(0.5f32),
        1 => Just(ONE_MINUS_EPSILON),
    ]
}

/// A float in `[lo, hi)` on a grid of 2²⁴ steps (integer-based: no float-range sampler).
pub fn float_in(lo: f32, hi: f32) -> impl Strategy<Value = f32> {
    (0u32..1 << 24)
        .prop_map(move |k| (lo + (hi - lo) * (k as f32 / (1u32 << 24) as f32)).min(hi.next_down()))
}

/// A table entry: often zero, else in a moderate range.
pub fn entry() -> impl Strategy<Value = f32> {
    prop_oneof![3 => Just(0.0f32), 7 => float_in(0.01, 100.0)]
}

/// A table of a length in `len` with at least one nonzero entry.
pub fn table_len(len: std::ops::Range<usize>) -> impl Strategy<Value = Vec<f32>> {
    (
        prop::collection::vec(entry(), len),
        any::<prop::sample::Index>(),
        float_in(0.01, 100.0),
    )
        .prop_map(|(mut v, i, x)| {
            let k = i.index(v.len());
            v[k] = x;
            v
        })
}
