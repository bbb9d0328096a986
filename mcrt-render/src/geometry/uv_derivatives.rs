//! The derivatives of a hit's position by its texture coordinates, `dp/du` and `dp/dv`, as
//! Mitsuba 3 defines them (what `bumpmap` tilts): their directions give the shading
//! tangent, their lengths how far a unit of `u` or `v` reaches on the surface.

use super::data::ShapeData;
use super::Geometry;
use glam::Vec3;
use mcrt::integrator::SurfacePoint;
use std::f32::consts::{PI, TAU};

impl Geometry {
    /// `(dp/du, dp/dv)` at `hit` in world space, as Mitsuba 3.9.1's `si.dp_du`, `si.dp_dv`:
    /// on a mesh with texture coordinates the solution of `p₁ − p₀ = dp/du Δu₁ + dp/dv Δv₁`,
    /// `p₂ − p₀ = dp/du Δu₂ + dp/dv Δv₂` (the rectangle's `to_world` of (2, 0, 0) and
    /// (0, 2, 0)); on a mesh without them, or where they are degenerate, the edges
    /// `(p₁ − p₀, p₂ − p₀)` (Mitsuba's barycentric parameterisation); on a sphere of radius
    /// `r`, `2π r (−y, x, 0)` and `π r (z cos φ, z sin φ, −sin θ)` in its object frame
    /// (`(x, y, z)` the unit normal there); on a disk, `(cos φ, sin φ, 0)` and
    /// `2π ρ (−sin φ, cos φ, 0)` through its `to_world`; on a cylinder, `2π (−y, x, 0)`
    /// (its radius in `(x, y)`) and its axis times its length. For a hit on a shape group's
    /// shape (through an instance), the group shape's derivatives in the group's space
    /// carried to world space by the instance's `to_world` linear part (Mitsuba 3's
    /// `instance.cpp`).
    pub fn uv_derivatives(&self, hit: &SurfacePoint) -> (Vec3, Vec3) {
        if hit.shape < self.own_shapes {
            return self.shape_uv_derivatives(hit);
        }
        self.through_instance(hit, |local| self.shape_uv_derivatives(local))
            .map_or((Vec3::ZERO, Vec3::ZERO), |(m, (du, dv))| (m * du, m * dv))
    }

