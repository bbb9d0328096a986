//! Helpers shared by `tests/it/distributed.rs` and `tests/distributed_processes.rs`.
#![allow(dead_code)] // each test file uses a different subset

use std::path::PathBuf;

/// A scratch folder for this test, empty.
pub fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("mcrt-distributed-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&d).ok();
    std::fs::create_dir_all(&d).expect("scratch folder");
    d
}

/// The largest distance in f32 ulps between two images' channels; non-finite fails.
pub fn max_ulps(a: &[mcrt::glam::Vec3], b: &[mcrt::glam::Vec3]) -> u32 {
    assert_eq!(a.len(), b.len());
    let mut worst = 0;
    for (p, q) in a.iter().zip(b) {
        for (x, y) in p.to_array().into_iter().zip(q.to_array()) {
            assert!(x.is_finite() && y.is_finite(), "{x} vs {y}");
            let d = if x.signum() == y.signum() || x == y {
                x.to_bits().abs_diff(y.to_bits())
            } else {
                u32::MAX
            };
            worst = worst.max(d);
        }
    }
    worst
}

/// One of this package's programs (`render`, `merge`), which Cargo builds for its
/// integration tests.
pub fn example(name: &str) -> PathBuf {
    match name {
        "render" => PathBuf::from(env!("CARGO_BIN_EXE_render")),
        "merge" => PathBuf::from(env!("CARGO_BIN_EXE_merge")),
        other => panic!("no program {other} in mcrt-render"),
    }
}
