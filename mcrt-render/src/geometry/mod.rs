//! Scene geometry in world space: ray casting, occlusion, and sampling points on shapes.
//!
//! [`Geometry::new`] turns the scene's [`ShapeDesc`]s into primitives: meshes, rectangles and
//! cubes become triangles (two per rectangle or cube face, as in Mitsuba 3), spheres and
//! disks stay analytic. An acceleration structure ([`AccelKind`]) sits on top. With the BVH,
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
//!   (r, φ/2π).
//!
//! # Shape sampling
//! See [`Geometry::sample_shape`]: densities are per unit solid angle at the reference point.
//! Spheres are sampled by the cone they subtend
//! ([`UniformCone`](mcrt::sampling::warp::UniformCone)), mesh triangles (chosen by area)
//! by [`SphericalTriangle`](mcrt::sampling::warp::SphericalTriangle), rectangles by
//! [`SphericalRectangle`](mcrt::sampling::warp::SphericalRectangle), disks uniformly by
//! area; uniform area sampling converted to solid angle is the fallback for tiny or sliver
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
mod data;
mod error;
mod file_mesh;
mod offset;
mod query;
mod sample;
mod tangent;
mod vertex_attributes;

pub use crate::accel::AccelKind;
pub use error::GeometryError;
pub use offset::{offset_origin, spawn_ray, spawn_ray_to};
pub(crate) use sample::RectangleSampler;
pub use sample::ShapeSampling;

use crate::accel::Aabb;
use crate::description::ShapeDesc;
use data::{Prim, PrimId, ShapeData};
use glam::{Vec2, Vec3, Vec3A};
use mcrt::integrator::SurfacePoint;
use mcrt::sampling::Frame;
use query::{HitRecord, RayQuery, Stored};
use rayon::prelude::*;
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
#[derive(Debug, Clone)]
pub struct Geometry {
    /// Primitives in the ray-query backend's slot order.
    prims: Vec<Prim>,
    ids: Vec<PrimId>,
    query: RayQuery,
    /// Per stored primitive: a triangle's unit front normal ([`SurfacePoint::ng`]), else zero.
    face_ng: Vec<Vec3>,
    shapes: Vec<ShapeData>,
    /// Per shape: world to object directions (a sphere's rotation, for its uv; else the
    /// identity).
    uv_frames: Vec<glam::Mat3>,
    bounds: Aabb,
    shape_sampling: ShapeSampling,
}

impl Geometry {
    /// Builds world-space geometry for `shapes` (OBJ file names resolve against
    /// `base_dir`) with the chosen acceleration structure.
    ///
    /// # Errors
    /// A transform that is not finite, affine and invertible; a sphere under a non-uniform
    /// scale; an invalid mesh; an unreadable OBJ file.
    pub fn new(
        shapes: &[ShapeDesc],
        base_dir: Option<&Path>,
        accel: AccelKind,
    ) -> Result<Self, GeometryError> {
        let built = build::build(shapes, base_dir)?;
        let q = RayQuery::build(accel, &built);
        // Gathers over every primitive, in parallel (`collect` keeps the order).
        let ids: Vec<PrimId> = q.slots.par_iter().map(|&i| built.ids[i as usize]).collect();
        Ok(Self {
            prims: q
                .slots
                .par_iter()
                .map(|&i| built.prims[i as usize])
                .collect(),
            face_ng: ids
                .par_iter()
                .map(|id| face_normal(&built.shapes, id))
                .collect(),
            ids,
            query: q.query,
            shapes: built.shapes,
            uv_frames: shapes.iter().map(build::uv_frame).collect(),
            bounds: q.bounds,
            shape_sampling: ShapeSampling::default(),
        })
    }

    /// Number of shapes.
    pub fn shape_count(&self) -> usize {
        self.shapes.len()
    }

    /// Number of primitives (triangles, spheres, disks).
    pub fn primitive_count(&self) -> usize {
        self.prims.len()
    }

