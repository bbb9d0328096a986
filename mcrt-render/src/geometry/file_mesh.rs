//! Shapes whose triangles come from a file (`obj`, `ply`, `serialized`): read, moved to
//! world space, and given Mitsuba's vertex normals (the file's, transformed; else smooth
//! normals computed from the faces; none with `face_normals`).

use super::data::{mesh, MeshData};
use super::error::GeometryError;
use crate::description::ShapeKind;
use crate::mesh_file::obj::read_obj;
use crate::mesh_file::{ply::read_ply, serialized::read_serialized, TriangleMesh};
use glam::{Affine3A, Mat3, Vec2, Vec3};
use rayon::prelude::*;
use std::path::{Path, PathBuf};

/// The world-space mesh of shape `i` if its kind is read from a file, else `None`.
pub(super) fn build(
    i: usize,
    kind: &ShapeKind,
    m: &Affine3A,
    flip: bool,
    base_dir: Option<&Path>,
) -> Option<Result<MeshData, GeometryError>> {
    let path = |f: &PathBuf| base_dir.map_or_else(|| f.clone(), |b| b.join(f));
    let failed = |e: crate::scene_error::SceneError| GeometryError::MeshFile {
        shape: i,
        message: e.to_string(),
    };
    let (read, face_normals, flip_v) = match kind {
        ShapeKind::Obj {
            filename,
            face_normals,
            flip_tex_coords,
        } => {
            let obj = read_obj(&path(filename)).map_err(|e| GeometryError::Obj {
                shape: i,
                message: e.to_string(),
            });
            (obj, *face_normals, *flip_tex_coords)
        }
        ShapeKind::Ply {
            filename,
            face_normals,
        } => (
            read_ply(&path(filename)).map_err(failed),
            *face_normals,
            false,
        ),
        ShapeKind::Serialized {
            filename,
            shape_index,
            face_normals,
        } => match read_serialized(&path(filename), *shape_index) {
            Ok(s) => (Ok(s.mesh), *face_normals || s.face_normals, false),
            Err(e) => (Err(failed(e)), false, false),
        },
        _ => return None,
    };
    Some(read.and_then(|mesh| world_mesh(i, mesh, m, flip, face_normals, flip_v)))
}

/// Transforms a file's mesh to world space and packs it.
fn world_mesh(
    i: usize,
    file: TriangleMesh,
    m: &Affine3A,
    flip: bool,
    face_normals: bool,
    flip_v: bool,
) -> Result<MeshData, GeometryError> {
    let pos: Vec<Vec3> = file
        .positions
        .par_iter()
        .map(|&p| m.transform_point3(p))
        .collect();
    let nrm = if face_normals {
        vec![]
    } else if file.normals.is_empty() {
        smooth_normals(&pos, &file.indices)
    } else {
        let nm = Mat3::from(m.matrix3).inverse().transpose();
        file.normals
            .par_iter()
            .map(|&n| (nm * n).normalize_or_zero())
            .collect()
    };
    let mut out = mesh(i, pos, nrm, file.indices, flip, false)?;
    out.uvs = if flip_v {
        file.uvs.iter().map(|t| Vec2::new(t.x, 1.0 - t.y)).collect()
    } else {
        file.uvs
    };
    Ok(out)
}

/// Vertex normals as the angle-weighted mean of the adjacent face normals (what Mitsuba
/// computes for meshes without normals unless `face_normals` is set). Vertices on no
/// face of nonzero area get a zero normal, which hit shading replaces by `ng`.
fn smooth_normals(pos: &[Vec3], indices: &[[u32; 3]]) -> Vec<Vec3> {
    let mut acc = vec![Vec3::ZERO; pos.len()];
    for t in indices {
        let p = t.map(|v| pos.get(v as usize).copied().unwrap_or(Vec3::ZERO));
        let n = (p[1] - p[0]).cross(p[2] - p[0]).normalize_or_zero();
        for k in 0..3 {
            let e1 = (p[(k + 1) % 3] - p[k]).normalize_or_zero();
            let e2 = (p[(k + 2) % 3] - p[k]).normalize_or_zero();
            let angle = e1.dot(e2).clamp(-1.0, 1.0).acos();
            if let Some(a) = acc.get_mut(t[k] as usize) {
                *a += n * angle;
            }
        }
    }
    acc.into_iter().map(Vec3::normalize_or_zero).collect()
}