    /// `(dp/du, dp/dv)` at `hit` in the space of its shape's data (world space for the
    /// scene's own shapes, the group's space for a group's shape).
    fn shape_uv_derivatives(&self, hit: &SurfacePoint) -> (Vec3, Vec3) {
        match self.shapes.get(hit.shape as usize) {
            Some(ShapeData::Mesh(m)) => {
                let Some(idx) = m.indices.get(hit.prim as usize) else {
                    return (Vec3::ZERO, Vec3::ZERO);
                };
                let p = idx.map(|v| m.positions.get(v as usize).copied().unwrap_or(Vec3::ZERO));
                let (e1, e2) = (p[1] - p[0], p[2] - p[0]);
                let uv = idx.map(|v| m.uvs.get(v as usize).copied());
                let [Some(a), Some(b), Some(c)] = uv else {
                    return (e1, e2);
                };
                let (d1, d2) = (b - a, c - a);
                let det = d1.x * d2.y - d1.y * d2.x;
                let du = (d2.y * e1 - d1.y * e2) / det;
                let dv = (d1.x * e2 - d2.x * e1) / det;
                if det != 0.0 && du.is_finite() && dv.is_finite() {
                    (du, dv)
                } else {
                    (e1, e2)
                }
            }
            Some(&ShapeData::Sphere { center, radius, .. }) => {
                // The object frame's rotation (the uv frame is the inverse of `to_world`'s
                // linear part, a uniform scale times a rotation).
                let to_object = self
                    .uv_frames
                    .get(hit.shape as usize)
                    .copied()
                    .unwrap_or(glam::Mat3::IDENTITY);
                let scale = to_object.x_axis.length();
                let to_world = (to_object * (1.0 / scale)).transpose();
                let l = (to_object * (hit.p - center)).normalize_or(Vec3::Z);
                let rd = l.x.hypot(l.y);
                let du = Vec3::new(-l.y, l.x, 0.0) * (TAU * radius);
                let dv = if rd > 0.0 {
                    Vec3::new(l.z * l.x / rd, l.z * l.y / rd, -rd)
                } else {
                    Vec3::X
                } * (PI * radius);
                (to_world * du, to_world * dv)
            }
            Some(ShapeData::Disk(d)) => {
                let local = d.to_object.transform_point3(hit.p);
                let r = local.x.hypot(local.y);
                let (c, s) = if r > 0.0 {
                    (local.x / r, local.y / r)
                } else {
                    (1.0, 0.0)
                };
                (
                    d.to_world.transform_vector3(Vec3::new(c, s, 0.0)),
                    d.to_world.transform_vector3(Vec3::new(-s, c, 0.0)) * (TAU * r),
                )
            }
            Some(ShapeData::Cylinder(c)) => {
                let local = c.to_object.transform_point3(hit.p);
                (
                    c.to_world
                        .transform_vector3(Vec3::new(-local.y, local.x, 0.0) * TAU),
                    c.to_world.transform_vector3(Vec3::Z * c.length),
                )
            }
            Some(ShapeData::Instance) | None => (Vec3::ZERO, Vec3::ZERO),
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::description::{ShapeDesc, ShapeKind};
    use crate::geometry::{AccelKind, Geometry, Ray};
    use glam::{Mat4, Vec3};

    /// Mitsuba 3.9.1's `si.dp_du`, `si.dp_dv` of `scene.ray_intersect` (`scalar_rgb`) for a
    /// ray along −z from these origins (the script in tests/data/REFERENCES.md, "Normal and
    /// bump maps").
    #[test]
    fn derivatives_match_mitsuba() {
        let t = |m: Mat4| m;
        let cases = [
            (
                ShapeDesc {
                    to_world: t(Mat4::from_rotation_z(30f32.to_radians())
                        * Mat4::from_scale(Vec3::new(2.0, 0.5, 1.0))),
                    ..ShapeDesc::new(ShapeKind::Rectangle)
                },
                Vec3::new(0.3, 0.2, 1.0),
                Vec3::new(3.4641, 2.0, 0.0),
                Vec3::new(-0.5, 0.866_025, 0.0),
            ),
            (
                ShapeDesc {
                    to_world: Mat4::from_rotation_x(20f32.to_radians()),
                    ..ShapeDesc::new(ShapeKind::Sphere {
                        center: Vec3::new(0.0, 0.0, -5.0),
                        radius: 2.0,
                    })
                },
                Vec3::new(0.3, 0.2, -1.0),
                Vec3::new(6.17274, 1.77128, 0.644_693),
                Vec3::new(1.57451, -3.74143, -4.79594),
            ),
            (
                ShapeDesc {
                    to_world: Mat4::from_translation(Vec3::new(0.0, 0.0, -1.0))
                        * Mat4::from_rotation_z(30f32.to_radians())
                        * Mat4::from_scale(Vec3::splat(1.5)),
                    ..ShapeDesc::new(ShapeKind::Disk)
                },
                Vec3::new(0.3, 0.2, 1.0),
                Vec3::new(1.24808, 0.83205, 0.0),
                Vec3::new(-1.25664, 1.88496, 0.0),
            ),
            (
                ShapeDesc::new(ShapeKind::Cylinder {
                    p0: Vec3::new(0.0, -2.0, 0.0),
                    p1: Vec3::new(0.0, 2.0, 0.0),
                    radius: 1.5,
                }),
                Vec3::new(0.3, 0.2, 5.0),
                Vec3::new(9.23436, 0.0, -1.88496),
                Vec3::new(0.0, 4.0, 0.0),
            ),
        ];
        for (shape, origin, want_du, want_dv) in cases {
            let kind = format!("{:?}", shape.kind);
            let geo = Geometry::new(&[shape], None, AccelKind::Bvh).expect("a geometry");
            let ray = Ray {
                origin,
                dir: -Vec3::Z,
            };
            let hit = geo.intersect(&ray, f32::INFINITY).expect("a hit");
            let (du, dv) = geo.uv_derivatives(&hit);
            for (got, want) in [(du, want_du), (dv, want_dv)] {
                assert!(
                    got.is_finite() && (got - want).length() < 2e-4 * want.length(),
                    "{kind}: {got} vs {want}"
                );
            }
        }
    }

    /// A shape inside a shape group, instanced by a rotation, a scale and a translation,
    /// has the frame, `dp/du` and `dp/dv` of the same shape written without instancing
    /// (its `to_world` the instance's times its own), as in Mitsuba 3, where the instance
    /// carries the group shape's derivatives by its `to_world` and builds the frame from
    /// them. Each shape kind, rays from several origins.
    #[test]
    fn instanced_frame_equals_plain_frame() {
        use crate::description::{Checked, ShapeGroupDesc};
        use std::sync::Arc;
        let own =
            Mat4::from_rotation_z(25f32.to_radians()) * Mat4::from_scale(Vec3::new(1.0, 0.6, 1.0));
        let kinds = [
            ShapeKind::Rectangle,
            ShapeKind::Disk,
            ShapeKind::Sphere {
                center: Vec3::new(0.1, -0.2, 0.3),
                radius: 0.8,
            },
            ShapeKind::Cylinder {
                p0: Vec3::new(-0.2, 0.0, -1.0),
                p1: Vec3::new(0.3, 0.1, 1.0),
                radius: 0.7,
            },
        ];
        let instance = Mat4::from_translation(Vec3::new(0.2, -0.1, -4.0))
            * Mat4::from_axis_angle(Vec3::new(1.0, 2.0, 0.5).normalize(), 0.7)
            * Mat4::from_scale(Vec3::splat(1.3));
        for kind in kinds {
            // The sphere and the cylinder keep a uniform cross-section (as Mitsuba's).
            let own = if matches!(kind, ShapeKind::Sphere { .. } | ShapeKind::Cylinder { .. }) {
                Mat4::from_rotation_z(25f32.to_radians())
            } else {
                own
            };
            let inner = ShapeDesc {
                to_world: own,
                ..ShapeDesc::new(kind.clone())
            };
            let group = Arc::new(
                Checked::new(ShapeGroupDesc {
                    id: Some("g".into()),
                    shapes: vec![Checked::new(inner).expect("a valid shape")],
                })
                .expect("a valid group"),
            );
            let instanced = ShapeDesc {
                to_world: instance,
                ..ShapeDesc::new(ShapeKind::Instance(group))
            };
            let plain = ShapeDesc {
                to_world: instance * own,
                ..ShapeDesc::new(kind.clone())
            };
            let a = Geometry::new(&[instanced], None, AccelKind::Bvh).expect("instanced");
            let b = Geometry::new(&[plain], None, AccelKind::Bvh).expect("plain");
            let mut hits = 0;
            for (x, y) in [(0.0, 0.0), (0.3, 0.2), (-0.4, 0.5), (0.6, -0.3)] {
                let ray = Ray {
                    origin: Vec3::new(x, y, 0.0),
                    dir: -Vec3::Z,
                };
                let (Some(ha), Some(hb)) = (
                    a.intersect(&ray, f32::INFINITY),
                    b.intersect(&ray, f32::INFINITY),
                ) else {
                    continue;
                };
                hits += 1;
                assert!(ha.shape >= 1 && hb.shape == 0, "{kind:?}");
                let frame = |g: &Geometry, h: &mcrt::integrator::SurfacePoint| {
                    let turn = g.tangent_turn(h);
                    [turn.x * h.frame.s + turn.y * h.frame.t, h.frame.n, h.ng]
                };
                let (du_a, dv_a) = a.uv_derivatives(&ha);
                let (du_b, dv_b) = b.uv_derivatives(&hb);
                let pairs = [
                    (ha.p, hb.p),
                    // Only its direction is defined (`Geometry::tangent`).
                    (
                        a.tangent(&ha).normalize_or_zero(),
                        b.tangent(&hb).normalize_or_zero(),
                    ),
                    (du_a, du_b),
                    (dv_a, dv_b),
                ]
                .into_iter()
                .chain(frame(&a, &ha).into_iter().zip(frame(&b, &hb)));
                for (got, want) in pairs {
                    assert!(
                        got.is_finite()
                            && want.length() > 0.0
                            && (got - want).length() <= 2e-5 * want.length().max(1.0),
                        "{kind:?} at ({x}, {y}): {got} vs {want}"
                    );
                }
            }
            assert!(hits >= 2, "{kind:?}: only {hits} hits");
        }
    }
}
