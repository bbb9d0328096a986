//! The scene as the estimators see it: geometry, materials and lights behind
//! [`mcrt::integrator::Scene`], specialised at compile time on the material type and on
//! whether the scene has delta lights and an environment.

use super::material::Material;
use crate::camera::Camera;
use crate::geometry::{offset_origin, Geometry, Ray};
use crate::light::Lights;
use glam::{Vec2, Vec3};
use mcrt::integrator::{LightSample, Scene, SurfacePoint};
use std::sync::atomic::{AtomicBool, Ordering};

/// A scene specialised on its material type `B` and on whether delta lights (`DELTA`) and
/// an environment (`ENV`) may be present: when a flag is `false` the code paths for it are
/// constant false and compiled out; when `true` the lights are asked at run time.
pub(crate) struct SceneView<'a, B, const DELTA: bool, const ENV: bool> {
    pub(crate) geometry: &'a Geometry,
    pub(crate) bsdfs: Vec<B>,
    pub(crate) lights: &'a Lights,
    /// The camera, for the bidirectional estimators' camera endpoint.
    pub(crate) camera: &'a Camera,
    /// The scene's bounding sphere (centre, radius): where lights at infinity emit from.
    pub(crate) world: (Vec3, f32),
    /// The pixel filter, by which the camera places its film samples.
    pub(crate) filter: &'a crate::film::PixelFilter,
    /// Once set, [`Scene::trace`] finds nothing, so that a path ends at its next bounce:
    /// a path tracer's path without a bound on its length (`max_depth` −1 or huge and a
    /// huge `rr_depth` in a closed white room) stops when the render is cancelled. The
    /// render loop discards the sample that was running.
    pub(crate) stop: &'a AtomicBool,
}

impl<B: Material, const DELTA: bool, const ENV: bool> Scene for SceneView<'_, B, DELTA, ENV> {
    type Bsdf<'b>
        = B::At<'b>
    where
        Self: 'b;

    #[inline]
    fn intersect(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<SurfacePoint> {
        self.geometry.intersect(&Ray { origin, dir }, t_max)
    }

    #[inline(always)]
    fn trace(&self, from: &SurfacePoint, dir: Vec3) -> Option<SurfacePoint> {
        if self.stop.load(Ordering::Relaxed) {
            return None;
        }
        let origin = offset_origin(from.p, from.ng, dir);
        self.geometry.intersect(&Ray { origin, dir }, f32::INFINITY)
    }

    #[inline(always)]
    fn occluded(&self, from: &SurfacePoint, dir: Vec3, dist: f32) -> bool {
        let origin = offset_origin(from.p, from.ng, dir);
        self.geometry.occluded(&Ray { origin, dir }, dist)
    }

    #[inline]
    fn bsdf(&self, sp: &SurfacePoint) -> B::At<'_> {
        self.bsdfs[sp.shape as usize].at(self.geometry, sp)
    }

    #[inline]
    fn is_emitter(&self, sp: &SurfacePoint) -> bool {
        self.lights.area_radiance(sp.shape).is_some()
    }

    #[inline]
    fn emitted(&self, sp: &SurfacePoint, wo: Vec3) -> Vec3 {
        match self.lights.area_radiance(sp.shape) {
            Some(l) if sp.ng.dot(wo) > 0.0 => match self.lights.area_texture(sp.shape) {
                Some(t) => t.eval(self.geometry.tex_coords(sp)),
                None => l,
            },
            _ => Vec3::ZERO,
        }
    }

    #[inline]
    fn has_environment(&self) -> bool {
        ENV && self.lights.has_environment()
    }

    #[inline]
    fn environment(&self, dir: Vec3) -> Vec3 {
        if ENV {
            self.lights.environment(dir)
        } else {
            Vec3::ZERO
        }
    }

    #[inline]
    fn has_delta_lights(&self) -> bool {
        DELTA && self.lights.has_delta()
    }

    #[inline]
    fn sample_light(&self, from: &SurfacePoint, u_pick: Vec2, u: Vec2) -> Option<LightSample> {
        self.lights.sample(self.geometry, from, u_pick, u)
    }

    #[inline]
    fn samples_light_choice(&self) -> bool {
        self.lights.reads_pick()
    }

    #[inline]
    fn light_pdf(&self, from: &SurfacePoint, hit: &SurfacePoint) -> f32 {
        self.lights.pdf_hit(self.geometry, from, hit)
    }

    #[inline]
    fn environment_pdf(&self, from: &SurfacePoint, dir: Vec3) -> f32 {
        if ENV {
            self.lights.pdf_environment(from, dir)
        } else {
            0.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bsdf::{AnyBsdf, Diffuse, Sided};
    use crate::camera::Camera;
    use crate::description::{EmitterDesc, SceneDescription};
    use crate::geometry::{AccelKind, ShapeSampling};
    use mcrt::integrator::PathTracer;
    use mcrt::sampling::sampler::SampleSource;

    /// Counts the values drawn (a constant value is enough here).
    struct Counting(u32);

    impl SampleSource for Counting {
        fn next_1d(&mut self) -> f32 {
            self.0 += 1;
            0.37
        }
    }

    /// Values drawn by one direct-lighting path (`max_depth` 2: one vertex, no roulette)
    /// from the centre of the Cornell box's camera.
    fn draws(desc: &SceneDescription) -> u32 {
        let geo = Geometry::new(&desc.shapes, None, AccelKind::Bvh)
            .unwrap()
            .with_shape_sampling(ShapeSampling::Area);
        let lights = Lights::new(desc, &geo, 10.0).unwrap();
        let bsdfs: Vec<Sided<Diffuse>> = desc
            .shapes
            .iter()
            .map(|s| {
                let b = AnyBsdf::from_desc(&s.bsdf).unwrap();
                Sided {
                    bsdf: b.bsdf.as_diffuse().unwrap(),
                    two_sided: b.two_sided,
                }
            })
            .collect();
        let camera = Camera::new(&desc.sensor).unwrap();
        let scene = SceneView::<_, true, false> {
            geometry: &geo,
            bsdfs,
            lights: &lights,
            camera: &camera,
            world: geo.bounding_sphere(),
            filter: &crate::film::PixelFilter::Box,
            stop: &AtomicBool::new(false),
        };
        let f = &desc.sensor.film;
        let ray = camera.generate_ray(Vec2::new(f.width as f32, f.height as f32) * 0.5);
        let pt = PathTracer {
            max_depth: 2,
            ..PathTracer::default()
        };
        let mut rng = Counting(0);
        let r = pt.li(&scene, ray.origin, ray.dir, f32::INFINITY, &mut rng);
        assert!(r.radiance.is_finite() && r.rays >= 2, "{r:?}");
        rng.0
    }

    /// A diffuse vertex lit by one rectangle draws the light sample and the BSDF sample
    /// only (2 + 2 values); a second light adds nothing: the light choice reuses the light
    /// sample's first value (`LightChoice::sample`).
    #[test]
    fn path_vertex_draws_only_what_is_read() {
        let mut desc = crate::cornell_box::cornell_box();
        assert_eq!(draws(&desc), 4);
        let point = EmitterDesc::Point {
            position: Vec3::new(0.0, 1.0, 0.0),
            intensity: crate::description::Colour::WHITE,
        };
        desc.emitters
            .push(crate::description::Checked::new(point).unwrap());
        assert_eq!(draws(&desc), 4);
    }
}
