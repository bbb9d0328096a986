//! An orthonormal frame: converts directions between world space and a z-up local frame,
//! the one in which the warps sample directions and BSDFs are written.

use glam::Vec3;

/// An orthonormal basis `(s, t, n)`; local coordinates are `(x, y, z) = (·s, ·t, ·n)`.
///
/// The warps of [`crate::sampling::warp`] sample about `+z`; [`Frame::to_world`] turns such a
/// sample into a direction about any unit axis `n` (a cone toward a light, a lobe about a
/// normal), and the shading frame of a surface point ([`crate::integrator::SurfacePoint::frame`]).
///
/// ```
/// use mcrt::glam::{Vec2, Vec3};
/// use mcrt::sampling::warp::{UniformCone, Warp};
/// use mcrt::sampling::Frame;
///
/// let f = Frame::from_normal(Vec3::new(0.0, 1.0, 0.0));
/// let w = Vec3::new(0.3, 0.8, -0.2).normalize();
/// assert!((f.to_world(f.to_local(w)) - w).length() < 1e-6);
/// assert!((f.to_local(w).z - w.y).abs() < 1e-6);
///
/// // A cone of half-angle 0.1 rad about +y instead of +z.
/// let cone = UniformCone::from_angle(0.1).unwrap();
/// let d = f.to_world(cone.sample(Vec2::new(0.3, 0.7)));
/// assert!(d.y >= 0.1f32.cos() - 1e-6);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    /// First tangent.
    pub s: Vec3,
    /// Second tangent.
    pub t: Vec3,
    /// The normal (local +z).
    pub n: Vec3,
}

impl Frame {
    /// A frame around the unit normal `n`, without branches on the pole.
    ///
    /// Duff, Burgess, Christensen, Hery, Kensler, Liani, Villemin 2017, "Building an
    /// Orthonormal Basis, Revisited", JCGT 6(1).
    #[inline]
    pub fn from_normal(n: Vec3) -> Self {
        let sign = 1.0f32.copysign(n.z);
        let a = -1.0 / (sign + n.z);
        let b = n.x * n.y * a;
        let s = Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
        let t = Vec3::new(b, sign + n.y * n.y * a, -n.y);
        Self { s, t, n }
    }

    /// World direction to local coordinates.
    #[inline]
    pub fn to_local(&self, w: Vec3) -> Vec3 {
        Vec3::new(w.dot(self.s), w.dot(self.t), w.dot(self.n))
    }

    /// Local coordinates to a world direction.
    #[inline]
    pub fn to_world(&self, v: Vec3) -> Vec3 {
        self.s * v.x + self.t * v.y + self.n * v.z
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orthonormal_for_many_normals() {
        let normals = [
            Vec3::Z,
            -Vec3::Z,
            Vec3::X,
            Vec3::new(0.0, -1.0, 1e-7).normalize(),
            Vec3::new(0.3, -0.4, -0.866).normalize(),
        ];
        for n in normals {
            let f = Frame::from_normal(n);
            for (a, b) in [(f.s, f.t), (f.t, f.n), (f.s, f.n)] {
                let d = a.dot(b);
                assert!(d.is_finite() && d.abs() < 1e-5, "{n:?}");
            }
            for v in [f.s, f.t, f.n] {
                let l = v.length();
                assert!(l.is_finite() && (l - 1.0).abs() < 1e-5);
            }
            assert!((f.s.cross(f.t) - f.n).length() < 1e-5, "right-handed");
        }
    }
}
