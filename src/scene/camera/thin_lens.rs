//! The thin-lens camera's rays (Mitsuba 3's `thinlens` sensor).
//!
//! In camera space the film position maps to the point `q = f·(tx(1 − 2x/w), ty(1 − 2y/h), 1)`
//! on the plane in focus, `f` the focus distance (the pinhole's direction scaled to that
//! plane); the ray leaves the lens point `a = (r·d, 0)`, `d` a point of the unit disk by the
//! concentric map (Shirley & Chiu 1997, "A Low Distortion Map Between Disk and Square",
//! Journal of Graphics Tools 2(3)), toward `q`. Every ray through one film position meets on
//! the focus plane; the clip planes are the planes `z = near`, `z = far`, as for the pinhole.
//! Mitsuba 3 weighs these rays by 1, as we do.

use super::Camera;
use crate::sampling::warp::{UniformDiskConcentric, Warp};
use crate::scene::geometry::Ray;
use glam::{Vec2, Vec3};

impl Camera {
    /// Whether rays need a lens sample: a thin lens with a positive aperture.
    #[inline]
    pub fn has_lens(&self) -> bool {
        matches!(self.lens, Some((r, _)) if r > 0.0)
    }

    /// The thin lens's aperture radius and focus distance, if the camera has a lens.
    pub fn lens(&self) -> Option<(f32, f32)> {
        self.lens
    }

    /// The ray through film position `film` (pixels, as [`Camera::generate_ray`]) and the
    /// lens point of `u_lens ∈ [0,1)²`, with its `t_max` to the far clip plane; the
    /// pinhole's ray when the camera has no lens. The origin lies on the near clip plane.
    #[inline]
    pub fn generate_ray_through_lens(&self, film: Vec2, u_lens: Vec2) -> (Ray, f32) {
        let Some((radius, focus)) = self.lens else {
            return self.generate_ray_with_tmax(film);
        };
        let s = (film + self.offset) * self.inv_res;
        let q = Vec3::new(
            self.tan_half.x * (1.0 - 2.0 * s.x),
            self.tan_half.y * (1.0 - 2.0 * s.y),
            1.0,
        ) * focus;
        let a = (UniformDiskConcentric.sample(u_lens) * radius).extend(0.0);
        // The direction with z = 1, so that the clip planes are plain t values along it.
        let v = (q - a) / focus;
        let world = self.to_world.transform_vector3(v);
        let len = world.length();
        let origin = self.to_world.transform_point3(a) + world * self.near;
        (
            Ray {
                origin,
                dir: world / len,
            },
            (self.far - self.near) * len,
        )
    }
}

#[cfg(test)]
mod tests {
    use crate::scene::camera::Camera;
    use crate::scene::description::{SensorDesc, ThinLensDesc};
    use glam::{Mat4, Vec2, Vec3};

    fn lens_camera(radius: f32, focus: f32) -> Camera {
        let sensor = SensorDesc {
            fov: 40.0,
            to_world: Mat4::from_translation(Vec3::new(0.5, -1.0, 2.0))
                * Mat4::from_rotation_y(0.3),
            lens: Some(ThinLensDesc {
                aperture_radius: radius,
                focus_distance: focus,
            }),
            ..SensorDesc::default()
        };
        Camera::new(&sensor).unwrap()
    }

    /// Every ray through one film position crosses the focus plane at the pinhole ray's
    /// point there, whatever the lens sample.
    #[test]
    fn rays_through_one_film_position_meet_on_the_focus_plane() {
        let cam = lens_camera(0.25, 3.0);
        let axis = cam.forward();
        let eye = cam.position();
        for film in [Vec2::new(384.0, 288.0), Vec2::new(10.5, 500.25)] {
            let (pin, _) = cam.generate_ray_with_tmax(film);
            let t_pin = (3.0 - (pin.origin - eye).dot(axis)) / pin.dir.dot(axis);
            let target = pin.origin + pin.dir * t_pin;
            for u in [
                Vec2::new(0.1, 0.9),
                Vec2::new(0.7, 0.3),
                Vec2::new(0.999, 0.5),
            ] {
                let (ray, t_max) = cam.generate_ray_through_lens(film, u);
                let t = (3.0 - (ray.origin - eye).dot(axis)) / ray.dir.dot(axis);
                let hit = ray.origin + ray.dir * t;
                let err = (hit - target).length();
                assert!(err.is_finite() && err < 1e-4, "{film} {u}: off by {err}");
                let near = (ray.origin - eye).dot(axis);
                assert!(
                    near.is_finite() && (near - 0.01).abs() < 1e-5,
                    "near {near}"
                );
                let far = (ray.origin + ray.dir * t_max - eye).dot(axis);
                assert!(
                    far.is_finite() && (far / 1e4 - 1.0).abs() < 1e-4,
                    "far {far}"
                );
                let len = ray.dir.length();
                assert!(len.is_finite() && (len - 1.0).abs() < 1e-5);
            }
        }
    }

    /// The lens point lies on the aperture disk: at the disk's rim for a sample on the
    /// square's edge, on the axis for the centre sample.
    #[test]
    fn the_lens_point_covers_the_aperture_disk() {
        let cam = lens_camera(0.25, 3.0);
        let axis = cam.forward();
        let film = Vec2::new(200.0, 100.0);
        let off_axis = |u: Vec2| {
            let (ray, _) = cam.generate_ray_through_lens(film, u);
            // Back from the near plane to the lens plane (z = 0 in camera space).
            let t = (ray.origin - cam.position()).dot(axis) / ray.dir.dot(axis);
            (ray.origin - ray.dir * t - cam.position()).length()
        };
        let centre = off_axis(Vec2::splat(0.5));
        assert!(centre.is_finite() && centre < 1e-5, "{centre}");
        let rim = off_axis(Vec2::new(1.0, 0.3));
        assert!(rim.is_finite() && (rim - 0.25).abs() < 1e-5, "{rim}");
    }

    #[test]
    fn a_zero_aperture_needs_no_lens_sample_and_bad_lenses_are_refused() {
        assert!(!lens_camera(0.0, 3.0).has_lens());
        assert!(lens_camera(0.1, 3.0).has_lens());
        for (r, f) in [
            (-0.1, 1.0),
            (f32::NAN, 1.0),
            (0.1, 0.0),
            (0.1, f32::INFINITY),
        ] {
            let sensor = SensorDesc {
                lens: Some(ThinLensDesc {
                    aperture_radius: r,
                    focus_distance: f,
                }),
                ..SensorDesc::default()
            };
            assert!(Camera::new(&sensor).is_err(), "{r} {f}");
        }
    }
}
