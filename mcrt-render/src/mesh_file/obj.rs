//! A reader for Wavefront OBJ triangle meshes: positions, texture coordinates, normals and
//! faces.
//!
//! Faces may be polygons (fan-triangulated from their first vertex) and use the forms
//! `v`, `v/vt`, `v//vn` and `v/vt/vn`, with 1-based or negative (relative) indices. As in
//! Mitsuba 3, every distinct (position, texture coordinate, normal) triple becomes one
//! vertex. Other statements (`o`, `g`, `s`, `usemtl`, `mtllib`, lines, points) are ignored.
//! Texture coordinates are kept as the file gives them; the `obj` shape flips `v` to
//! `1 − v` unless `flip_tex_coords` is false, as Mitsuba does.

pub use crate::mesh_file::TriangleMesh as ObjMesh;
use crate::scene_error::{SceneError, SceneErrorKind};
use glam::{Vec2, Vec3};
use std::collections::HashMap;
use std::path::Path;

/// Reads the OBJ file at `path`, a regular file of at most
/// [`MAX_OBJ_BYTES`](crate::io::MAX_OBJ_BYTES), line by line: a line may have at most
/// 1/1024 of the memory budget ([`crate::memory`]) and the mesh read so far must fit in
/// the budget, so a huge or sparse file is refused at the line where it passes a limit,
/// without being read whole. Errors name the file and the line. Normals (or texture
/// coordinates) are empty when some face corner has none.
pub fn read_obj(path: &Path) -> Result<ObjMesh, SceneError> {
    use std::io::{BufRead, Read};
    let io = |e: std::io::Error| SceneError::io(path, &e);
    let file = crate::io::open_regular(path).map_err(io)?;
    let cap = crate::io::MAX_OBJ_BYTES;
    if file.metadata().map_err(io)?.len() > cap {
        return Err(io(std::io::Error::other(format!(
            "longer than {cap} bytes"
        ))));
    }
    let budget = crate::memory::max_memory();
    let max_line = (budget / 1024).max(4096) as usize;
    let mut input = std::io::BufReader::with_capacity(1 << 16, file);
    let (mut r, mut bytes, mut line_no) = (Reader::default(), Vec::new(), 0u32);
    let at = |line_no: u32, m: String| {
        SceneError::new(
            Some(path),
            Some(line_no),
            None,
            None,
            SceneErrorKind::Memory(m),
        )
    };
    loop {
        bytes.clear();
        let n = (&mut input)
            .take(max_line as u64 + 1)
            .read_until(b'\n', &mut bytes)
            .map_err(io)?;
        if n == 0 {
            break;
        }
        line_no = line_no.saturating_add(1);
        if bytes.len() > max_line && bytes.last() != Some(&b'\n') {
            return Err(at(
                line_no,
                format!(
                    "the line is longer than {}, the most a line may have under the memory \
                     budget of {} (1/1024 of it); raise the limit with --max-memory",
                    crate::memory::format_size(max_line as u64),
                    crate::memory::format_size(budget)
                ),
            ));
        }
        let text = String::from_utf8_lossy(&bytes);
        let line = text.strip_suffix('\n').unwrap_or(&text);
        let line = line.strip_suffix('\r').unwrap_or(line);
        r.line(line, line_no, Some(path))?;
        let need = r.bytes_after_growth();
        if need > crate::memory::available() {
            let m = crate::memory::over_budget("the mesh read so far", need);
            return Err(at(line_no, m));
        }
    }
    r.finish(Some(path))
}

/// Parses OBJ text; `path` is used in messages.
///
/// ```
/// use mcrt_render::mesh_file::obj::parse_obj;
/// let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
/// let mesh = parse_obj(text, None).unwrap();
/// assert_eq!(mesh.positions.len(), 4);
/// assert_eq!(mesh.indices, vec![[0, 1, 2], [0, 2, 3]]);
/// assert!(mesh.normals.is_empty() && mesh.uvs.is_empty());
/// ```
pub fn parse_obj(text: &str, path: Option<&Path>) -> Result<ObjMesh, SceneError> {
    let mut r = Reader::default();
    for (i, line) in text.lines().enumerate() {
        let line_no = u32::try_from(i + 1).unwrap_or(u32::MAX);
        r.line(line, line_no, path)?;
    }
    r.finish(path)
}

