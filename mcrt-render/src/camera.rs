//! The perspective camera, with Mitsuba 3's `perspective` sensor semantics.
//!
//! Camera space looks down +z with +y up and +x to the image's *left* (Mitsuba's
//! convention: its `lookat` builds the frame with `left = up × dir`). The film position
//! `(x, y)` in pixels, `(0, 0)` the top-left corner, maps to the camera-space direction
//! `(tx·(1 − 2x/w), tx/a·(1 − 2y/h), 1)` with `a = w/h` and `tx = tan(fov_x / 2)`.
//! `fov` spans the axis `fov_axis` names; `smaller` means y when `a > 1`, else x; `larger`
//! means x when `a > 1`, else y; a vertical fov converts as `tan(fov_x/2) = a·tan(fov_y/2)`.
//!
//! An orthographic camera (Mitsuba 3's `orthographic`, [`Projection::Orthographic`]) maps
//! the film position to the camera-space point `(1 − 2x/w, (1 − 2y/h)/a, near)` and sends
//! the ray along `to_world`'s +z; see `camera/orthographic.rs`.
//!
//! Clipping: Mitsuba starts a camera ray at `t = near_clip / d_z` and ends it at
//! `far_clip / d_z` (unit camera-space direction `d`): the near and far planes are planes
//! `z = near`, `z = far` in camera space, not spheres. [`Camera::generate_ray`] starts the
//! ray on the near plane; [`Camera::generate_ray_with_tmax`] also returns the distance from
//! there to the far plane.
//!
//! ```
//! use mcrt::glam::{Vec2, Vec3};
//! use mcrt_render::camera::Camera;
//! use mcrt_render::description::SensorDesc;
//!
//! let cam = Camera::new(&SensorDesc::default()).unwrap(); // 768×576, 45° along x
//! let ray = cam.generate_ray(Vec2::new(384.0, 288.0));     // the image centre
//! assert!((ray.dir - Vec3::Z).length() < 1e-6);
//! // The left edge of the image looks towards camera-space +x.
//! assert!(cam.generate_ray(Vec2::new(0.0, 288.0)).dir.x > 0.0);
//! ```

mod error;
mod orthographic;
mod thin_lens;

pub use error::CameraError;

use crate::description::{FovAxis, Projection, SensorDesc};
use crate::geometry::Ray;
use glam::{Affine3A, Mat3, Vec2, Vec3};

/// A perspective camera: a pinhole, or a thin lens (Mitsuba 3's `thinlens`; see
/// [`Camera::generate_ray_through_lens`]); or an orthographic one (Mitsuba 3's
/// `orthographic`; see [`Camera::is_orthographic`]).
#[derive(Debug, Clone)]
pub struct Camera {
    /// Parallel rays along the camera's +z (Mitsuba 3's `orthographic`).
    orthographic: bool,
    /// The thin lens: aperture radius and focus distance; `None` for a pinhole.
    lens: Option<(f32, f32)>,
    to_world: Affine3A,
    to_camera: Affine3A,
    /// The rendered window's size in pixels (the whole film unless it is cropped).
    width: u32,
    height: u32,
    /// The window's top-left corner on the whole film, in pixels.
    offset: Vec2,
    /// The whole film's size in pixels.
    res: Vec2,
    /// 1/w, 1/h of the whole film.
    inv_res: Vec2,
    /// tan(fov_x/2), tan(fov_y/2).
    tan_half: Vec2,
    near: f32,
    far: f32,
}

