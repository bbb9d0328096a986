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
use crate::geometry::Ray;
use glam::{Vec2, Vec3};
use mcrt::sampling::warp::{UniformDiskConcentric, Warp};

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

/// The thin lens as an endpoint of light subpaths (bidirectional estimators).
///
/// For a fixed lens point `a` the film position maps to the focus-plane point `q` linearly,
/// so the direction from `a` toward `q` has the pinhole's density `1/(A cos³θ)` per
/// steradian, `θ` now the angle between that direction and the viewing axis: the focus
/// plane's image area `f²A` and `dA_q/dω = f²/cos³θ` give `(1/(f²A))·f²/cos³θ` (Veach 1997,
/// thesis, section 10.1.3; pbrt-v4, section 5.2.3, the same for a lens). The lens point is
/// uniform over the aperture in both the camera subpath and the connection to the camera,
/// so its density cancels between strategies; the importance per steradian of a
/// connection is the direction density again, as for the pinhole.
impl Camera {
    /// The world-space lens point of `u_lens ∈ [0,1)²` (the concentric map onto the
    /// aperture, as [`Camera::generate_ray_through_lens`] uses); the camera's position
    /// without a lens.
    pub fn lens_point(&self, u_lens: Vec2) -> Vec3 {
        match self.lens {
            Some((radius, _)) => self
                .to_world
                .transform_point3((UniformDiskConcentric.sample(u_lens) * radius).extend(0.0)),
            None => self.position(),
        }
    }

    /// The lens point a camera ray leaves from: its origin (on the near plane) traced back
    /// along `dir` to the lens plane; the camera's position without a lens.
    pub fn lens_point_of_ray(&self, origin: Vec3, dir: Vec3) -> Vec3 {
        if self.lens.is_none() {
            return self.position();
        }
        let along = self.to_camera.transform_vector3(dir).z;
        let back = self.to_camera.transform_point3(origin).z / along;
        if back.is_finite() {
            origin - dir * back
        } else {
            self.position()
        }
    }

    /// The focus-plane point (camera space) of the line from the camera-space lens point
    /// `a` along `d`; `None` unless `d` points forward.
    fn focus_point(&self, a: Vec3, d: Vec3) -> Option<Vec3> {
        let focus = self.lens.map_or(1.0, |(_, f)| f);
        if d.z.is_nan() || d.z <= 0.0 {
            return None;
        }
        let q = a + d * ((focus - a.z) / d.z);
        q.is_finite().then_some(q)
    }

    /// [`Camera::direction_density`] for a ray leaving the world-space lens point `lens`
    /// along `dir`: the film position it came through (inside the image or not) and
    /// `1/(A cos³θ)`.
    pub(crate) fn direction_density_from(&self, lens: Vec3, dir: Vec3) -> Option<(Vec2, f32)> {
        if self.lens.is_none() {
            return self.direction_density(dir);
        }
        let a = self.to_camera.transform_point3(lens);
        let d = self.to_camera.transform_vector3(dir);
        let r = self.raster_of_local(self.focus_point(a, d)?)?;
        let cos = d.z / d.length();
        (cos.is_finite() && cos > 0.0).then(|| (r, 1.0 / (self.image_area() * cos * cos * cos)))
    }

    /// Density per steradian of the direction of [`Camera::generate_ray_through_lens`] from
    /// the lens point `lens` (see [`Camera::lens_point`]) for a film position uniform over
    /// the image (0 outside the field of view); also the importance `W(ω)` there. For a
    /// pinhole, [`Camera::direction_pdf`].
    pub fn direction_pdf_from_lens(&self, lens: Vec3, dir: Vec3) -> f32 {
        match self.direction_density_from(lens, dir) {
            Some((r, pdf)) if self.inside(r) => pdf,
            _ => 0.0,
        }
    }

    /// The film position whose rays through the world-space lens point `lens` pass through
    /// the world point `p` (inside the image or not), if `p` lies between the clip planes.
    pub(crate) fn raster_through_lens(&self, lens: Vec3, p: Vec3) -> Option<Vec2> {
        if self.lens.is_none() {
            return self.raster_of_unbounded(p);
        }
        let q = self.to_camera.transform_point3(p);
        if !(q.z >= self.near && q.z <= self.far) {
            return None;
        }
        let a = self.to_camera.transform_point3(lens);
        self.raster_of_local(self.focus_point(a, q - a)?)
    }
}

#[cfg(test)]
mod tests {
    use crate::camera::Camera;
    use crate::description::{SensorDesc, ThinLensDesc};
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

    /// The lens as an endpoint: the lens point a ray leaves from is the sample's point, and
    /// a point on the ray maps back to the ray's film position through that lens point.
    #[test]
    fn lens_points_and_film_positions_invert_the_rays() {
        let cam = lens_camera(0.25, 3.0);
        for (film, u) in [
            (Vec2::new(384.0, 288.0), Vec2::new(0.1, 0.9)),
            (Vec2::new(10.5, 500.25), Vec2::new(0.7, 0.3)),
            (Vec2::new(700.0, 20.0), Vec2::new(0.999, 0.5)),
        ] {
            let (ray, _) = cam.generate_ray_through_lens(film, u);
            let lens = cam.lens_point(u);
            let back = cam.lens_point_of_ray(ray.origin, ray.dir);
            assert!((back - lens).length() < 1e-5, "{back} against {lens}");
            for t in [0.5, 2.0, 9.0] {
                let r = cam
                    .raster_through_lens(lens, ray.origin + ray.dir * t)
                    .unwrap();
                let err = (r - film).length();
                assert!(err.is_finite() && err < 2e-2, "{film} {u} {t}: {r}");
            }
            let pdf = cam.direction_pdf_from_lens(lens, ray.dir);
            let cos = ray.dir.dot(cam.forward());
            let (pin, _) = cam.generate_ray_with_tmax(film);
            let pin_cos = pin.dir.dot(cam.forward());
            // The pinhole's density at its own angle, scaled to this ray's angle.
            let expect = cam.direction_pdf(pin.dir) * (pin_cos / cos).powi(3);
            assert!(
                pdf.is_finite() && (pdf / expect - 1.0).abs() < 1e-3,
                "{pdf} against {expect}"
            );
        }
        // Behind the lens plane and outside the clip range: no film position.
        assert!(cam
            .raster_through_lens(
                cam.lens_point(Vec2::splat(0.3)),
                cam.position() - cam.forward()
            )
            .is_none());
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
