//! Mitsuba 3's `cylinder`: an open tube (no caps) of radius `r` about the segment from `p0`
//! to `p1`, normals outward (inward with `flip_normals`).
//!
//! As Mitsuba 3 builds it, the object-to-world map is `to_world · translate(p0) ·
//! frame(p1 − p0) · scale(r, r, |p1 − p0|)` (the frame of the unit axis is the one of Duff
//! et al. 2017, [`Frame::from_normal`]); its scale is taken out, leaving a rigid map of the
//! tube `x² + y² = r'², 0 ≤ z ≤ L'` in its local frame. A `to_world` that shears, scales the
//! cross-section non-uniformly or mirrors is refused (Mitsuba 3 warns and renders something
//! else). Surface coordinates are `(φ/2π, z/L')` with `φ` the local azimuth in `[0, 2π)`, as
//! Mitsuba's; light sampling is uniform by area, as Mitsuba's.

use super::error::GeometryError;
use super::ShapeSample;
use crate::accel::Aabb;
use glam::{Affine3A, Mat3, Vec2, Vec3};
use mcrt::sampling::Frame;
use std::f32::consts::TAU;

/// A cylinder in world space.
#[derive(Debug, Clone)]
pub(crate) struct CylinderData {
    /// Local to world: a rotation and translation (no scale).
    pub(crate) to_world: Affine3A,
    /// World to local.
    pub(crate) to_object: Affine3A,
    /// World-space radius `r'`.
    pub(crate) radius: f32,
    /// World-space length `L'`.
    pub(crate) length: f32,
    /// `flip_normals`.
    pub(crate) flip: bool,
}

impl CylinderData {
    /// The cylinder of Mitsuba's parameters under the object-to-world map `m`.
    pub(crate) fn new(
        shape: usize,
        m: &Affine3A,
        p0: Vec3,
        p1: Vec3,
        radius: f32,
        flip: bool,
    ) -> Result<Self, GeometryError> {
        let invalid = |what: &str| GeometryError::InvalidShape {
            shape,
            what: format!("cylinder: {what}"),
        };
        let axis = p1 - p0;
        let len = axis.length();
        if !(radius > 0.0 && radius.is_finite() && len > 0.0 && len.is_finite()) {
            return Err(invalid(
                "radius must be finite and > 0, p0 and p1 finite and distinct",
            ));
        }
        let f = Frame::from_normal(axis / len);
        let lin = Mat3::from(m.matrix3) * Mat3::from_cols(f.s * radius, f.t * radius, f.n * len);
        let (a, b, c) = (lin.x_axis, lin.y_axis, lin.z_axis);
        let (la, lb, lc) = (a.length(), b.length(), c.length());
        let tol = 1e-4 * la.max(lb).max(lc);
        let orthogonal =
            a.dot(b).abs() <= tol * la && b.dot(c).abs() <= tol * lc && a.dot(c).abs() <= tol * lc;
        if !(orthogonal && (la - lb).abs() <= tol) {
            return Err(invalid(
                "to_world may not shear or scale the cross-section non-uniformly",
            ));
        }
        if lin.determinant() <= 0.0 {
            return Err(invalid("to_world may not mirror"));
        }
        let rot = Mat3::from_cols(a / la, b / lb, c / lc);
        let to_world = Affine3A::from_mat3_translation(rot, m.transform_point3(p0));
        Ok(Self {
            to_world,
            to_object: to_world.inverse(),
            radius: 0.5 * (la + lb),
            length: lc,
            flip,
        })
    }

    /// The surface area `2π r' L'`.
    pub(crate) fn area(&self) -> f32 {
        TAU * self.radius * self.length
    }

    /// Bounds: the boxes of the two end circles (as Mitsuba 3's).
    pub(crate) fn bounds(&self) -> Aabb {
        let x1 = self.to_world.transform_vector3(Vec3::X * self.radius);
        let x2 = self.to_world.transform_vector3(Vec3::Y * self.radius);
        let x = (x1 * x1 + x2 * x2).powf(0.5);
        let p0 = self.to_world.transform_point3(Vec3::ZERO);
        let p1 = self.to_world.transform_point3(Vec3::Z * self.length);
        Aabb {
            min: (p0 - x).min(p1 - x),
            max: (p0 + x).max(p1 + x),
        }
    }

