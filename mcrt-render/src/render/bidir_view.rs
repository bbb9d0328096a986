//! The built-in scene as the bidirectional estimators see it: emission from every light
//! (`light/emission.rs`) and the camera, a pinhole or a thin lens, as an endpoint.

use super::material::Material;
use super::view::SceneView;
use glam::{Vec2, Vec3};
use mcrt::integrator::{BidirectionalScene, CameraConnection, EmissionSample, SurfacePoint};

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
        self.connect_from(self.camera.position(), p)
    }

    fn film_size(&self) -> (u32, u32) {
        (self.camera.width(), self.camera.height())
    }

    fn camera_has_lens(&self) -> bool {
        self.camera.has_lens()
    }

    fn camera_ray_through_lens(&self, raster: Vec2, u_lens: Vec2) -> (Vec3, Vec3, f32) {
        let (ray, t_max) = self.camera.generate_ray_through_lens(raster, u_lens);
        (ray.origin, ray.dir, t_max)
    }

    fn camera_lens_point(&self, origin: Vec3, dir: Vec3) -> Vec3 {
        self.camera.lens_point_of_ray(origin, dir)
    }

    fn camera_pdf_from_lens(&self, lens: Vec3, dir: Vec3) -> f32 {
        let Some((raster, pdf)) = self.camera.direction_density_from(lens, dir) else {
            return 0.0;
        };
        let (w, h) = self.film_size();
        pdf * self.filter.coverage(raster, w, h)
    }

    fn connect_camera_through_lens(
        &self,
        p: Vec3,
        u_lens: Vec2,
    ) -> Option<(Vec3, CameraConnection)> {
        let lens = self.camera.lens_point(u_lens);
        self.connect_from(lens, p).map(|c| (lens, c))
    }
}

impl<B: Material, const DELTA: bool, const ENV: bool> SceneView<'_, B, DELTA, ENV> {
    /// The connection of `p` to the camera through the world-space lens point `lens` (the
    /// camera's position for a pinhole): the film position of the line through both, and
    /// the importance per steradian there, `1/(A cos³θ)`.
    fn connect_from(&self, lens: Vec3, p: Vec3) -> Option<CameraConnection> {
        let raster = self.camera.raster_through_lens(lens, p)?;
        let (w, h) = self.film_size();
        if self.filter.coverage(raster, w, h) <= 0.0 {
            return None;
        }
        let d = lens - p;
        let dist = d.length();
        if dist.is_nan() || dist <= 0.0 {
            return None;
        }
        let wi = d / dist;
        let importance = self
            .camera
            .direction_density_from(lens, -wi)
            .map_or(0.0, |(_, pdf)| pdf);
        (importance > 0.0).then_some(CameraConnection {
            raster,
            wi,
            dist,
            importance,
        })
    }
}
