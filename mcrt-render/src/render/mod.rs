//! The renderer: builds the estimators' view of a [`SceneDescription`] and renders it in
//! parallel into a [`Film`].
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
mod effects;
mod error;
mod material;
mod mlt_loop;
mod split;
mod tiles;
mod view;

pub use effects::Effects;
pub use error::RenderError;
pub(crate) use view::SceneView;

pub use crate::geometry::{AccelKind, ShapeSampling};

use crate::bsdf::{AnyBsdf, Sided, TexturedBsdf};
use crate::camera::Camera;
use crate::description::{
    IntegratorDesc, IntegratorKind, SamplerKind, SceneDescription, ShapeKind,
};
use crate::film::{write_exr, write_png, Crop, Film, ImageError, PixelFilter, SampleRange};
use crate::geometry::Geometry;
use crate::light::Lights;
use glam::{Vec3, Vec4Swizzles};
use material::Material;
use mcrt::integrator::{
    Bdpt, DirectIntegrator, Integrator, MisWeightCheck, MisWeightOutcome, Mlt, PathTracer, Strategy,
};
use mcrt::sampling::sampler::{
    AnySampler, CmjSampler, HaltonSampler, IndependentSampler, R2Sampler, Sampler, Sobol4dSampler,
    SobolSampler, StratifiedSampler,
};
use mcrt::sampling::SamplingError;
use std::path::Path;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

/// Overrides of what the scene file says.
#[derive(Debug, Clone, PartialEq)]
pub struct RenderOptions {
    /// Samples per pixel (else the file's `sample_count`).
    pub spp: Option<u32>,
    /// Seed (else the file's sampler seed).
    pub seed: Option<u64>,
    /// Worker threads; 0 uses all cores. At most [`MAX_THREADS`]: more are clamped to it
    /// (the `render` program refuses them).
    pub threads: usize,
    /// Sampling strategy at every vertex (else MIS with the power heuristic).
    pub strategy: Option<Strategy>,
    /// Acceleration structure.
    pub accel: AccelKind,
    /// How area lights on triangles and rectangles are sampled by the path tracer and the
    /// direct integrator (by default [`ShapeSampling::Auto`]: by solid angle from near, by
    /// area from far); `bdpt` and `mlt` always sample them by
    /// area (their other strategies cover the region near a light where solid-angle sampling
    /// helps, at a fraction of its cost).
    pub light_sampling: ShapeSampling,
    /// Sample generator (else the file's `sampler` type).
    pub sampler: Option<SamplerKind>,
    /// Integrator type (else the file's); the file's `max_depth` and `rr_depth` carry over
    /// where both have them.
    pub integrator: Option<IntegratorKind>,
    /// Bidirectional path tracing with this strategy `(s, t)` alone at unit weight (for
    /// tests and pictures of one strategy).
    pub bdpt_only: Option<(u32, u32)>,
    /// Pick the render loop specialised to the scene's effects (default). `false` always
    /// runs the general loop (every material type, point lights and environment checked at
    /// run time); for benchmarks and tests of the specialisation.
    pub specialize: bool,
    /// Render only the pixel samples with these indices (`render --samples START..END`),
    /// exactly those a render of every sample draws for them; else all of them. Not with
    /// `mlt`, whose Markov chains are not divided by pixel sample.
    pub samples: Option<SampleRange>,
    /// Render only these pixels (`render --crop x0,y0,x1,y1`); else the whole image. Not
    /// with `mlt`.
    pub crop: Option<Crop>,
}

impl Default for RenderOptions {
    fn default() -> Self {
        Self {
            spp: None,
            seed: None,
            threads: 0,
            strategy: None,
            accel: AccelKind::Bvh,
            sampler: None,
            light_sampling: ShapeSampling::Auto,
            specialize: true,
            integrator: None,
            bdpt_only: None,
            samples: None,
            crop: None,
        }
    }
}

