//! Turning [`ShapeDesc`]s into world-space primitives and per-shape data.

use super::data::{mesh, Built, DiskData, Prim, PrimId, ShapeData};
use super::error::GeometryError;
use super::query::TriSoa;
use super::sample::{front_normal, RectangleSampler};
use crate::description::{ShapeDesc, ShapeKind};
use glam::{Affine3A, Mat3, Vec2, Vec3};
use rayon::prelude::*;
use std::path::Path;

#[cfg(test)]
pub(crate) fn build(shapes: &[ShapeDesc], base_dir: Option<&Path>) -> Result<Built, GeometryError> {
    build_refs(&shapes.iter().collect::<Vec<_>>(), base_dir)
}

/// [`build`] over shapes given by reference (a scene's shapes followed by its groups').
pub(crate) fn build_refs(
    shapes: &[&ShapeDesc],
    base_dir: Option<&Path>,
) -> Result<Built, GeometryError> {
    let mut out = Built {
        prims: Vec::new(),
        ids: Vec::new(),
        shapes: Vec::with_capacity(shapes.len()),
    };
    // Bytes held by the shapes built so far, primitives counted at what building the
    // structure over them will take: each mesh file's reader sees only the rest of the
    // budget, and the sum is checked after each shape.
    let mut held = 0u64;
    for (i, desc) in shapes.iter().enumerate() {
        let m = affine(i, desc)?;
        let data = crate::memory::with_held(held, || shape_data(i, desc, &m, base_dir))?;
        push_prims(&mut out, i as u32, &data);
        held = held.saturating_add(shape_bytes(&data));
        let need =
            held.saturating_add(crate::memory::bytes(out.prims.len() as u64, BYTES_PER_PRIM));
        crate::memory::check(
            &format!(
                "the shapes up to this one ({} primitives) with their acceleration structure",
                out.prims.len()
            ),
            need,
        )
        .map_err(|message| GeometryError::Memory { shape: i, message })?;
        out.shapes.push(data);
    }
    Ok(out)
}

/// Heap bytes per primitive while the geometry is built and after: the primitive and its
/// id twice (input order, then the structure's slot order), its face normal, and the
/// acceleration structure's bound on any input (512 bytes, `docs/geometry.md`, "Bounds on
/// degenerate input").
const BYTES_PER_PRIM: usize =
    2 * (std::mem::size_of::<Prim>() + std::mem::size_of::<PrimId>()) + 12 + 512;

/// Heap bytes of a shape's own data: a mesh's vertices, triangles and triangle choice
/// (an alias table column and a probability per triangle).
fn shape_bytes(data: &ShapeData) -> u64 {
    match data {
        ShapeData::Mesh(m) => {
            let per_vertex = m.positions.len() * 12 + m.normals.len() * 12 + m.uvs.len() * 8;
            (per_vertex + m.indices.len() * (12 + 16)) as u64
        }
        _ => 0,
    }
}

fn push_prims(out: &mut Built, shape: u32, data: &ShapeData) {
    let mut push = |p: Prim, prim: u32| {
        out.prims.push(p);
        out.ids.push(PrimId { shape, prim });
    };
    match data {
        ShapeData::Mesh(m) => {
            let tri = |t: &[u32; 3]| Prim::Tri(TriSoa::new(t.map(|v| m.positions[v as usize])));
            out.prims.par_extend(m.indices.par_iter().map(tri));
            out.ids
                .extend((0..m.indices.len() as u32).map(|prim| PrimId { shape, prim }));
        }
        &ShapeData::Sphere { center, radius, .. } => push(Prim::Sphere { center, radius }, 0),
        ShapeData::Disk(_) => push(Prim::Disk(shape), 0),
        ShapeData::Instance => {}
        ShapeData::Cylinder(_) => push(Prim::Cylinder(shape), 0),
    }
}

