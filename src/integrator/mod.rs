//! Estimators of the light transport equation: a path tracer and a direct-lighting
//! integrator, generic over a few small traits ([`Scene`], [`Bsdf`], [`SampleSource`]) so that
//! any renderer can use them with its own geometry, materials and lights.
//!
//! Conventions: BSDFs work in a z-up local [`Frame`] around the shading normal; `wo` points
//! toward the viewer and `wi` toward the light; every directional pdf is per unit solid
//! angle. Radiance is linear RGB in [`glam::Vec3`].
//!
//! ```
//! use mcrt::integrator::{PathTracer, Strategy};
//!
//! let pt = PathTracer { max_depth: 2, rr_depth: 5, strategy: Strategy::MisPower };
//! assert_eq!(pt.strategy.name(), "power");
//! ```

mod direct;
mod frame;
mod path;
mod strategy;
mod traits;

pub use direct::DirectIntegrator;
pub use frame::Frame;
pub use path::{PathResult, PathTracer};
pub use strategy::Strategy;
pub use traits::{Bsdf, BsdfFlags, BsdfSample, LightSample, SampleSource, Scene, SurfacePoint};

/// `x > 0`, false for NaN: the guard in front of every division by a density.
#[inline]
pub fn is_positive(x: f32) -> bool {
    x > 0.0
}

/// Either estimator, chosen at run time from the scene's `integrator` element.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Integrator {
    /// Path tracing.
    Path(PathTracer),
    /// Direct lighting.
    Direct(DirectIntegrator),
}

impl Integrator {
    /// Estimates the radiance along one camera ray.
    #[inline]
    pub fn li<S: Scene, R: SampleSource>(
        &self,
        scene: &S,
        origin: glam::Vec3,
        dir: glam::Vec3,
        t_max: f32,
        rng: &mut R,
    ) -> PathResult {
        match self {
            Integrator::Path(p) => p.li(scene, origin, dir, t_max, rng),
            Integrator::Direct(d) => d.li(scene, origin, dir, t_max, rng),
        }
    }

    /// The strategy either estimator uses.
    pub fn strategy(&self) -> Strategy {
        match self {
            Integrator::Path(p) => p.strategy,
            Integrator::Direct(d) => d.strategy,
        }
    }

    /// Replaces the strategy.
    pub fn set_strategy(&mut self, s: Strategy) {
        match self {
            Integrator::Path(p) => p.strategy = s,
            Integrator::Direct(d) => d.strategy = s,
        }
    }
}
