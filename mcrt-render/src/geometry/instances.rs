//! Instances of shape groups (Mitsuba 3's `shapegroup` and `instance`): the second level of
//! a two-level acceleration structure.
//!
//! Each distinct group is built once, in its own space, as a [`Level`] with its own
//! acceleration structure. An instance holds its group's index, its `to_world`, the
//! inverse and the inverse transpose (for normals), never a copy of the group's
//! primitives, so memory grows by a few hundred bytes per instance. A top-level structure
//! of the same [`AccelKind`] holds the instances' world-space boxes (the group's box
//! transformed). A ray that reaches an instance is carried into the group's space
//! (`o' = M⁻¹o`, `d' = M⁻¹d`, not renormalised, so `t` is the same along both) and
//! traversed there; the hit is carried back: the point by `M`, normals by `M⁻ᵀ` and
//! renormalised, as Mitsuba 3's `instance.cpp` does, so shading stays right under
//! non-uniform scale. Texture coordinates and the primitive are the group's.

use super::data::ShapeData;
use super::error::GeometryError;
use super::level::Level;
use super::query::HitRecord;
use super::Ray;
use crate::accel::{vec_bytes, Aabb, Accel, AccelKind};
use crate::description::{Checked, ShapeDesc, ShapeGroupDesc, ShapeKind};
use glam::{Affine3A, Mat3A, Vec3};
use mcrt::integrator::SurfacePoint;
use mcrt::sampling::Frame;
use std::collections::HashMap;
use std::sync::Arc;

/// One instance: its group and transforms.
#[derive(Debug, Clone)]
struct Instance {
    group: u32,
    to_world: Affine3A,
    to_object: Affine3A,
    /// `M⁻ᵀ` of `to_world`'s linear part.
    normal: Mat3A,
}

impl Instance {
    /// The ray in the group's space (same `t` along it).
    #[inline(always)]
    fn ray_to_object(&self, ray: &Ray) -> Ray {
        Ray {
            origin: self.to_object.transform_point3(ray.origin),
            dir: self.to_object.transform_vector3(ray.dir),
        }
    }
}

/// The groups, the instances, and the structure over the instances' world boxes.
#[derive(Debug, Clone)]
pub(super) struct Instancing {
    groups: Vec<Level>,
    /// Instances of non-empty groups, in the order the top-level structure numbers them.
    list: Vec<Instance>,
    accel: Accel,
    /// The union of the instances' world boxes.
    pub(super) bounds: Aabb,
}

impl Instancing {
    /// Builds the instances among `shapes` (the scene's own shapes) over `groups`, already
    /// built in the order `order` (that of
    /// `description::groups_of`).
    pub(super) fn build(
        accel: AccelKind,
        shapes: &[&ShapeDesc],
        order: &[&Arc<Checked<ShapeGroupDesc>>],
        groups: Vec<Level>,
    ) -> Result<Self, GeometryError> {
        let index: HashMap<*const Checked<ShapeGroupDesc>, u32> = order
            .iter()
            .enumerate()
            .map(|(k, g)| (Arc::as_ptr(g), k as u32))
            .collect();
        let count = shapes
            .iter()
            .filter(|s| matches!(s.kind, ShapeKind::Instance(_)))
            .count();
        let mut list = Vec::with_capacity(count);
        let mut boxes = Vec::with_capacity(count);
        for (i, &s) in shapes.iter().enumerate() {
            let ShapeKind::Instance(g) = &s.kind else {
                continue;
            };
            let group = index[&Arc::as_ptr(g)];
            let b = groups[group as usize].bounds;
            if b.is_empty() {
                continue; // nothing to hit
            }
            let to_world = super::build::affine(i, s)?;
            let normal = to_world.matrix3.inverse().transpose();
            if !normal.is_finite() {
                return Err(GeometryError::BadTransform {
                    shape: i,
                    what: "its inverse is not finite",
                });
            }
            let corners: Vec<Vec3> = (0..8)
                .map(|c| {
                    let pick =
                        |bit: u32, lo: f32, hi: f32| if (c >> bit) & 1 == 1 { hi } else { lo };
                    to_world.transform_point3(Vec3::new(
                        pick(0, b.min.x, b.max.x),
                        pick(1, b.min.y, b.max.y),
                        pick(2, b.min.z, b.max.z),
                    ))
                })
                .collect();
            boxes.push(Aabb::from_points(&corners));
            list.push(Instance {
                group,
                to_world,
                to_object: to_world.inverse(),
                normal,
            });
        }
        list.shrink_to_fit();
        Ok(Self {
            groups,
            list,
            accel: Accel::build(accel, &boxes),
            bounds: boxes.iter().fold(Aabb::EMPTY, |a, b| a.union(*b)),
        })
    }

