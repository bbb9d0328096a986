//! A small scene for the estimators' unit tests: the inside of a unit sphere, Lambertian
//! (albedo ½), lit by the cap `z ≥ ½` of its own surface, with a pinhole camera's geometry at
//! its centre (used by BDPT's weight check and the guided tracer's record tests).

use crate::integrator::{Bsdf, BsdfFlags, BsdfSample, LightSample, Scene, SurfacePoint};
use crate::sampling::Frame;
use glam::{Vec2, Vec3};
use std::f32::consts::{FRAC_1_PI, PI};

/// Half the side of the camera's image plane at distance 1 (`tan` of half the field of view).
pub(crate) const TAN_HALF: f32 = 0.8;
/// Film size in pixels.
pub(crate) const FILM: u32 = 16;

/// Lambertian reflection with albedo ½ whose `pdf` is `scale` times the density its
/// `sample` draws from (cosine-weighted).
pub(crate) struct Lambert {
    pub(crate) scale: f32,
}

impl Bsdf for Lambert {
    fn flags(&self) -> BsdfFlags {
        BsdfFlags {
            smooth: true,
            ..BsdfFlags::default()
        }
    }
    fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Vec3::ZERO;
        }
        Vec3::splat(0.5 * wi.z * FRAC_1_PI)
    }
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        self.scale * wi.z * FRAC_1_PI
    }
    fn sample(&self, wo: Vec3, _u1: f32, u: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let wi = cosine(u);
        BsdfSample::from_value(wi, self.eval(wo, wi), wi.z * FRAC_1_PI, 1.0)
    }
    fn samples_component(&self) -> bool {
        false
    }
}

/// A cosine-weighted direction about `z`.
pub(crate) fn cosine(u: Vec2) -> Vec3 {
    let r = u.x.sqrt();
    let (s, c) = (2.0 * PI * u.y).sin_cos();
    Vec3::new(r * c, r * s, (1.0 - u.x).max(0.0).sqrt())
}

/// The inside of the unit sphere; `emission_scale` multiplies the direction density that
/// `emission_pdf` states.
pub(crate) struct InsideSphere {
    pub(crate) bsdf: Lambert,
    pub(crate) emission_scale: f32,
}

impl InsideSphere {
    pub(crate) fn new(bsdf_scale: f32, emission_scale: f32) -> Self {
        Self {
            bsdf: Lambert { scale: bsdf_scale },
            emission_scale,
        }
    }

    /// The surface point at `p` on the sphere, its front side facing the inside.
    pub(crate) fn point(p: Vec3, t: f32) -> SurfacePoint {
        let n = -p;
        SurfacePoint {
            t,
            ..SurfacePoint::new(p, n, Frame::from_normal(n))
        }
    }

    /// The far hit of the ray from `o` (inside or on the sphere) along the unit `dir`.
    pub(crate) fn hit(o: Vec3, dir: Vec3) -> Option<SurfacePoint> {
        let b = o.dot(dir);
        let c = o.length_squared() - 1.0;
        let t = -b + (b * b - c).max(0.0).sqrt();
        (t > 1e-4).then(|| Self::point((o + t * dir).normalize(), t))
    }

    pub(crate) fn on_light(p: Vec3) -> bool {
        p.z >= 0.5
    }

    /// A point uniform on the light (the cap `z ≥ ½`, area π).
    pub(crate) fn light_point(u: Vec2) -> SurfacePoint {
        let z = 0.5 + 0.5 * u.x;
        let r = (1.0 - z * z).max(0.0).sqrt();
        let (s, c) = (2.0 * PI * u.y).sin_cos();
        Self::point(Vec3::new(r * c, r * s, z), 0.0)
    }

    /// The film position and density per steradian of the camera direction `dir`.
    pub(crate) fn camera_density(dir: Vec3) -> Option<(Vec2, f32)> {
        let c = -dir.z;
        if c <= 0.0 {
            return None;
        }
        let (x, y) = (dir.x / c, dir.y / c);
        if x.abs() >= TAN_HALF || y.abs() >= TAN_HALF {
            return None;
        }
        let f = FILM as f32;
        let raster = Vec2::new(
            (x / TAN_HALF + 1.0) * 0.5 * f,
            (1.0 - y / TAN_HALF) * 0.5 * f,
        );
        let area = 4.0 * TAN_HALF * TAN_HALF;
        Some((raster, 1.0 / (area * c * c * c)))
    }
}

impl Scene for InsideSphere {
    type Bsdf<'a> = &'a Lambert;

    fn intersect(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<SurfacePoint> {
        Self::hit(origin, dir).filter(|h| h.t <= t_max)
    }
    fn trace(&self, from: &SurfacePoint, dir: Vec3) -> Option<SurfacePoint> {
        if from.ng.dot(dir) <= 0.0 {
            return None;
        }
        Self::hit(from.p, dir)
    }
    fn occluded(&self, _from: &SurfacePoint, _dir: Vec3, _dist: f32) -> bool {
        false // the inside of a convex surface sees all of it
    }
    fn bsdf(&self, _sp: &SurfacePoint) -> &Lambert {
        &self.bsdf
    }
    fn is_emitter(&self, sp: &SurfacePoint) -> bool {
        Self::on_light(sp.p)
    }
    fn emitted(&self, sp: &SurfacePoint, wo: Vec3) -> Vec3 {
        if Self::on_light(sp.p) && sp.ng.dot(wo) > 0.0 {
            Vec3::ONE
        } else {
            Vec3::ZERO
        }
    }
    fn sample_light(&self, from: &SurfacePoint, _u_pick: Vec2, u: Vec2) -> Option<LightSample> {
        let l = Self::light_point(u);
        let d = l.p - from.p;
        let dist = d.length();
        let wi = d / dist;
        let pdf = self.light_pdf(from, &l);
        (pdf > 0.0 && pdf.is_finite()).then_some(LightSample {
            wi,
            dist,
            radiance: Vec3::ONE,
            pdf,
            delta: false,
        })
    }
    fn samples_light_choice(&self) -> bool {
        false
    }
    fn light_pdf(&self, from: &SurfacePoint, hit: &SurfacePoint) -> f32 {
        if !Self::on_light(hit.p) {
            return 0.0;
        }
        let d = hit.p - from.p;
        let d2 = d.length_squared();
        let cos = hit.ng.dot(-d).max(0.0) / d2.sqrt();
        if cos > 0.0 {
            FRAC_1_PI * d2 / cos
        } else {
            0.0
        }
    }
}