    /// Heap bytes held by the acceleration structure (not the primitives): O(n) in the
    /// primitive count for the BVH and the grid, O(n log n) at most for the kd-tree, for any
    /// input (`docs/geometry.md`, "Bounds on degenerate input").
    pub fn accel_heap_bytes(&self) -> usize {
        self.query.heap_bytes()
    }

    /// The acceleration structure in use.
    pub fn accel_kind(&self) -> AccelKind {
        self.query.kind()
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
        let (t, rec) = self.query.closest(self.stored(), ray, t_max)?;
        Some(self.make_hit(ray, t, rec))
    }

    /// True when anything is hit with `0 < t < t_max`.
    #[inline(never)]
    pub fn occluded(&self, ray: &Ray, t_max: f32) -> bool {
        self.query.any(self.stored(), ray, t_max)
    }

    #[inline(always)]
    fn stored(&self) -> Stored<'_> {
        Stored {
            prims: &self.prims,
            shapes: &self.shapes,
        }
    }

    /// Fills in the surface data of a hit found by the search.
    #[inline(always)]
    fn make_hit(&self, ray: &Ray, t: f32, rec: HitRecord) -> SurfacePoint {
        let id = self.ids[rec.slot as usize];
        let mut p = ray.at(t);
        let mut uv = Vec2::new(rec.b1, rec.b2);
        let (ng, ns) = match &self.shapes[id.shape as usize] {
            ShapeData::Mesh(m) => {
                let b0 = 1.0 - rec.b1 - rec.b2;
                if let Prim::Tri(tri) = &self.prims[rec.slot as usize] {
                    p = tri.point(Vec3A::new(b0, rec.b1, rec.b2));
                }
                let ng = self.face_ng[rec.slot as usize];
                let ns = if m.normals.is_empty() {
                    ng
                } else {
                    let sign = if m.flip { -1.0 } else { 1.0 };
                    let idx = m.indices[id.prim as usize];
                    let [na, nb, nc] = idx.map(|v| m.normals[v as usize]);
                    sign * (na * b0 + nb * rec.b1 + nc * rec.b2).normalize_or(ng * sign)
                };
                (ng, ns)
            }
            &ShapeData::Sphere {
                center,
                radius,
                flip,
            } => {
                let n = (p - center).normalize_or(Vec3::Z);
                p = center + radius * n;
                let ng = if flip { -n } else { n };
                // (φ, θ) of the object-space normal, as Mitsuba 3.
                let frame = self.uv_frames.get(id.shape as usize);
                let n = frame.map_or(n, |f| (*f * n).normalize_or(n));
                let phi = n.y.atan2(n.x);
                let phi = if phi < 0.0 { phi + 2.0 * PI } else { phi };
                uv = Vec2::new(phi / (2.0 * PI), n.z.clamp(-1.0, 1.0).acos() / PI);
                (ng, ng)
            }
            ShapeData::Disk(d) => {
                let local = d.to_object.transform_point3(p);
                let local = Vec3::new(local.x, local.y, 0.0);
                p = d.to_world.transform_point3(local);
                let phi = local.y.atan2(local.x);
                let phi = if phi < 0.0 { phi + 2.0 * PI } else { phi };
                uv = Vec2::new(local.truncate().length(), phi / (2.0 * PI));
                (d.normal, d.normal)
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
        }
    }
}

/// The unit front normal of a triangle (zero for other primitives), as hits report it.
fn face_normal(shapes: &[ShapeData], id: &PrimId) -> Vec3 {
    match &shapes[id.shape as usize] {
        ShapeData::Mesh(m) => {
            let [a, b, c] = m.indices[id.prim as usize].map(|v| m.positions[v as usize]);
            let sign = if m.flip { -1.0 } else { 1.0 };
            sign * (b - a).cross(c - a).normalize_or(Vec3::Z)
        }
        _ => Vec3::ZERO,
    }
}
