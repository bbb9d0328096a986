//! The shading tangent of a hit: Mitsuba 3's `dp/du`, and the turn about the shading normal
//! from the frame built from the normal alone (`Frame::from_normal`, which every isotropic
//! material keeps) to Mitsuba's shading frame (`s` = `dp/du` made orthogonal to the normal).

use super::data::ShapeData;
use super::Geometry;
use glam::{Vec2, Vec3};
use mcrt::integrator::SurfacePoint;
use std::f32::consts::TAU;

impl Geometry {
    /// `dp/du` at `hit` (world space, not normalised), as Mitsuba 3 defines it: on a mesh
    /// with texture coordinates, the derivative of position by the texture's u (the
    /// rectangle's object-space x, the cube's per-face axes); on a mesh without them, the
    /// edge from vertex 0 to vertex 1 (Mitsuba's barycentric parameterisation); on a sphere,
    /// the direction of growing φ about its object-space z axis; on a disk, the radial
    /// direction. Zero where it is undefined (a degenerate triangle).
    ///
    /// A hit on a shape group's shape (through an instance) gets the group shape's `dp/du`
    /// in the group's space carried to world space by the instance's `to_world` linear part,
    /// as Mitsuba 3's `instance.cpp` does.
    pub fn tangent(&self, hit: &SurfacePoint) -> Vec3 {
        if hit.shape < self.own_shapes {
            return self.shape_tangent(hit);
        }
        self.through_instance(hit, |local| self.shape_tangent(local))
            .map_or(Vec3::ZERO, |(m, t)| m * t)
    }

    /// `dp/du` at `hit` in the space of its shape's data (world space for the scene's own
    /// shapes, the group's space for a group's shape).
    fn shape_tangent(&self, hit: &SurfacePoint) -> Vec3 {
        match self.shapes.get(hit.shape as usize) {
            Some(ShapeData::Mesh(m)) => {
                let Some(idx) = m.indices.get(hit.prim as usize) else {
                    return Vec3::ZERO;
                };
                let [p0, p1, p2] = idx.map(|v| m.positions.get(v as usize).copied());
                let (Some(p0), Some(p1), Some(p2)) = (p0, p1, p2) else {
                    return Vec3::ZERO;
                };
                let uv = idx.map(|v| m.uvs.get(v as usize).copied());
                match uv {
                    [Some(a), Some(b), Some(c)] => {
                        triangle_dp_du(p1 - p0, p2 - p0, b - a, c - a).unwrap_or(p1 - p0)
                    }
                    _ => p1 - p0,
                }
            }
            Some(ShapeData::Sphere { .. }) => {
                // φ = 2π u about the object's z axis: dp/du ∝ (−sin φ, cos φ, 0) there.
                let (s, c) = (TAU * hit.uv.x).sin_cos();
                let to_world = self
                    .uv_frames
                    .get(hit.shape as usize)
                    .map_or(glam::Mat3::IDENTITY, |f| f.inverse());
                to_world * Vec3::new(-s, c, 0.0)
            }
            Some(ShapeData::Disk(d)) => {
                let (s, c) = (TAU * hit.uv.y).sin_cos();
                d.to_world.transform_vector3(Vec3::new(c, s, 0.0))
            }
            Some(ShapeData::Cylinder(c)) => {
                // φ = 2π u about the tube's axis: dp/du ∝ (−sin φ, cos φ, 0) in its frame.
                let (s, co) = (TAU * hit.uv.x).sin_cos();
                c.to_world.transform_vector3(Vec3::new(-s, co, 0.0))
            }
            Some(ShapeData::Instance) | None => Vec3::ZERO,
        }
    }

    /// (cos γ, sin γ) of the turn γ about the shading normal from `hit.frame`'s `s` axis to
    /// Mitsuba's shading tangent (the projection of [`Geometry::tangent`]): the local
    /// direction (x, y, z) of `hit.frame` is (x cos γ + y sin γ, −x sin γ + y cos γ, z) in
    /// Mitsuba's frame. (1, 0) where the tangent is undefined or along the normal.
    pub fn tangent_turn(&self, hit: &SurfacePoint) -> Vec2 {
        let dp_du = self.tangent(hit);
        Vec2::new(dp_du.dot(hit.frame.s), dp_du.dot(hit.frame.t))
            .try_normalize()
            .unwrap_or(Vec2::X)
    }
}

/// dp/du of a triangle with edges `e1`, `e2` from vertex 0 and texture-coordinate edges
/// `d1`, `d2`; `None` when the texture coordinates are degenerate.
fn triangle_dp_du(e1: Vec3, e2: Vec3, d1: Vec2, d2: Vec2) -> Option<Vec3> {
    let det = d1.x * d2.y - d1.y * d2.x;
    let dp_du = (d2.y * e1 - d1.y * e2) / det;
    (det != 0.0 && dp_du.is_finite()).then_some(dp_du)
}

#[cfg(test)]
mod tests {
    use crate::description::{ShapeDesc, ShapeKind};
    use crate::geometry::{AccelKind, Geometry, Ray};
    use glam::{Mat4, Vec3};

    /// Mitsuba 3.9.1's `si.sh_frame.s` for these rays (`scene.ray_intersect`).
    #[test]
    fn shading_tangent_matches_mitsuba() {
        let rot = Mat4::from_rotation_z(30f32.to_radians());
        let cases = [
            (
                ShapeDesc {
                    to_world: rot,
                    ..ShapeDesc::new(ShapeKind::Rectangle)
                },
                Vec3::new(0.3, 0.2, 1.0),
                Vec3::new(0.866_025, 0.5, 0.0),
            ),
            (
                ShapeDesc::new(ShapeKind::Sphere {
                    center: Vec3::new(0.0, 0.0, -5.0),
                    radius: 1.0,
                }),
                Vec3::new(0.3, 0.2, -3.0),
                Vec3::new(-0.5547, 0.83205, 0.0),
            ),
        ];
        for (shape, origin, want) in cases {
            let geo = Geometry::new(&[shape], None, AccelKind::Bvh).expect("a geometry");
            let hit = geo
                .intersect(
                    &Ray {
                        origin,
                        dir: -Vec3::Z,
                    },
                    f32::INFINITY,
                )
                .expect("a hit");
            let turn = geo.tangent_turn(&hit);
            let s = turn.x * hit.frame.s + turn.y * hit.frame.t;
            assert!(
                s.is_finite() && (s - want).length() < 1e-4,
                "{origin}: {s} vs {want}"
            );
        }
    }
}
