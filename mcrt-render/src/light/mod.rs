//! Lights: area emitters on shapes (front side only), point and spot lights, directional
//! lights, a constant environment and an environment map, chosen for next-event estimation by power, or, with a few lights
//! that all have a position, by their estimated contribution at the shading point
//! (`choice.rs`), or, with many lights, by a light BVH beside the lights without a position
//! (`bvh_choice.rs`).

mod build;
mod bvh_choice;
mod choice;
mod emission;
mod envmap;
mod error;
mod projector;
mod resampled;
mod spot;
#[cfg(test)]
mod tests;

pub(crate) use build::texture_aspect;
use bvh_choice::BvhChoice;
pub use bvh_choice::LightBvhUse;
use choice::LightChoice;

pub use envmap::EnvMap;
pub use error::LightError;
pub use projector::Projector;
pub use resampled::MAX_LIGHT_CANDIDATES;
pub use spot::Spot;

use crate::geometry::{Geometry, RectangleSampler, ShapeSample, ShapeSampling};
use crate::texture::Texture;
use glam::{Vec2, Vec3};
use mcrt::integrator::{is_positive, LightSample, SurfacePoint};
use mcrt::sampling::warp::{UniformSphere, Warp};

/// One light.
#[derive(Debug, Clone, PartialEq)]
pub enum Light {
    /// Constant radiance leaving the front side of a shape.
    Area {
        /// The shape's index in the geometry.
        shape: u32,
        /// Emitted radiance.
        radiance: Vec3,
    },
    /// An isotropic point light.
    Point {
        /// Position.
        position: Vec3,
        /// Radiant intensity (W/sr).
        intensity: Vec3,
    },
    /// Radiance arriving equally from every direction, sampled uniformly over the sphere
    /// (pdf 1/(4π) per steradian).
    Constant {
        /// Radiance.
        radiance: Vec3,
    },
    /// An environment map.
    EnvMap(Box<EnvMap>),
    /// A spot light: a point light whose intensity falls off in a cone.
    Spot(Box<Spot>),
    /// A projector: a point light that projects an image.
    Projector(Box<Projector>),
    /// Light arriving along one direction everywhere: a Dirac delta in direction.
    Directional {
        /// Unit direction the light travels along.
        direction: Vec3,
        /// Irradiance on a surface facing the light (W/m²).
        irradiance: Vec3,
    },
}

/// All lights of a scene with the distribution that chooses among them.
#[derive(Debug, Clone)]
pub struct Lights {
    lights: Vec<Light>,
    /// Chooses a light; `None` when no light emits. (Also the power choice of light
    /// subpaths.)
    picker: Option<LightChoice>,
    /// With many lights: the choice of next-event estimation instead of `picker`.
    bvh: Option<BvhChoice>,
    shape_light: Vec<Option<u32>>,
    /// Per shape: its emitted radiance if it is an area light (one load per hit).
    shape_radiance: Vec<Option<Vec3>>,
    /// Per shape: the texture of its textured area emission (empty when no area light is
    /// textured).
    shape_texture: Vec<Option<Texture>>,
    env: Option<u32>,
    has_delta: bool,
    /// Per light: the sampler of an area light on a rectangle (the geometry's own), so that
    /// sampling it needs no shape lookup.
    rectangles: Vec<Option<RectangleSampler>>,
    /// How [`Lights::sample`] proceeds, chosen once.
    plan: SamplePlan,
    /// [`Lights::sample`] reads `u_pick`: a light on a triangle mesh (the
    /// choice among several lights reads `u.x`).
    reads_pick: bool,
    /// Candidates of resampled next-event estimation over the light BVH (`resampled.rs`);
    /// 0 or 1: one BVH sample, no resampling.
    candidates: u32,
}

/// How [`Lights::sample`] proceeds, chosen once when the lights are built (with the
/// geometry's [`ShapeSampling`]).
#[derive(Debug, Clone, Copy, PartialEq)]
enum SamplePlan {
    /// No light emits: no sample.
    Nothing,
    /// The only light is a rectangle sampled by area (the Cornell box with
    /// `--light-sampling area`): no choice, a few dozen instructions, inline.
    LoneRectangleByArea,
    /// The only light is a rectangle sampled by solid angle: no choice; points clearly behind
    /// it are rejected before the warp.
    LoneRectangleBySolidAngle,
    /// The only light is a rectangle sampled by area from far and by solid angle from near
    /// ([`ShapeSampling::Auto`], the default): the far case inline as
    /// `LoneRectangleByArea`, the near one as `LoneRectangleBySolidAngle`.
    LoneRectangleByDistance,
    /// Choose a light (probability 1 for a lone light), then sample it.
    Choose {
        /// Exactly one light.
        single: bool,
    },
}

