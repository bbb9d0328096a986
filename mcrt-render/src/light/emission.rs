//! Lights as the start of light subpaths (bidirectional estimators): a light chosen by
//! power, a point on it by area, a direction by its emission profile.
//!
//! - area lights: a point uniform by area ([`Geometry::sample_area`]), a direction
//!   cosine-distributed about the front normal (`pdf = cos θ / π`);
//! - point lights: the position, a direction uniform over the sphere (`1/(4π)`);
//! - spot lights: the position, a direction uniform in the cutoff cone;
//! - projectors: the position, a direction through a point uniform on the image;
//! - textured area lights: as area lights, their radiance the texture's at the point;
//! - directional lights: the ray origin uniform on the disk of the scene's bounding
//!   sphere's radius perpendicular to the light's direction, one radius out against it
//!   (`1/(πR²)` per unit area), travelling along it (the choice probability alone for its
//!   Dirac delta of direction);
//! - environments: a direction `w` toward the light by the light's own sampling, then a
//!   ray origin uniform on the disk of the scene's bounding sphere's radius perpendicular
//!   to `w`, one radius out (`1/(πR²)` per unit area), travelling along `−w`.

use super::{Light, Lights};
use crate::geometry::Geometry;
use glam::{Vec2, Vec3};
use mcrt::integrator::{is_positive, EmissionSample, EmitterKind, SurfacePoint};
use mcrt::sampling::warp::{CosineHemisphere, UniformDiskConcentric, UniformSphere, Warp};
use std::f32::consts::PI;

/// A surface point for a light without a surface (its normal zero, so rays leave it
/// without an offset).
fn bare(p: Vec3, n: Vec3, shape: u32) -> SurfacePoint {
    SurfacePoint {
        p,
        ng: n,
        frame: mcrt::sampling::Frame::from_normal(if n == Vec3::ZERO { Vec3::Z } else { n }),
        t: 0.0,
        shape,
        prim: 0,
        uv: Vec2::ZERO,
        instance: 0,
    }
}

impl Lights {
    /// Probability of choosing light `i` to start a light subpath (by power).
    pub(crate) fn emission_pmf(&self, i: u32) -> f32 {
        self.picker
            .as_ref()
            .map_or(0.0, |c| c.power().pmf(i as usize))
    }

    /// The light index of the area light on shape `shape`.
    pub(crate) fn light_of_shape(&self, shape: u32) -> Option<u32> {
        *self.shape_light.get(shape as usize)?
    }

    /// The light index of the environment.
    pub fn environment_index(&self) -> Option<u32> {
        self.env
    }

    /// Intensity (W/sr) that light `light`, a spot light or a projector, sends along the unit direction
    /// `dir`; `None` for every other light.
    pub(crate) fn spot_intensity(&self, light: u32, dir: Vec3) -> Option<Vec3> {
        match self.lights.get(light as usize)? {
            Light::Spot(spot) => Some(spot.intensity_toward(dir)),
            Light::Projector(p) => Some(p.intensity_toward(dir)),
            _ => None,
        }
    }