impl Camera {
    /// The camera a sensor description asks for (its film gives the resolution).
    ///
    /// # Errors
    /// See [`CameraError`].
    pub fn new(sensor: &SensorDesc) -> Result<Self, CameraError> {
        let (w, h) = (sensor.film.width, sensor.film.height);
        if w == 0 || h == 0 {
            return Err(CameraError::EmptyFilm {
                width: w,
                height: h,
            });
        }
        let orthographic = sensor.projection == Projection::Orthographic;
        let fov_valid = sensor.fov > 0.0 && sensor.fov < 180.0;
        if !orthographic && !fov_valid {
            return Err(CameraError::InvalidFov(sensor.fov));
        }
        let (near, far) = (sensor.near_clip, sensor.far_clip);
        if !(near > 0.0 && near < far && far.is_finite()) {
            return Err(CameraError::InvalidClip { near, far });
        }
        let m = sensor.to_world;
        let det = Mat3::from_mat4(m).determinant();
        if !m.is_finite() || m.row(3).distance(glam::Vec4::W) > 1e-6 || det == 0.0 {
            return Err(CameraError::BadTransform);
        }
        let aspect = w as f32 / h as f32;
        let axis = match sensor.fov_axis {
            FovAxis::Smaller if aspect > 1.0 => FovAxis::Y,
            FovAxis::Smaller => FovAxis::X,
            FovAxis::Larger if aspect > 1.0 => FovAxis::X,
            FovAxis::Larger => FovAxis::Y,
            a => a,
        };
        let t = (0.5 * sensor.fov.to_radians()).tan();
        // The orthographic camera's half width in camera space is 1 (`camera/orthographic.rs`).
        let tan_x = if orthographic {
            1.0
        } else if axis == FovAxis::Y {
            t * aspect
        } else {
            t
        };
        let win = sensor.film.window();
        let fits = |o: u32, n: u32, full: u32| n > 0 && o.checked_add(n).is_some_and(|e| e <= full);
        if !(fits(win.offset_x, win.width, w) && fits(win.offset_y, win.height, h)) {
            return Err(CameraError::EmptyFilm {
                width: win.width,
                height: win.height,
            });
        }
        let lens = match sensor.lens {
            None => None,
            Some(l) => {
                let (r, f) = (l.aperture_radius, l.focus_distance);
                if !(r.is_finite() && r >= 0.0 && f.is_finite() && f > 0.0) {
                    return Err(CameraError::InvalidLens {
                        aperture_radius: r,
                        focus_distance: f,
                    });
                }
                Some((r, f))
            }
        };
        if orthographic && lens.is_some() {
            return Err(CameraError::OrthographicLens);
        }
        Ok(Self {
            orthographic,
            lens,
            to_world: Affine3A::from_mat4(m),
            to_camera: Affine3A::from_mat4(m).inverse(),
            width: win.width,
            height: win.height,
            offset: Vec2::new(win.offset_x as f32, win.offset_y as f32),
            res: Vec2::new(w as f32, h as f32),
            inv_res: Vec2::new(1.0 / w as f32, 1.0 / h as f32),
            tan_half: Vec2::new(tan_x, tan_x / aspect),
            near,
            far,
        })
    }

    /// Width in pixels of the rendered window (the film, or its crop window).
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels of the rendered window (the film, or its crop window).
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The horizontal field of view in degrees (whatever axis the description used); 0 for
    /// an orthographic camera.
    pub fn fov_x(&self) -> f32 {
        if self.orthographic {
            return 0.0;
        }
        2.0 * self.tan_half.x.atan().to_degrees()
    }

    /// The camera's position in world space.
    pub fn position(&self) -> Vec3 {
        self.to_world.translation.into()
    }

    /// The ray through film position `film` (pixels, `[0,w)×[0,h)`, `(0,0)` the top-left
    /// corner of the rendered window): unit direction, origin on the near clip plane.
    #[inline]
    pub fn generate_ray(&self, film: Vec2) -> Ray {
        self.generate_ray_with_tmax(film).0
    }

    /// [`Camera::generate_ray`] and the ray's `t_max`: the distance from its origin to the
    /// far clip plane.
    #[inline]
    pub fn generate_ray_with_tmax(&self, film: Vec2) -> (Ray, f32) {
        if self.orthographic {
            return self.orthographic_ray(film);
        }
        let s = (film + self.offset) * self.inv_res;
        let local = Vec3::new(
            self.tan_half.x * (1.0 - 2.0 * s.x),
            self.tan_half.y * (1.0 - 2.0 * s.y),
            1.0,
        );
        // With the unnormalised local direction (z = 1), near and far are plain t values.
        let world = self.to_world.transform_vector3(local);
        let len = world.length();
        let dir = world / len;
        let origin = self.position() + world * self.near;
        (Ray { origin, dir }, (self.far - self.near) * len)
    }
}

/// The camera as an endpoint of light subpaths (pinhole: a delta in position).
///
/// With the film position uniform over the image, the camera ray's direction has density
/// `p(ω) = 1/(A cos³θ)` per steradian, `A = 4·tan(fov_x/2)·tan(fov_y/2)` the image's area
/// on the plane one unit in front, `θ` the angle to the viewing axis; the importance that
/// makes `∫ W L dω` the image's mean pixel value is the same function. Exact when
/// `to_world` is a similarity (rotation, reflection, uniform scale, translation), which
/// `Camera::is_similarity` tells.
impl Camera {
    /// Unit direction the camera looks along.
    pub fn forward(&self) -> Vec3 {
        self.to_world.transform_vector3(Vec3::Z).normalize_or_zero()
    }

