//! The `serialized` shape's reader: Mitsuba's compressed mesh format, decompressed by the
//! `flate2` crate, read from the format's description in Mitsuba 3's documentation of the
//! plugin.
//!
//! Little endian throughout. A file holds one or more meshes, each a 4-byte header (the
//! format identifier `0x041C` and the version, 3 or 4, as `u16`s) followed by one zlib
//! stream: `u32` flags (`0x1` normals, `0x2` texture coordinates, `0x8` colours, `0x10`
//! face normals, `0x2000` double precision), in version 4 the shape's name ending in a
//! zero byte, the `u64` vertex and triangle counts, then the positions, normals,
//! texture coordinates and colours as present (three, three, two and three values per
//! vertex, `f32` or `f64`), then three `u32` indices per triangle. The file ends with a
//! dictionary: the offset of every mesh (`u64` in version 4, `u32` in version 3) and their
//! `u32` count, which `shape_index` looks up.

use super::{error, read_file, TriangleMesh};
use crate::scene_error::{SceneError, SceneErrorKind};
use flate2::read::ZlibDecoder;
use glam::{Vec2, Vec3};
use std::io::Read;
use std::path::Path;

/// The format identifier that starts every mesh.
pub const SERIALIZED_MAGIC: u16 = 0x041C;

/// Flag bits of a mesh's header.
const HAS_NORMALS: u32 = 0x1;
const HAS_UVS: u32 = 0x2;
const HAS_COLORS: u32 = 0x8;
const FACE_NORMALS: u32 = 0x10;
const DOUBLE: u32 = 0x2000;

/// Longest shape name read, in bytes.
const MAX_NAME: usize = 1 << 16;

/// Most bytes one byte of a zlib stream can inflate to (deflate's limit is 1032:1, plus
/// slack), used to refuse counts no file of its size could hold.
const MAX_INFLATION: u64 = 1040;

/// One mesh of a `serialized` file.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SerializedMesh {
    /// The geometry.
    pub mesh: TriangleMesh,
    /// The shape's name (empty in version 3 files).
    pub name: String,
    /// The file asks for face normals (flag `0x10`).
    pub face_normals: bool,
}

/// Reads mesh `shape_index` of the `serialized` file at `path` (a regular file of at most
/// [`MAX_MESH_BYTES`](super::MAX_MESH_BYTES)). Errors name the file and the mesh.
pub fn read_serialized(path: &Path, shape_index: u32) -> Result<SerializedMesh, SceneError> {
    parse_serialized(&read_file(path)?, shape_index, Some(path))
}

/// Parses mesh `shape_index` of a `serialized` file held in memory; `path` is used in
/// messages. See [`write_serialized`] for an example.
pub fn parse_serialized(
    bytes: &[u8],
    shape_index: u32,
    path: Option<&Path>,
) -> Result<SerializedMesh, SceneError> {
    let place = format!("mesh {shape_index}");
    let fail = |m: String| {
        error(
            path,
            None,
            Some(place.clone()),
            SceneErrorKind::Serialized(m),
        )
    };
    let (version, offset) = locate(bytes, shape_index).map_err(fail)?;
    let stream = &bytes[offset + 4..];
    let mut z = Stream(ZlibDecoder::new(stream));
    read_mesh(&mut z, version, stream.len()).map_err(fail)
}

/// The version and the byte offset of mesh `index`.
fn locate(bytes: &[u8], index: u32) -> Result<(u16, usize), String> {
    let version = header(bytes, 0)?;
    if index == 0 {
        return Ok((version, 0));
    }
    let len = bytes.len();
    let count = le_u32(bytes, len.saturating_sub(4)).ok_or("no end-of-file dictionary")?;
    if index >= count {
        return Err(format!(
            "shape_index {index} is out of range: the file holds {count} meshes"
        ));
    }
    let entry = if version == 4 { 8 } else { 4 };
    let from_end = (count - index) as usize * entry + 4;
    let at = len
        .checked_sub(from_end)
        .ok_or("the end-of-file dictionary is longer than the file")?;
    let offset = match version {
        4 => le_u64(bytes, at).map(|o| usize::try_from(o).unwrap_or(usize::MAX)),
        _ => le_u32(bytes, at).map(|o| o as usize),
    }
    .ok_or("truncated dictionary")?;
    if offset.checked_add(4).is_none_or(|end| end > at) {
        return Err(format!("mesh {index}'s offset {offset} is past the meshes"));
    }
    let v = header(bytes, offset)?;
    if v != version {
        return Err(format!("mesh {index} has version {v}, the file {version}"));
    }
    Ok((version, offset))
}

/// The version in the 4-byte mesh header at `at`.
fn header(bytes: &[u8], at: usize) -> Result<u16, String> {
    let word = |k| {
        bytes
            .get(at + k..at + k + 2)
            .map(|b| u16::from_le_bytes([b[0], b[1]]))
    };
    match (word(0), word(2)) {
        (Some(SERIALIZED_MAGIC), Some(v @ (3 | 4))) => Ok(v),
        (Some(SERIALIZED_MAGIC), Some(v)) => Err(format!("unsupported version {v}")),
        (Some(m), Some(_)) => Err(format!(
            "not a serialized mesh at byte {at} (identifier {m:#06x}, expected 0x041c)"
        )),
        _ => Err("truncated header".into()),
    }
}

