//! The `ply` shape's reader: Stanford PLY meshes in ASCII and binary (little and big
//! endian) encodings, parsed by the `ply-rs-bw` crate.
//!
//! As Mitsuba 3 reads them: the `vertex` element gives positions `x`, `y`, `z` (required),
//! normals `nx`, `ny`, `nz` (all three, or none) and texture coordinates under any of the
//! names `u`/`v`, `s`/`t`, `texture_u`/`texture_v`, `texture_s`/`texture_t` (not flipped);
//! the `face` element's list `vertex_indices` (or `vertex_index`) gives the faces. Any
//! scalar type is accepted for any of them. Other properties (colours, …) and other
//! elements are read past and ignored. Faces with more than three corners are
//! fan-triangulated (Mitsuba 3.9 refuses them; the OBJ reader splits them the same way).
//!
//! Binary payloads are decoded by `mesh_file/ply_binary.rs` (the same values, faster); ASCII
//! ones by `ply-rs-bw`.

use super::ply_binary::{scalar_size, ItemError, Payload};
use super::{error, push_fan, read_file, TriangleMesh};
use crate::scene_error::{SceneError, SceneErrorKind};
use glam::{Vec2, Vec3};
use ply_rs_bw::parser::{Parser, Reader};
use ply_rs_bw::ply::{
    ElementDef, Encoding, Header, PropertyAccess, PropertyAccessResult, PropertyType, ScalarType,
};
use std::path::Path;

/// Names of the texture coordinate pair, in the order they are looked for.
const UV_NAMES: [[&str; 2]; 4] = [
    ["u", "v"],
    ["s", "t"],
    ["texture_u", "texture_v"],
    ["texture_s", "texture_t"],
];

/// Reads the PLY file at `path`, a regular file of at most
/// [`MAX_MESH_BYTES`](super::MAX_MESH_BYTES). Errors name the file and the header line,
/// or the element and its index in the data.
///
/// The header is read first and what the file would take in memory (its bytes, and the
/// mesh its element counts describe) is checked against the memory budget
/// ([`crate::memory`]) before the rest is read.
pub fn read_ply(path: &Path) -> Result<TriangleMesh, SceneError> {
    use std::io::Read;
    const HEAD: u64 = 1 << 20;
    let io = |e: std::io::Error| SceneError::io(path, &e);
    let file = crate::io::open_regular(path).map_err(io)?;
    let len = file.metadata().map_err(io)?.len();
    let mut head = Vec::new();
    file.take(HEAD).read_to_end(&mut head).map_err(io)?;
    let header = Parser::<Skip>::new().read_header(&mut Reader::new(&head[..]));
    match header {
        Ok(header) => check_memory(&header, len).map_err(|(name, m)| {
            let line = element_line(&head, &name);
            let at = Some(format!("element \"{name}\""));
            error(Some(path), line, at, SceneErrorKind::Memory(m))
        })?,
        // A header that does not end in the first MiB of a larger file: refused unread.
        Err(_) if len > HEAD => {
            let m = format!("no end_header in the first {HEAD} bytes");
            return Err(error(
                Some(path),
                None,
                Some("header".into()),
                SceneErrorKind::Ply(m),
            ));
        }
        Err(_) => {} // parse_ply says what is wrong
    }
    drop(head);
    parse_ply(&read_file(path)?, Some(path))
}

/// The header line (1-based) that declares element `name`, if it is found.
fn element_line(bytes: &[u8], name: &str) -> Option<u32> {
    let text = String::from_utf8_lossy(&bytes[..bytes.len().min(1 << 20)]);
    let k = text.lines().position(|l| {
        let mut w = l.split_whitespace();
        w.next() == Some("element") && w.next() == Some(name)
    })?;
    u32::try_from(k + 1).ok()
}

/// Checks what reading a file of `len` bytes with `header` would take in memory against
/// the budget: the file's bytes, and per vertex its position, normal and texture
/// coordinates (and, for ASCII, the parsed row), per face at least one triangle (and, for
/// ASCII, the parsed row and its list).
fn check_memory(header: &Header, len: u64) -> Result<(), (String, String)> {
    let ascii = header.encoding == Encoding::Ascii;
    let mut need = len;
    for (name, def) in &header.elements {
        let per = match name.as_str() {
            "vertex" => {
                let row = if ascii {
                    std::mem::size_of::<VertexRow>()
                } else {
                    0
                };
                12 + 12 + 8 + row
            }
            "face" => {
                12 + if ascii {
                    std::mem::size_of::<FaceRow>() + 12
                } else {
                    0
                }
            }
            _ => 0,
        };
        let bytes = crate::memory::bytes(def.count as u64, per);
        need = need.saturating_add(bytes);
        if need > crate::memory::available() {
            let what = format!(
                "reading this file ({len} bytes, element \"{name}\" of {} items)",
                def.count
            );
            return Err((name.clone(), crate::memory::over_budget(&what, need)));
        }
    }
    Ok(())
}

