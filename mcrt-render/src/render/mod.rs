//! The renderer: builds the estimators' view of a [`SceneDescription`] and renders it in
//! parallel into a [`Film`](crate::film::Film).
//!
//! **Simulating only what a scene calls for.** [`Effects::of`] inspects materials, lights and
//! `max_depth`; [`Renderer::render`] then picks one of eight monomorphised render loops: the
//! material type is `Sided<Diffuse>` when every material is Lambertian (no glossy, mirror or
//! refraction code is compiled into that loop) and `Sided<AnyBsdf>` otherwise, and the
//! presence of point lights and of an environment are const generic flags, so a scene
//! without them never tests for them. `max_depth = 2` ends the path loop after the emitter
//! found by the first bounce's BSDF sample, so no indirect bounce is ever traced.
//!
//! ```no_run
//! use mcrt_render::render::{RenderOptions, Renderer};
//! use std::sync::atomic::AtomicBool;
//!
//! let desc = mcrt_render::cornell_box::cornell_box();
//! let r = Renderer::new(&desc, &RenderOptions { spp: Some(16), ..Default::default() })?;
//! let out = r.render(&|_, _| {}, &AtomicBool::new(false));
//! out.write_exr(std::path::Path::new("cornell-box.exr"))?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod bidir;
mod bidir_view;
mod dispatch;
mod effects;
mod error;
mod estimator;
mod guided_combine;
mod guided_loop;
mod material;
mod mlt_loop;
mod options;
mod output;
mod samples;
mod split;
mod tiles;
mod view;

pub use effects::Effects;
pub use error::RenderError;
pub use guided_loop::GuidingReport;
pub use options::RenderOptions;
pub use output::RenderOutput;

pub use crate::geometry::{AccelKind, ShapeSampling};

use crate::bsdf::{AnyBsdf, Sided, TexturedBsdf};
use crate::camera::Camera;
use crate::description::SceneDescription;
use crate::film::{Crop, PixelFilter, SampleRange};
use crate::geometry::Geometry;
use crate::light::Lights;
use mcrt::integrator::{Bdpt, Integrator, MisWeightCheck, MisWeightOutcome};
use mcrt::sampling::sampler::AnySampler;
use std::sync::atomic::AtomicBool;

/// A scene ready to render.
pub struct Renderer {
    geometry: Geometry,
    lights: Lights,
    bsdfs: Vec<Sided<AnyBsdf>>,
    /// The materials with their textures, when any shape has a textured parameter.
    textured: Option<Vec<TexturedBsdf>>,
    camera: Camera,
    integrator: Integrator,
    /// The guided path tracer, when the scene's integrator is `guided` (then `integrator`
    /// is the path tracer with the same depth, roulette and strategy).
    guided: Option<guided_loop::GuidedSetup>,
    filter: PixelFilter,
    width: u32,
    height: u32,
    spp: u32,
    sampler: AnySampler,
    threads: usize,
    effects: Effects,
    specialize: bool,
    seed: u64,
    samples: SampleRange,
    crop: Crop,
    identity: u64,
    /// The `moment` integrator's nested name, if the scene has one.
    moment: Option<String>,
    /// The further integrators nested in `moment`, with their names (empty without one).
    moment_more: Vec<(String, Integrator)>,
}

/// A stop flag that is never set.
static NEVER: AtomicBool = AtomicBool::new(false);

/// The most worker threads a render uses ([`RenderOptions::threads`] is clamped to it):
/// far more than any machine has cores, and few enough that spawning them is harmless.
pub const MAX_THREADS: usize = 1024;

/// Runs `f` in a pool of `threads` rayon threads, at most [`MAX_THREADS`] (0: the global
/// pool, all cores; also if the pool cannot be made).
fn on_threads<R: Send>(threads: usize, f: impl FnOnce() -> R + Send) -> R {
    if threads > 0 {
        let n = threads.min(MAX_THREADS);
        if let Ok(pool) = rayon::ThreadPoolBuilder::new().num_threads(n).build() {
            return pool.install(f);
        }
    }
    f()
}

