//! What the light BVH needs of an emitting shape: the [`LightBounds`] of each emitting
//! triangle of a mesh (every triangle a light of its own) or of a whole shape, and sampling
//! one triangle alone.

use super::mesh;
use crate::accel::Aabb;
use crate::geometry::data::ShapeData;
use crate::geometry::{Geometry, ShapeSample};
use glam::{Vec2, Vec3};
use mcrt::sampling::light_bvh::LightBounds;
use std::f32::consts::PI;

/// A light's bounds with normals in every direction (a sphere, a cylinder, a textured mesh
/// kept whole): pbrt-v4's bounds of a non-planar shape.
fn any_direction(b: Aabb, power: f32) -> LightBounds {
    LightBounds {
        min: b.min,
        max: b.max,
        axis: Vec3::Z,
        cos_theta_o: -1.0,
        cos_theta_e: 0.0,
        two_sided: false,
        power,
    }
}

impl Geometry {
    /// The bounds of each triangle of shape `shape` as a diffuse emitter of mean radiance
    /// `radiance` (power `π·area·radiance`, the front normal), if the shape is a triangle
    /// mesh sampled triangle by triangle (not a `rectangle`, which is sampled whole).
    pub(crate) fn triangle_light_bounds(
        &self,
        shape: u32,
        radiance: f32,
    ) -> Option<Vec<LightBounds>> {
        let ShapeData::Mesh(m) = self.own_shape(shape)? else {
            return None;
        };
        if m.rectangle.is_some() {
            return None;
        }
        let bounds = mesh::triangles(m)
            .map(|([a, b, c], n)| {
                let area = 0.5 * (b - a).cross(c - a).length();
                let power = PI * area * radiance;
                let finite = n != Vec3::ZERO && power.is_finite();
                LightBounds::planar(
                    a.min(b).min(c),
                    a.max(b).max(c),
                    if finite { n } else { Vec3::Z },
                    false,
                    if finite { power } else { 0.0 },
                )
            })
            .collect();
        Some(bounds)
    }

    /// The bounds of shape `shape` as one emitter of power `power`: planar for a rectangle
    /// and a disk, every direction otherwise; `None` for an index out of range or a shape
    /// without points.
    pub(crate) fn shape_light_bounds(&self, shape: u32, power: f32) -> Option<LightBounds> {
        let (center, radius) = self.shape_bounding_sphere(shape)?;
        let sphere_box = Aabb {
            min: center - Vec3::splat(radius),
            max: center + Vec3::splat(radius),
        };
        match self.own_shape(shape)? {
            ShapeData::Mesh(m) => match &m.rectangle {
                Some(r) => {
                    let corners = [Vec2::ZERO, Vec2::X, Vec2::Y, Vec2::ONE].map(|u| r.point(u));
                    let b = Aabb::from_points(&corners);
                    Some(LightBounds::planar(b.min, b.max, r.normal(), false, power))
                }
                None => Some(any_direction(Aabb::from_points(&m.positions), power)),
            },
            ShapeData::Disk(d) => Some(LightBounds::planar(
                sphere_box.min,
                sphere_box.max,
                d.normal,
                false,
                power,
            )),
            _ => Some(any_direction(sphere_box, power)),
        }
    }

    /// The number of triangles of shape `shape` if it is a triangle mesh sampled triangle by
    /// triangle (not a `rectangle`).
    pub(crate) fn triangle_count(&self, shape: u32) -> Option<usize> {
        match self.own_shape(shape)? {
            ShapeData::Mesh(m) if m.rectangle.is_none() => Some(m.indices.len()),
            _ => None,
        }
    }

    /// A point on triangle `k` of mesh `shape` alone, density per steradian at `reference`
    /// among that triangle's points (by solid angle or area as the geometry's
    /// [`ShapeSampling`](super::ShapeSampling) says); `None` for anything but a triangle of a
    /// mesh sampled by triangles, or an infinite density.
    pub(crate) fn sample_triangle(
        &self,
        shape: u32,
        k: u32,
        reference: Vec3,
        u: Vec2,
    ) -> Option<ShapeSample> {
        match self.own_shape(shape)? {
            ShapeData::Mesh(m) => {
                mesh::sample_triangle(m, self.shape_sampling, reference, k as usize, u)
            }
            _ => None,
        }
    }

    /// The density of [`Geometry::sample_triangle`] at the point `at` (position, front
    /// normal, triangle) of mesh `shape`; 0 if it never gives it.
    pub(crate) fn triangle_pdf_at(
        &self,
        shape: u32,
        reference: Vec3,
        at: (Vec3, Vec3, u32),
    ) -> f32 {
        let pdf = match self.own_shape(shape) {
            Some(ShapeData::Mesh(m)) => mesh::pdf_triangle(m, self.shape_sampling, reference, at),
            _ => None,
        };
        pdf.unwrap_or(0.0)
    }
}
