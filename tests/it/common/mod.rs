//! Helpers of the core crate's tests: the suite's settings (shared with the renderer crate's
//! statistical tests) and the samplers the harness tests draw from.
#![allow(dead_code)] // each test file uses a different subset

pub mod samplers;
mod suite;
pub use suite::*;