fn le_u32(b: &[u8], at: usize) -> Option<u32> {
    Some(u32::from_le_bytes(b.get(at..at + 4)?.try_into().ok()?))
}

fn le_u64(b: &[u8], at: usize) -> Option<u64> {
    Some(u64::from_le_bytes(b.get(at..at + 8)?.try_into().ok()?))
}

/// A decompressing reader with messages for what went wrong.
struct Stream<'a>(ZlibDecoder<&'a [u8]>);

impl Stream<'_> {
    /// Exactly `n` bytes, grown as they arrive (never reserved up front).
    fn bytes(&mut self, n: u64, what: &str) -> Result<Vec<u8>, String> {
        let mut out = Vec::new();
        (&mut self.0)
            .take(n)
            .read_to_end(&mut out)
            .map_err(|e| format!("zlib stream: {e} (while reading {what})"))?;
        if (out.len() as u64) < n {
            return Err(format!(
                "truncated: {what} needs {n} bytes, the stream ends after {}",
                out.len()
            ));
        }
        Ok(out)
    }

    fn u32(&mut self, what: &str) -> Result<u32, String> {
        let b = self.bytes(4, what)?;
        Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }

    fn u64(&mut self, what: &str) -> Result<u64, String> {
        let b = self.bytes(8, what)?;
        Ok(u64::from_le_bytes(b.try_into().unwrap_or([0; 8])))
    }

    /// `n` floats of `size` bytes (4 or 8), as `f32`.
    fn floats(&mut self, n: u64, size: u64, what: &str) -> Result<Vec<f32>, String> {
        let b = self.bytes(n * size, what)?;
        Ok(if size == 8 {
            b.chunks_exact(8)
                .map(|c| f64::from_le_bytes(c.try_into().unwrap_or([0; 8])) as f32)
                .collect()
        } else {
            b.chunks_exact(4)
                .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
                .collect()
        })
    }
}

fn read_mesh(z: &mut Stream, version: u16, compressed: usize) -> Result<SerializedMesh, String> {
    let flags = z.u32("the flags")?;
    let mut name = Vec::new();
    if version == 4 {
        loop {
            match z.bytes(1, "the shape name")?[0] {
                0 => break,
                c if name.len() < MAX_NAME => name.push(c),
                _ => return Err(format!("shape name longer than {MAX_NAME} bytes")),
            }
        }
    }
    let vertices = z.u64("the vertex count")?;
    let faces = z.u64("the triangle count")?;
    if vertices > u64::from(u32::MAX) {
        return Err(format!(
            "{vertices} vertices (at most 2^32 - 1 are supported)"
        ));
    }
    let size = if flags & DOUBLE != 0 { 8 } else { 4 };
    let mut per_vertex = 3;
    for (bit, n) in [(HAS_NORMALS, 3), (HAS_UVS, 2), (HAS_COLORS, 3)] {
        if flags & bit != 0 {
            per_vertex += n;
        }
    }
    let need = u128::from(vertices) * per_vertex * size as u128 + u128::from(faces) * 12;
    if need > u128::from(compressed as u64 * MAX_INFLATION) {
        return Err(format!(
            "{vertices} vertices and {faces} triangles need {need} bytes, more than \
             {compressed} compressed bytes can hold"
        ));
    }
    let vec3s = |f: Vec<f32>| -> Vec<Vec3> { f.chunks_exact(3).map(Vec3::from_slice).collect() };
    let mut mesh = TriangleMesh {
        positions: vec3s(z.floats(vertices * 3, size, "the positions")?),
        ..TriangleMesh::default()
    };
    if flags & HAS_NORMALS != 0 {
        mesh.normals = vec3s(z.floats(vertices * 3, size, "the normals")?);
    }
    if flags & HAS_UVS != 0 {
        let f = z.floats(vertices * 2, size, "the texture coordinates")?;
        mesh.uvs = f.chunks_exact(2).map(Vec2::from_slice).collect();
    }
    if flags & HAS_COLORS != 0 {
        z.bytes(vertices * 3 * size, "the vertex colours")?;
    }
    let idx = z.bytes(faces * 12, "the triangles")?;
    mesh.indices = idx
        .chunks_exact(12)
        .map(|c| {
            let i = |k: usize| u32::from_le_bytes([c[k], c[k + 1], c[k + 2], c[k + 3]]);
            [i(0), i(4), i(8)]
        })
        .collect();
    // The stream must end here; reading its end checks its checksum.
    match z.0.read(&mut [0u8; 1]) {
        Ok(0) => {}
        Ok(_) => return Err("data after the triangles in the mesh's stream".into()),
        Err(e) => return Err(format!("zlib stream: {e} (at its end)")),
    }
    mesh.check()?;
    Ok(SerializedMesh {
        mesh,
        name: String::from_utf8_lossy(&name).into_owned(),
        face_normals: flags & FACE_NORMALS != 0,
    })
}

