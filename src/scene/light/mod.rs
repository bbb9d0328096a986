//! Lights: area emitters on shapes (front side only), point lights, a constant environment
//! and an environment map, chosen for next-event estimation by power, or, with a few lights
//! that all have a position, by their estimated contribution at the shading point
//! (`choice.rs`).

mod build;
mod choice;
mod emission;
mod envmap;
mod rect;

use choice::LightChoice;

pub use envmap::EnvMap;
use rect::AreaRect;

use crate::integrator::{is_positive, LightSample, SurfacePoint};
use crate::sampling::warp::RectangleFrame;
use crate::scene::render::geo::{Geometry, Hit, ShapeSampling};
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

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
}

/// Why the lights of a scene could not be set up.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LightError(pub String);

impl std::fmt::Display for LightError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "light setup: {}", self.0)
    }
}

impl std::error::Error for LightError {}

/// All lights of a scene with the distribution that chooses among them.
#[derive(Debug, Clone)]
pub struct Lights {
    lights: Vec<Light>,
    /// Chooses a light; `None` when no light emits.
    picker: Option<LightChoice>,
    shape_light: Vec<Option<u32>>,
    /// Per shape: its emitted radiance if it is an area light (one load per hit).
    shape_radiance: Vec<Option<Vec3>>,
    env: Option<u32>,
    has_delta: bool,
    /// Per light: the rectangle of an area light on a rectangle shape, sampled here
    /// directly when the geometry samples rectangles by area (same points, same density).
    rects: Vec<Option<AreaRect>>,
    /// Exactly one light: no choice to sample (its probability is 1).
    single: bool,
    /// The scene's only light, an emitting rectangle (its choice probability is 1).
    only_rect: Option<(AreaRect, Vec3)>,
    /// That rectangle's frame for solid-angle sampling, built from the same corner and
    /// edges as the geometry's own (so the same warp and the same bits).
    only_rect_frame: Option<Box<RectangleFrame>>,
    /// [`Lights::sample`] reads `u_pick`: a light on a triangle mesh.
    reads_pick: bool,
}

fn mean(v: Vec3) -> f32 {
    (v.x + v.y + v.z) / 3.0
}