/// A scene ready to render.
pub struct Renderer {
    geometry: Geometry,
    lights: Lights,
    bsdfs: Vec<Sided<AnyBsdf>>,
    /// The materials with their textures, when any shape has a textured parameter.
    textured: Option<Vec<TexturedBsdf>>,
    camera: Camera,
    integrator: Integrator,
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
}

/// A finished (or cancelled) render.
pub struct RenderOutput {
    /// The accumulated samples.
    pub film: Film,
    /// Samples rendered.
    pub samples: u64,
    /// Rays cast.
    pub rays: u64,
    /// Samples whose value came out NaN or infinite; they are added to their pixel as 0
    /// and counted here (a correct render has none).
    pub nonfinite_samples: u64,
    /// Wall-clock render time in seconds.
    pub seconds: f64,
    /// For bidirectional path tracing: what each strategy contributed.
    pub strategies: Option<mcrt::integrator::StrategyStats>,
}

/// Radius of a sphere about the origin that holds every shape (approximate for meshes read
/// from files, which count as a unit cube).
fn scene_radius(desc: &SceneDescription) -> f32 {
    let mut r = 1.0f32;
    for s in &desc.shapes {
        let pts: Vec<Vec3> = match &s.kind {
            ShapeKind::Mesh { positions, .. } => positions.clone(),
            ShapeKind::Sphere { center, radius } => (0..8)
                .map(|i| *center + Vec3::new(bit(i, 0), bit(i, 1), bit(i, 2)) * *radius)
                .collect(),
            _ => (0..8)
                .map(|i| Vec3::new(bit(i, 0), bit(i, 1), bit(i, 2)))
                .collect(),
        };
        for p in pts {
            r = r.max((s.to_world * p.extend(1.0)).xyz().length());
        }
    }
    r
}

