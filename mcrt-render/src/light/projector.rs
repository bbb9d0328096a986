//! Mitsuba 3's `projector`: a pinhole light that projects an image, the reciprocal of the
//! `perspective` camera (its pixel-to-direction map is the camera's).
//!
//! In the light's frame (looking along +z, +x toward the image's left edge), the direction
//! through `(x, y, 1)` meets the image at `u = ½(1 − x·c)`, `v = ½(1 − a·y·c)`, with
//! `c = 1/tan(fov_x/2)` and `a` the image's width over height; directions outside
//! `[0, 1]²` or behind the light carry nothing. The radiant intensity toward such a
//! direction, at angle θ to the axis, is `I = π · scale · s · E(u, v) / cos³θ` (`s` the
//! uniform scale of `to_world`), so that the plane `z = 1` receives `π · scale · E`
//! everywhere: Mitsuba 3's `sample_direction` returns `π · scale · E / (z_local² · (−n·d))`
//! with `n` the transformed, unnormalised +z, which is `I / d²`. The power is
//! `∫ I dω = π · scale · s · A · Ē` (`dω = cos³θ dA` on the plane, `A` its area in the
//! image, `Ē` the image's mean). Light subpaths leave through a point uniform on that
//! image rectangle: density `1/(A cos³θ)` per steradian.

use super::LightError;
use crate::texture::Texture;
use crate::validate::is_similarity;
use glam::{Affine3A, Mat4, Vec2, Vec3};
use std::f32::consts::PI;

/// A projector light.
#[derive(Debug, Clone, PartialEq)]
pub struct Projector {
    position: Vec3,
    to_world: Affine3A,
    to_local: Affine3A,
    irradiance: Texture,
    /// `π · scale · s`: the factor of `E / cos³θ` in the intensity.
    factor: f32,
    /// `1/tan(fov_x/2)`.
    cot: f32,
    /// Image width over height.
    aspect: f32,
    /// Area of the image rectangle on the plane `z = 1`.
    plane_area: f32,
}

impl Projector {
    /// The projector of Mitsuba's parameters; `aspect` is the image's width over height
    /// (1 for a texture without a resolution), `x_fov` in degrees.
    ///
    /// # Errors
    /// [`LightError::Projector`] for a field of view outside (0°, 180°), a negative or
    /// non-finite scale, or a `to_world` that is not a rotation, uniform scale and
    /// translation.
    pub fn new(
        irradiance: Texture,
        aspect: f32,
        scale: f32,
        x_fov: f32,
        to_world: Mat4,
    ) -> Result<Self, LightError> {
        let bad = |what: &str| Err(LightError::Projector(what.to_string()));
        if !(x_fov > 0.0 && x_fov < 180.0) {
            return bad("fov must lie in (0, 180) degrees");
        }
        if !(scale.is_finite() && scale >= 0.0) {
            return bad("scale must be finite and non-negative");
        }
        if !(aspect.is_finite() && aspect > 0.0) {
            return bad("the image has no size");
        }
        if !(to_world.is_finite() && is_similarity(&to_world)) {
            return bad("to_world must be a rotation, uniform scale and translation");
        }
        let to_world = Affine3A::from_mat4(to_world);
        let s = to_world.transform_vector3(Vec3::Z).length();
        let cot = 1.0 / (0.5 * x_fov.to_radians()).tan();
        Ok(Self {
            position: to_world.translation.into(),
            to_local: to_world.inverse(),
            to_world,
            irradiance,
            factor: PI * scale * s,
            cot,
            aspect,
            plane_area: 4.0 / (cot * cot * aspect),
        })
    }

    /// The light's position.
    pub fn position(&self) -> Vec3 {
        self.position
    }

    /// The image coordinates of the local direction `d`, if it passes through the image.
    fn image_uv(&self, d: Vec3) -> Option<Vec2> {
        if d.z.is_nan() || d.z <= 0.0 {
            return None;
        }
        let uv = Vec2::new(
            0.5 * (1.0 - self.cot * d.x / d.z),
            0.5 * (1.0 - self.aspect * self.cot * d.y / d.z),
        );
        (uv.cmpge(Vec2::ZERO).all() && uv.cmple(Vec2::ONE).all()).then_some(uv)
    }

    /// Intensity (W/sr) along the unit world direction `dir` leaving the light.
    pub fn intensity_toward(&self, dir: Vec3) -> Vec3 {
        let d = self.to_local.transform_vector3(dir);
        let Some(uv) = self.image_uv(d) else {
            return Vec3::ZERO;
        };
        let cos = d.z / d.length();
        let i = self.irradiance.eval(uv) * (self.factor / (cos * cos * cos));
        if i.is_finite() {
            i
        } else {
            Vec3::ZERO
        }
    }

    /// Emitted power's channel mean, `π · scale · s · A · Ē`.
    pub fn power(&self) -> f32 {
        self.factor * self.plane_area * self.irradiance.mean().max(0.0)
    }

    /// A direction of a light subpath through a point uniform on the image rectangle: the
    /// unit world direction, the intensity along it and its density per steradian.
    pub fn sample_direction(&self, u: Vec2) -> (Vec3, Vec3, f32) {
        let local = Vec3::new(
            (1.0 - 2.0 * u.x) / self.cot,
            (1.0 - 2.0 * u.y) / (self.aspect * self.cot),
            1.0,
        );
        let dir = self.to_world.transform_vector3(local).normalize();
        (dir, self.intensity_toward(dir), self.pdf_direction(dir))
    }

