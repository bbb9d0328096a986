//! Helpers of the renderer crate's tests: the statistical suite's settings, read from the
//! core crate's `tests/common/suite.rs` so that both crates share one Šidák budget
//! (`N_TESTS` counts the chi-square runs of the whole workspace), and the replicate
//! comparison of the estimator tests.
#![allow(dead_code)] // each test file uses a different subset

pub mod blocks;
pub mod published;
pub mod replicates;
#[path = "../../../tests/common/suite.rs"]
mod suite;
#[allow(unused_imports)] // the replicate tests use none of the suite settings
pub use suite::*;
