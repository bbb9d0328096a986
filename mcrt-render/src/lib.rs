//! # mcrt-render: a renderer built on mcrt
//!
//! The [`mcrt`] library's first user: a renderer of a subset of Mitsuba 3's XML scene format,
//! built only on the library's public API. It holds the reference scene used by the programs
//! and the tests: its description (what a scene file says), the Mitsuba 3 XML loader,
//! geometry and acceleration, materials, lights, the camera, and the render loop; its
//! programs are `render` (a scene file, or the Cornell box, to EXR and PNG), `merge` (parts
//! of a distributed render) and `exr2png`.
//!
//! ```sh
//! cargo run --release --bin render                      # the Cornell box
//! cargo run --release --bin render -- scene.xml --spp 256
//! ```
//!
//! One home per job; dependencies run down this list: a module imports only modules above
//! it (lights use the geometry, the renderer uses both; the library `mcrt` knows nothing of
//! this crate):
//!
//! | module | its job |
//! |---|---|
//! | [`io`] | reading files from users: regular files only, at most so many bytes; EXR images with a bound on their pixels |
//! | [`scene_error`] | the scene error type, located by file, line, column and element ([`scene_error::SceneError`]) |
//! | [`scene_warning`] | the scene warning type, located as errors are ([`scene_warning::SceneWarning`]) |
//! | [`transform`] | matrices that place things: Mitsuba 3's [`transform::look_at`] |
//! | [`texture`] | `bitmap` and `checkerboard` textures: image decoding, filtering, wrapping |
//! | [`description`] | what a scene file says, as plain data ([`description::SceneDescription`]) |
//! | [`cornell_box`] | the built-in scene, as a description |
//! | [`bsdf`] | materials, built from their descriptions |
//! | [`validate`] | the limits a description must keep, shared by the loader and the renderer |
//! | [`loader`] | Mitsuba 3 XML → description, with located errors |
//! | [`mesh_file`] | OBJ, PLY and `serialized` meshes → one triangle-mesh type |
//! | [`accel`] | acceleration structures over bounding boxes, knowing nothing of primitives |
//! | [`geometry`] | shapes in world space: their data (`geometry/data.rs`), ray queries (`geometry/query/`: the one switch over backends), shape sampling (`geometry/sample/`: one sampler per shape), ray offsets |
//! | [`light`] | emitters, the choice among them, and next-event and emission sampling through the geometry's shape samplers |
//! | [`camera`] | the pinhole and thin-lens cameras |
//! | [`film`] | pixel filters, accumulation, image files written, comparison with references |
//! | [`render`] | the tiled render loop that runs the integrators on a scene |
#![forbid(unsafe_code)]
#![deny(missing_docs)]
#![deny(rustdoc::broken_intra_doc_links)]

pub mod accel;
pub mod bsdf;
pub mod camera;
pub mod cornell_box;
pub mod description;
pub mod film;
pub mod geometry;
mod invalid;
pub mod io;
pub mod light;
pub mod loader;
pub mod memory;
pub mod mesh_file;
mod param_defs;
pub mod render;
pub mod scene_error;
pub mod scene_warning;
pub mod texture;
pub mod transform;
pub mod validate;