    /// Density per steradian with which [`Projector::sample_direction`] returns the unit
    /// world direction `dir`: `1/(A cos³θ)` through the image, else 0.
    pub fn pdf_direction(&self, dir: Vec3) -> f32 {
        let d = self.to_local.transform_vector3(dir);
        if self.image_uv(d).is_none() {
            return 0.0;
        }
        let r = d.length() / d.z;
        r * r * r / self.plane_area
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::texture::Checkerboard;

    fn constant(c: f32) -> Texture {
        Texture::Checkerboard(Checkerboard {
            color0: Vec3::splat(c),
            color1: Vec3::splat(c),
            ..Checkerboard::default()
        })
    }

    /// A constant image lights the plane z = 1 with `π · scale · E` everywhere inside the
    /// image (and nothing outside); the direction density integrates to 1 over the image.
    #[test]
    fn constant_image_lights_the_unit_plane_evenly() {
        let p = Projector::new(constant(0.5), 2.0, 3.0, 60.0, Mat4::IDENTITY).unwrap();
        let half = 1.0 / p.cot;
        for (x, y) in [
            (0.0, 0.0),
            (0.9 * half, 0.4 * half),
            (-0.5 * half, -0.45 * half),
        ] {
            let q = Vec3::new(x, y, 1.0);
            let d2 = q.length_squared();
            let dir = q / d2.sqrt();
            let e = p.intensity_toward(dir).x * dir.z / d2;
            assert!(e.is_finite() && (e - PI * 1.5).abs() < 1e-4, "{x} {y}: {e}");
        }
        assert_eq!(
            p.intensity_toward(Vec3::new(0.0, 0.6 * half, 1.0).normalize()),
            Vec3::ZERO
        );
        assert_eq!(p.intensity_toward(-Vec3::Z), Vec3::ZERO);
        // ∫ pdf dω over the image by a midpoint rule on the plane (dω = cos³θ dA).
        let n = 200;
        let (w, h) = (2.0 * half, half);
        let mut sum = 0.0f64;
        for i in 0..n {
            for j in 0..n {
                let q = Vec3::new(
                    -half + w * (i as f32 + 0.5) / n as f32,
                    -0.5 * half + h * (j as f32 + 0.5) / n as f32,
                    1.0,
                );
                let cos = 1.0 / q.length();
                sum += f64::from(p.pdf_direction(q.normalize()) * cos * cos * cos);
            }
        }
        let total = sum * f64::from(w * h) / f64::from(n * n);
        assert!((total - 1.0).abs() < 1e-3, "{total}");
        let (dir, i, pdf) = p.sample_direction(Vec2::new(0.3, 0.8));
        assert!(pdf.is_finite() && (pdf - p.pdf_direction(dir)).abs() < 1e-5 * pdf);
        assert!((i - p.intensity_toward(dir)).length() < 1e-5);
        let power = p.power();
        assert!(power.is_finite() && (power - PI * 3.0 * p.plane_area * 0.5).abs() < 1e-4);
    }

    /// Mitsuba 3.9.1's `projector` (irradiance (0.5, 0.25, 1), scale 2, fov 40, to_world
    /// translate (0.5, 1, −0.5) · rotate(y, 30°) · scale 1.5): the radiance its
    /// `sample_direction` returns at four points, which is `I / d²` here.
    #[test]
    fn matches_mitsuba_values() {
        let irr = Texture::Checkerboard(Checkerboard {
            color0: Vec3::new(0.5, 0.25, 1.0),
            color1: Vec3::new(0.5, 0.25, 1.0),
            ..Checkerboard::default()
        });
        let m = Mat4::from_translation(Vec3::new(0.5, 1.0, -0.5))
            * Mat4::from_rotation_y(30f32.to_radians())
            * Mat4::from_scale(Vec3::splat(1.5));
        let p = Projector::new(irr, 1.0, 2.0, 40.0, m).unwrap();
        for (at, want) in [
            ([1.5, 1.0, 1.232_05], 1.178_097_7),
            ([2.3, 1.2, 2.098_075], 0.477_485_5),
            ([1.05, 0.7, 0.899_038], 2.198_735_5),
            ([2.5, 1.9, 2.964_1], 0.301_887_5),
        ] {
            let d = Vec3::from(at) - p.position();
            let got = p.intensity_toward(d.normalize()).x / d.length_squared();
            assert!(
                got.is_finite() && (got / want - 1.0).abs() < 1e-4,
                "{at:?}: {got}"
            );
        }
    }

    /// The image's orientation as Mitsuba 3's: `u = 0` at local +x (the image's left as the
    /// light sees it), `v = 0` at local +y (its top).
    #[test]
    fn image_orientation() {
        let p = Projector::new(constant(1.0), 1.0, 1.0, 90.0, Mat4::IDENTITY).unwrap();
        let uv = p.image_uv(Vec3::new(0.5, 0.5, 1.0)).unwrap();
        assert!((uv - Vec2::new(0.25, 0.25)).length() < 1e-6, "{uv}");
        assert!(Projector::new(constant(1.0), 1.0, 1.0, 180.0, Mat4::IDENTITY).is_err());
        let squash = Mat4::from_scale(Vec3::new(1.0, 2.0, 1.0));
        assert!(Projector::new(constant(1.0), 1.0, 1.0, 40.0, squash).is_err());
    }
}