/// One face corner: position, texture coordinate and normal indices (0-based).
type Corner = (usize, Option<usize>, Option<usize>);

#[derive(Default)]
struct Reader {
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    uvs: Vec<Vec2>,
    vertex_of: HashMap<Corner, u32>,
    missing_normal: bool,
    missing_uv: bool,
    mesh: ObjMesh,
}

/// The bytes of `v` once it has grown for its next item (doubled when full).
fn grown<T>(v: &Vec<T>) -> u64 {
    let cap = if v.len() == v.capacity() {
        (2 * v.capacity()).max(4)
    } else {
        v.capacity()
    };
    (cap * std::mem::size_of::<T>()) as u64
}

impl Reader {
    /// Reads line `line_no`; errors name it.
    fn line(&mut self, line: &str, line_no: u32, path: Option<&Path>) -> Result<(), SceneError> {
        self.statement(line).map_err(|m| {
            let keyword = line.split_whitespace().next().map(str::to_string);
            SceneError::new(path, Some(line_no), None, keyword, SceneErrorKind::Obj(m))
        })
    }

    /// What the lists read so far take once each has grown once more (an upper bound on
    /// what the next line can make them take).
    fn bytes_after_growth(&self) -> u64 {
        let entry = (std::mem::size_of::<(Corner, u32)>() + 1) as u64;
        let map = (self.vertex_of.capacity() as u64 * 2).max(4) * entry;
        grown(&self.positions)
            + grown(&self.normals)
            + grown(&self.uvs)
            + grown(&self.mesh.positions)
            + grown(&self.mesh.normals)
            + grown(&self.mesh.uvs)
            + grown(&self.mesh.indices)
            + map
    }

    /// The mesh, once every line is read.
    fn finish(mut self, path: Option<&Path>) -> Result<ObjMesh, SceneError> {
        if self.mesh.indices.is_empty() {
            return Err(SceneError::new(
                path,
                None,
                None,
                None,
                SceneErrorKind::Obj("the file has no faces".into()),
            ));
        }
        if self.missing_normal {
            self.mesh.normals.clear();
        }
        if self.missing_uv {
            self.mesh.uvs.clear();
        }
        Ok(self.mesh)
    }

    fn statement(&mut self, line: &str) -> Result<(), String> {
        let line = line.split('#').next().unwrap_or("");
        let mut words = line.split_whitespace();
        match words.next() {
            Some("v") => self.positions.push(vec3(words)?),
            Some("vn") => self.normals.push(vec3(words)?),
            Some("vt") => self.uvs.push(vec2(words)?),
            Some("f") => self.face(words)?,
            _ => {}
        }
        Ok(())
    }

    fn face<'a>(&mut self, words: impl Iterator<Item = &'a str>) -> Result<(), String> {
        let corners: Vec<u32> = words.map(|w| self.corner(w)).collect::<Result<_, _>>()?;
        if corners.len() < 3 {
            return Err(format!(
                "a face needs at least 3 vertices, found {}",
                corners.len()
            ));
        }
        for k in 1..corners.len() - 1 {
            self.mesh
                .indices
                .push([corners[0], corners[k], corners[k + 1]]);
        }
        Ok(())
    }

    /// The mesh vertex of one face corner `v[/vt][/vn]`, created on first use.
    fn corner(&mut self, word: &str) -> Result<u32, String> {
        let mut parts = word.split('/');
        let v = index(parts.next(), self.positions.len(), "position", word)?;
        let vt = index(parts.next(), self.uvs.len(), "texture", word)?;
        let vn = index(parts.next(), self.normals.len(), "normal", word)?;
        if parts.next().is_some() {
            return Err(format!("malformed face vertex \"{word}\""));
        }
        let v = v.ok_or_else(|| format!("face vertex \"{word}\" has no position index"))?;
        let key = (v, vt, vn);
        if let Some(&id) = self.vertex_of.get(&key) {
            return Ok(id);
        }
        let id = u32::try_from(self.mesh.positions.len())
            .map_err(|_| "more than 2^32 vertices".to_string())?;
        self.mesh.positions.push(self.positions[v]);
        match vn {
            Some(n) => self.mesh.normals.push(self.normals[n]),
            None => {
                self.missing_normal = true;
                self.mesh.normals.push(Vec3::ZERO);
            }
        }
        match vt {
            Some(t) => self.mesh.uvs.push(self.uvs[t]),
            None => {
                self.missing_uv = true;
                self.mesh.uvs.push(Vec2::ZERO);
            }
        }
        self.vertex_of.insert(key, id);
        Ok(id)
    }
}