/// A direction toward area light `shape` through [`Geometry::sample_shape`] (`u_rest` picks
/// a mesh triangle, `u` the point), its density times the light's choice probability `pick`.
fn sample_shape_light(
    geo: &Geometry,
    shape: u32,
    radiance: Vec3,
    from: Vec3,
    (u_rest, u): (f32, Vec2),
    pick: f32,
) -> Option<LightSample> {
    let s = geo.sample_shape(shape, from, u_rest, u)?;
    let d = s.p - from;
    let dist = d.length();
    if !is_positive(dist) {
        return None;
    }
    let wi = d / dist;
    if s.n.dot(wi) >= 0.0 || !is_positive(s.pdf) || !s.pdf.is_finite() {
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

/// A direction toward rectangle light `r` sampled by area from `from`, its density times
/// the light's choice probability `pick`.
#[inline(always)]
fn rect_light_sample(
    r: &AreaRect,
    radiance: Vec3,
    from: Vec3,
    u: Vec2,
    pick: f32,
) -> Option<LightSample> {
    let s = r.sample(from, u)?;
    Some(LightSample {
        wi: s.wi,
        dist: s.dist,
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

    /// Probability of choosing light `i` at shading point `p`.
    #[inline]
    fn pmf(&self, p: Vec3, i: u32) -> f32 {
        self.picker.as_ref().map_or(0.0, |t| t.pmf(p, i as usize))
    }

    /// Whether [`Lights::sample`] reads its `u_pick` argument (`u_pick.y` chooses a triangle):
    /// a light is a triangle mesh. The choice among several lights reads `u.x` and reuses
    /// it (see [`Lights::sample`]), so it needs no value of its own.
    pub fn reads_pick(&self) -> bool {
        self.reads_pick
    }

    /// Whether any light is a point light.
    pub fn has_delta(&self) -> bool {
        self.has_delta
    }

    /// Whether there is an environment light.
    pub fn has_environment(&self) -> bool {
        self.env.is_some()
    }

    /// Emitted radiance of shape `shape` if it is an area light.
    #[inline]
    pub fn area_radiance(&self, shape: u32) -> Option<Vec3> {
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
        // A lone rectangle light sampled by area (the Cornell box) inline; everything else
        // out of line.
        if let Some((r, radiance)) = &self.only_rect {
            if geo.shape_sampling() == ShapeSampling::Area {
                return rect_light_sample(r, *radiance, from.p, u, 1.0);
            }
        }
        self.sample_out_of_line(geo, from, u_pick, u)
    }

    /// [`Lights::sample`] out of line: a lone rectangle sampled by solid angle, then the
    /// general case. (Hinted `inline` rather than forced out of line: the compiler then keeps
    /// it out of line by its size and inlines the spherical-rectangle warp into it, which
    /// `#[inline(never)]` here prevented, 35 M instructions worse on the Cornell box.)
    #[inline]
    fn sample_out_of_line(
        &self,
        geo: &Geometry,
        from: &SurfacePoint,
        u_pick: Vec2,
        u: Vec2,
    ) -> Option<LightSample> {
        // (By area, `sample` has taken the lone rectangle already.)
        if let Some((r, radiance)) = &self.only_rect {
            if geo.shape_sampling() == ShapeSampling::SolidAngle {
                if r.surely_behind(from.p) {
                    return None;
                }
                if let Some(f) = &self.only_rect_frame {
                    if let Some(ls) = rect::solid_angle_sample(f, r.normal(), *radiance, from.p, u)
                    {
                        return ls;
                    }
                }
            }
        }
        self.sample_chosen(geo, from, u_pick, u)
    }

    /// [`Lights::sample`] in general: the choice of light, then its own sampling.
    fn sample_chosen(
        &self,
        geo: &Geometry,
        from: &SurfacePoint,
        u_pick: Vec2,
        u: Vec2,
    ) -> Option<LightSample> {
        let picker = self.picker.as_ref()?;
        // The light is chosen with `u.x`, which is then reused for the light's own point
        // (see `LightChoice::sample`), so each light's points stay stratified.
        let (i, pick, u) = if self.single {
            (0, 1.0, u)
        } else {
            let (i, pick, rest) = picker.sample(from.p, u.x);
            (i, pick, Vec2::new(rest, u.y))
        };
        match self.lights[i] {
            Light::Area { shape, radiance } => match &self.rects[i] {
                Some(r) if geo.shape_sampling() == ShapeSampling::Area => {
                    rect_light_sample(r, radiance, from.p, u, pick)
                }
                _ => sample_shape_light(geo, shape, radiance, from.p, (u_pick.y, u), pick),
            },
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
                let z = 1.0 - 2.0 * u.x;
                let r = (1.0 - z * z).max(0.0).sqrt();
                let (s, c) = (2.0 * PI * u.y).sin_cos();
                Some(LightSample {
                    wi: Vec3::new(r * c, r * s, z),
                    dist: f32::INFINITY,
                    radiance,
                    pdf: pick / (4.0 * PI),
                    delta: false,
                })
            }
        }
    }

    /// Density (per steradian, with the choice) with which [`Lights::sample`] at `from`
    /// returns the direction toward `hit` on an area light.
    pub fn pdf_hit(&self, geo: &Geometry, from: &SurfacePoint, hit: &SurfacePoint) -> f32 {
        let Some(Some(i)) = self.shape_light.get(hit.shape as usize) else {
            return 0.0;
        };
        let h = Hit {
            t: hit.t,
            p: hit.p,
            ng: hit.ng,
            ns: hit.frame.n,
            uv: hit.uv,
            shape: hit.shape,
            prim: hit.prim,
        };
        geo.shape_pdf(hit.shape, from.p, &h) * self.pmf(from.p, *i)
    }

    /// The same for the environment along `dir`.
    pub fn pdf_environment(&self, from: &SurfacePoint, dir: Vec3) -> f32 {
        match self.env {
            Some(i) => match &self.lights[i as usize] {
                Light::EnvMap(m) => self.pmf(from.p, i) * m.pdf(dir),
                _ => self.pmf(from.p, i) / (4.0 * PI),
            },
            None => 0.0,
        }
    }
}
