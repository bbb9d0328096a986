//! Scene geometry in world space: ray casting, occlusion, and sampling points on shapes.
//!
//! [`Geometry::new`] turns the scene's [`ShapeDesc`]s into primitives: meshes, rectangles and
//! cubes become triangles (two per rectangle or cube face, as in Mitsuba 3), spheres,
//! disks and cylinders (`cylinder.rs`) stay analytic. An acceleration structure ([`AccelKind`]) sits on top. With the BVH,
//! two triangles of a mesh that form a planar parallelogram (every rectangle and cube face)
//! are stored and intersected as one quad; hits still report the triangle and its
//! barycentrics (`docs/geometry.md`, "Quads").
//!
//! # Conventions
//! - [`Ray::dir`] need not be unit length; every `t` is in units of its length. The renderer
//!   passes unit directions for camera and BSDF rays; [`spawn_ray_to`] returns a non-unit one.
//! - A hit needs `0 < t < t_max`. No epsilon is applied: rays leaving a surface must start at
//!   [`offset_origin`] (or use [`spawn_ray`] / [`spawn_ray_to`]).
//! - A hit is a [`SurfacePoint`], the type the estimators take: the point, the normals and the
//!   shading frame, `t`, and the shape, primitive and surface coordinates.
//! - [`SurfacePoint::ng`] is the unit normal of the shape's *front* side, never flipped towards the
//!   ray: rectangles and disks `+z` of object space (transformed as a normal), cubes and
//!   spheres outwards, meshes by their winding (counter-clockwise seen from the front);
//!   `flip_normals` negates it. The shading normal `frame.n` interpolates the mesh's vertex
//!   normals where it has them, else equals `ng`; it is negated by `flip_normals` too.
//! - [`SurfacePoint::uv`]: barycentric weights (b₁, b₂) of vertices 1 and 2 for triangles; for spheres
//!   (φ/2π, θ/π) of the object-space normal (the `to_world` rotation undone); for disks
//!   (r, φ/2π); for cylinders (φ/2π, z/L) in their local frame.
//!
//! # Shape sampling
//! See [`Geometry::sample_shape`]: densities are per unit solid angle at the reference point.
//! Spheres are sampled by the cone they subtend
//! ([`UniformCone`](mcrt::sampling::warp::UniformCone)), mesh triangles (chosen by area)
//! by [`SphericalTriangle`](mcrt::sampling::warp::SphericalTriangle), rectangles by
//! [`SphericalRectangle`](mcrt::sampling::warp::SphericalRectangle), disks and cylinders
//! uniformly by area; uniform area sampling converted to solid angle is the fallback for tiny or sliver
//! solid angles, references inside spheres and sheared rectangles (`docs/geometry.md`).
//!
//! ```
//! use mcrt::glam::{Mat4, Vec3};
//! use mcrt_render::description::{ShapeDesc, ShapeKind};
//! use mcrt_render::geometry::{AccelKind, Geometry, Ray};
//!
//! // Mitsuba's rectangle [-1,1]² at z = 0, facing +z, moved to z = -2.
//! let mut rect = ShapeDesc::new(ShapeKind::Rectangle);
//! rect.to_world = Mat4::from_translation(Vec3::new(0.0, 0.0, -2.0));
//! let geo = Geometry::new(&[rect], None, AccelKind::Bvh).unwrap();
//! let ray = Ray { origin: Vec3::ZERO, dir: -Vec3::Z };
//! let hit = geo.intersect(&ray, f32::INFINITY).unwrap();
//! assert!((hit.t - 2.0).abs() < 1e-6);
//! assert_eq!(hit.ng, Vec3::Z);
//! assert!(geo.occluded(&ray, 3.0) && !geo.occluded(&ray, 1.5));
//! ```

mod build;
mod cylinder;
mod data;
mod error;
mod file_mesh;
mod instances;
mod level;
mod offset;
mod query;
mod sample;
mod tangent;
mod uv_derivatives;
mod vertex_attributes;

pub use crate::accel::AccelKind;
pub use error::GeometryError;
pub use offset::{offset_origin, spawn_ray, spawn_ray_to};
pub(crate) use sample::RectangleSampler;
pub use sample::ShapeSampling;

