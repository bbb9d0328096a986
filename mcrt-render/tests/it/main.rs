//! The renderer's integration tests, one module per former test file, in one binary: each
//! binary links the whole renderer, so one link instead of about 45 (docs/testing.md, "CI
//! time"). Run one file's tests with `cargo test --release -p mcrt-render --test it
//! MODULE::`, e.g. `reference_match::`.
//!
//! Separate binaries remain for the tests that must not share a process with the others:
//! `distributed_processes`, `hostile_output` and `memory_budget` run the `render` and
//! `merge` programs (and send them signals), and `hostile_input` times the loader.

mod common;
#[path = "../distributed_common/mod.rs"]
mod distributed_common;

mod accel;
mod bdpt_weights;
mod bidirectional;
mod bsdf_mitsuba_values;
mod camera;
mod chi2_bidirectional;
mod chi2_blend_mask;
mod chi2_bsdf;
mod chi2_envmap;
mod chi2_lights;
mod chi2_plastic;
mod chi2_principled;
mod chi2_rough_dielectric;
mod distributed;
mod distributed_moment;
mod emitter_mitsuba_values;
mod envmap_variance;
mod furnace;
mod hostile_geometry;
mod instancing;
mod loader;
mod loader_compat;
mod loader_errors;
mod loader_integrators;
mod loader_mutation;
mod loader_principled;
mod many_lights_guided;
mod mesh_files;
mod moment_nested;
mod published_compat;
mod published_instanced_frames;
mod published_instancing;
mod published_integrators;
mod published_lights;
mod published_maps;
mod published_orthographic;
mod published_params;
mod published_shading;
mod reference_match;
mod render;
mod render_samplers;
mod shape_sampling;
mod strategies;
mod textures;