    /// Whether `to_world`'s linear part preserves angles (orthogonal columns of one length).
    pub(crate) fn is_similarity(&self) -> bool {
        let m = self.to_world.matrix3;
        let (x, y, z) = (
            Vec3::from(m.x_axis),
            Vec3::from(m.y_axis),
            Vec3::from(m.z_axis),
        );
        let l = x.length();
        let tol = 1e-4 * l * l;
        (y.length() - l).abs() < 1e-4 * l
            && (z.length() - l).abs() < 1e-4 * l
            && x.dot(y).abs() < tol
            && y.dot(z).abs() < tol
            && x.dot(z).abs() < tol
    }

    /// The film position in pixels of the camera-space point `q` (in front of the camera),
    /// whether or not it is inside the image.
    fn raster_of_local(&self, q: Vec3) -> Option<Vec2> {
        if q.z.is_nan() || q.z <= 0.0 {
            return None;
        }
        let s = Vec2::new(
            0.5 * (1.0 - q.x / (q.z * self.tan_half.x)),
            0.5 * (1.0 - q.y / (q.z * self.tan_half.y)),
        );
        let r = s * self.res - self.offset;
        r.is_finite().then_some(r)
    }

    /// Whether a film position lies inside the image.
    fn inside(&self, r: Vec2) -> bool {
        r.x >= 0.0 && r.y >= 0.0 && r.x < self.width as f32 && r.y < self.height as f32
    }

    /// Density per steradian of the direction of [`Camera::generate_ray`] for a film
    /// position uniform over the image (0 outside the field of view); also the importance
    /// `W(ω)`.
    pub fn direction_pdf(&self, dir: Vec3) -> f32 {
        match self.direction_density(dir) {
            Some((r, pdf)) if self.inside(r) => pdf,
            _ => 0.0,
        }
    }

    /// The film position of the direction `dir` (anywhere on the image plane, inside the
    /// image or not) and `1/(A cos³θ)`, the density per steradian that a film position
    /// uniform over the image would give there; `None` behind the camera, and always for an
    /// orthographic camera (its directions are a delta: no density per steradian).
    pub(crate) fn direction_density(&self, dir: Vec3) -> Option<(Vec2, f32)> {
        if self.orthographic {
            return None;
        }
        let q = self.to_camera.transform_vector3(dir);
        let len = q.length();
        let r = self.raster_of_local(q)?;
        if len.is_nan() || len <= 0.0 {
            return None;
        }
        let cos = q.z / len;
        Some((r, 1.0 / (self.image_area() * cos * cos * cos)))
    }

    /// The image plane's area (one unit in front) that the rendered window covers.
    fn image_area(&self) -> f32 {
        let window = self.width as f32 * self.height as f32 * self.inv_res.x * self.inv_res.y;
        4.0 * self.tan_half.x * self.tan_half.y * window
    }

    /// The film position of the world point `p`, if `p` is in the field of view and between
    /// the clip planes.
    pub fn raster_of(&self, p: Vec3) -> Option<Vec2> {
        self.raster_of_unbounded(p).filter(|r| self.inside(*r))
    }