use crate::accel::Aabb;
use crate::description::{ShapeDesc, ShapeKind};
use data::{Prim, ShapeData};
use glam::{Vec2, Vec3, Vec3A};
use instances::Instancing;
use level::Level;
use mcrt::integrator::SurfacePoint;
use mcrt::sampling::Frame;
use query::HitRecord;
use std::f32::consts::PI;
use std::path::Path;

/// A ray `origin + t · dir`. `dir` need not be unit length; distances are in its units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ray {
    /// Where the ray starts.
    pub origin: Vec3,
    /// Its direction (nonzero; unit for camera and BSDF rays).
    pub dir: Vec3,
}

impl Ray {
    /// The point at parameter `t`.
    #[inline]
    pub fn at(&self, t: f32) -> Vec3 {
        self.origin + t * self.dir
    }
}

/// A point sampled on a shape, seen from a reference point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeSample {
    /// The point.
    pub p: Vec3,
    /// Unit normal of the shape's front side at `p`.
    pub n: Vec3,
    /// Density per unit solid angle at the reference point.
    pub pdf: f32,
}

/// The scene's shapes in world space with an acceleration structure.
///
/// Instances of shape groups ([`ShapeKind::Instance`]) form a second level: each group is
/// built once in its own space with a structure of the same kind, and a structure over the
/// instances' world boxes finds the instances a ray reaches (`geometry/instances.rs`).
/// Shapes are numbered as [`SceneDescription::all_shapes`](
/// crate::description::SceneDescription::all_shapes) lists them: the shapes given, then the
/// shapes of each distinct group. Shapes inside groups cannot be sampled (they may not
/// emit): their [`Geometry::shape_area`] is 0 and [`Geometry::sample_shape`] gives `None`.
#[derive(Debug, Clone)]
pub struct Geometry {
    /// The shapes' own primitives (not the groups').
    top: Level,
    /// Every shape's data, in the numbering above (groups' shapes in their group's space).
    shapes: Vec<ShapeData>,
    /// How many of `shapes` are the scene's own (the rest are in groups).
    own_shapes: u32,
    /// Per shape: world to object directions (a sphere's rotation, for its uv; else the
    /// identity).
    uv_frames: Vec<glam::Mat3>,
    /// The instances and their groups, if there are any.
    instancing: Option<Box<Instancing>>,
    bounds: Aabb,
    shape_sampling: ShapeSampling,
}

impl Geometry {
    /// Builds world-space geometry for `shapes` (OBJ file names resolve against
    /// `base_dir`) with the chosen acceleration structure.
    ///
    /// # Errors
    /// A transform that is not finite, affine and invertible; a sphere under a non-uniform
    /// scale; an invalid mesh; an unreadable OBJ file; an instance inside a shape group
    /// (nested instancing, refused as by Mitsuba 3).
    pub fn new<S: std::borrow::Borrow<ShapeDesc>>(
        shapes: &[S],
        base_dir: Option<&Path>,
        accel: AccelKind,
    ) -> Result<Self, GeometryError> {
        let shapes: Vec<&ShapeDesc> = shapes.iter().map(|s| s.borrow()).collect();
        Self::of_shapes(&shapes, base_dir, accel)
    }

    /// [`Geometry::new`] of the shapes, one build whatever holds them.
    fn of_shapes(
        shapes: &[&ShapeDesc],
        base_dir: Option<&Path>,
        accel: AccelKind,
    ) -> Result<Self, GeometryError> {
        let groups = crate::description::groups_of(shapes);
        let mut all: Vec<&ShapeDesc> = shapes.to_vec();
        let mut firsts = Vec::with_capacity(groups.len());
        for g in &groups {
            firsts.push(all.len() as u32);
            all.extend(g.shapes.iter().map(|s| &**s));
        }
        if let Some(i) =
            (shapes.len()..all.len()).find(|&i| matches!(all[i].kind, ShapeKind::Instance(_)))
        {
            return Err(GeometryError::InvalidShape {
                shape: i,
                what: "an instance inside a shape group (nested instancing is not supported, \
                       as in Mitsuba 3)"
                    .into(),
            });
        }
        let built = build::build_refs(&all, base_dir)?;
        let own = shapes.len() as u32;
        let top = Level::build(accel, built.shapes_view(0, own));
        let instancing = if groups.is_empty() {
            None
        } else {
            let levels = (0..groups.len())
                .map(|k| {
                    let end = firsts.get(k + 1).copied().unwrap_or(all.len() as u32);
                    Level::build(accel, built.shapes_view(firsts[k], end))
                })
                .collect();
            Some(Box::new(Instancing::build(accel, shapes, &groups, levels)?))
        };
        let bounds = match &instancing {
            Some(i) => top.bounds.union(i.bounds),
            None => top.bounds,
        };
        Ok(Self {
            top,
            uv_frames: all.iter().map(|d| build::uv_frame(d)).collect(),
            shapes: built.shapes,
            own_shapes: own,
            instancing,
            bounds,
            shape_sampling: ShapeSampling::default(),
        })
    }

