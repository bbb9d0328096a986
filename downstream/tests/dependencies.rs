//! The library's normal dependencies, as a user's build compiles them: `cargo tree -p mcrt
//! -e normal --prefix none --offline` on the workspace's root manifest lists exactly the
//! crates below, with default features (at most 10, the target of the dependency diet) and
//! without. A new dependency of `mcrt` (or one that stops being optional) fails this test
//! until the list, the README's figures and the changelog are updated together.
//!
//! It runs the `cargo` that runs the tests (`CARGO`), offline, and only reads the lock file
//! and the manifests: `cargo tree` takes no build-directory lock, so it does not wait on the
//! `cargo test` that started it.

#![forbid(unsafe_code)]

use std::collections::BTreeSet;
use std::path::PathBuf;
use std::process::Command;

/// The crate names `cargo tree -p mcrt -e normal --prefix none` prints, with `extra`
/// arguments (feature selection).
fn normal_dependencies(extra: &[&str]) -> (BTreeSet<String>, String) {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let manifest = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join("Cargo.toml");
    let output = Command::new(&cargo)
        .args([
            "tree",
            "--offline",
            "-p",
            "mcrt",
            "-e",
            "normal",
            "--prefix",
            "none",
        ])
        .args(extra)
        .arg("--manifest-path")
        .arg(&manifest)
        .output()
        .unwrap_or_else(|e| panic!("running {cargo} tree: {e}"));
    let stdout = String::from_utf8_lossy(&output.stdout).into_owned();
    assert!(
        output.status.success(),
        "{cargo} tree {extra:?} failed ({}):\n{}\n{stdout}",
        output.status,
        String::from_utf8_lossy(&output.stderr)
    );
    // One line per package: `name vX.Y.Z [(path)] [(*)]`.
    let names = stdout
        .lines()
        .filter_map(|line| line.split_whitespace().next())
        .map(str::to_owned)
        .collect();
    (names, stdout)
}

fn set(names: &[&str]) -> BTreeSet<String> {
    names.iter().map(|&n| n.to_owned()).collect()
}

#[test]
fn default_features_pull_in_only_the_listed_crates() {
    let (names, tree) = normal_dependencies(&[]);
    let expected = set(&[
        "mcrt",
        "glam",
        "rand_core",
        "rand_pcg",
        // `stats`: one chi-square CDF, without statrs's default features.
        "statrs",
        "approx",
        "num-traits",
        // `sobol`.
        "sobol_burley",
    ]);
    assert_eq!(names, expected, "cargo tree printed:\n{tree}");
    assert!(names.len() <= 10, "{} crates:\n{tree}", names.len());
}

#[test]
fn no_default_features_pull_in_only_the_core_crates() {
    let (names, tree) = normal_dependencies(&["--no-default-features"]);
    assert_eq!(
        names,
        set(&["mcrt", "glam", "rand_core", "rand_pcg"]),
        "cargo tree printed:\n{tree}"
    );
}
