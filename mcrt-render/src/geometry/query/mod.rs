//! Ray queries: the one place where the geometry finds what a ray hits.
//!
//! [`RayQuery`] is the switch over backends. With [`AccelKind::Bvh`] the primitives live in
//! the 4-wide BVH's leaves, packed for SIMD tests ([`packed_bvh`]: quads, that is triangle
//! pairs forming a parallelogram ([`pairing`], [`quad4`]), and other triangles four at a
//! time ([`tri4`])); with [`AccelKind::Bvh8`] in the 8-wide BVH's leaves of up to eight
//! units, eight at a time ([`packed_bvh8`], [`quad8`], [`tri8`]). Every other kind goes through the primitive-agnostic [`Accel`], which
//! calls back per primitive into the scalar tests ([`scalar`]).
//!
//! Primitives are stored in the backend's *slot* order ([`QueryBuild::slots`]); queries
//! report slots ([`HitRecord::slot`]).

mod packed_bvh;
mod packed_bvh8;
#[cfg(test)]
mod packets8_tests;
mod pairing;
mod quad4;
mod quad8;
pub(super) mod scalar;
mod tri4;
mod tri8;

pub(crate) use scalar::TriSoa;

use super::data::{Prim, PrimsView, ShapeData};
use super::Ray;
use crate::accel::{Aabb, Accel, AccelKind, Bvh4};
use packed_bvh::PackedBvh;
use packed_bvh8::PackedBvh8;
use pairing::Unit;
use rayon::prelude::*;
use scalar::{hit_disk, hit_sphere, TriRay};

/// Where a closest-hit query found its hit: stored primitive (slot) and barycentrics.
#[derive(Debug, Clone, Copy)]
pub(super) struct HitRecord {
    pub(super) slot: u32,
    pub(super) b1: f32,
    pub(super) b2: f32,
}

/// The stored primitives, in slot order, and the shape data disks need.
#[derive(Clone, Copy)]
pub(super) struct Stored<'a> {
    pub(super) prims: &'a [Prim],
    pub(super) shapes: &'a [ShapeData],
}

impl Stored<'_> {
    /// Intersects slot `i`: `(t, b1, b2)`, barycentrics only for triangles. `tri` is the
    /// ray prepared for triangles, when the caller has one.
    #[inline(always)]
    fn hit(&self, ray: &Ray, tri: Option<&TriRay>, i: u32, t_max: f32) -> Option<(f32, f32, f32)> {
        match &self.prims[i as usize] {
            Prim::Tri(v) => match tri {
                Some(r) => r.hit(v, t_max),
                None => TriRay::new(ray.origin, ray.dir).hit(v, t_max),
            },
            &Prim::Sphere { center, radius } => {
                hit_sphere(ray.origin, ray.dir, center, radius, t_max).map(|t| (t, 0.0, 0.0))
            }
            &Prim::Disk(s) => match &self.shapes[s as usize] {
                ShapeData::Disk(d) => {
                    hit_disk(ray.origin, ray.dir, &d.to_object, t_max).map(|(t, _)| (t, 0.0, 0.0))
                }
                _ => None,
            },
            &Prim::Cylinder(s) => match &self.shapes[s as usize] {
                ShapeData::Cylinder(c) => c.hit(ray.origin, ray.dir, t_max).map(|t| (t, 0.0, 0.0)),
                _ => None,
            },
        }
    }
}

/// The ray-query backend.
#[derive(Debug, Clone)]
pub(super) enum RayQuery {
    /// The 4-wide BVH with packed leaves.
    PackedBvh(PackedBvh),
    /// The 8-wide BVH with leaves of up to 8 units, packed 8 lanes wide.
    PackedBvh8(PackedBvh8),
    /// Any other structure, one primitive per callback.
    Accel(Accel),
}

/// A built backend and the slot order it stores primitives in.
pub(super) struct QueryBuild {
    pub(super) query: RayQuery,
    /// `slots[s]` is the input index (in the level's primitives) of the primitive in slot `s`.
    pub(super) slots: Vec<u32>,
    /// The bounding box of every primitive.
    pub(super) bounds: Aabb,
}