pub(super) fn affine(i: usize, desc: &ShapeDesc) -> Result<Affine3A, GeometryError> {
    let m = desc.to_world;
    let bad = |what| Err(GeometryError::BadTransform { shape: i, what });
    if !m.is_finite() {
        return bad("not finite");
    }
    if m.row(3).distance(glam::Vec4::W) > 1e-6 {
        return bad("projective (last row is not 0 0 0 1)");
    }
    let a = Affine3A::from_mat4(m);
    let det = Mat3::from(a.matrix3).determinant();
    if det == 0.0 || !det.is_finite() {
        return bad("singular");
    }
    Ok(a)
}

fn shape_data(
    i: usize,
    desc: &ShapeDesc,
    m: &Affine3A,
    base_dir: Option<&Path>,
) -> Result<ShapeData, GeometryError> {
    let flip = desc.flip_normals;
    if let Some(mesh) = super::file_mesh::build(i, &desc.kind, m, flip, base_dir) {
        return Ok(ShapeData::Mesh(mesh?));
    }
    let mirrored = Mat3::from(m.matrix3).determinant() < 0.0;
    Ok(match &desc.kind {
        ShapeKind::Rectangle => {
            let p = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
                .map(|(x, y)| m.transform_point3(Vec3::new(x, y, 0.0)));
            let mut mesh = mesh(
                i,
                p.to_vec(),
                vec![],
                vec![[0, 1, 2], [0, 2, 3]],
                flip,
                mirrored,
            )?;
            // Mitsuba 3's rectangle: uv = (x + 1, y + 1) / 2 in object space.
            mesh.uvs = vec![Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y];
            let (corner, ex, ey) = (p[0], p[1] - p[0], p[3] - p[0]);
            let n = front_normal(&mesh, mesh.indices[0].map(|v| mesh.positions[v as usize]));
            mesh.rectangle = Some(RectangleSampler::new([corner, ex, ey], n, mesh.area));
            ShapeData::Mesh(mesh)
        }
        ShapeKind::Cube => {
            let (pos, idx) = cube();
            let uvs = cube_uvs(&pos);
            let pos = pos.into_iter().map(|p| m.transform_point3(p)).collect();
            let mut mesh = mesh(i, pos, vec![], idx, flip, mirrored)?;
            mesh.uvs = uvs;
            ShapeData::Mesh(mesh)
        }
        ShapeKind::Mesh {
            positions,
            normals,
            indices,
        } => {
            let pos = positions
                .par_iter()
                .map(|&p| m.transform_point3(p))
                .collect();
            let nm = Mat3::from(m.matrix3).inverse().transpose();
            let nrm = normals
                .par_iter()
                .map(|&n| (nm * n).normalize_or_zero())
                .collect();
            ShapeData::Mesh(mesh(i, pos, nrm, indices.clone(), flip, false)?)
        }
        &ShapeKind::Sphere { center, radius } => sphere(i, m, center, radius, flip)?,
        // Its group is built on its own (`geometry/instances.rs`).
        ShapeKind::Instance(_) => ShapeData::Instance,
        ShapeKind::Disk => disk(m, flip),
        &ShapeKind::Cylinder { p0, p1, radius } => ShapeData::Cylinder(
            super::cylinder::CylinderData::new(i, m, p0, p1, radius, flip)?,
        ),
        // Read by `file_mesh::build` above.
        ShapeKind::Obj { .. } | ShapeKind::Ply { .. } | ShapeKind::Serialized { .. } => {
            return Err(GeometryError::InvalidShape {
                shape: i,
                what: "a mesh file shape was not read".into(),
            })
        }
    })
}