    /// Number of shapes: those given and those of their shape groups (see [`Geometry`]).
    pub fn shape_count(&self) -> usize {
        self.shapes.len()
    }

    /// Number of primitives stored (triangles, spheres, disks): a shape group's count once,
    /// however many instances it has.
    pub fn primitive_count(&self) -> usize {
        self.top.prims.len() + self.instancing.as_ref().map_or(0, |i| i.primitive_count())
    }

    /// Number of instances of shape groups (those of empty groups not counted).
    pub fn instance_count(&self) -> usize {
        self.instancing.as_ref().map_or(0, |i| i.len())
    }

    /// Heap bytes held by the acceleration structure (not the primitives): O(n) in the
    /// primitive count for the BVH and the grid, O(n log n) at most for the kd-tree, for any
    /// input (`docs/geometry.md`, "Bounds on degenerate input"). With instances: each
    /// group's structure once, plus the instances (their transforms) and the structure over
    /// them, O(instances).
    pub fn accel_heap_bytes(&self) -> usize {
        self.top.accel_bytes() + self.instancing.as_ref().map_or(0, |i| i.accel_bytes())
    }

    /// Heap bytes held by the stored primitives and their per-primitive data (a shape
    /// group's once), not counting the shapes' vertex data.
    pub fn primitive_heap_bytes(&self) -> usize {
        self.top.prim_bytes() + self.instancing.as_ref().map_or(0, |i| i.prim_bytes())
    }

    /// The acceleration structure in use.
    pub fn accel_kind(&self) -> AccelKind {
        self.top.query.kind()
    }

    /// Shape `shape`'s data if it is one of the scene's own shapes (not in a group, not an
    /// instance): what the shape samplers may use.
    #[inline]
    fn own_shape(&self, shape: u32) -> Option<&ShapeData> {
        if shape >= self.own_shapes {
            return None;
        }
        self.shapes
            .get(shape as usize)
            .filter(|d| !matches!(d, ShapeData::Instance))
    }

    /// The world-space bounding box of all shapes (empty when there are none).
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// A sphere holding every shape: (centre, radius); (origin, 0) for an empty scene.
    pub fn bounding_sphere(&self) -> (Vec3, f32) {
        if self.bounds.is_empty() {
            return (Vec3::ZERO, 0.0);
        }
        let c = self.bounds.center();
        (c, (self.bounds.max - c).length())
    }

    /// The nearest hit with `0 < t < t_max`.
    #[inline(never)]
    pub fn intersect(&self, ray: &Ray, t_max: f32) -> Option<SurfacePoint> {
        let top = self
            .top
            .query
            .closest(self.top.stored(&self.shapes), ray, t_max);
        if let Some(inst) = &self.instancing {
            let bound = top.as_ref().map_or(t_max, |h| h.0);
            if let Some(sp) = self.intersect_instances(inst, ray, bound) {
                return Some(sp);
            }
        }
        let (t, rec) = top?;
        Some(self.make_hit(&self.top, ray, t, rec))
    }

    /// The nearest hit on an instance with `0 < t < bound`, in world space. Out of line:
    /// a scene without instances never enters it, and its code stays out of `intersect`.
    #[inline(never)]
    fn intersect_instances(
        &self,
        inst: &instances::Instancing,
        ray: &Ray,
        bound: f32,
    ) -> Option<SurfacePoint> {
        let (k, t, rec) = inst.closest(&self.shapes, ray, bound)?;
        let (group, local) = inst.local(k, ray);
        Some(inst.hit_to_world(k, self.make_hit(group, &local, t, rec)))
    }

