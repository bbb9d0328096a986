//! The sampling core: warps, distributions, change of variables, MIS weights and samplers.
//!
//! Needs only [`glam`] (and `rand_core` for the independent sampler).

pub mod distribution;
mod error;
pub mod jacobian;
pub mod mis;
pub mod sampler;
pub mod warp;

pub use error::SamplingError;
