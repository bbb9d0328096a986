//! Helpers of the renderer crate's tests: the statistical suite's settings, read from the
//! core crate's `tests/it/common/suite.rs` so that both crates share one Šidák budget
//! (`N_TESTS` counts the chi-square runs of the whole workspace and the renderer's image
//! comparisons, each at `per_test_alpha()`), the replicate comparison of the estimator
//! tests, the published-scene comparison and the loader tests' located-error check.
#![allow(dead_code)] // each test file uses a different subset

pub mod blocks;
pub mod located;
pub mod published;
pub mod replicates;
#[path = "../../../../tests/it/common/suite.rs"]
mod suite;
#[allow(unused_imports)] // the replicate tests use none of the suite settings
pub use suite::*;
