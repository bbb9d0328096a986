//! The built-in scene as the bidirectional estimators see it: emission from every light
//! (`light/emission.rs`) and the pinhole camera as an endpoint.

use super::material::Material;
use super::view::SceneView;
use crate::integrator::{BidirectionalScene, CameraConnection, EmissionSample, SurfacePoint};
use glam::{Vec2, Vec3};

impl<B: Material, const DELTA: bool, const ENV: bool> BidirectionalScene
    for SceneView<'_, B, DELTA, ENV>
{
    fn sample_emission(&self, u_pick: Vec2, u_pos: Vec2, u_dir: Vec2) -> Option<EmissionSample> {
        self.lights
            .sample_emission(self.geometry, self.world, u_pick, u_pos, u_dir)
    }

    fn emission_pdf(&self, light: u32, point: &SurfacePoint, dir: Vec3) -> (f32, f32) {
        self.lights
            .emission_pdf(self.geometry, self.world, light, point, dir)
    }

    fn point_intensity(&self, light: u32, dir: Vec3) -> Option<Vec3> {
        self.lights.spot_intensity(light, dir)
    }

    fn emitter_at(&self, sp: &SurfacePoint) -> Option<u32> {
        self.lights.light_of_shape(sp.shape)
    }

    fn environment_light(&self) -> Option<u32> {
        if ENV {
            self.lights.environment_index()
        } else {
            None
        }
    }

    fn camera_ray(&self, raster: Vec2) -> (Vec3, Vec3, f32) {
        let (ray, t_max) = self.camera.generate_ray_with_tmax(raster);
        (ray.origin, ray.dir, t_max)
    }

    fn camera_position(&self) -> Vec3 {
        self.camera.position()
    }

    fn camera_forward(&self) -> Vec3 {
        self.camera.forward()
    }

    /// The camera samples film positions by the pixel filter around every pixel centre:
    /// the density is the uniform one times the filter's coverage there (1 inside the image
    /// for the box filter; reaching past the border for the Gaussian).
    fn camera_pdf(&self, dir: Vec3) -> f32 {
        let Some((raster, pdf)) = self.camera.direction_density(dir) else {
            return 0.0;
        };
        let (w, h) = self.film_size();
        pdf * self.filter.coverage(raster, w, h)
    }

    fn connect_camera(&self, p: Vec3) -> Option<CameraConnection> {
        let raster = self.camera.raster_of_unbounded(p)?;
        let (w, h) = self.film_size();
        if self.filter.coverage(raster, w, h) <= 0.0 {
            return None;
        }
        let d = self.camera.position() - p;
        let dist = d.length();
        if dist.is_nan() || dist <= 0.0 {
            return None;
        }
        let wi = d / dist;
        let importance = self
            .camera
            .direction_density(-wi)
            .map_or(0.0, |(_, pdf)| pdf);
        (importance > 0.0).then_some(CameraConnection {
            raster,
            wi,
            dist,
            importance,
        })
    }

    fn film_size(&self) -> (u32, u32) {
        (self.camera.width(), self.camera.height())
    }
}