    /// An emitted ray: a light by power (`u_pick.x`), a triangle of a mesh light by area
    /// (`u_pick.y`), a point on it (`u_pos`), a direction (`u_dir`); `world` is the scene's bounding sphere (centre, radius).
    pub fn sample_emission(
        &self,
        geo: &Geometry,
        world: (Vec3, f32),
        u_pick: Vec2,
        u_pos: Vec2,
        u_dir: Vec2,
    ) -> Option<EmissionSample> {
        let (i, pick) = self.picker.as_ref()?.power().sample_with_pmf(u_pick.x);
        if !is_positive(pick) {
            return None;
        }
        let light = i as u32;
        match &self.lights[i] {
            &Light::Area { shape, radiance } => {
                let s = geo.sample_area(shape, u_pick.y, u_pos)?;
                let radiance = self.area_radiance_at(geo, shape, radiance, u_pick.y, s.p);
                let local = CosineHemisphere.sample(u_dir);
                let frame = mcrt::sampling::Frame::from_normal(s.n);
                let dir = frame.to_world(local);
                let pdf_dir = CosineHemisphere.pdf(local);
                let mut point = bare(s.p, s.n, shape);
                point.frame = frame;
                Some(EmissionSample {
                    light,
                    kind: EmitterKind::Area,
                    point,
                    dir,
                    radiance,
                    pdf_pos: s.pdf * pick,
                    pdf_dir,
                })
            }
            &Light::Point {
                position,
                intensity,
            } => Some(EmissionSample {
                light,
                kind: EmitterKind::Point,
                point: bare(position, Vec3::ZERO, u32::MAX),
                dir: UniformSphere.sample(u_dir),
                radiance: intensity,
                pdf_pos: pick,
                pdf_dir: 1.0 / (4.0 * PI),
            }),
            Light::Spot(_) | Light::Projector(_) => {
                let ((dir, intensity, pdf_dir), position) = match &self.lights[i] {
                    Light::Spot(s) => (s.sample_direction(u_dir), s.position()),
                    Light::Projector(p) => (p.sample_direction(u_dir), p.position()),
                    _ => return None,
                };
                Some(EmissionSample {
                    light,
                    kind: EmitterKind::Point,
                    point: bare(position, Vec3::ZERO, u32::MAX),
                    dir,
                    radiance: intensity,
                    pdf_pos: pick,
                    pdf_dir,
                })
            }
            &Light::Directional {
                direction,
                irradiance,
            } => {
                let (origin, pdf_disk) = disk_origin(world, -direction, u_dir);
                Some(EmissionSample {
                    light,
                    kind: EmitterKind::Directional,
                    point: bare(origin, Vec3::ZERO, u32::MAX),
                    dir: direction,
                    radiance: irradiance,
                    pdf_pos: pick,
                    pdf_dir: pdf_disk,
                })
            }
            Light::Constant { .. } | Light::EnvMap(_) => {
                let (w, radiance, pdf_w) = match &self.lights[i] {
                    Light::EnvMap(m) => m.sample(u_pos)?,
                    Light::Constant { radiance } => {
                        (UniformSphere.sample(u_pos), *radiance, 1.0 / (4.0 * PI))
                    }
                    _ => return None,
                };
                let (origin, pdf_disk) = disk_origin(world, w, u_dir);
                Some(EmissionSample {
                    light,
                    kind: EmitterKind::Infinite,
                    point: bare(origin, Vec3::ZERO, u32::MAX),
                    dir: -w,
                    radiance,
                    pdf_pos: pdf_w * pick,
                    pdf_dir: pdf_disk,
                })
            }
        }
    }

    /// Densities `(pdf_pos, pdf_dir)` of [`Lights::sample_emission`] for light `light`,
    /// point `point` on it and the direction of travel `dir` (see
    /// [`mcrt::integrator::BidirectionalScene::emission_pdf`]).
    pub fn emission_pdf(
        &self,
        geo: &Geometry,
        world: (Vec3, f32),
        light: u32,
        point: &SurfacePoint,
        dir: Vec3,
    ) -> (f32, f32) {
        let pick = self.emission_pmf(light);
        match self.lights.get(light as usize) {
            Some(&Light::Area { shape, .. }) => {
                let area = geo.shape_area(shape);
                let cos = point.ng.dot(dir);
                let pdf_dir = if cos > 0.0 { cos / PI } else { 0.0 };
                (if area > 0.0 { pick / area } else { 0.0 }, pdf_dir)
            }
            Some(Light::Point { .. }) => (pick, 1.0 / (4.0 * PI)),
            Some(Light::Spot(spot)) => (pick, spot.pdf_direction(dir)),
            Some(Light::Projector(p)) => (pick, p.pdf_direction(dir)),
            Some(Light::Directional { .. }) => (pick, disk_pdf(world)),
            Some(Light::EnvMap(m)) => (pick * m.pdf(-dir), disk_pdf(world)),
            Some(Light::Constant { .. }) => (pick / (4.0 * PI), disk_pdf(world)),
            None => (0.0, 0.0),
        }
    }
}

/// A ray origin for a light at infinity arriving from the unit direction `w`: uniform on
/// the disk of the world's radius perpendicular to `w`, one radius out toward the light;
/// with its density per unit area.
fn disk_origin((center, radius): (Vec3, f32), w: Vec3, u: Vec2) -> (Vec3, f32) {
    let radius = radius.max(1e-3);
    let frame = mcrt::sampling::Frame::from_normal(w);
    let d = UniformDiskConcentric.sample(u) * radius;
    let origin = center + radius * w + frame.s * d.x + frame.t * d.y;
    (origin, 1.0 / (PI * radius * radius))
}

/// Density per unit area of the emission disk of a light at infinity.
fn disk_pdf((_, radius): (Vec3, f32)) -> f32 {
    let r = radius.max(1e-3);
    1.0 / (PI * r * r)
}