/// The sampler for a scene's `sampler` type (see `sampling::sampler` for the mapping of
/// Mitsuba's tags; stratified counts round up to a square; Halton and R2 are ours only).
fn make_sampler(kind: SamplerKind, spp: u32, seed: u64) -> Result<AnySampler, SamplingError> {
    Ok(match kind {
        SamplerKind::Independent => IndependentSampler::new(spp, seed)?.into(),
        SamplerKind::Stratified => StratifiedSampler::new(spp, seed, true)?.into(),
        SamplerKind::LowDiscrepancy => Sobol4dSampler::new(spp, seed)?.into(),
        SamplerKind::Sobol => SobolSampler::new(spp, seed)?.into(),
        SamplerKind::Halton => HaltonSampler::new(spp, seed)?.into(),
        SamplerKind::R2 => R2Sampler::new(spp, seed)?.into(),
        SamplerKind::MultiJitter => CmjSampler::new(spp, seed, true)?.into(),
        SamplerKind::Orthogonal => match AnySampler::by_name("orthogonal", spp, seed) {
            Some(s) => s?,
            None => unreachable!("`orthogonal` is one of AnySampler::NAMES"),
        },
    })
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

fn bit(i: u32, b: u32) -> f32 {
    if (i >> b) & 1 == 1 {
        1.0
    } else {
        -1.0
    }
}

impl Renderer {
    /// Prepares a scene: geometry, lights, materials, camera and integrator. First refuses,
    /// naming the part of the scene, whatever [`validate::scene`](crate::validate::scene)
    /// refuses (with `opts.spp` in place of the file's sample count, if given).
    /// Mesh files are read and the acceleration structure built on `opts.threads` threads,
    /// as the render runs.
    pub fn new(desc: &SceneDescription, opts: &RenderOptions) -> Result<Self, RenderError> {
        on_threads(opts.threads, || Self::prepare(desc, opts))
    }

    fn prepare(desc: &SceneDescription, opts: &RenderOptions) -> Result<Self, RenderError> {
        let spp = opts.spp.unwrap_or(desc.sensor.sampler.sample_count);
        crate::validate::scene(desc, spp).map_err(RenderError::Invalid)?;
        // The bidirectional estimators' s = 1 strategy samples rectangles and triangles by
        // area: their other strategies cover what solid-angle sampling adds near a light,
        // at a fraction of its cost (spheres keep cone sampling either way).
        let kind = opts.integrator.unwrap_or(desc.integrator.kind());
        let shape_sampling = match kind {
            IntegratorKind::Bdpt | IntegratorKind::Mlt => ShapeSampling::Area,
            _ => opts.light_sampling,
        };
        // The loader has resolved mesh file names against the scene file's folder already
        // (a description built in code names them relative to the working directory).
        let geo = Geometry::new(&desc.shapes, None, opts.accel)
            .map_err(RenderError::Geometry)?
            .with_shape_sampling(shape_sampling);
        let lights = Lights::new(desc, &geo, scene_radius(desc)).map_err(RenderError::Lights)?;
        let camera = Camera::new(&desc.sensor).map_err(RenderError::Camera)?;
        let bsdfs = desc
            .shapes
            .iter()
            .enumerate()
            .map(|(i, s)| {
                AnyBsdf::from_desc(&s.bsdf).map_err(|error| RenderError::Material {
                    shape: i,
                    id: s.id.clone(),
                    error,
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let textured = desc.shapes.iter().any(|s| s.bsdf.is_textured()).then(|| {
            bsdfs
                .iter()
                .zip(&desc.shapes)
                .map(|(b, s)| TexturedBsdf::with_base(b.clone(), &s.bsdf))
                .collect::<Vec<_>>()
        });
        let strategy = opts.strategy.unwrap_or_default();
        let integrator_desc = match opts.integrator {
            Some(kind) => desc.integrator.with_kind(kind),
            None => desc.integrator,
        };
        if let IntegratorDesc::Mlt { max_depth, .. } = integrator_desc {
            let most = crate::validate::MAX_MLT_DEPTH;
            if !(1..=most).contains(&max_depth) {
                return Err(RenderError::Invalid(format!(
                    "integrator: max_depth {max_depth} (the scene's, carried over to mlt) must \
                     lie in [1, {most}] for mlt: a chain keeps its length, and every length \
                     has its own bootstrap samples and image; lower it in the scene or with -D"
                )));
            }
        }
        let integrator = match integrator_desc {
            IntegratorDesc::Path {
                max_depth,
                rr_depth,
            } => Integrator::Path(PathTracer {
                max_depth,
                rr_depth,
                strategy,
            }),
            IntegratorDesc::Direct {
                emitter_samples,
                bsdf_samples,
            } => Integrator::Direct(DirectIntegrator {
                emitter_samples,
                bsdf_samples,
                strategy,
            }),
            IntegratorDesc::Bdpt {
                max_depth,
                rr_depth,
            } => Integrator::Bdpt(Bdpt {
                max_depth,
                rr_depth,
                strategy,
                only: opts.bdpt_only,
            }),
            IntegratorDesc::Mlt {
                max_depth,
                bootstrap_samples,
                chains,
                mutations_per_pixel,
                large_step_prob,
                sigma,
            } => Integrator::Mlt(Mlt {
                max_depth: max_depth.max(1) as u32,
                bootstrap_samples,
                chains,
                mutations_per_pixel,
                large_step_prob,
                sigma,
                strategy,
            }),
        };
        if matches!(integrator, Integrator::Bdpt(_) | Integrator::Mlt(_)) {
            if !camera.is_similarity() {
                return Err(RenderError::Unsupported {
                    integrator: integrator.name(),
                    reason: "the camera's to_world must be a rotation, uniform scale and \
                             translation (its importance is exact only then)",
                });
            }
            if matches!(strategy, Strategy::BsdfOnly | Strategy::LightOnly)
                && matches!(integrator, Integrator::Mlt(_))
            {
                return Err(RenderError::Unsupported {
                    integrator: "mlt",
                    reason: "it weighs its strategies by MIS: use --strategy balance or power",
                });
            }
        }
        let film = &desc.sensor.film;
        if film.width == 0 || film.height == 0 {
            return Err(RenderError::EmptyFilm {
                width: film.width,
                height: film.height,
            });
        }
        // The rendered window: the whole film, or its crop window (the camera maps it).
        let (width, height) = (camera.width(), camera.height());
        let (w64, h64) = (u64::from(width), u64::from(height));
        crate::memory::check(
            &format!("the film of {width} × {height} pixels"),
            Film::bytes_for(w64, h64),
        )
        .map_err(RenderError::Invalid)?;
        if let Integrator::Mlt(m) = &integrator {
            let need = mlt_loop::state_bytes(m, w64, h64);
            crate::memory::check(
                &format!(
                    "Metropolis light transport at {width} × {height} pixels and max_depth {} \
                     (its chains' images, per-length sums and bootstrap)",
                    m.max_depth
                ),
                need.saturating_add(Film::bytes_for(w64, h64)),
            )
            .map_err(RenderError::Invalid)?;
        }
        let mut effects = Effects::of(&bsdfs, &lights, &integrator);
        if textured.is_some() {
            effects.textures = true;
            effects.diffuse_only = false;
        }
        let file_spp = match integrator {
            Integrator::Mlt(m) => m.mutations_per_pixel,
            _ => desc.sensor.sampler.sample_count,
        };
        let spp = opts.spp.unwrap_or(file_spp);
        let seed = opts.seed.unwrap_or(desc.sensor.sampler.seed);
        let kind = opts.sampler.unwrap_or(desc.sensor.sampler.kind);
        let sampler = make_sampler(kind, spp, seed).map_err(RenderError::Sampler)?;
        let spp = sampler.samples_per_pixel();
        let (samples, crop) = split::window(opts, &integrator, spp, width, height)?;
        let mut resolved = desc.clone();
        resolved.integrator = integrator_desc;
        resolved.sensor.sampler = crate::description::SamplerDesc {
            kind,
            sample_count: spp,
            seed,
        };
        let identity = split::render_identity(
            &resolved,
            None,
            &format!(
                "{integrator:?} {:?} {shape_sampling:?} {}",
                opts.accel, opts.specialize
            ),
        )
        .map_err(RenderError::Invalid)?;
        Ok(Self {
            geometry: geo,
            lights,
            bsdfs,
            textured,
            camera,
            integrator,
            filter: PixelFilter::from_desc(&film.filter),
            width,
            height,
            spp,
            sampler,
            threads: opts.threads,
            effects,
            specialize: opts.specialize,
            seed,
            samples,
            crop,
            identity,
        })
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

    /// The integrator (with the strategy in use).
    pub fn integrator(&self) -> &Integrator {
        &self.integrator
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

    /// Renders the sample range and crop; `progress(done, total)` is called with sample
    /// counts from worker threads, and setting `cancel` stops early, keeping every sample
    /// taken (pixels then report their own counts). The film is the whole image; pixels
    /// outside the crop hold no sample.
    pub fn render(
        &self,
        progress: &(dyn Fn(u64, u64) + Sync),
        cancel: &AtomicBool,
    ) -> RenderOutput {
        let start = Instant::now();
        let params = tiles::LoopParams {
            camera: &self.camera,
            integrator: &self.integrator,
            filter: &self.filter,
            width: self.width,
            height: self.height,
            spp: self.spp,
            samples: self.samples,
            window: self.crop,
            sampler: &self.sampler,
            seed: self.seed,
            t_max: f32::INFINITY,
            progress,
            cancel,
        };
        let (film, stats) = on_threads(self.threads, || self.dispatch(&params));
        RenderOutput {
            film,
            samples: stats.samples,
            rays: stats.rays,
            nonfinite_samples: stats.nonfinite,
            seconds: start.elapsed().as_secs_f64(),
            strategies: stats.strategies,
        }
    }

    fn dispatch(&self, p: &tiles::LoopParams<'_>) -> (Film, tiles::LoopStats) {
        let e = self.effects;
        // Textures: materials formed per hit (with or without specialisation).
        if let Some(textured) = &self.textured {
            return if self.specialize {
                self.run_specialised(textured.clone(), p)
            } else {
                self.run_loop(
                    &self.view::<_, true, true>(textured.clone(), self.stop(p)),
                    p,
                )
            };
        }
        if !self.specialize {
            return self.run_loop(
                &self.view::<_, true, true>(self.bsdfs.clone(), self.stop(p)),
                p,
            );
        }
        if e.diffuse_only {
            let bsdfs: Vec<_> = self
                .bsdfs
                .iter()
                .map(|b| Sided {
                    bsdf: b.bsdf.as_diffuse().unwrap_or(crate::bsdf::Diffuse {
                        reflectance: Vec3::ZERO,
                    }),
                    two_sided: b.two_sided,
                })
                .collect();
            self.run_specialised(bsdfs, p)
        } else {
            self.run_specialised(self.bsdfs.clone(), p)
        }
    }

    fn run_specialised<B: Material + Sync>(
        &self,
        bsdfs: Vec<B>,
        p: &tiles::LoopParams<'_>,
    ) -> (Film, tiles::LoopStats) {
        match (self.effects.delta_lights, self.effects.environment) {
            (false, false) => self.run_loop(&self.view::<B, false, false>(bsdfs, self.stop(p)), p),
            (true, false) => self.run_loop(&self.view::<B, true, false>(bsdfs, self.stop(p)), p),
            (false, true) => self.run_loop(&self.view::<B, false, true>(bsdfs, self.stop(p)), p),
            (true, true) => self.run_loop(&self.view::<B, true, true>(bsdfs, self.stop(p)), p),
        }
    }

    /// What stops a path of the render's integrator at its next bounce: the cancel flag
    /// for the path tracer, whose paths have no bound on their length (`max_depth` −1 and
    /// a huge `rr_depth`), never for the others (the bidirectional paths stop at
    /// `MAX_VERTICES`, `mlt`'s at [`crate::validate::MAX_MLT_DEPTH`], `direct`'s at once).
    fn stop<'a>(&self, p: &tiles::LoopParams<'a>) -> &'a AtomicBool {
        match self.integrator {
            Integrator::Path(_) => p.cancel,
            _ => &NEVER,
        }
    }

    /// The estimators' view of the scene with materials `bsdfs`, whose paths end once
    /// `stop` is set.
    fn view<'a, B, const DELTA: bool, const ENV: bool>(
        &'a self,
        bsdfs: Vec<B>,
        stop: &'a AtomicBool,
    ) -> SceneView<'a, B, DELTA, ENV> {
        SceneView {
            geometry: &self.geometry,
            bsdfs,
            lights: &self.lights,
            camera: &self.camera,
            world: self.geometry.bounding_sphere(),
            filter: &self.filter,
            stop,
        }
    }

    /// The render loop of the integrator.
    fn run_loop<B: Material + Sync, const DELTA: bool, const ENV: bool>(
        &self,
        view: &SceneView<'_, B, DELTA, ENV>,
        p: &tiles::LoopParams<'_>,
    ) -> (Film, tiles::LoopStats) {
        match &self.integrator {
            Integrator::Bdpt(b) => bidir::render_loop_bdpt(view, p, b),
            Integrator::Mlt(m) => mlt_loop::render_mlt(view, p, m),
            _ => tiles::render_loop(view, p),
        }
    }
}

impl RenderOutput {
    /// The image (per-pixel means), row-major from the top-left.
    pub fn image(&self) -> Vec<Vec3> {
        self.film.mean()
    }

    /// Writes the image as linear float RGB EXR.
    pub fn write_exr(&self, path: &Path) -> Result<(), ImageError> {
        write_exr(path, self.film.width(), self.film.height(), &self.image())
    }

    /// Writes the image as sRGB PNG.
    pub fn write_png(&self, path: &Path) -> Result<(), ImageError> {
        write_png(path, self.film.width(), self.film.height(), &self.image())
    }

    /// Writes the per-pixel variance of the estimate as EXR.
    pub fn write_variance_exr(&self, path: &Path) -> Result<(), ImageError> {
        write_exr(
            path,
            self.film.width(),
            self.film.height(),
            &self.film.variance(),
        )
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