/// Mitsuba's cube: [−1,1]³, 4 vertices and 2 triangles per face, counter-clockwise seen
/// from outside.
pub(super) fn cube() -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let mut pos = Vec::with_capacity(24);
    let mut idx = Vec::with_capacity(12);
    for a in 0..3 {
        let (n, u, v) = (
            Vec3::AXES[a],
            Vec3::AXES[(a + 1) % 3],
            Vec3::AXES[(a + 2) % 3],
        );
        for s in [-1.0f32, 1.0] {
            let c = n * s;
            let base = pos.len() as u32;
            pos.extend([c - u - v, c + u - v, c + u + v, c - u + v]);
            // u × v = n: counter-clockwise about +n; reverse on the −n face.
            if s > 0.0 {
                idx.extend([[base, base + 1, base + 2], [base, base + 2, base + 3]]);
            } else {
                idx.extend([[base, base + 2, base + 1], [base, base + 3, base + 2]]);
            }
        }
    }
    (pos, idx)
}

/// The texture coordinates of [`cube`]'s vertices: those of Mitsuba 3's cube mesh, an
/// affine map of the position on each face (read from Mitsuba 3.9.1's vertex buffers;
/// `tests/data/REFERENCES.md`, "Textures").
pub(super) fn cube_uvs(pos: &[Vec3]) -> Vec<Vec2> {
    pos.iter()
        .enumerate()
        .map(|(i, p)| {
            let h = |x: f32| 0.5 * (x + 1.0);
            // Faces in `cube`'s order: −x, +x, −y, +y, −z, +z.
            match i / 4 {
                0 => Vec2::new(h(p.y), h(p.z)),
                1 => Vec2::new(h(p.y), h(-p.z)),
                2 => Vec2::new(h(p.z), h(p.x)),
                3 => Vec2::new(h(-p.x), h(-p.z)),
                4 => Vec2::new(h(-p.y), h(p.x)),
                _ => Vec2::new(h(p.y), h(p.x)),
            }
        })
        .collect()
}

/// World to object directions of a sphere's `to_world` (its rotation, possibly mirrored;
/// the scale is undone by normalising), for its texture coordinates; the identity for other
/// shapes and for transforms that are not invertible (refused elsewhere).
pub(super) fn uv_frame(desc: &ShapeDesc) -> Mat3 {
    let m = Mat3::from_mat4(desc.to_world);
    match desc.kind {
        ShapeKind::Sphere { .. } if m.determinant().is_normal() => m.inverse(),
        _ => Mat3::IDENTITY,
    }
}

fn sphere(
    i: usize,
    m: &Affine3A,
    center: Vec3,
    radius: f32,
    flip: bool,
) -> Result<ShapeData, GeometryError> {
    if !(radius > 0.0 && radius.is_finite() && center.is_finite()) {
        return Err(GeometryError::InvalidShape {
            shape: i,
            what: format!("sphere radius {radius} must be finite and > 0, centre finite"),
        });
    }
    let cols = [m.matrix3.x_axis, m.matrix3.y_axis, m.matrix3.z_axis].map(Vec3::from);
    let s = cols.map(Vec3::length);
    let tol = 1e-4 * s[0];
    let uniform = (s[1] - s[0]).abs() <= tol && (s[2] - s[0]).abs() <= tol;
    let orthogonal = cols[0].dot(cols[1]).abs() <= tol * s[0]
        && cols[1].dot(cols[2]).abs() <= tol * s[0]
        && cols[0].dot(cols[2]).abs() <= tol * s[0];
    if !(uniform && orthogonal) {
        return Err(GeometryError::NonUniformSphereScale { shape: i });
    }
    Ok(ShapeData::Sphere {
        center: m.transform_point3(center),
        radius: radius * (s[0] + s[1] + s[2]) / 3.0,
        flip,
    })
}

fn disk(m: &Affine3A, flip: bool) -> ShapeData {
    let nm = Mat3::from(m.matrix3).inverse().transpose();
    let n = (nm * Vec3::Z).normalize();
    let ex = m.transform_vector3(Vec3::X);
    let ey = m.transform_vector3(Vec3::Y);
    ShapeData::Disk(DiskData {
        to_world: *m,
        to_object: m.inverse(),
        normal: if flip { -n } else { n },
        area: std::f32::consts::PI * ex.cross(ey).length(),
    })
}