/// `0 < x < ∞` (false for NaN), as one integer comparison of the bits: the positive
/// finite floats, subnormals included, are exactly the bit patterns `1..=0x7f7f_ffff`. (The
/// two float comparisons compile to a dozen instructions of class tests.)
#[inline(always)]
fn positive_finite(x: f32) -> bool {
    x.to_bits().wrapping_sub(1) < 0x7f7f_ffff
}

fn mean(v: Vec3) -> f32 {
    (v.x + v.y + v.z) / 3.0
}

/// The direction from `from` toward a point sampled on an emitter's shape, with the shape
/// density (per steradian) times the light's choice probability `pick`; `None` when the
/// point is seen from behind (area lights emit from their front) or the density is not
/// finite and positive.
#[inline(always)]
fn toward_area_light(s: ShapeSample, radiance: Vec3, from: Vec3, pick: f32) -> Option<LightSample> {
    let d = s.p - from;
    let dist = d.length();
    if !is_positive(dist) {
        return None;
    }
    let wi = d / dist;
    if s.n.dot(wi) >= 0.0 || !positive_finite(s.pdf) {
        return None;
    }
    Some(LightSample {
        wi,
        dist,
        radiance,
        pdf: s.pdf * pick,
        delta: false,
    })
}

impl Lights {
    /// The lights.
    pub fn lights(&self) -> &[Light] {
        &self.lights
    }

    /// Probability of choosing light `i` (its triangle `prim`, where the light BVH chooses
    /// triangles) at the shading point `from`.
    #[inline]
    fn pmf(&self, from: &SurfacePoint, i: u32, prim: u32) -> f32 {
        if let Some(b) = &self.bvh {
            return b.pmf(from.p, from.frame.n, i as usize, prim);
        }
        self.picker
            .as_ref()
            .map_or(0.0, |t| t.pmf(from.p, i as usize))
    }

    /// Resamples next-event estimation's light sample from `m` light-BVH candidates (at most
    /// [`MAX_LIGHT_CANDIDATES`]; 0 or 1: one BVH sample), where the tree chooses and every
    /// light is an untextured rectangle or a mesh split by triangle (`resampled.rs`);
    /// returns whether resampling is on.
    pub fn set_light_candidates(&mut self, m: u32) -> bool {
        self.candidates = if self.resampling_applies() {
            m.min(MAX_LIGHT_CANDIDATES)
        } else {
            0
        };
        self.candidates > 1
    }

    /// The number of lights the light BVH chooses among (each emitting triangle of a mesh
    /// counted), or `None` when next-event estimation chooses without it.
    pub fn bvh_lights(&self) -> Option<usize> {
        self.bvh.as_ref().map(BvhChoice::bvh_lights)
    }

    /// Whether [`Lights::sample`] reads its `u_pick` argument (`u_pick.y` chooses a triangle):
    /// a light is a triangle mesh. The choice among several lights reads `u.x` and reuses
    /// it (see [`Lights::sample`]), so it needs no value of its own.
    pub(crate) fn reads_pick(&self) -> bool {
        self.reads_pick
    }

    /// The texture of the area light on shape `shape`, if its emission is textured.
    #[inline]
    pub(crate) fn area_texture(&self, shape: u32) -> Option<&Texture> {
        self.shape_texture.get(shape as usize)?.as_ref()
    }

    /// The radiance of the area light on shape `shape` at the point `p` that sampling it
    /// with `u_pick` gave: the constant, or the texture at the point's coordinates.
    #[inline]
    fn area_radiance_at(
        &self,
        geo: &Geometry,
        shape: u32,
        radiance: Vec3,
        u_pick: f32,
        p: Vec3,
    ) -> Vec3 {
        match self.area_texture(shape) {
            Some(t) => t.eval(geo.sample_tex_coords(shape, u_pick, p)),
            None => radiance,
        }
    }

    /// Whether any light is a Dirac delta (point, spot or directional light).
    pub(crate) fn has_delta(&self) -> bool {
        self.has_delta
    }

    /// Whether there is an environment light.
    pub fn has_environment(&self) -> bool {
        self.env.is_some()
    }

