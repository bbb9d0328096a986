//! The one file that calls the renderer. Until `mcrt::scene::render` (branch `transport`) is
//! in `main`, [`backend`] reports what is missing and the rendering study is skipped.

use crate::render_study::Backend;

/// The renderer behind the rendering study, or why there is none.
pub fn backend() -> Result<Box<dyn Backend>, String> {
    Err(
        "the renderer is not in this build yet: examples/convergence/renderer.rs must wrap \
         mcrt::scene::render::Renderer (strategy via mcrt::integrator::Strategy, and a \
         sampler choice) once branch `transport` is merged into main"
            .into(),
    )
}
