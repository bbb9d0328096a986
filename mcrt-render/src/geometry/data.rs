//! The world-space data of the shapes, as [`build`](super::build) makes it from the
//! descriptions and as the ray queries (`query/`) and the shape samplers (`sample/`) read
//! it: primitives, per-shape data, and the packing of a triangle mesh.

use super::cylinder::CylinderData;
use super::error::GeometryError;
use super::query::scalar::TriSoa;
use super::sample::rectangle::RectangleSampler;
use glam::{Affine3A, Vec2, Vec3};
use mcrt::sampling::distribution::AliasTable;
use rayon::prelude::*;

/// One primitive as the acceleration structure sees it.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Prim {
    /// A triangle, world-space vertices.
    Tri(TriSoa),
    /// A sphere.
    Sphere { center: Vec3, radius: f32 },
    /// A disk: index of its shape.
    Disk(u32),
    /// A cylinder: index of its shape.
    Cylinder(u32),
}

/// Which shape a primitive belongs to, and its index within that shape.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PrimId {
    pub(crate) shape: u32,
    pub(crate) prim: u32,
}

/// A world-space triangle mesh (meshes, OBJ files, rectangles, cubes).
#[derive(Debug, Clone)]
pub(crate) struct MeshData {
    pub(crate) positions: Vec<Vec3>,
    /// World-space unit vertex normals, or empty.
    pub(crate) normals: Vec<Vec3>,
    /// Per-vertex texture coordinates, or empty (meshes read from files).
    pub(crate) uvs: Vec<Vec2>,
    pub(crate) indices: Vec<[u32; 3]>,
    /// `flip_normals`.
    pub(crate) flip: bool,
    /// Triangle choice by area (`None` when the mesh has no area).
    pub(crate) pick: Option<AliasTable>,
    /// Total area.
    pub(crate) area: f32,
    /// A `rectangle` shape's sampler (it is sampled as a whole, not by triangles).
    pub(crate) rectangle: Option<RectangleSampler>,
}

/// A world-space disk.
#[derive(Debug, Clone)]
pub(crate) struct DiskData {
    pub(crate) to_world: Affine3A,
    pub(crate) to_object: Affine3A,
    /// Unit front normal (after `flip_normals`).
    pub(crate) normal: Vec3,
    pub(crate) area: f32,
}

/// The per-shape data that hits and samples need.
#[derive(Debug, Clone)]
pub(crate) enum ShapeData {
    Mesh(MeshData),
    Sphere {
        center: Vec3,
        radius: f32,
        flip: bool,
    },
    Disk(DiskData),
    /// An instance of a shape group: no primitives of its own (its group's shapes follow
    /// the scene's in the numbering, `description::instancing`).
    Instance,
    Cylinder(CylinderData),
}

/// Everything built from the descriptions, primitives in input order.
pub(crate) struct Built {
    pub(crate) prims: Vec<Prim>,
    pub(crate) ids: Vec<PrimId>,
    pub(crate) shapes: Vec<ShapeData>,
}

/// The primitives of one level of the geometry (the scene's own, or one shape group's),
/// with the data of every shape (indexed by [`PrimId::shape`]).
#[derive(Clone, Copy)]
pub(crate) struct PrimsView<'a> {
    pub(crate) prims: &'a [Prim],
    pub(crate) ids: &'a [PrimId],
    pub(crate) shapes: &'a [ShapeData],
}

impl Built {
    /// All primitives.
    #[cfg(test)]
    pub(crate) fn view(&self) -> PrimsView<'_> {
        PrimsView {
            prims: &self.prims,
            ids: &self.ids,
            shapes: &self.shapes,
        }
    }

    /// The primitives of shapes `first..end` (contiguous: primitives are in shape order).
    pub(crate) fn shapes_view(&self, first: u32, end: u32) -> PrimsView<'_> {
        let a = self.ids.partition_point(|id| id.shape < first);
        let b = self.ids.partition_point(|id| id.shape < end);
        PrimsView {
            prims: &self.prims[a..b],
            ids: &self.ids[a..b],
            shapes: &self.shapes,
        }
    }
}

/// Validates and packs a world-space mesh. `reverse` reverses the winding (used for
/// rectangles and cubes under a mirroring transform, so that the face normal stays the
/// transformed object-space normal, as for Mitsuba's analytic rectangle).
pub(crate) fn mesh(
    i: usize,
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    mut indices: Vec<[u32; 3]>,
    flip: bool,
    reverse: bool,
) -> Result<MeshData, GeometryError> {
    let invalid = |what: String| Err(GeometryError::InvalidShape { shape: i, what });
    if let Some(k) = positions.iter().position(|p| !p.is_finite()) {
        return invalid(format!("vertex {k} is not finite"));
    }
    if !normals.is_empty() && normals.len() != positions.len() {
        return invalid(format!(
            "{} normals for {} vertices",
            normals.len(),
            positions.len()
        ));
    }
    if let Some(k) = indices
        .iter()
        .position(|t| t.iter().any(|&v| v as usize >= positions.len()))
    {
        return invalid(format!(
            "triangle {k} indexes past the {} vertices",
            positions.len()
        ));
    }
    if reverse {
        indices.iter_mut().for_each(|t| t.swap(1, 2));
    }
    let areas: Vec<f32> = indices
        .par_iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| positions[v as usize]);
            0.5 * (b - a).cross(c - a).length()
        })
        .collect();
    Ok(MeshData {
        positions,
        normals,
        uvs: Vec::new(),
        indices,
        flip,
        pick: AliasTable::new(&areas).ok(),
        area: areas.iter().map(|&a| f64::from(a)).sum::<f64>() as f32,
        rectangle: None,
    })
}