impl Renderer {
    /// Prepares a scene: geometry, lights, materials, camera and integrator. The description
    /// is not checked again: its parts are [`Checked`](crate::description::Checked) ones,
    /// checked when they were made (by the loader, or in code). An `opts.integrator` of
    /// another kind is made from the scene's and checked; then the sample count is resolved
    /// once, after every override (`opts.spp`, or `mutations_per_pixel` for `mlt`, rounded
    /// by the sampler), and a render past the work limit is refused.
    /// Mesh files are read and the acceleration structure built on `opts.threads` threads,
    /// as the render runs.
    pub fn new(desc: &SceneDescription, opts: &RenderOptions) -> Result<Self, RenderError> {
        on_threads(opts.threads, || Self::prepare(desc, opts))
    }

    /// The effects this scene needs.
    pub fn effects(&self) -> Effects {
        self.effects
    }

    /// The sample generator.
    pub fn sampler(&self) -> &AnySampler {
        &self.sampler
    }

    /// Samples per pixel that [`Renderer::render`] will take (after the sampler's rounding).
    pub fn spp(&self) -> u32 {
        self.spp
    }

    /// Image size.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// The integrator (with the strategy in use); for `guided`, the path tracer it guides
    /// (same depth, roulette and strategy: see [`Renderer::guided`]).
    pub fn integrator(&self) -> &Integrator {
        &self.integrator
    }

    /// The number of lights the light BVH of next-event estimation chooses among (each
    /// emitting triangle of a mesh counted), or `None` when the scene has too few lights
    /// with a position for it.
    pub fn light_bvh_lights(&self) -> Option<usize> {
        self.lights.bvh_lights()
    }

    /// The guided path tracer, when the integrator is `guided`.
    pub fn guided(&self) -> Option<&mcrt::integrator::GuidedPathTracer> {
        self.guided.as_ref().map(|g| &g.tracer)
    }

    /// The integrator's name: `guided`, or [`Integrator::name`].
    pub fn integrator_name(&self) -> &'static str {
        if self.guided.is_some() {
            "guided"
        } else {
            self.integrator.name()
        }
    }

    /// Checks the multiple-importance weights of `bdpt` on this scene as the bidirectional
    /// estimators see it (materials, lights, the camera and the pixel filter's coverage):
    /// [`Bdpt::check_mis_weights`], a test of the scene's densities. The scene is the
    /// general render loop's (every material type, point lights and the environment handled
    /// at run time).
    ///
    /// ```
    /// use mcrt::integrator::{Bdpt, MisWeightCheck};
    /// use mcrt_render::render::{RenderOptions, Renderer};
    ///
    /// let desc = mcrt_render::cornell_box::cornell_box_with(1, 16, -1);
    /// let r = Renderer::new(&desc, &RenderOptions::default())?;
    /// let check = MisWeightCheck { paths: 50, ..MisWeightCheck::default() };
    /// r.check_mis_weights(&Bdpt::default(), &check).assert_passed();
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn check_mis_weights(&self, bdpt: &Bdpt, check: &MisWeightCheck) -> MisWeightOutcome {
        match &self.textured {
            Some(textured) => {
                bdpt.check_mis_weights(&self.view::<_, true, true>(textured.clone(), &NEVER), check)
            }
            None => bdpt.check_mis_weights(
                &self.view::<_, true, true>(self.bsdfs.clone(), &NEVER),
                check,
            ),
        }
    }
}

#[cfg(test)]
mod thread_tests {
    use super::on_threads;

    /// Scene preparation (mesh files, the BVH build) and rendering run on the pool
    /// `--threads` asks for.
    #[test]
    fn work_runs_on_the_requested_number_of_threads() {
        assert_eq!(on_threads(1, rayon::current_num_threads), 1);
        assert_eq!(on_threads(3, rayon::current_num_threads), 3);
        // Issue 26: far more threads than any machine has are clamped.
        assert_eq!(
            on_threads(usize::MAX, rayon::current_num_threads),
            super::MAX_THREADS
        );
        assert_eq!(
            on_threads(0, rayon::current_num_threads),
            rayon::current_num_threads()
        );
    }
}