impl RayQuery {
    /// Builds the backend of the given kind over `built`'s primitives.
    pub(super) fn build(kind: AccelKind, built: &PrimsView) -> QueryBuild {
        let prims = &built.prims;
        if matches!(kind, AccelKind::Bvh | AccelKind::Bvh8) {
            let units = pairing::units(built);
            let boxes: Vec<Aabb> = units
                .par_iter()
                .map(|u| unit_bounds(u, prims, built.shapes))
                .collect();
            let (slots, query) = if kind == AccelKind::Bvh {
                let (slots, packed) = PackedBvh::pack(Bvh4::build(&boxes), &units, prims);
                (slots, RayQuery::PackedBvh(packed))
            } else {
                let (slots, packed) = PackedBvh8::build(&boxes, &units, prims);
                (slots, RayQuery::PackedBvh8(packed))
            };
            return QueryBuild {
                query,
                slots,
                bounds: union(&boxes),
            };
        }
        let boxes: Vec<Aabb> = prims.iter().map(|p| prim_bounds(p, built.shapes)).collect();
        QueryBuild {
            query: RayQuery::Accel(Accel::build(kind, &boxes)),
            slots: (0..prims.len() as u32).collect(),
            bounds: union(&boxes),
        }
    }

    /// Heap bytes held by the structure.
    pub(super) fn heap_bytes(&self) -> usize {
        match self {
            RayQuery::PackedBvh(p) => p.heap_bytes(),
            RayQuery::PackedBvh8(p) => p.heap_bytes(),
            RayQuery::Accel(a) => a.heap_bytes(),
        }
    }

    /// Which structure this is.
    pub(super) fn kind(&self) -> AccelKind {
        match self {
            RayQuery::PackedBvh(_) => AccelKind::Bvh,
            RayQuery::PackedBvh8(_) => AccelKind::Bvh8,
            RayQuery::Accel(a) => a.kind(),
        }
    }

    /// The nearest hit with `0 < t < t_max`.
    #[inline(always)]
    pub(super) fn closest(
        &self,
        stored: Stored,
        ray: &Ray,
        t_max: f32,
    ) -> Option<(f32, HitRecord)> {
        match self {
            RayQuery::PackedBvh(p) => p.closest(stored, ray, t_max),
            RayQuery::PackedBvh8(p) => p.closest(stored, ray, t_max),
            RayQuery::Accel(accel) => {
                let tri = TriRay::new(ray.origin, ray.dir);
                let mut rec = HitRecord {
                    slot: 0,
                    b1: 0.0,
                    b2: 0.0,
                };
                let t = accel.closest(ray.origin, ray.dir, t_max, |i, bound| {
                    let (t, b1, b2) = stored.hit(ray, Some(&tri), i, bound)?;
                    rec = HitRecord { slot: i, b1, b2 };
                    Some(t)
                })?;
                Some((t, rec))
            }
        }
    }

    /// True when anything is hit with `0 < t < t_max`.
    #[inline(always)]
    pub(super) fn any(&self, stored: Stored, ray: &Ray, t_max: f32) -> bool {
        match self {
            RayQuery::PackedBvh(p) => p.any(stored, ray, t_max),
            RayQuery::PackedBvh8(p) => p.any(stored, ray, t_max),
            RayQuery::Accel(accel) => {
                let tri = TriRay::new(ray.origin, ray.dir);
                accel.any(ray.origin, ray.dir, t_max, |i, bound| {
                    stored.hit(ray, Some(&tri), i, bound).is_some()
                })
            }
        }
    }
}

fn union(boxes: &[Aabb]) -> Aabb {
    boxes.iter().fold(Aabb::EMPTY, |b, p| b.union(*p))
}

/// The bounds of a BVH unit: one primitive, or both triangles of a quad.
fn unit_bounds(u: &Unit, prims: &[Prim], shapes: &[ShapeData]) -> Aabb {
    match *u {
        Unit::One(i) => prim_bounds(&prims[i as usize], shapes),
        Unit::Pair { first, second, .. } => prim_bounds(&prims[first as usize], shapes)
            .union(prim_bounds(&prims[second as usize], shapes)),
    }
}

fn prim_bounds(p: &Prim, shapes: &[ShapeData]) -> Aabb {
    match p {
        Prim::Tri(v) => Aabb::from_points(&v.vertices()),
        &Prim::Sphere { center, radius } => Aabb {
            min: center - glam::Vec3::splat(radius),
            max: center + glam::Vec3::splat(radius),
        },
        &Prim::Disk(s) => match &shapes[s as usize] {
            ShapeData::Disk(d) => {
                let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
                    .map(|(x, y)| d.to_world.transform_point3(glam::Vec3::new(x, y, 0.0)));
                Aabb::from_points(&corners)
            }
            _ => Aabb::EMPTY,
        },
        &Prim::Cylinder(s) => match &shapes[s as usize] {
            ShapeData::Cylinder(c) => c.bounds(),
            _ => Aabb::EMPTY,
        },
    }
}
