//! Triangle meshes read from files: Wavefront OBJ ([`obj`]), PLY ([`ply`])
//! and Mitsuba's `serialized` format ([`serialized`]), all into one [`TriangleMesh`].
//!
//! Every reader takes only a regular file of at most [`MAX_MESH_BYTES`], never allocates
//! more than the file's contents can fill (counts in a header are checked against the
//! bytes that follow before anything is reserved), and reports a malformed file as a
//! [`SceneError`] naming the file and, where the format has them, the line (ASCII) or the
//! element and its index (binary).

pub mod obj;
pub mod ply;
mod ply_binary;
#[cfg(test)]
mod ply_binary_tests;
pub mod serialized;

use crate::scene_error::{SceneError, SceneErrorKind};
use glam::{Vec2, Vec3};
use std::path::Path;

/// Largest mesh file read, in bytes (4 GiB), for every format.
pub const MAX_MESH_BYTES: u64 = 1 << 32;

/// An indexed triangle mesh as a file gives it, in object space.
///
/// ```
/// use mcrt_render::mesh_file::TriangleMesh;
/// let m = TriangleMesh {
///     positions: vec![mcrt::glam::Vec3::ZERO, mcrt::glam::Vec3::X, mcrt::glam::Vec3::Y],
///     indices: vec![[0, 1, 2]],
///     ..TriangleMesh::default()
/// };
/// assert!(m.check().is_ok());
/// ```
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TriangleMesh {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Per-vertex normals, as many as positions, or empty when the file has none (Mitsuba
    /// then computes smooth normals unless `face_normals` is set).
    pub normals: Vec<Vec3>,
    /// Per-vertex texture coordinates, as many as positions, or empty.
    pub uvs: Vec<Vec2>,
    /// Triangles as indices into `positions` (and `normals`, `uvs`).
    pub indices: Vec<[u32; 3]>,
}

impl TriangleMesh {
    /// Checks what every reader guarantees: finite positions, normals and texture
    /// coordinates; attribute arrays empty or one per vertex; indices in range; at least
    /// one triangle. The message says what is wrong.
    pub fn check(&self) -> Result<(), String> {
        let n = self.positions.len();
        if self.indices.is_empty() {
            return Err("the mesh has no faces".into());
        }
        for (what, len) in [("normals", self.normals.len()), ("uvs", self.uvs.len())] {
            if len != 0 && len != n {
                return Err(format!("{len} {what} for {n} vertices"));
            }
        }
        if let Some(k) = self.positions.iter().position(|p| !p.is_finite()) {
            return Err(format!("vertex {k}'s position is not finite"));
        }
        if let Some(k) = self.normals.iter().position(|p| !p.is_finite()) {
            return Err(format!("vertex {k}'s normal is not finite"));
        }
        if let Some(k) = self.uvs.iter().position(|p| !p.is_finite()) {
            return Err(format!("vertex {k}'s texture coordinates are not finite"));
        }
        if let Some(k) = self
            .indices
            .iter()
            .position(|t| t.iter().any(|&v| v as usize >= n))
        {
            return Err(format!(
                "face {k} refers to vertex {} of {n}",
                self.indices[k].iter().max().copied().unwrap_or(0)
            ));
        }
        Ok(())
    }
}

/// Appends a face of `corners` as a fan from its first corner (a triangle stays as it
/// is; a quad becomes two triangles, as Mitsuba's OBJ reader splits it).
pub(crate) fn push_fan(indices: &mut Vec<[u32; 3]>, corners: &[u32]) {
    for k in 1..corners.len().saturating_sub(1) {
        indices.push([corners[0], corners[k], corners[k + 1]]);
    }
}

/// The contents of the mesh file at `path` (a regular file of at most
/// [`MAX_MESH_BYTES`]), or an error naming it.
pub(crate) fn read_file(path: &Path) -> Result<Vec<u8>, SceneError> {
    crate::io::read_capped(path, MAX_MESH_BYTES).map_err(|e| SceneError::io(path, &e))
}

/// An error in mesh file `path` at an optional line and place (`element`), of `kind`.
pub(crate) fn error(
    path: Option<&Path>,
    line: Option<u32>,
    element: Option<String>,
    kind: SceneErrorKind,
) -> SceneError {
    SceneError::new(path, line, None, element, kind)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fans_and_checks() {
        let mut idx = Vec::new();
        push_fan(&mut idx, &[4, 5, 6, 7, 8]);
        assert_eq!(idx, vec![[4, 5, 6], [4, 6, 7], [4, 7, 8]]);
        push_fan(&mut idx, &[1, 2]);
        assert_eq!(idx.len(), 3);
        let mut m = TriangleMesh {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
            indices: vec![[0, 1, 2]],
            ..TriangleMesh::default()
        };
        assert!(m.check().is_ok());
        m.uvs = vec![Vec2::ZERO; 2];
        assert!(m.check().unwrap_err().contains("2 uvs for 3 vertices"));
        m.uvs.clear();
        m.indices.push([0, 1, 3]);
        assert!(m.check().unwrap_err().contains("face 1"));
        m.indices.pop();
        m.normals = vec![Vec3::Z, Vec3::Z, Vec3::NAN];
        assert!(m.check().unwrap_err().contains("vertex 2"));
    }
}
