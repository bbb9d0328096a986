//! Estimators of the light transport equation: a path tracer (and one guided by a learned
//! SD-tree, [`GuidedPathTracer`]), a direct-lighting integrator, bidirectional path tracing
//! and Metropolis light transport, generic over a few small traits ([`Scene`], [`Bsdf`],
//! [`SampleSource`]) so that any renderer can use them with its own geometry, materials and
//! lights.
//!
//! Conventions: BSDFs work in a z-up local [`Frame`](crate::sampling::Frame) around the shading normal; `wo` points
//! toward the viewer and `wi` toward the light; every directional pdf is per unit solid
//! angle. Radiance is linear RGB in [`glam::Vec3`].
//!
//! A renderer tests its scene's densities, as the bidirectional estimators' weights see
//! them, with [`Bdpt::check_mis_weights`]: on random paths the weights of all strategies must
//! sum to 1 and the estimator's own weights must equal those recomputed from the `pdf`
//! methods alone (a `pdf` that disagrees with its sampling routine fails).
//!
//! ```
//! use mcrt::integrator::{PathTracer, Strategy};
//!
//! let pt = PathTracer {
//!     max_depth: 2,
//!     rr_depth: 5,
//!     strategy: Strategy::MisPower,
//!     hide_emitters: false,
//! };
//! assert_eq!(pt.strategy.name(), "power");
//! ```

pub(crate) mod bdpt;
mod bidirectional;
mod direct;
mod guided;
mod mlt;
mod path;
mod strategy;
#[cfg(test)]
pub(crate) mod test_scene;
mod traits;

use crate::sampling::sampler::SampleSource;
pub use bdpt::{
    Bdpt, BdptBuffers, MisWeightCheck, MisWeightOutcome, MisWeightStrategy, Splat, StrategyStats,
};
pub use bidirectional::{BidirectionalScene, CameraConnection, EmissionSample, EmitterKind};
pub use direct::DirectIntegrator;
pub use guided::{GuidedPathTracer, GuidedSample};
pub use mlt::{brightness as mlt_brightness, Mlt, MltChain, MltPath, PrimarySamples};
pub use path::{PathResult, PathTracer};
pub use strategy::Strategy;
pub use traits::{Bsdf, BsdfFlags, BsdfSample, LightSample, Scene, SurfacePoint};

/// The relative shortening of every shadow ray: the estimators ask [`Scene::occluded`] about
/// `dist · (1 − SHADOW_EPSILON)` when they want to know whether the point at distance `dist`
/// is visible, so that the surface of that point (a light, a vertex of the other subpath)
/// cannot hide itself.
pub const SHADOW_EPSILON: f32 = 1e-3;

/// Whether something hides the point at distance `dist` along `dir` from `from` (a light at
/// infinity when `dist` is infinite): [`Scene::occluded`] over the distance shortened by
/// [`SHADOW_EPSILON`]. Every estimator's visibility test goes through here. A distance that
/// is not finite (infinite, or NaN from a caller's bug) tests the whole ray.
#[inline(always)]
pub(crate) fn occluded<S: Scene + ?Sized>(
    scene: &S,
    from: &SurfacePoint,
    dir: glam::Vec3,
    dist: f32,
) -> bool {
    let t_max = if dist.is_finite() {
        dist * (1.0 - SHADOW_EPSILON)
    } else {
        f32::INFINITY
    };
    scene.occluded(from, dir, t_max)
}

/// Most emitter surfaces a camera ray passes through when emitters are hidden (a guard
/// against a scene whose `trace` keeps returning the same point).
const MAX_HIDDEN_EMITTERS: u32 = 64;

/// The first hit of the camera ray from `origin` along `dir` (up to `t_max`) that is not an
/// emitter: with `hide_emitters`, the ray passes through every emitter surface, as Mitsuba
/// 3's `hide_emitters` does for the sampling integrators (and `None` then means the ray sees
/// only the hidden sky). Rays cast are added to `rays`.
#[inline(always)]
pub(crate) fn camera_hit<S: Scene + ?Sized>(
    scene: &S,
    origin: glam::Vec3,
    dir: glam::Vec3,
    t_max: f32,
    hide_emitters: bool,
    rays: &mut u32,
) -> Option<SurfacePoint> {
    let hit = scene.intersect(origin, dir, t_max);
    *rays += 1;
    if hide_emitters {
        return past_emitters(scene, hit, dir, rays);
    }
    hit
}

