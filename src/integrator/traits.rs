//! The small traits a renderer implements so that the estimators can run on its geometry,
//! materials and lights.

use crate::sampling::Frame;
use glam::{Vec2, Vec3};

/// A point where a ray met a surface: what the built-in renderer's ray queries return
/// (`mcrt::scene::geometry::Geometry::intersect`) and what the estimators take.
///
/// The estimators read `p`, `ng` and `frame`; `t`, `shape`, `prim`, `instance` and `uv` are
/// the scene's own (its [`Scene::bsdf`] or [`Scene::emitted`] may look them up). [`SurfacePoint::new`]
/// fills those with 0; set the ones a scene uses with struct update syntax:
///
/// ```
/// use mcrt::glam::Vec3;
/// use mcrt::integrator::SurfacePoint;
/// use mcrt::sampling::Frame;
///
/// let n = Vec3::Y;
/// let sp = SurfacePoint { shape: 3, ..SurfacePoint::new(Vec3::ZERO, n, Frame::from_normal(n)) };
/// assert_eq!((sp.shape, sp.prim, sp.t), (3, 0, 0.0));
/// ```
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
    /// The renderer's instance index, for a hit on a shape reached through an instance of a
    /// shape group (Mitsuba 3's `si.instance`); 0 otherwise (opaque to the estimators).
    pub instance: u32,
}

impl SurfacePoint {
    /// A surface point at `p` with unit geometric normal `ng` (of the surface's front side)
    /// and shading frame `frame` (whose `n` is the shading normal; often
    /// `Frame::from_normal(ng)`): the fields the estimators read. `t`, `shape`, `prim`,
    /// `instance` and `uv` are 0.
    #[inline]
    #[must_use]
    pub fn new(p: Vec3, ng: Vec3, frame: Frame) -> Self {
        Self {
            p,
            ng,
            frame,
            t: 0.0,
            shape: 0,
            prim: 0,
            uv: Vec2::ZERO,
            instance: 0,
        }
    }
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

impl BsdfSample {
    /// The sample of a component that is not a Dirac delta: direction `wi`, the BSDF's value
    /// `f` there (times `|cos θ_i|`, as [`BsdfSample::weight`] counts it), its density `pdf`
    /// and the relative index `eta` crossed; `None` unless `pdf` is positive and finite.
    #[inline]
    pub fn from_value(wi: Vec3, f: Vec3, pdf: f32, eta: f32) -> Option<Self> {
        (super::is_positive(pdf) && pdf.is_finite()).then(|| Self {
            wi,
            weight: f / pdf,
            pdf,
            delta: false,
            eta,
        })
    }
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

/// A reference to a BSDF is the BSDF (what [`Scene::bsdf`] returns for stored materials).
impl<B: Bsdf + ?Sized> Bsdf for &B {
    #[inline(always)]
    fn flags(&self) -> BsdfFlags {
        (**self).flags()
    }
    #[inline(always)]
    fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        (**self).eval(wo, wi)
    }
    #[inline(always)]
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        (**self).pdf(wo, wi)
    }
    #[inline(always)]
    fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        (**self).eval_pdf(wo, wi)
    }
    #[inline(always)]
    fn sample(&self, wo: Vec3, u1: f32, u2: Vec2) -> Option<BsdfSample> {
        (**self).sample(wo, u1, u2)
    }
    #[inline(always)]
    fn eval_adjoint(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        (**self).eval_adjoint(wo, wi)
    }
    #[inline(always)]
    fn samples_component(&self) -> bool {
        (**self).samples_component()
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

/// What the estimators need from a scene: ray casting, materials and lights.
///
/// Eight methods are required; the environment (`has_environment`, `environment`,
/// `environment_pdf`), `has_delta_lights` and `samples_light_choice` have defaults for a
/// scene without a light at infinity or point lights. `examples/custom_scene.rs` implements
/// a complete scene (and a BSDF) and compares the path tracer with the analytic answer.
pub trait Scene {
    /// The material at a surface point; an enum or a single concrete type (the latter lets
    /// the compiler drop every code path the scene does not need). Usually a reference to a
    /// material the scene stores (`&'a M`); a scene with textures forms it per hit and
    /// returns it by value.
    type Bsdf<'a>: Bsdf
    where
        Self: 'a;

    /// First hit along a camera ray from `origin` in unit direction `dir`, up to `t_max`.
    fn intersect(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<SurfacePoint>;

    /// First hit along a ray leaving the surface point `from` in direction `dir` (the scene
    /// offsets the origin against self-intersection).
    fn trace(&self, from: &SurfacePoint, dir: Vec3) -> Option<SurfacePoint>;

    /// Whether anything is hit at a distance `t` with `0 < t < dist` along the ray leaving
    /// the surface point `from` in unit direction `dir` (the scene offsets the origin against
    /// self-intersection, as in [`Scene::trace`]); `dist` is `f32::INFINITY` for a light at
    /// infinity. A plain ray query: the estimators, when they test whether the point at
    /// distance `d` is visible, pass `d · (1 − SHADOW_EPSILON)`
    /// ([`SHADOW_EPSILON`](super::SHADOW_EPSILON)), so the surface of that point (a light's,
    /// a vertex's) never hides it, and the scene need not shorten `dist` itself.
    fn occluded(&self, from: &SurfacePoint, dir: Vec3, dist: f32) -> bool;

    /// The material at a surface point.
    fn bsdf(&self, sp: &SurfacePoint) -> Self::Bsdf<'_>;

    /// Whether the surface point lies on an area emitter (cheap test before
    /// [`Scene::emitted`]).
    fn is_emitter(&self, sp: &SurfacePoint) -> bool;

    /// Radiance emitted at `sp` toward the unit world direction `wo`.
    fn emitted(&self, sp: &SurfacePoint, wo: Vec3) -> Vec3;

    /// Whether the scene has a light at infinity (environment). The default, `false`, is for
    /// a scene without one; a scene with one overrides this, [`Scene::environment`] and
    /// [`Scene::environment_pdf`].
    #[inline]
    fn has_environment(&self) -> bool {
        false
    }

    /// Radiance arriving from infinity against the unit ray direction `dir` (the ray
    /// escaped along `dir`). Default: none (zero).
    #[inline]
    fn environment(&self, _dir: Vec3) -> Vec3 {
        Vec3::ZERO
    }

    /// Whether any light is a Dirac delta (point light). The default, `false`, is for a
    /// scene whose lights all have area (or are at infinity).
    #[inline]
    fn has_delta_lights(&self) -> bool {
        false
    }

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

    /// The same for the environment, seen from `from` along `dir`. Default: 0 (no
    /// environment).
    #[inline]
    fn environment_pdf(&self, _from: &SurfacePoint, _dir: Vec3) -> f32 {
        0.0
    }
}