    /// Emitted radiance of shape `shape` if it is an area light.
    #[inline]
    pub(crate) fn area_radiance(&self, shape: u32) -> Option<Vec3> {
        *self.shape_radiance.get(shape as usize)?
    }

    /// Radiance arriving from the environment against the ray direction `dir`.
    #[inline]
    pub fn environment(&self, dir: Vec3) -> Vec3 {
        match self.env.map(|i| &self.lights[i as usize]) {
            Some(Light::Constant { radiance }) => *radiance,
            Some(Light::EnvMap(m)) => m.eval(dir),
            _ => Vec3::ZERO,
        }
    }

    /// Chooses a light (by power, or by its estimated contribution at `from`: see the
    /// module docs) with `u.x`, and samples a direction toward it from `from` with `u`, its
    /// `x` reused (rescaled from the chosen light's share of `[0, 1)`, as Mitsuba 3 does), so
    /// that each light receives stratified points from a stratified `u`; `u_pick.y` chooses
    /// a triangle of a mesh light, and `u_pick.x` is not read.
    #[inline(always)]
    pub fn sample(
        &self,
        geo: &Geometry,
        from: &SurfacePoint,
        u_pick: Vec2,
        u: Vec2,
    ) -> Option<LightSample> {
        match self.plan {
            SamplePlan::LoneRectangleByArea => {
                let (r, radiance) = self.lone_rectangle()?;
                let s = r.sample(ShapeSampling::Area, from.p, u)?;
                toward_area_light(s, radiance, from.p, 1.0)
            }
            SamplePlan::LoneRectangleByDistance => {
                let (r, radiance) = self.lone_rectangle()?;
                if r.by_solid_angle(ShapeSampling::Auto, from.p) {
                    return self.sample_general(geo, from, u_pick, u);
                }
                let s = r.sample(ShapeSampling::Area, from.p, u)?;
                toward_area_light(s, radiance, from.p, 1.0)
            }
            _ => self.sample_general(geo, from, u_pick, u),
        }
    }

    /// The first light's rectangle sampler and radiance.
    #[inline(always)]
    fn lone_rectangle(&self) -> Option<(&RectangleSampler, Vec3)> {
        match (self.rectangles.first(), self.lights.first()) {
            (Some(Some(r)), Some(&Light::Area { radiance, .. })) => Some((r, radiance)),
            _ => None,
        }
    }