/// Writes `meshes` as a version-4, single-precision `serialized` file (with normals and
/// texture coordinates where a mesh has them), the format [`parse_serialized`] reads.
///
/// ```
/// use mcrt::glam::Vec3;
/// use mcrt_render::mesh_file::serialized::{parse_serialized, write_serialized};
/// use mcrt_render::mesh_file::TriangleMesh;
/// let tri = TriangleMesh {
///     positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
///     indices: vec![[0, 1, 2]],
///     ..TriangleMesh::default()
/// };
/// let quad = TriangleMesh {
///     positions: vec![Vec3::ZERO, Vec3::X, Vec3::ONE, Vec3::Y],
///     indices: vec![[0, 1, 2], [0, 2, 3]],
///     ..TriangleMesh::default()
/// };
/// let bytes = write_serialized(&[("tri", &tri), ("quad", &quad)]);
/// let second = parse_serialized(&bytes, 1, None).unwrap();
/// assert_eq!((second.name.as_str(), &second.mesh), ("quad", &quad));
/// assert!(parse_serialized(&bytes, 2, None).is_err());
/// ```
pub fn write_serialized(meshes: &[(&str, &TriangleMesh)]) -> Vec<u8> {
    use flate2::write::ZlibEncoder;
    use std::io::Write;
    let mut out = Vec::new();
    let mut offsets = Vec::new();
    for (name, m) in meshes {
        offsets.push(out.len() as u64);
        out.extend(SERIALIZED_MAGIC.to_le_bytes());
        out.extend(4u16.to_le_bytes());
        let mut flags = 0x1000;
        flags |= if m.normals.is_empty() { 0 } else { HAS_NORMALS };
        flags |= if m.uvs.is_empty() { 0 } else { HAS_UVS };
        let mut raw: Vec<u8> = Vec::new();
        raw.extend(u32::to_le_bytes(flags));
        raw.extend(name.bytes().filter(|&b| b != 0));
        raw.push(0);
        raw.extend((m.positions.len() as u64).to_le_bytes());
        raw.extend((m.indices.len() as u64).to_le_bytes());
        let floats = m
            .positions
            .iter()
            .chain(&m.normals)
            .flat_map(|v| v.to_array());
        let floats = floats.chain(m.uvs.iter().flat_map(|v| v.to_array()));
        raw.extend(floats.flat_map(f32::to_le_bytes));
        raw.extend(m.indices.iter().flatten().flat_map(|i| i.to_le_bytes()));
        let mut enc = ZlibEncoder::new(Vec::new(), flate2::Compression::default());
        // Writing to a Vec cannot fail.
        let _ = enc.write_all(&raw);
        out.extend(enc.finish().unwrap_or_default());
    }
    for o in &offsets {
        out.extend(o.to_le_bytes());
    }
    out.extend((offsets.len() as u32).to_le_bytes());
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quad() -> TriangleMesh {
        TriangleMesh {
            positions: vec![Vec3::ZERO, Vec3::X, Vec3::ONE, Vec3::Y],
            normals: vec![Vec3::Z; 4],
            uvs: vec![Vec2::ZERO, Vec2::X, Vec2::ONE, Vec2::Y],
            indices: vec![[0, 1, 2], [0, 2, 3]],
        }
    }

    #[test]
    fn round_trip_and_dictionary() {
        let q = quad();
        let bytes = write_serialized(&[("a", &q), ("b", &q)]);
        for i in 0..2 {
            let m = parse_serialized(&bytes, i, None).unwrap();
            assert_eq!(m.mesh, q);
            assert!(!m.face_normals);
        }
        let e = parse_serialized(&bytes, 7, Some(Path::new("x.serialized"))).unwrap_err();
        assert!(e.to_string().contains("x.serialized, in mesh 7"), "{e}");
        assert!(e.to_string().contains("holds 2 meshes"), "{e}");
    }

    #[test]
    fn damage_is_an_error() {
        let bytes = write_serialized(&[("a", &quad())]);
        // Cutting into the mesh's stream (before the 12-byte dictionary) is an error; no
        // single-byte change panics.
        for n in 0..bytes.len() - 12 {
            assert!(
                parse_serialized(&bytes[..n], 0, None).is_err(),
                "cut at {n}"
            );
        }
        for k in 0..bytes.len() {
            let mut b = bytes.clone();
            b[k] ^= 0x5a;
            let _ = parse_serialized(&b, 0, None);
        }
        let mut b = bytes.clone();
        b[0] = 0;
        let e = parse_serialized(&b, 0, None).unwrap_err();
        assert!(e.to_string().contains("identifier"), "{e}");
        b = bytes.clone();
        b[2] = 5;
        assert!(parse_serialized(&b, 0, None).is_err());
        b = bytes.clone();
        b[10] ^= 0xff;
        assert!(parse_serialized(&b, 0, None).is_err());
    }
}
