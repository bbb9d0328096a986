//! The orthographic camera's rays (Mitsuba 3's `orthographic` sensor).
//!
//! Mitsuba 3 maps camera space to the film by `orthographic_projection` (its
//! `include/mitsuba/render/sensor.h`): `x` in `[-1, 1]` spans the film's width, right to left
//! as for the perspective camera, `y` in `[-1/a, 1/a]` its height (`a` = width / height, so
//! pixels are square), and `z` from `near_clip` to `far_clip`. Its inverse sends the film
//! position `(x, y)` in pixels to the camera-space point
//! `(1 − 2x/w, (1 − 2y/h)/a, near)`; the ray leaves that point's world image under
//! `to_world` along `to_world`'s +z (normalised), with `t_max = far − near` in world units
//! (Mitsuba takes the clip distances as they are, unscaled by `to_world`). `to_world`'s scale
//! therefore sets the view's extent: a scale of 1.5 in x and y shows a 3 × 3/a window.
//! Rays are weighed by 1.
//!
//! As an endpoint of light paths the camera is a delta in direction: no light path can be
//! connected to it, and it has no density per steradian (`Camera::direction_density` is
//! `None`). Mitsuba 3's `orthographic` has no `sample_direction` either; the loader refuses
//! it with the integrators that connect light paths to the camera (`bdpt`, `mlt`,
//! `ptracer`; `docs/scene-format.md`).

use super::Camera;
use crate::geometry::Ray;
use glam::{Vec2, Vec3};

impl Camera {
    /// Whether the camera is orthographic (Mitsuba 3's `orthographic`): parallel rays along
    /// [`Camera::forward`] from the near plane.
    pub fn is_orthographic(&self) -> bool {
        self.orthographic
    }

    /// The orthographic ray through film position `film` (pixels of the rendered window)
    /// and its `t_max`, `far − near`.
    #[inline]
    pub(super) fn orthographic_ray(&self, film: Vec2) -> (Ray, f32) {
        let s = (film + self.offset) * self.inv_res;
        // `tan_half` holds the half extents 1 and 1/a for this camera.
        let local = Vec3::new(
            self.tan_half.x * (1.0 - 2.0 * s.x),
            self.tan_half.y * (1.0 - 2.0 * s.y),
            self.near,
        );
        let origin = self.to_world.transform_point3(local);
        let dir = self.to_world.transform_vector3(Vec3::Z).normalize_or_zero();
        (Ray { origin, dir }, self.far - self.near)
    }

    /// The film position in pixels of the camera-space point `q` under the orthographic
    /// projection (inside the image or not).
    pub(super) fn orthographic_raster(&self, q: Vec3) -> Option<Vec2> {
        let s = Vec2::new(
            0.5 * (1.0 - q.x / self.tan_half.x),
            0.5 * (1.0 - q.y / self.tan_half.y),
        );
        let r = s * self.res - self.offset;
        r.is_finite().then_some(r)
    }
}

#[cfg(test)]
mod tests {
    use crate::camera::Camera;
    use crate::description::{Checked, FilmDesc, Projection, SensorDesc, ThinLensDesc};
    use crate::transform::look_at;
    use glam::{Mat4, Vec2, Vec3};

    /// The published scene's sensor: scale 1.5, looking from (-5, 0, 3) at (0, 0, 1), on a
    /// 200 × 120 film, near 1, far 1000.
    fn published() -> Camera {
        let to_world = look_at(Vec3::new(-5.0, 0.0, 3.0), Vec3::new(0.0, 0.0, 1.0), Vec3::Z)
            .unwrap()
            * Mat4::from_scale(Vec3::new(1.5, 1.5, 1.0));
        let sensor = SensorDesc {
            projection: Projection::Orthographic,
            near_clip: 1.0,
            far_clip: 1000.0,
            to_world,
            film: Checked::new(FilmDesc {
                width: 200,
                height: 120,
                ..FilmDesc::default()
            })
            .unwrap(),
            ..SensorDesc::default()
        };
        Camera::new(&sensor).unwrap()
    }

    #[test]
    fn rays_are_parallel_and_span_the_scaled_square_with_the_films_aspect() {
        let cam = published();
        assert!(cam.is_orthographic());
        let forward = (Vec3::new(0.0, 0.0, 1.0) - Vec3::new(-5.0, 0.0, 3.0)).normalize();
        let (centre, t_max) = cam.generate_ray_with_tmax(Vec2::new(100.0, 60.0));
        assert_eq!(t_max, 999.0);
        // The centre ray leaves the near plane on the axis: 1 unit (unscaled z) ahead.
        let want = Vec3::new(-5.0, 0.0, 3.0) + forward;
        assert!((centre.origin - want).length() < 1e-5, "{}", centre.origin);
        let corner = cam.generate_ray(Vec2::new(0.0, 0.0));
        let far = cam.generate_ray(Vec2::new(200.0, 120.0));
        for r in [centre, corner, far] {
            assert!((r.dir - forward).length() < 1e-6, "{}", r.dir);
        }
        // Across the image: 2 · 1.5 wide, 2 · 1.5 / (200/120) = 1.8 high.
        let span = far.origin - corner.origin;
        let diag = span.length();
        assert!(
            diag.is_finite() && (diag - 3f32.hypot(1.8)).abs() < 1e-4,
            "{diag}"
        );
        // The film's top-left corner is camera-space +x (to the left), +y (up): world +z.
        assert!(corner.origin.z > far.origin.z);
        assert!(span.dot(forward).abs() < 1e-5);
    }

    #[test]
    fn raster_of_inverts_the_rays_and_the_direction_is_a_delta() {
        let cam = published();
        for film in [Vec2::new(0.5, 0.5), Vec2::new(123.25, 77.75)] {
            let ray = cam.generate_ray(film);
            let back = cam.raster_of(ray.at(4.0)).expect("in view");
            assert!((back - film).length() < 1e-3, "{back} vs {film}");
            assert_eq!(cam.direction_pdf(ray.dir), 0.0);
        }
        assert!(cam.raster_of(cam.position() - cam.forward()).is_none());
        assert_eq!(cam.fov_x(), 0.0);
    }

    #[test]
    fn a_lens_is_refused() {
        let sensor = SensorDesc {
            projection: Projection::Orthographic,
            lens: Some(ThinLensDesc {
                aperture_radius: 0.1,
                focus_distance: 1.0,
            }),
            ..SensorDesc::default()
        };
        assert_eq!(
            Checked::new(sensor.clone()).unwrap_err().param,
            "aperture_radius"
        );
        assert!(Camera::new(&sensor).is_err());
    }
}
