//! The small traits a renderer implements so that the estimators can run on its geometry,
//! materials and lights.

use super::Frame;
use glam::{Vec2, Vec3};

/// A point where a ray met a surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    /// Position in world space.
    pub p: Vec3,
    /// Unit geometric normal of the surface's front side (not flipped toward the ray).
    pub ng: Vec3,
    /// Shading frame; its `n` is the shading normal of the front side.
    pub frame: Frame,
    /// Ray parameter of the hit.
    pub t: f32,
    /// The renderer's shape index (opaque to the estimators).
    pub shape: u32,
    /// The renderer's primitive index within the shape (opaque to the estimators).
    pub prim: u32,
    /// Surface parameters of the hit (opaque to the estimators).
    pub uv: Vec2,
}

/// Properties of a BSDF that the estimators (and the renderer's effect analysis) use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct BsdfFlags {
    /// Has a component with a density (diffuse or glossy): next-event estimation helps.
    pub smooth: bool,
    /// Has a Dirac component (mirror, smooth glass): only BSDF sampling finds it.
    pub delta: bool,
    /// Has a glossy (microfacet) component.
    pub glossy: bool,
    /// Transmits light through the surface.
    pub transmission: bool,
}

/// One sample of a BSDF.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BsdfSample {
    /// The sampled direction (toward the light), in the local frame.
    pub wi: Vec3,
    /// `f · |cos θ_i| / pdf`, per RGB channel.
    pub weight: Vec3,
    /// Density of `wi` per unit solid angle; for a Dirac component, the discrete
    /// probability of choosing it.
    pub pdf: f32,
    /// The sampled component is a Dirac delta (no MIS with light sampling).
    pub delta: bool,
    /// Relative index of refraction crossed (1 for reflection); radiance was scaled by
    /// `1/eta²`, and Russian roulette multiplies it back.
    pub eta: f32,
}

/// A BSDF in its local, z-up frame. `wo` points toward the viewer, `wi` toward the light;
/// both are unit vectors.
pub trait Bsdf {
    /// What the BSDF contains.
    fn flags(&self) -> BsdfFlags;

    /// `f(wo, wi) · |cos θ_i|` per RGB channel, the non-delta part only.
    fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3;

    /// Density per unit solid angle with which [`Bsdf::sample`] returns `wi` (non-delta
    /// part only; 0 for a pure delta BSDF).
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32;

    /// [`Bsdf::eval`] and [`Bsdf::pdf`] at once; override when that is cheaper.
    fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        (self.eval(wo, wi), self.pdf(wo, wi))
    }

    /// Samples `wi` given `wo`: `u1` picks a component, `u2` the direction.
    fn sample(&self, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample>;

    /// The adjoint BSDF for importance transport (light subpaths), times the cosine:
    /// `f*(wo, wi)·|cos θ_i| = f(wi, wo)·|cos θ_i|`, with `wo` toward the light side (the
    /// previous vertex of a light subpath) and `wi` toward the camera side (Veach 1997,
    /// thesis, section 5.2). The default, [`Bsdf::eval`], is exact for every symmetric
    /// BSDF (reflection; `f(wo, wi) = f(wi, wo)`). A BSDF with a non-delta transmission
    /// that scales radiance by `1/η²` overrides it without that factor. Sampled delta
    /// components need nothing here: the estimators undo the `1/η²` of a sample's weight
    /// from [`BsdfSample::eta`].
    #[inline]
    fn eval_adjoint(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        self.eval(wo, wi)
    }

    /// Whether [`Bsdf::sample`] reads `u1` (a choice among components, such as reflection
    /// or refraction). When `false` [`PathTracer`](super::PathTracer) and
    /// [`DirectIntegrator`](super::DirectIntegrator) do not draw `u1` from their sample
    /// source and pass `0.5`. The default, `true`, is always correct.
    #[inline]
    fn samples_component(&self) -> bool {
        true
    }
}

/// One sample of the light arriving at a point, from next-event estimation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LightSample {
    /// Unit direction from the shading point toward the light, world space.
    pub wi: Vec3,
    /// Distance to the sampled point (`f32::INFINITY` for a light at infinity).
    pub dist: f32,
    /// Radiance arriving along `-wi` if unoccluded (for a point light, intensity / d²).
    pub radiance: Vec3,
    /// Density per unit solid angle, times the probability of choosing that light; for a
    /// delta light, only the choice probability.
    pub pdf: f32,
    /// The light is a Dirac delta in direction (point light): no MIS.
    pub delta: bool,
}