/// Parses a PLY file held in memory; `path` is used in messages.
///
/// ```
/// use mcrt_render::mesh_file::ply::parse_ply;
/// let text = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
///             property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
///             end_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";
/// let mesh = parse_ply(text.as_bytes(), None).unwrap();
/// assert_eq!(mesh.indices, vec![[0, 1, 2], [0, 2, 3]]);
/// assert!(mesh.normals.is_empty() && mesh.uvs.is_empty());
/// ```
pub fn parse_ply(bytes: &[u8], path: Option<&Path>) -> Result<TriangleMesh, SceneError> {
    let fail = |line: Option<usize>, element: Option<String>, m: String| {
        let line = line.map(|l| u32::try_from(l).unwrap_or(u32::MAX));
        error(path, line, element, SceneErrorKind::Ply(m))
    };
    let mut reader = Reader::new(bytes);
    let header = Parser::<Skip>::new()
        .read_header(&mut reader)
        .map_err(|e| fail(e.line(), Some("header".into()), e.to_string()))?;
    check_budget(&header, bytes.len()).map_err(|m| fail(None, Some("header".into()), m))?;
    check_memory(&header, bytes.len() as u64).map_err(|(name, m)| {
        let (line, at) = (
            element_line(bytes, &name),
            Some(format!("element \"{name}\"")),
        );
        error(path, line, at, SceneErrorKind::Memory(m))
    })?;
    let ascii = header.encoding == Encoding::Ascii;
    // Layouts first, so that a wrong header is reported before any data is read.
    let mut layout = VertexLayout {
        normals: false,
        uvs: false,
    };
    for (name, def) in &header.elements {
        let at = || Some(format!("element \"{name}\""));
        match name.as_str() {
            "vertex" => layout = VertexLayout::of(def).map_err(|m| fail(None, at(), m))?,
            "face" => face_layout(def).map_err(|m| fail(None, at(), m))?,
            _ => {}
        }
    }
    let mut mesh = TriangleMesh::default();
    let (mut has_vertex, mut has_face) = (false, false);
    // Binary files: the bytes after the header, decoded here.
    let big = header.encoding == Encoding::BinaryBigEndian;
    let rest = &bytes[bytes.len() - reader.get_ref().len()..];
    let mut binary = (!ascii).then(|| Payload::new(rest, big));
    for (name, def) in &header.elements {
        let place = |i: Option<usize>| match i {
            Some(i) => format!("element \"{name}\" {i} of {}", def.count),
            None => format!("element \"{name}\""),
        };
        // Where an ASCII data error is: its line (binary ones are located by `item`).
        let locate = |e: ply_rs_bw::parser::ParseError| {
            let line = if ascii { e.line() } else { None };
            fail(line, Some(place(None)), e.to_string())
        };
        let item = |(i, m): ItemError| fail(None, Some(place(Some(i))), m);
        if (name == "vertex" && has_vertex) || (name == "face" && has_face) {
            return Err(fail(
                None,
                Some(place(None)),
                "a second such element".into(),
            ));
        }
        match (name.as_str(), binary.as_mut()) {
            ("vertex", Some(b)) => {
                has_vertex = true;
                b.vertices(def, layout.normals, layout.uvs, &mut mesh)
                    .map_err(item)?;
            }
            ("face", Some(b)) => {
                has_face = true;
                b.faces(def, &mut mesh).map_err(item)?;
            }
            (_, Some(b)) => b.skip(def).map_err(item)?,
            ("vertex", None) => {
                has_vertex = true;
                let rows = Parser::<VertexRow>::new()
                    .read_payload_for_element(&mut reader, def, &header)
                    .map_err(locate)?;
                mesh.positions = rows.iter().map(|r| Vec3::from(r.p)).collect();
                if layout.normals {
                    mesh.normals = rows.iter().map(|r| Vec3::from(r.n)).collect();
                }
                if layout.uvs {
                    mesh.uvs = rows.iter().map(|r| Vec2::from(r.uv)).collect();
                }
            }
            ("face", None) => {
                has_face = true;
                let rows = Parser::<FaceRow>::new()
                    .read_payload_for_element(&mut reader, def, &header)
                    .map_err(locate)?;
                mesh.indices.reserve(rows.len());
                for (i, r) in rows.iter().enumerate() {
                    if r.negative {
                        return Err(fail(None, Some(place(Some(i))), "negative index".into()));
                    }
                    if r.corners.len() < 3 {
                        let m = format!("a face needs 3 corners, found {}", r.corners.len());
                        return Err(fail(None, Some(place(Some(i))), m));
                    }
                    push_fan(&mut mesh.indices, &r.corners);
                }
            }
            (_, None) => {
                Parser::<Skip>::new()
                    .read_payload_for_element(&mut reader, def, &header)
                    .map_err(locate)?;
            }
        }
    }
    if !has_vertex {
        return Err(fail(None, None, "no \"vertex\" element".into()));
    }
    mesh.check().map_err(|m| fail(None, None, m))?;
    Ok(mesh)
}

