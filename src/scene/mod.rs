//! The reference scene used by the renderer and the tests: its description (what a scene
//! file says), the Mitsuba 3 XML loader, geometry and acceleration, materials, lights, the
//! camera, and the render loop.

pub mod accel;
pub mod bsdf;
pub mod camera;
pub mod cornell_box;
pub mod description;
pub mod film;
pub mod geometry;
pub mod light;
pub mod loader;
pub mod mesh_file;
pub mod obj;
pub mod render;
pub mod validate;