/// A source of uniform sample values in `[0,1)` for one pixel sample. Every
/// [`crate::sampling::sampler::Sampler`] is one (positioned on its pixel sample first).
pub trait SampleSource {
    /// One value in `[0,1)`.
    fn next_1d(&mut self) -> f32;
    /// Two values in `[0,1)²`.
    fn next_2d(&mut self) -> Vec2 {
        let x = self.next_1d();
        Vec2::new(x, self.next_1d())
    }
    /// Switches to the sample stream `stream` (the bidirectional estimators draw the camera
    /// subpath from stream 0, the light subpath from 1 and connections from 2). Sources
    /// without streams ignore it (the default); Metropolis sampling keeps one stream per
    /// role so that a path's primary sample coordinates keep their meaning when its length
    /// changes (Hachisuka et al. 2014).
    #[inline]
    fn start_stream(&mut self, _stream: u32) {}
}

/// What the estimators need from a scene: ray casting, materials and lights.
pub trait Scene {
    /// The material type; an enum or a single concrete type (the latter lets the compiler
    /// drop every code path the scene does not need).
    type Bsdf: Bsdf;

    /// First hit along a camera ray from `origin` in unit direction `dir`, up to `t_max`.
    fn intersect(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<SurfacePoint>;

    /// First hit along a ray leaving the surface point `from` in direction `dir` (the scene
    /// offsets the origin against self-intersection).
    fn trace(&self, from: &SurfacePoint, dir: Vec3) -> Option<SurfacePoint>;

    /// Whether something blocks the segment from `from` along `dir` for `dist`
    /// (`f32::INFINITY` for a light at infinity).
    fn occluded(&self, from: &SurfacePoint, dir: Vec3, dist: f32) -> bool;

    /// The material at a surface point.
    fn bsdf(&self, sp: &SurfacePoint) -> &Self::Bsdf;

    /// Whether the surface point lies on an area emitter (cheap test before
    /// [`Scene::emitted`]).
    fn is_emitter(&self, sp: &SurfacePoint) -> bool;

    /// Radiance emitted at `sp` toward the unit world direction `wo`.
    fn emitted(&self, sp: &SurfacePoint, wo: Vec3) -> Vec3;

    /// Whether the scene has a light at infinity (environment).
    fn has_environment(&self) -> bool;

    /// Radiance arriving from infinity against the unit ray direction `dir` (the ray
    /// escaped along `dir`).
    fn environment(&self, dir: Vec3) -> Vec3;

    /// Whether any light is a Dirac delta (point light).
    fn has_delta_lights(&self) -> bool;

    /// Next-event estimation: choose a light, a part of it such as a triangle and a direction
    /// toward it. `u` drives the direction; `u_pick` whatever choices the scene does not make
    /// with `u`. The renderer's scene chooses the light with `u.x` and reuses it, rescaled,
    /// for the light's point (so each light's points keep the stratification of `u`; a
    /// separate, decorrelated value for the choice loses it), and reads `u_pick.y` for a
    /// triangle of a mesh light only.
    fn sample_light(&self, from: &SurfacePoint, u_pick: Vec2, u: Vec2) -> Option<LightSample>;

    /// Whether [`Scene::sample_light`] reads `u_pick` (a choice it does not make with `u`,
    /// such as a mesh light's triangle). When `false` [`PathTracer`](super::PathTracer) and
    /// [`DirectIntegrator`](super::DirectIntegrator) do not draw `u_pick` from their sample
    /// source and pass `(0.5, 0.5)`. The default, `true`, is always
    /// correct.
    #[inline]
    fn samples_light_choice(&self) -> bool {
        true
    }

    /// Density per unit solid angle (with the light choice) with which
    /// [`Scene::sample_light`] at `from` returns the direction toward the emitter point `hit`.
    fn light_pdf(&self, from: &SurfacePoint, hit: &SurfacePoint) -> f32;

    /// The same for the environment, seen from `from` along `dir`.
    fn environment_pdf(&self, from: &SurfacePoint, dir: Vec3) -> f32;
}

/// Dimensions between the starts of two sample streams of a [`Sampler`] (the first stream
/// starts after the pixel filter's dimension).
const STREAM_DIMENSIONS: u32 = 1024;

impl<S: crate::sampling::sampler::Sampler> SampleSource for S {
    #[inline]
    fn start_stream(&mut self, stream: u32) {
        crate::sampling::sampler::Sampler::skip_to_dimension(
            self,
            1 + stream.saturating_mul(STREAM_DIMENSIONS),
        );
    }
    #[inline]
    fn next_1d(&mut self) -> f32 {
        crate::sampling::sampler::Sampler::next_1d(self)
    }
    #[inline]
    fn next_2d(&mut self) -> Vec2 {
        crate::sampling::sampler::Sampler::next_2d(self)
    }
}