/// Refuses a header whose elements could not fit in the file: each element takes at least
/// one byte in ASCII (its line break; two per property) and its fixed-size properties' bytes in
/// binary, so no count can make the reader allocate beyond what `len` bytes can fill.
fn check_budget(header: &Header, len: usize) -> Result<(), String> {
    let mut need: u128 = 0;
    for (name, def) in &header.elements {
        let per: u128 = match header.encoding {
            Encoding::Ascii => 2 * def.properties.len() as u128,
            _ => def
                .properties
                .values()
                .map(|p| match &p.data_type {
                    PropertyType::Scalar(t) | PropertyType::List(t, _) => scalar_size(t) as u128,
                })
                .sum(),
        };
        need += def.count as u128 * per.max(1);
        if need > len as u128 {
            return Err(format!(
                "element \"{name}\" declares {} items, more than the file's {len} bytes can hold",
                def.count
            ));
        }
    }
    Ok(())
}

/// Which vertex attributes the header declares.
struct VertexLayout {
    normals: bool,
    uvs: bool,
}

impl VertexLayout {
    fn of(def: &ElementDef) -> Result<Self, String> {
        let scalar = |n: &str| match def.properties.get(n).map(|p| &p.data_type) {
            None => Ok(false),
            Some(PropertyType::Scalar(_)) => Ok(true),
            Some(PropertyType::List(..)) => Err(format!("vertex property \"{n}\" is a list")),
        };
        for n in ["x", "y", "z"] {
            if !scalar(n)? {
                return Err(format!("no vertex property \"{n}\""));
            }
        }
        let normals = [scalar("nx")?, scalar("ny")?, scalar("nz")?];
        if normals.iter().any(|&b| b) && !normals.iter().all(|&b| b) {
            return Err("vertex normals need all of nx, ny and nz".into());
        }
        let mut uvs = false;
        for [u, v] in UV_NAMES {
            match (scalar(u)?, scalar(v)?) {
                (true, true) => uvs = true,
                (false, false) => {}
                _ => {
                    return Err(format!(
                        "texture coordinate \"{u}\" without \"{v}\" or back"
                    ))
                }
            }
        }
        Ok(Self {
            normals: normals[0],
            uvs,
        })
    }
}

/// Checks that the face element has its index list.
fn face_layout(def: &ElementDef) -> Result<(), String> {
    let list = ["vertex_indices", "vertex_index"]
        .iter()
        .find_map(|n| def.properties.get(*n));
    match list.map(|p| &p.data_type) {
        Some(PropertyType::List(_, t)) if !matches!(t, ScalarType::Float | ScalarType::Double) => {
            Ok(())
        }
        Some(_) => Err("\"vertex_indices\" must be a list of integers".into()),
        None => Err("no face property \"vertex_indices\" or \"vertex_index\"".into()),
    }
}

/// An element read past: every property ignored, nothing kept.
struct Skip;

impl PropertyAccess for Skip {
    fn new() -> Self {
        Skip
    }
}

/// One vertex: position, normal and texture coordinates, whichever the file has.
struct VertexRow {
    p: [f32; 3],
    n: [f32; 3],
    uv: [f32; 2],
}

impl VertexRow {
    fn set(&mut self, name: &str, v: f64) -> PropertyAccessResult {
        let slot = match name {
            "x" => &mut self.p[0],
            "y" => &mut self.p[1],
            "z" => &mut self.p[2],
            "nx" => &mut self.n[0],
            "ny" => &mut self.n[1],
            "nz" => &mut self.n[2],
            "u" | "s" | "texture_u" | "texture_s" => &mut self.uv[0],
            "v" | "t" | "texture_v" | "texture_t" => &mut self.uv[1],
            _ => return PropertyAccessResult::Ignored,
        };
        *slot = v as f32;
        PropertyAccessResult::Set
    }
}