/// Three finite coordinates (a fourth, `w`, is ignored).
fn vec3<'a>(mut words: impl Iterator<Item = &'a str>) -> Result<Vec3, String> {
    let mut c = [0.0f32; 3];
    for x in &mut c {
        let w = words.next().ok_or("expected three coordinates")?;
        *x = match w.parse::<f32>() {
            Ok(v) if v.is_finite() => v,
            _ => return Err(format!("\"{w}\" is not a finite number")),
        };
    }
    Ok(Vec3::from(c))
}

/// Two finite texture coordinates `u v` (a missing `v` is 0, as OBJ allows; a third, `w`,
/// is ignored).
fn vec2<'a>(mut words: impl Iterator<Item = &'a str>) -> Result<Vec2, String> {
    let mut c = [0.0f32; 2];
    for (k, x) in c.iter_mut().enumerate() {
        let Some(w) = words.next() else {
            if k == 0 {
                return Err("expected texture coordinates".into());
            }
            break;
        };
        *x = match w.parse::<f32>() {
            Ok(v) if v.is_finite() => v,
            _ => return Err(format!("\"{w}\" is not a finite number")),
        };
    }
    Ok(Vec2::from(c))
}

/// A 1-based or negative index into a list of `count` items; empty is `None`.
fn index(s: Option<&str>, count: usize, what: &str, word: &str) -> Result<Option<usize>, String> {
    let s = match s {
        None | Some("") => return Ok(None),
        Some(s) => s,
    };
    let i: i64 = s
        .parse()
        .map_err(|_| format!("malformed {what} index in \"{word}\""))?;
    let resolved = if i > 0 {
        i - 1
    } else if i < 0 {
        count as i64 + i
    } else {
        -1
    };
    if resolved < 0 || resolved >= count as i64 {
        return Err(format!(
            "{what} index {i} in \"{word}\" is out of range (1..={count} or negative)"
        ));
    }
    Ok(Some(resolved as usize))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn forms_negative_indices_and_dedup() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n\
                    f -3//1 -2//1 -1//1\nf 1/1/1 2/1/1 3/1/1\nf 1//1 2//1 3//1\n";
        let m = parse_obj(text, None).unwrap();
        assert_eq!(m.positions.len(), 6);
        assert_eq!(m.normals, vec![Vec3::Z; 6]);
        assert_eq!(m.indices, vec![[0, 1, 2], [3, 4, 5], [0, 1, 2]]);
        // One corner without a texture coordinate: none are kept.
        assert!(m.uvs.is_empty());
        let uv = parse_obj(
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.25 0.5\nvt 1\nf 1/1 2/2 3/1\n",
            None,
        )
        .unwrap();
        assert_eq!(
            uv.uvs,
            vec![Vec2::new(0.25, 0.5), Vec2::X, Vec2::new(0.25, 0.5)]
        );
        assert!(parse_obj("vt\n", None).is_err());
        assert!(parse_obj("vt 0 nan\n", None).is_err());
    }

    #[test]
    fn errors_name_the_line() {
        let e = parse_obj("v 0 0 0\nv 1 0 0\nf 1 2 7\n", Some(Path::new("m.obj"))).unwrap_err();
        assert_eq!(e.line, Some(3));
        assert!(e.to_string().contains("m.obj, line 3"), "{e}");
        assert!(parse_obj("v 0 0\n", None).is_err());
        assert!(parse_obj("v 0 0 0\nf 1 1\n", None).is_err());
        assert!(parse_obj("v 0 0 0\nf 0 1 1\n", None).is_err());
        assert!(parse_obj("v 0 0 nan\n", None).is_err());
        assert!(parse_obj("# nothing\n", None).is_err());
        assert!(parse_obj("v 0 0 0\nf 1/1 1 1\n", None).is_err());
    }
}
