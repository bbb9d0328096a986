//! Helpers shared by `tests/distributed.rs` and `tests/distributed_processes.rs`.
#![allow(dead_code)] // each test file uses a different subset

use std::path::{Path, PathBuf};

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

/// An example built next to the test binaries (`cargo test` builds every example):
/// `target/<profile>/examples/NAME`.
pub fn example(name: &str) -> PathBuf {
    let exe = std::env::current_exe().expect("test binary path");
    let profile_dir = exe
        .parent()
        .and_then(Path::parent)
        .expect("target/<profile>");
    let p = profile_dir.join("examples").join(name);
    assert!(
        p.is_file(),
        "{} is missing: run `cargo test --release` (it builds the examples) or \
         `cargo build --release --example {name}`",
        p.display()
    );
    p
}
