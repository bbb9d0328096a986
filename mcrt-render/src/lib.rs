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
//! One home per job; dependencies run down this list (lights use the geometry, the renderer
//! uses both; the library `mcrt` knows nothing of this crate):
//!
//! | module | its job |
//! |---|---|
//! | [`description`] | what a scene file says, as plain data ([`description::SceneDescription`]) |
//! | [`loader`] | Mitsuba 3 XML → description, with located errors; [`validate`] its limits |
//! | [`mesh_file`] | OBJ, PLY and `serialized` meshes → one triangle-mesh type |
//! | [`accel`] | acceleration structures over bounding boxes, knowing nothing of primitives |
//! | [`geometry`] | shapes in world space: ray queries (`geometry/query/`: the one switch over backends), shape sampling (`geometry/sample/`: one sampler per shape), ray offsets |
//! | [`bsdf`] | materials |
//! | [`texture`] | `bitmap` and `checkerboard` textures: image decoding, filtering, wrapping |
//! | [`light`] | emitters, the choice among them, and next-event and emission sampling through the geometry's shape samplers |
//! | [`camera`] | the pinhole camera |
//! | [`film`] | pixel filters, accumulation, image files, comparison with references |
//! | [`render`] | the tiled render loop that runs the integrators on a scene |
//! | [`cornell_box`] | the built-in scene |
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
pub mod io;
pub mod light;
pub mod loader;
pub mod mesh_file;
pub mod render;
pub mod texture;
pub mod validate;
