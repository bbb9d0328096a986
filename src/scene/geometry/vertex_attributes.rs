//! Per-vertex attributes of mesh hits beyond the shading normal: texture coordinates.

use super::build::ShapeData;
use super::Geometry;
use crate::integrator::SurfacePoint;
use glam::Vec2;

impl Geometry {
    /// The texture coordinates at `hit`, as Mitsuba 3 defines them: on a mesh with
    /// per-vertex texture coordinates (`obj`, `ply`, `serialized` files that have them)
    /// their interpolation by the hit's barycentrics, else [`SurfacePoint::uv`] (barycentrics of
    /// vertices 1 and 2 on other triangles, the sphere's and disk's own parameters).
    ///
    /// ```
    /// use mcrt::glam::{Mat4, Vec2, Vec3};
    /// use mcrt::scene::description::{ShapeDesc, ShapeKind};
    /// use mcrt::scene::geometry::{AccelKind, Geometry, Ray};
    /// let geo = Geometry::new(&[ShapeDesc::new(ShapeKind::Rectangle)], None, AccelKind::Bvh)
    ///     .unwrap();
    /// let ray = Ray { origin: Vec3::new(0.5, 0.5, 1.0), dir: -Vec3::Z };
    /// let hit = geo.intersect(&ray, f32::INFINITY).unwrap();
    /// assert_eq!(geo.tex_coords(&hit), hit.uv);
    /// ```
    pub fn tex_coords(&self, hit: &SurfacePoint) -> Vec2 {
        match self.shapes.get(hit.shape as usize) {
            Some(ShapeData::Mesh(m)) if !m.uvs.is_empty() => {
                let Some(t) = m.indices.get(hit.prim as usize) else {
                    return hit.uv;
                };
                let [a, b, c] = t.map(|v| m.uvs[v as usize]);
                a * (1.0 - hit.uv.x - hit.uv.y) + b * hit.uv.x + c * hit.uv.y
            }
            _ => hit.uv,
        }
    }
}
