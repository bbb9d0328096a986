//! Per-vertex attributes of mesh hits beyond the shading normal: texture coordinates.

use super::data::ShapeData;
use super::Geometry;
use glam::{Vec2, Vec3};
use mcrt::integrator::SurfacePoint;

impl Geometry {
    /// The texture coordinates at `hit`, as Mitsuba 3 defines them: on a mesh with
    /// per-vertex texture coordinates (`obj`, `ply`, `serialized` files that have them, and
    /// the `rectangle`, whose uv is `((x + 1)/2, (y + 1)/2)` in object space, and the `cube`,
    /// with Mitsuba's per-face coordinates) their interpolation by the hit's barycentrics,
    /// else [`SurfacePoint::uv`] (barycentrics of vertices 1 and 2 on other triangles, as Mitsuba
    /// gives meshes without texture coordinates; the sphere's (φ/2π, θ/π) and the disk's
    /// (r, φ/2π)).
    ///
    /// ```
    /// use mcrt::glam::{Mat4, Vec2, Vec3};
    /// use mcrt_render::description::{ShapeDesc, ShapeKind};
    /// use mcrt_render::geometry::{AccelKind, Geometry, Ray};
    /// let geo = Geometry::new(&[ShapeDesc::new(ShapeKind::Rectangle)], None, AccelKind::Bvh)
    ///     .unwrap();
    /// let ray = Ray { origin: Vec3::new(0.5, -0.5, 1.0), dir: -Vec3::Z };
    /// let hit = geo.intersect(&ray, f32::INFINITY).unwrap();
    /// assert!((geo.tex_coords(&hit) - Vec2::new(0.75, 0.25)).length() < 1e-6);
    /// ```
    pub fn tex_coords(&self, hit: &SurfacePoint) -> Vec2 {
        self.tex_coords_at(hit.shape, hit.prim, hit.uv)
    }

    /// [`Geometry::tex_coords`] of the hit on primitive `prim` of shape `shape` with surface
    /// coordinates `uv` ([`SurfacePoint::uv`]).
    #[inline]
    pub fn tex_coords_at(&self, shape: u32, prim: u32, uv: Vec2) -> Vec2 {
        match self.shapes.get(shape as usize) {
            Some(ShapeData::Mesh(m)) if !m.uvs.is_empty() => {
                let Some(t) = m.indices.get(prim as usize) else {
                    return uv;
                };
                let [a, b, c] = t.map(|v| m.uvs.get(v as usize).copied().unwrap_or(Vec2::ZERO));
                a * (1.0 - uv.x - uv.y) + b * uv.x + c * uv.y
            }
            _ => uv,
        }
    }

    /// The texture coordinates ([`Geometry::tex_coords`]) of the point `p` that
    /// [`Geometry::sample_shape`] or [`Geometry::sample_area`] returned for shape `shape`
    /// with `u_pick` (which chose the triangle of a mesh): for textured emission at sampled
    /// points. `Vec2::ZERO` for an index out of range.
    pub fn sample_tex_coords(&self, shape: u32, u_pick: f32, p: Vec3) -> Vec2 {
        match self.shapes.get(shape as usize) {
            Some(ShapeData::Mesh(m)) if m.rectangle.is_some() && m.positions.len() == 4 => {
                // Mitsuba's rectangle: uv = (s, t) of p = p₀ + s (p₁ − p₀) + t (p₃ − p₀).
                let [a, b, _, d] = [0, 1, 2, 3].map(|i| m.positions[i]);
                barycentric(p - a, b - a, d - a)
            }
            Some(ShapeData::Mesh(m)) => {
                let Some(k) = m.pick.as_ref().map(|t| t.sample_with_pmf(u_pick).0) else {
                    return Vec2::ZERO;
                };
                let [a, b, c] = m.indices[k].map(|v| m.positions[v as usize]);
                let w = barycentric(p - a, b - a, c - a);
                self.tex_coords_at(shape, k as u32, w)
            }
            Some(&ShapeData::Sphere { center, .. }) => {
                self.sphere_uv(shape, (p - center).normalize_or(Vec3::Z))
            }
            Some(ShapeData::Disk(d)) => {
                let local = d.to_object.transform_point3(p);
                super::disk_uv(Vec3::new(local.x, local.y, 0.0))
            }
            Some(ShapeData::Cylinder(c)) => c.surface_uv(p),
            // An instance emits nothing (emitters in shape groups are refused).
            Some(ShapeData::Instance) | None => Vec2::ZERO,
        }
    }
}

/// The coordinates `(s, t)` of `v = s e₁ + t e₂` (least squares, for `v` in the plane of the
/// edges); zero for degenerate edges.
fn barycentric(v: Vec3, e1: Vec3, e2: Vec3) -> Vec2 {
    let (d00, d01, d11) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
    let (d20, d21) = (v.dot(e1), v.dot(e2));
    let det = d00 * d11 - d01 * d01;
    let st = Vec2::new(d11 * d20 - d01 * d21, d00 * d21 - d01 * d20) / det;
    if st.is_finite() {
        st
    } else {
        Vec2::ZERO
    }
}

#[cfg(test)]
mod tests {
    use crate::description::{ShapeDesc, ShapeKind};
    use crate::geometry::{AccelKind, Geometry, Ray};
    use glam::{Vec2, Vec3};
    use std::f32::consts::FRAC_1_SQRT_2;

