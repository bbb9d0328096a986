//! Running a prepared scene: the render loop specialised to its effects (materials, point
//! lights, environment) and its integrator.

use super::material::Material;
use super::view::SceneView;
use super::{bidir, mlt_loop, on_threads, tiles, RenderOutput, Renderer};
use crate::bsdf::Sided;
use crate::film::Film;
use glam::Vec3;
use mcrt::integrator::Integrator;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

impl Renderer {
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
            moment: self.moment.as_deref(),
            moment_more: &self.moment_more,
        };
        let (film, stats) = on_threads(self.threads, || self.dispatch(&params));
        RenderOutput {
            film,
            samples: stats.samples,
            rays: stats.rays,
            nonfinite_samples: stats.nonfinite,
            seconds: start.elapsed().as_secs_f64(),
            strategies: stats.strategies,
            guiding: stats.guiding,
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
            _ => &super::NEVER,
        }
    }

    /// The estimators' view of the scene with materials `bsdfs`, whose paths end once
    /// `stop` is set.
    pub(super) fn view<'a, B, const DELTA: bool, const ENV: bool>(
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
        if let Some(g) = &self.guided {
            let b = self.geometry.bounds();
            return super::guided_loop::render_guided(view, p, g, (b.min, b.max));
        }
        match &self.integrator {
            Integrator::Bdpt(b) => bidir::render_loop_bdpt(view, p, b),
            Integrator::Mlt(m) => mlt_loop::render_mlt(view, p, m),
            _ => tiles::render_loop(view, p),
        }
    }
}