    /// [`Lights::sample`] for every plan but the inline one. (Hinted `inline` rather than
    /// forced out of line, so that the compiler keeps it out of line by its size and inlines
    /// the spherical-rectangle warp into it.)
    #[inline]
    fn sample_general(
        &self,
        geo: &Geometry,
        from: &SurfacePoint,
        u_pick: Vec2,
        u: Vec2,
    ) -> Option<LightSample> {
        debug_assert!(self.plan == SamplePlan::Nothing || self.sampling_matches(geo));
        let single = match self.plan {
            SamplePlan::Nothing => return None,
            // Reached for `LoneRectangleByDistance` only from near (see `sample`).
            SamplePlan::LoneRectangleBySolidAngle | SamplePlan::LoneRectangleByDistance => {
                let (r, radiance) = self.lone_rectangle()?;
                if r.surely_behind(from.p) {
                    return None;
                }
                let s = r.sample(ShapeSampling::SolidAngle, from.p, u)?;
                return toward_area_light(s, radiance, from.p, 1.0);
            }
            SamplePlan::LoneRectangleByArea => true,
            SamplePlan::Choose { single } => single,
        };
        let picker = self.picker.as_ref()?;
        // The light is chosen with `u.x`, which is then reused for the light's own point
        // (see `LightChoice::sample`), so each light's points stay stratified. The light
        // BVH chooses with `u_pick.x` (and may choose one triangle of a mesh).
        let (i, pick, u, triangle) = if let Some(b) = &self.bvh {
            if self.candidates > 1 {
                return self.sample_resampled(b, self.candidates, geo, from, u_pick, u);
            }
            let c = b.sample(from.p, from.frame.n, u_pick.x)?;
            (c.light, c.pick, u, c.triangle)
        } else if single {
            (0, 1.0, u, None)
        } else {
            let (i, pick, rest) = picker.sample(from.p, u.x);
            (i, pick, Vec2::new(rest, u.y), None)
        };
        match self.lights[i] {
            Light::Area { shape, radiance } => {
                let s = match (triangle, &self.rectangles[i]) {
                    (Some(k), _) => geo.sample_triangle(shape, k, from.p, u)?,
                    (None, Some(r)) => r.sample(geo.shape_sampling(), from.p, u)?,
                    (None, None) => geo.sample_shape(shape, from.p, u_pick.y, u)?,
                };
                let radiance = self.area_radiance_at(geo, shape, radiance, u_pick.y, s.p);
                toward_area_light(s, radiance, from.p, pick)
            }
            Light::Point {
                position,
                intensity,
            } => {
                let d = position - from.p;
                let d2 = d.length_squared();
                if !is_positive(d2) {
                    return None;
                }
                let dist = d2.sqrt();
                Some(LightSample {
                    wi: d / dist,
                    dist,
                    radiance: intensity / d2,
                    pdf: pick,
                    delta: true,
                })
            }
            Light::Spot(_) | Light::Projector(_) => {
                let (position, intensity_toward): (Vec3, &dyn Fn(Vec3) -> Vec3) =
                    match &self.lights[i] {
                        Light::Spot(s) => (s.position(), &|w| s.intensity_toward(w)),
                        Light::Projector(p) => (p.position(), &|w| p.intensity_toward(w)),
                        _ => return None,
                    };
                let d = position - from.p;
                let d2 = d.length_squared();
                if !is_positive(d2) {
                    return None;
                }
                let dist = d2.sqrt();
                let wi = d / dist;
                let intensity = intensity_toward(-wi);
                if intensity == Vec3::ZERO {
                    return None;
                }
                Some(LightSample {
                    wi,
                    dist,
                    radiance: intensity / d2,
                    pdf: pick,
                    delta: true,
                })
            }
            Light::Directional {
                direction,
                irradiance,
            } => Some(LightSample {
                wi: -direction,
                dist: f32::INFINITY,
                radiance: irradiance,
                pdf: pick,
                delta: true,
            }),
            Light::EnvMap(ref m) => {
                let (wi, radiance, pdf) = m.sample(u)?;
                Some(LightSample {
                    wi,
                    dist: f32::INFINITY,
                    radiance,
                    pdf: pdf * pick,
                    delta: false,
                })
            }
            Light::Constant { radiance } => {
                let (wi, pdf) = UniformSphere.sample_with_pdf(u);
                Some(LightSample {
                    wi,
                    dist: f32::INFINITY,
                    radiance,
                    pdf: pick * pdf,
                    delta: false,
                })
            }
        }
    }

    /// Whether the plan was chosen for the geometry's current [`ShapeSampling`].
    fn sampling_matches(&self, geo: &Geometry) -> bool {
        match self.plan {
            SamplePlan::LoneRectangleByArea => geo.shape_sampling() == ShapeSampling::Area,
            SamplePlan::LoneRectangleBySolidAngle => {
                geo.shape_sampling() == ShapeSampling::SolidAngle
            }
            SamplePlan::LoneRectangleByDistance => geo.shape_sampling() == ShapeSampling::Auto,
            _ => true,
        }
    }

    /// Density (per steradian, with the choice) with which [`Lights::sample`] at `from`
    /// returns the direction toward `hit` on an area light.
    pub fn pdf_hit(&self, geo: &Geometry, from: &SurfacePoint, hit: &SurfacePoint) -> f32 {
        let Some(Some(i)) = self.shape_light.get(hit.shape as usize) else {
            return 0.0;
        };
        let at = (hit.p, hit.ng, hit.prim);
        if let Some(b) = &self.bvh {
            let pick = b.pmf(from.p, from.frame.n, *i as usize, hit.prim);
            if pick == 0.0 {
                return 0.0;
            }
            let pdf = if b.by_triangle(*i as usize) {
                geo.triangle_pdf_at(hit.shape, from.p, at)
            } else {
                geo.shape_pdf_at(hit.shape, from.p, at)
            };
            return pdf * pick;
        }
        geo.shape_pdf_at(hit.shape, from.p, at) * self.pmf(from, *i, hit.prim)
    }

    /// The same for the environment along `dir`.
    pub(crate) fn pdf_environment(&self, from: &SurfacePoint, dir: Vec3) -> f32 {
        match self.env {
            Some(i) => match &self.lights[i as usize] {
                Light::EnvMap(m) => self.pmf(from, i, 0) * m.pdf(dir),
                _ => self.pmf(from, i, 0) * UniformSphere.pdf(dir),
            },
            None => 0.0,
        }
    }
}