    /// For a hit on a shape group's shape: `f` of the hit carried into the group's space
    /// (through instance `hit.instance`), with the instance's `to_world` linear part, which
    /// carries tangent vectors back to world space. `None` without such an instance.
    #[inline(never)]
    fn through_instance<T>(
        &self,
        hit: &SurfacePoint,
        f: impl FnOnce(&SurfacePoint) -> T,
    ) -> Option<(glam::Mat3, T)> {
        let (local, to_world) = self.instancing.as_ref()?.hit_to_group(hit)?;
        Some((glam::Mat3::from(to_world), f(&local)))
    }

    /// True when anything is hit with `0 < t < t_max`.
    #[inline(never)]
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        self.top
            .query
            .any(self.top.stored(&self.shapes), ray, t_max)
            || self
                .instancing
                .as_ref()
                .is_some_and(|i| i.any(&self.shapes, ray, t_max))
    }

    /// Fills in the surface data of a hit found by the search in `level`.
    #[inline(always)]
    fn make_hit(&self, level: &Level, ray: &Ray, t: f32, rec: HitRecord) -> SurfacePoint {
        let slot = level.slots[rec.slot as usize];
        let id = slot.id;
        let mut uv = Vec2::new(rec.b1, rec.b2);
        // The point along the ray, computed only where it is used: a mesh hit takes the
        // point from its triangle's vertices.
        let (p, ng, ns) = match &self.shapes[id.shape as usize] {
            ShapeData::Mesh(m) => {
                let b0 = 1.0 - rec.b1 - rec.b2;
                let p = match &level.prims[rec.slot as usize] {
                    Prim::Tri(tri) => tri.point(Vec3A::new(b0, rec.b1, rec.b2)),
                    _ => ray.at(t),
                };
                let ng = slot.ng;
                let ns = if m.normals.is_empty() {
                    ng
                } else {
                    let sign = if m.flip { -1.0 } else { 1.0 };
                    let idx = m.indices[id.prim as usize];
                    let [na, nb, nc] = idx.map(|v| m.normals[v as usize]);
                    sign * (na * b0 + nb * rec.b1 + nc * rec.b2).normalize_or(ng * sign)
                };
                (p, ng, ns)
            }
            &ShapeData::Sphere {
                center,
                radius,
                flip,
            } => {
                let n = (ray.at(t) - center).normalize_or(Vec3::Z);
                let ng = if flip { -n } else { n };
                uv = self.sphere_uv(id.shape, n);
                (center + radius * n, ng, ng)
            }
            ShapeData::Disk(d) => {
                let local = d.to_object.transform_point3(ray.at(t));
                let local = Vec3::new(local.x, local.y, 0.0);
                uv = disk_uv(local);
                (d.to_world.transform_point3(local), d.normal, d.normal)
            }
            // Never stored as a primitive.
            ShapeData::Instance => (ray.at(t), Vec3::Z, Vec3::Z),
            ShapeData::Cylinder(c) => {
                let (q, n, st) = c.surface(ray.at(t));
                uv = st;
                (q, n, n)
            }
        };
        SurfacePoint {
            p,
            ng,
            frame: Frame::from_normal(ns),
            t,
            shape: id.shape,
            prim: id.prim,
            uv,
            instance: 0,
        }
    }
}

impl Geometry {
    /// A sphere's surface coordinates: (φ/2π, θ/π) of the object-space normal of the world
    /// normal `n` of shape `shape`, as Mitsuba 3.
    #[inline(always)]
    fn sphere_uv(&self, shape: u32, n: Vec3) -> Vec2 {
        let frame = self.uv_frames.get(shape as usize);
        let n = frame.map_or(n, |f| (*f * n).normalize_or(n));
        let phi = n.y.atan2(n.x);
        let phi = if phi < 0.0 { phi + 2.0 * PI } else { phi };
        Vec2::new(phi / (2.0 * PI), n.z.clamp(-1.0, 1.0).acos() / PI)
    }
}

/// A disk's surface coordinates (r, φ/2π) of the object-space point `local` (z = 0).
#[inline(always)]
fn disk_uv(local: Vec3) -> Vec2 {
    let phi = local.y.atan2(local.x);
    let phi = if phi < 0.0 { phi + 2.0 * PI } else { phi };
    Vec2::new(local.truncate().length(), phi / (2.0 * PI))
}