    /// Number of instances (of non-empty groups).
    pub(super) fn len(&self) -> usize {
        self.list.len()
    }

    /// Primitives stored once per group.
    pub(super) fn primitive_count(&self) -> usize {
        self.groups.iter().map(|g| g.prims.len()).sum()
    }

    /// Heap bytes of the groups' structures, the instances and the top-level structure.
    pub(super) fn accel_bytes(&self) -> usize {
        self.groups.iter().map(Level::accel_bytes).sum::<usize>()
            + vec_bytes(&self.list)
            + self.accel.heap_bytes()
    }

    /// Heap bytes of the groups' primitives.
    pub(super) fn prim_bytes(&self) -> usize {
        self.groups.iter().map(Level::prim_bytes).sum()
    }

    /// The nearest instance hit with `0 < t < t_max`: the instance, the ray in its
    /// group's space, `t` and the group's hit record. Out of line, so that the scene's own
    /// traversal stays inlined in `Geometry::intersect` (one copy of the generic search).
    #[inline(never)]
    pub(super) fn closest(
        &self,
        shapes: &[ShapeData],
        ray: &Ray,
        t_max: f32,
    ) -> Option<(u32, f32, HitRecord)> {
        let mut found = None;
        let t = self.accel.closest(ray.origin, ray.dir, t_max, |k, bound| {
            let inst = &self.list[k as usize];
            let g = &self.groups[inst.group as usize];
            let local = inst.ray_to_object(ray);
            let (t, rec) = g.query.closest(g.stored(shapes), &local, bound)?;
            found = Some((k, rec));
            Some(t)
        })?;
        let (k, rec) = found?;
        Some((k, t, rec))
    }

    /// True when some instance is hit with `0 < t < t_max` (out of line, as
    /// [`Instancing::closest`]).
    #[inline(never)]
    pub(super) fn any(&self, shapes: &[ShapeData], ray: &Ray, t_max: f32) -> bool {
        self.accel.any(ray.origin, ray.dir, t_max, |k, bound| {
            let inst = &self.list[k as usize];
            let g = &self.groups[inst.group as usize];
            g.query
                .any(g.stored(shapes), &inst.ray_to_object(ray), bound)
        })
    }

    /// Instance `k`'s group and the ray in its space.
    pub(super) fn local(&self, k: u32, ray: &Ray) -> (&Level, Ray) {
        let inst = &self.list[k as usize];
        (&self.groups[inst.group as usize], inst.ray_to_object(ray))
    }

    /// A hit in instance `k`'s group space carried to world space: the point by
    /// `to_world`, the normals by its inverse transpose (renormalised); its `instance` is
    /// `k`.
    pub(super) fn hit_to_world(&self, k: u32, mut sp: SurfacePoint) -> SurfacePoint {
        let inst = &self.list[k as usize];
        sp.instance = k;
        let ng = inst.normal.mul_vec3(sp.ng).normalize_or(sp.ng);
        let ns = inst.normal.mul_vec3(sp.frame.n).normalize_or(ng);
        sp.p = inst.to_world.transform_point3(sp.p);
        sp.ng = ng;
        sp.frame = Frame::from_normal(ns);
        sp
    }

    /// A world-space hit through instance `hit.instance` with its point carried back into
    /// the group's space (the rest as it is), and the instance's `to_world` linear part,
    /// which carries the group's tangent vectors (`dp/du`, `dp/dv`) to world space, as
    /// Mitsuba 3's `instance.cpp` does. `None` for an instance index out of range.
    pub(super) fn hit_to_group(&self, hit: &SurfacePoint) -> Option<(SurfacePoint, Mat3A)> {
        let inst = self.list.get(hit.instance as usize)?;
        let local = SurfacePoint {
            p: inst.to_object.transform_point3(hit.p),
            ..*hit
        };
        Some((local, inst.to_world.matrix3))
    }
}