    /// A shape, a ray's origin and direction, and the texture coordinates of its hit.
    type Case = (ShapeKind, [f32; 3], [f32; 3], [f32; 2]);

    /// Texture coordinates Mitsuba 3.9.1 reports for these rays (`si.uv` of
    /// `scene.ray_intersect`; the probe script is in tests/data/REFERENCES.md, "Textures").
    #[test]
    fn tex_coords_match_mitsuba() {
        let cases: &[Case] = &[
            (
                ShapeKind::Rectangle,
                [0.5, 0.5, 1.0],
                [0.0, 0.0, -1.0],
                [0.75, 0.75],
            ),
            (
                ShapeKind::Rectangle,
                [-0.5, 0.5, 1.0],
                [0.0, 0.0, -1.0],
                [0.25, 0.75],
            ),
            (
                ShapeKind::Rectangle,
                [-0.9, -0.9, 1.0],
                [0.0, 0.0, -1.0],
                [0.05, 0.05],
            ),
            (
                ShapeKind::Disk,
                [0.5, 0.5, 1.0],
                [0.0, 0.0, -1.0],
                [FRAC_1_SQRT_2, 0.125],
            ),
            (
                ShapeKind::Disk,
                [0.5, -0.5, 1.0],
                [0.0, 0.0, -1.0],
                [FRAC_1_SQRT_2, 0.875],
            ),
            (
                ShapeKind::Cube,
                [0.5, 0.2, 5.0],
                [0.0, 0.0, -1.0],
                [0.6, 0.75],
            ),
            (
                ShapeKind::Cube,
                [0.5, 0.2, -5.0],
                [0.0, 0.0, 1.0],
                [0.4, 0.75],
            ),
            (
                ShapeKind::Cube,
                [5.0, 0.5, 0.2],
                [-1.0, 0.0, 0.0],
                [0.75, 0.4],
            ),
            (
                ShapeKind::Cube,
                [-5.0, 0.5, 0.2],
                [1.0, 0.0, 0.0],
                [0.75, 0.6],
            ),
            (
                ShapeKind::Cube,
                [0.5, 5.0, 0.2],
                [0.0, -1.0, 0.0],
                [0.25, 0.4],
            ),
            (
                ShapeKind::Cube,
                [0.5, -5.0, 0.2],
                [0.0, 1.0, 0.0],
                [0.6, 0.75],
            ),
        ];
        let sphere = ShapeKind::Sphere {
            center: Vec3::ZERO,
            radius: 1.0,
        };
        let spheres: &[([f32; 3], [f32; 3], [f32; 2])] = &[
            ([0.0, 5.0, 0.0], [0.0, -1.0, 0.0], [0.25, 0.5]),
            ([-5.0, 0.0, 0.3], [1.0, 0.0, 0.0], [0.5, 0.403_013]),
            ([0.0, -5.0, 0.3], [0.0, 1.0, 0.0], [0.75, 0.403_013]),
            ([0.6, 0.3, -5.0], [0.0, 0.0, 1.0], [0.073_791_8, 0.765_942]),
        ];
        let all = cases
            .iter()
            .cloned()
            .chain(spheres.iter().map(|&(o, d, uv)| (sphere.clone(), o, d, uv)));
        for accel in [AccelKind::Bvh, AccelKind::Grid] {
            for (kind, o, d, want) in all.clone() {
                let geo = Geometry::new(&[ShapeDesc::new(kind.clone())], None, accel).unwrap();
                let ray = Ray {
                    origin: Vec3::from(o),
                    dir: Vec3::from(d),
                };
                let hit = geo.intersect(&ray, f32::INFINITY).unwrap();
                let uv = geo.tex_coords(&hit);
                let err = (uv - Vec2::from(want)).abs().max_element();
                assert!(
                    err.is_finite() && err < 1e-5,
                    "{kind:?} {o:?}: {uv} vs {want:?}"
                );
            }
        }
    }

    /// A sphere's uv is that of its object-space normal: Mitsuba 3.9.1 for a unit sphere
    /// under translate (1, 2, 3) · rotate(x, −90°) · scale 0.5.
    #[test]
    fn rotated_sphere_tex_coords_match_mitsuba() {
        let mut s = ShapeDesc::new(ShapeKind::Sphere {
            center: Vec3::ZERO,
            radius: 1.0,
        });
        s.to_world = glam::Mat4::from_translation(Vec3::new(1.0, 2.0, 3.0))
            * glam::Mat4::from_rotation_x(-std::f32::consts::FRAC_PI_2)
            * glam::Mat4::from_scale(Vec3::splat(0.5));
        let geo = Geometry::new(&[s], None, AccelKind::Bvh).unwrap();
        let cases = [
            ([-5.0, 2.0, 3.1], [1.0, 0.0, 0.0], [0.532_047, 0.5]),
            ([1.0, 2.0, 10.0], [0.0, 0.0, -1.0], [0.75, 0.5]),
            ([1.2, -5.0, 3.1], [0.0, 1.0, 0.0], [0.926_208, 0.852_416]),
        ];
        for (o, d, want) in cases {
            let ray = Ray {
                origin: Vec3::from(o),
                dir: Vec3::from(d),
            };
            let hit = geo.intersect(&ray, f32::INFINITY).unwrap();
            let uv = geo.tex_coords(&hit);
            let err = (uv - Vec2::from(want)).abs().max_element();
            assert!(err.is_finite() && err < 1e-5, "{o:?}: {uv} vs {want:?}");
        }
    }
}
