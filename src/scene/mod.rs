//! The reference scene used by the renderer and the tests: its description (what a scene
//! file says), the Mitsuba 3 XML loader, geometry and acceleration, materials, lights, the
//! camera, and the render loop.

pub mod description;