    /// A sphere holding the cylinder: (centre, radius).
    pub(crate) fn bounding_sphere(&self) -> (Vec3, f32) {
        let c = self
            .to_world
            .transform_point3(Vec3::Z * (0.5 * self.length));
        (c, self.radius.hypot(0.5 * self.length))
    }

    /// The nearer hit with `0 < t < t_max` of the ray `origin + t·dir` (any nonzero
    /// length), in f64 as Mitsuba 3 computes it on the CPU: the nearer root of
    /// `x² + y² = r²` whose `z` is in `[0, L]`, else the farther one.
    #[inline]
    pub(crate) fn hit(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<f32> {
        let o = self.to_object.transform_point3(origin).as_dvec3();
        let d = self.to_object.transform_vector3(dir).as_dvec3();
        let r = f64::from(self.radius);
        let a = d.x * d.x + d.y * d.y;
        let b = 2.0 * (d.x * o.x + d.y * o.y);
        let c = o.x * o.x + o.y * o.y - r * r;
        let (near, far) = solve_quadratic(a, b, c)?;
        let len = f64::from(self.length);
        let ok = |t: f64| {
            let z = o.z + d.z * t;
            let t32 = t as f32;
            (t32 > 0.0 && t32 < t_max && (0.0..=len).contains(&z)).then_some(t32)
        };
        ok(near).or_else(|| ok(far))
    }

    /// The surface at world point `p` of a hit: the point moved onto the tube, the unit
    /// front normal and the surface coordinates `(φ/2π, z/L')`.
    #[inline]
    pub(crate) fn surface(&self, p: Vec3) -> (Vec3, Vec3, Vec2) {
        let local = self.to_object.transform_point3(p);
        let rho = local.truncate().length();
        let radial = (local.truncate() / rho).extend(0.0);
        let radial = if radial.is_finite() { radial } else { Vec3::X };
        let n = self.to_world.transform_vector3(radial);
        let p = p + n * (self.radius - rho);
        let phi = local.y.atan2(local.x);
        let phi = if phi < 0.0 { phi + TAU } else { phi };
        let uv = Vec2::new(phi / TAU, local.z / self.length);
        (p, if self.flip { -n } else { n }, uv)
    }

    /// A point uniform by area (`u.x` along the axis, `u.y` the azimuth, as Mitsuba 3's
    /// `sample_position`), its front normal, and the density `1/area`.
    pub(crate) fn sample_area(&self, u: Vec2) -> ShapeSample {
        let (sin, cos) = (TAU * u.y).sin_cos();
        let radial = Vec3::new(cos, sin, 0.0);
        let p = self
            .to_world
            .transform_point3(radial * self.radius + Vec3::Z * (u.x * self.length));
        let n = self.to_world.transform_vector3(radial);
        ShapeSample {
            p,
            n: if self.flip { -n } else { n },
            pdf: 1.0 / self.area(),
        }
    }

    /// The surface coordinates `(φ/2π, z/L')` of a world point on the cylinder.
    pub(crate) fn surface_uv(&self, p: Vec3) -> Vec2 {
        self.surface(p).2
    }
}

/// The real roots of `a t² + b t + c` in increasing order (Press et al., *Numerical
/// Recipes*, 3rd ed., section 5.6, the form without cancellation); `None` without real
/// roots or for `a = 0`.
fn solve_quadratic(a: f64, b: f64, c: f64) -> Option<(f64, f64)> {
    if a == 0.0 {
        return None;
    }
    let disc = b * b - 4.0 * a * c;
    if disc.is_nan() || disc < 0.0 {
        return None;
    }
    let q = -0.5 * (b + disc.sqrt().copysign(b));
    let (t0, t1) = (q / a, if q != 0.0 { c / q } else { q / a });
    Some(if t0 <= t1 { (t0, t1) } else { (t1, t0) })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit() -> CylinderData {
        CylinderData::new(0, &Affine3A::IDENTITY, Vec3::ZERO, Vec3::Z, 1.0, false).unwrap()
    }

    /// Hits from outside and from inside, a miss past the end, and the open ends: a ray
    /// along the axis misses.
    #[test]
    fn hits_and_misses() {
        let c = unit();
        let t = c.hit(Vec3::new(-5.0, 0.0, 0.5), Vec3::X, f32::INFINITY);
        assert_eq!(t, Some(4.0));
        let t = c.hit(Vec3::new(0.0, 0.0, 0.5), Vec3::X * 2.0, f32::INFINITY);
        assert_eq!(t, Some(0.5));
        assert_eq!(
            c.hit(Vec3::new(-5.0, 0.0, 1.5), Vec3::X, f32::INFINITY),
            None
        );
        assert_eq!(
            c.hit(Vec3::new(0.0, 0.5, -3.0), Vec3::Z, f32::INFINITY),
            None
        );
        assert_eq!(c.hit(Vec3::new(-5.0, 0.0, 0.5), Vec3::X, 4.0), None);
        // Through the open end: misses the near wall (z < 0 there), hits the far one inside.
        let d = Vec3::new(1.0, 0.0, 0.4);
        let t = c
            .hit(Vec3::new(-1.5, 0.0, -0.25), d, f32::INFINITY)
            .unwrap();
        assert!(t.is_finite() && (t - 2.5).abs() < 1e-6, "{t}");
    }

    /// The normal and uv of Mitsuba 3's cylinder: outward, `(φ/2π, z/L)`.
    #[test]
    fn surface_and_samples() {
        let c = CylinderData::new(
            0,
            &Affine3A::from_translation(Vec3::new(1.0, 2.0, 3.0)),
            Vec3::ZERO,
            Vec3::new(0.0, 0.0, 2.0),
            0.5,
            true,
        )
        .unwrap();
        let (p, n, uv) = c.surface(Vec3::new(1.0, 2.5, 4.0));
        assert!((p - Vec3::new(1.0, 2.5, 4.0)).length() < 1e-6);
        assert!((n + Vec3::Y).length() < 1e-6, "flipped: {n}");
        assert!((uv - Vec2::new(0.25, 0.5)).length() < 1e-6, "{uv}");
        let s = c.sample_area(Vec2::new(0.25, 0.5));
        assert!((s.p - Vec3::new(0.5, 2.0, 3.5)).length() < 1e-6, "{}", s.p);
        assert!((s.n - Vec3::X).length() < 1e-6);
        assert!((s.pdf * TAU * 0.5 * 2.0 - 1.0).abs() < 1e-6);
        let (sc, sr) = c.bounding_sphere();
        assert!(
            (sc - Vec3::new(1.0, 2.0, 4.0)).length() < 1e-6 && (sr - 1.25f32.sqrt()).abs() < 1e-6
        );
    }

    #[test]
    fn bad_parameters_are_refused() {
        let id = Affine3A::IDENTITY;
        assert!(CylinderData::new(0, &id, Vec3::ZERO, Vec3::ZERO, 1.0, false).is_err());
        assert!(CylinderData::new(0, &id, Vec3::ZERO, Vec3::Z, 0.0, false).is_err());
        let squash = Affine3A::from_scale(Vec3::new(1.0, 2.0, 1.0));
        assert!(CylinderData::new(0, &squash, Vec3::ZERO, Vec3::Z, 1.0, false).is_err());
        let stretch = Affine3A::from_scale(Vec3::new(2.0, 2.0, 5.0));
        let c = CylinderData::new(0, &stretch, Vec3::ZERO, Vec3::Z, 1.0, false).unwrap();
        assert!((c.radius - 2.0).abs() < 1e-6 && (c.length - 5.0).abs() < 1e-6);
        let mirror = Affine3A::from_scale(Vec3::new(1.0, 1.0, -1.0));
        assert!(CylinderData::new(0, &mirror, Vec3::ZERO, Vec3::Z, 1.0, false).is_err());
    }
}