impl PropertyAccess for VertexRow {
    fn new() -> Self {
        Self {
            p: [0.0; 3],
            n: [0.0; 3],
            uv: [0.0; 2],
        }
    }
    fn set_char(&mut self, name: &str, v: i8) -> PropertyAccessResult {
        self.set(name, v.into())
    }
    fn set_uchar(&mut self, name: &str, v: u8) -> PropertyAccessResult {
        self.set(name, v.into())
    }
    fn set_short(&mut self, name: &str, v: i16) -> PropertyAccessResult {
        self.set(name, v.into())
    }
    fn set_ushort(&mut self, name: &str, v: u16) -> PropertyAccessResult {
        self.set(name, v.into())
    }
    fn set_int(&mut self, name: &str, v: i32) -> PropertyAccessResult {
        self.set(name, v.into())
    }
    fn set_uint(&mut self, name: &str, v: u32) -> PropertyAccessResult {
        self.set(name, v.into())
    }
    fn set_float(&mut self, name: &str, v: f32) -> PropertyAccessResult {
        self.set(name, v.into())
    }
    fn set_double(&mut self, name: &str, v: f64) -> PropertyAccessResult {
        self.set(name, v)
    }
}

/// One face: its corner indices, and whether one was negative.
struct FaceRow {
    corners: Vec<u32>,
    negative: bool,
}

impl FaceRow {
    fn set<T: TryInto<u32> + Copy>(&mut self, name: &str, v: Vec<T>) -> PropertyAccessResult {
        if name != "vertex_indices" && name != "vertex_index" {
            return PropertyAccessResult::Ignored;
        }
        self.corners.clear();
        for x in v {
            match x.try_into() {
                Ok(i) => self.corners.push(i),
                Err(_) => self.negative = true,
            }
        }
        PropertyAccessResult::Set
    }
}

impl PropertyAccess for FaceRow {
    fn new() -> Self {
        Self {
            corners: Vec::new(),
            negative: false,
        }
    }
    fn set_list_char(&mut self, name: &str, v: Vec<i8>) -> PropertyAccessResult {
        self.set(name, v)
    }
    fn set_list_uchar(&mut self, name: &str, v: Vec<u8>) -> PropertyAccessResult {
        self.set(name, v)
    }
    fn set_list_short(&mut self, name: &str, v: Vec<i16>) -> PropertyAccessResult {
        self.set(name, v)
    }
    fn set_list_ushort(&mut self, name: &str, v: Vec<u16>) -> PropertyAccessResult {
        self.set(name, v)
    }
    fn set_list_int(&mut self, name: &str, v: Vec<i32>) -> PropertyAccessResult {
        self.set(name, v)
    }
    fn set_list_uint(&mut self, name: &str, v: Vec<u32>) -> PropertyAccessResult {
        self.set(name, v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEAD: &str = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n\
                        property float y\nproperty float z\n";

    fn ascii(extra_header: &str, body: &str) -> Result<TriangleMesh, SceneError> {
        let text = format!("{HEAD}{extra_header}end_header\n{body}");
        parse_ply(text.as_bytes(), Some(Path::new("m.ply")))
    }

    #[test]
    fn ascii_triangle_and_errors_with_lines() {
        let faces = "element face 1\nproperty list uchar int vertex_indices\n";
        let m = ascii(faces, "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").unwrap();
        assert_eq!(m.indices, vec![[0, 1, 2]]);
        // Line 11 is the second vertex.
        let e = ascii(faces, "0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n").unwrap_err();
        assert!(e.to_string().contains("m.ply, line 11"), "{e}");
        let e = ascii(faces, "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n").unwrap_err();
        assert!(
            e.to_string().contains("face 0 refers to vertex 7 of 3"),
            "{e}"
        );
        let e = ascii(faces, "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n").unwrap_err();
        assert!(e.to_string().contains("negative index"), "{e}");
        let e = ascii(faces, "0 0 0\n1 0 0\n0 1 0\n").unwrap_err();
        assert!(e.to_string().contains("element \"face\""), "{e}");
        let e = ascii(faces, "0 0 0\n1 0 0\n0 1 nan\n3 0 1 2\n").unwrap_err();
        assert!(e.to_string().contains("line 12"), "{e}");
        let e = ascii(faces, "0 0 0\n1 0 0\n0 1 1e39\n3 0 1 2\n").unwrap_err();
        assert!(
            e.to_string().contains("vertex 2's position is not finite"),
            "{e}"
        );
    }

    #[test]
    fn header_budget_refuses_huge_counts() {
        let text = "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000000\n\
                    property float x\nproperty float y\nproperty float z\nend_header\n";
        let e = parse_ply(text.as_bytes(), None).unwrap_err();
        assert!(e.to_string().contains("more than the file's"), "{e}");
        let text = "ply\nformat binary_little_endian 1.0\nelement empty 1000000000000\n\
                    end_header\n";
        assert!(parse_ply(text.as_bytes(), None).is_err());
    }
}