    /// [`Camera::raster_of`] without the image's bounds (a pixel filter reaches past them).
    pub(crate) fn raster_of_unbounded(&self, p: Vec3) -> Option<Vec2> {
        let q = self.to_camera.transform_point3(p);
        if !(q.z >= self.near && q.z <= self.far) {
            return None;
        }
        if self.orthographic {
            return self.orthographic_raster(q);
        }
        self.raster_of_local(q)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::description::{Checked, FilmDesc};

    fn sensor(fov: f32, axis: FovAxis, w: u32, h: u32) -> SensorDesc {
        SensorDesc {
            fov,
            fov_axis: axis,
            film: Checked::new(FilmDesc {
                width: w,
                height: h,
                ..FilmDesc::default()
            })
            .unwrap(),
            ..SensorDesc::default()
        }
    }

    #[test]
    fn a_crop_window_is_exactly_that_part_of_the_image() {
        let full = sensor(50.0, FovAxis::X, 120, 90);
        let mut cropped = full.clone();
        cropped.film = (cropped.film)
            .changed(|f| {
                f.crop = Some(crate::description::CropWindow {
                    offset_x: 30,
                    offset_y: 20,
                    width: 40,
                    height: 25,
                })
            })
            .unwrap();
        let (a, b) = (Camera::new(&full).unwrap(), Camera::new(&cropped).unwrap());
        assert_eq!((b.width(), b.height()), (40, 25));
        let off = Vec2::new(30.0, 20.0);
        for p in [
            Vec2::new(0.0, 0.0),
            Vec2::new(12.3, 7.9),
            Vec2::new(39.9, 24.9),
        ] {
            let (ra, rb) = (a.generate_ray(p + off), b.generate_ray(p));
            assert!((ra.dir - rb.dir).abs().max_element() < 1e-6, "{p}");
            let back = b.direction_density(rb.dir).unwrap();
            assert!((back.0 - p).abs().max_element() < 1e-3, "{p}: {}", back.0);
            // Uniform over a window of 1000/10800 of the image: density 10.8× the full one.
            let full_pdf = a.direction_density(ra.dir).unwrap().1;
            let ratio = back.1 / full_pdf;
            assert!(ratio.is_finite() && (ratio - 10.8).abs() < 1e-3, "{ratio}");
        }
        assert_eq!(
            b.direction_pdf(a.generate_ray(Vec2::new(5.0, 5.0)).dir),
            0.0
        );
        // A window past the film cannot be made (the film's checked constructor refuses it).
        let past = cropped.film.changed(|f| {
            f.crop = Some(crate::description::CropWindow {
                offset_x: 100,
                offset_y: 0,
                width: 40,
                height: 10,
            })
        });
        assert_eq!(past.unwrap_err().param, "crop_width");
    }

    #[test]
    fn fov_axes_follow_mitsuba() {
        let wide = |a| Camera::new(&sensor(60.0, a, 200, 100)).unwrap().fov_x();
        let y_to_x = 2.0 * (30f32.to_radians().tan() * 2.0).atan().to_degrees();
        for (a, want) in [
            (FovAxis::X, 60.0),
            (FovAxis::Y, y_to_x),
            (FovAxis::Smaller, y_to_x),
            (FovAxis::Larger, 60.0),
        ] {
            let got = wide(a);
            assert!(
                got.is_finite() && (got - want).abs() < 1e-3,
                "{a:?}: {got} vs {want}"
            );
        }
        let tall = |a| Camera::new(&sensor(60.0, a, 100, 200)).unwrap().fov_x();
        assert!((tall(FovAxis::Smaller) - 60.0).abs() < 1e-3);
        assert!((tall(FovAxis::Larger) - tall(FovAxis::Y)).abs() < 1e-3);
    }

    #[test]
    fn rejects_bad_sensors() {
        assert!(Camera::new(&sensor(0.0, FovAxis::X, 10, 10)).is_err());
        assert!(Camera::new(&sensor(180.0, FovAxis::X, 10, 10)).is_err());
        // An empty film cannot even be made (its checked constructor refuses it).
        let empty = FilmDesc {
            width: 0,
            height: 10,
            ..FilmDesc::default()
        };
        assert_eq!(Checked::new(empty).unwrap_err().param, "width");
        let mut s = sensor(45.0, FovAxis::X, 10, 10);
        s.near_clip = 2.0 * s.far_clip;
        assert!(Camera::new(&s).is_err());
    }

    #[test]
    fn raster_of_inverts_generate_ray() {
        let mut s = sensor(50.0, FovAxis::X, 64, 48);
        s.to_world = glam::Mat4::from_translation(Vec3::new(1.0, 2.0, 3.0))
            * glam::Mat4::from_rotation_y(0.3);
        let cam = Camera::new(&s).unwrap();
        assert!(cam.is_similarity());
        for film in [
            Vec2::new(0.5, 0.5),
            Vec2::new(10.25, 40.75),
            Vec2::new(63.5, 1.0),
        ] {
            let ray = cam.generate_ray(film);
            let back = cam.raster_of(ray.at(2.0)).expect("in view");
            assert!(
                back.is_finite() && (back - film).length() < 1e-3,
                "{back} {film}"
            );
            let pdf = cam.direction_pdf(ray.dir);
            assert!(pdf.is_finite() && pdf > 0.0);
        }
        assert_eq!(cam.direction_pdf(-cam.forward()), 0.0);
        assert!(cam.raster_of(cam.position() - cam.forward()).is_none());
    }

    #[test]
    fn near_and_far_planes_are_planes() {
        let mut s = sensor(90.0, FovAxis::X, 100, 100);
        s.near_clip = 0.5;
        s.far_clip = 10.0;
        let cam = Camera::new(&s).unwrap();
        let (ray, t_max) = cam.generate_ray_with_tmax(Vec2::new(0.0, 50.0));
        assert!(ray.origin.is_finite() && t_max.is_finite());
        assert!((ray.origin.z - 0.5).abs() < 1e-6);
        assert!((ray.at(t_max).z - 10.0).abs() < 1e-4);
    }
}
