//! The library's integration tests, one module per former test file, in one binary so that
//! the renderer-free tests link once (docs/testing.md, "CI time"). Run one file's tests with
//! `cargo test --release -p mcrt --test it MODULE::`, e.g. `chi2_warps::`.
//!
//! The chi-square modules need the feature `stats` and the samplers' module `sobol`, as their
//! `required-features` did when they were binaries of their own.

#[cfg(feature = "stats")]
mod common;
#[path = "../../examples/custom_scene.rs"]
#[allow(dead_code)] // the example's `main`
mod custom_scene;
#[path = "common/props.rs"]
mod props;
mod warp_basic_support;

#[cfg(feature = "stats")]
mod chi2_anisotropic_microfacet;
#[cfg(feature = "stats")]
mod chi2_calibration;
#[cfg(feature = "stats")]
mod chi2_distributions;
#[cfg(feature = "stats")]
mod chi2_guiding;
#[cfg(feature = "stats")]
mod chi2_harness;
#[cfg(feature = "stats")]
mod chi2_harness_edges;
#[cfg(feature = "stats")]
mod chi2_light_bvh;
#[cfg(feature = "stats")]
mod chi2_warps;
#[cfg(feature = "stats")]
mod chi2_warps_toolbox;
mod distribution_properties;
mod distribution_properties_2d;
mod integrator_custom_scene;
mod integrator_guided;
mod light_bvh_properties;
mod ris_unbiased;
#[cfg(feature = "sobol")]
mod samplers;
mod streaming_properties;
mod warp_accuracy_basic;
mod warp_edge_inputs;
mod warp_integrals_microfacet;
mod warp_lat_long;
mod warp_properties_basic;
mod warp_properties_microfacet;
mod warp_properties_toolbox;