/// The first hit at or after `hit` along `dir` that is not an emitter (out of line: only
/// `hide_emitters` renders come here).
#[cold]
#[inline(never)]
fn past_emitters<S: Scene + ?Sized>(
    scene: &S,
    mut hit: Option<SurfacePoint>,
    dir: glam::Vec3,
    rays: &mut u32,
) -> Option<SurfacePoint> {
    let mut passed = 0;
    while let Some(sp) = hit.filter(|sp| scene.is_emitter(sp)) {
        passed += 1;
        if passed > MAX_HIDDEN_EMITTERS {
            return None;
        }
        hit = scene.trace(&sp, dir);
        *rays += 1;
    }
    hit
}

/// `x > 0`, false for NaN: the guard in front of every division by a density.
#[inline]
pub fn is_positive(x: f32) -> bool {
    x > 0.0
}

/// Samples `bsdf` at `wo`, drawing the component choice `u1` from `samples` only when the
/// BSDF reads it (`0.5` otherwise), then the direction `u2`: the one sampling step of every
/// estimator's random walk.
#[inline(always)]
pub(crate) fn sample_bsdf<B: Bsdf, R: SampleSource>(
    bsdf: &B,
    wo: glam::Vec3,
    samples: &mut R,
) -> Option<BsdfSample> {
    let u1 = component_value(bsdf, samples);
    let u2 = samples.next_2d();
    bsdf.sample(wo, u1, u2)
}

/// The value with which `bsdf` chooses its component: drawn from `samples` if it has
/// components to choose from, else ½ (no dimension spent).
#[inline]
pub(crate) fn component_value<B: Bsdf, R: SampleSource>(bsdf: &B, samples: &mut R) -> f32 {
    if bsdf.samples_component() {
        samples.next_1d()
    } else {
        0.5
    }
}

/// An estimator, chosen at run time from the scene's `integrator` element.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Integrator {
    /// Path tracing.
    Path(PathTracer),
    /// Direct lighting.
    Direct(DirectIntegrator),
    /// Bidirectional path tracing.
    Bdpt(Bdpt),
    /// Metropolis light transport.
    Mlt(Mlt),
}

impl Integrator {
    /// Estimates the radiance along one camera ray, for the per-ray estimators (path
    /// tracing, direct lighting). [`Bdpt`] and [`Mlt`] are not per-ray estimators (they
    /// splat onto the film and need a [`BidirectionalScene`]): for them this returns zero
    /// radiance and no rays; call [`Bdpt::sample`], or run [`MltChain`]s (the renderer does).
    #[inline]
    pub fn li<S: Scene, R: SampleSource>(
        &self,
        scene: &S,
        origin: glam::Vec3,
        dir: glam::Vec3,
        t_max: f32,
        samples: &mut R,
    ) -> PathResult {
        match self {
            Integrator::Path(p) => p.li(scene, origin, dir, t_max, samples),
            Integrator::Direct(d) => d.li(scene, origin, dir, t_max, samples),
            Integrator::Bdpt(_) | Integrator::Mlt(_) => PathResult::default(),
        }
    }

    /// The name of the integrator type (`path`, `direct`, `bdpt`, `mlt`).
    pub fn name(&self) -> &'static str {
        match self {
            Integrator::Path(_) => "path",
            Integrator::Direct(_) => "direct",
            Integrator::Bdpt(_) => "bdpt",
            Integrator::Mlt(_) => "mlt",
        }
    }

    /// The strategy either estimator uses.
    pub fn strategy(&self) -> Strategy {
        match self {
            Integrator::Path(p) => p.strategy,
            Integrator::Direct(d) => d.strategy,
            Integrator::Bdpt(b) => b.strategy,
            Integrator::Mlt(m) => m.strategy,
        }
    }

    /// Replaces the strategy.
    pub fn set_strategy(&mut self, s: Strategy) {
        match self {
            Integrator::Path(p) => p.strategy = s,
            Integrator::Direct(d) => d.strategy = s,
            Integrator::Bdpt(b) => b.strategy = s,
            Integrator::Mlt(m) => m.strategy = s,
        }
    }
}
