//! The sampling core: warps, distributions, change of variables, MIS weights and samplers,
//! the [`Frame`] that turns directions sampled about `+z` toward any axis, and three streaming
//! utilities ([`WeightedReservoir`], [`Resampler`], [`VarianceEstimator`]), and the light BVH that picks one of
//! many lights ([`light_bvh::LightBvh`]).
//!
//! Needs only [`glam`] (and `rand_core` with `rand_pcg` for the independent sampler).

pub mod distribution;
mod error;
mod frame;
pub mod guiding;
pub mod jacobian;
pub mod light_bvh;
pub mod mis;
mod reservoir;
mod ris;
pub mod sampler;
pub(crate) mod unit;
mod variance;
pub mod warp;

pub use error::SamplingError;
pub use frame::Frame;
pub use reservoir::WeightedReservoir;
pub use ris::Resampler;
pub use unit::ONE_MINUS_EPSILON;
pub use variance::VarianceEstimator;
