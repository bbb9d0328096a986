//! The payload of a binary PLY file (either byte order), decoded straight from the bytes
//! with the header's property layout worked out once per element instead of per value.
//! `ply.rs` parses the header with `ply-rs-bw` and hands the bytes after it here; values
//! are read exactly as its row types take them (each scalar through `f64`).

use super::{push_fan, TriangleMesh};
use glam::{Vec2, Vec3};
use ply_rs_bw::ply::{ElementDef, PropertyType, ScalarType};

/// Where a vertex property's value goes: position, normal or texture coordinate
/// component (0–7), or nowhere.
fn vertex_slot(name: &str) -> Option<usize> {
    Some(match name {
        "x" => 0,
        "y" => 1,
        "z" => 2,
        "nx" => 3,
        "ny" => 4,
        "nz" => 5,
        "u" | "s" | "texture_u" | "texture_s" => 6,
        "v" | "t" | "texture_v" | "texture_t" => 7,
        _ => return None,
    })
}

/// A decoding error: the index of the element item it is in, and what is wrong.
pub(super) type ItemError = (usize, String);

/// The bytes after the header, read front to back.
pub(super) struct Payload<'a> {
    bytes: &'a [u8],
    big_endian: bool,
}

impl<'a> Payload<'a> {
    /// The payload `bytes` in the given byte order.
    pub(super) fn new(bytes: &'a [u8], big_endian: bool) -> Self {
        Self { bytes, big_endian }
    }

    /// The next `N` bytes in little-endian order.
    #[inline(always)]
    fn take<const N: usize>(&mut self) -> Option<[u8; N]> {
        let (head, rest) = self.bytes.split_first_chunk::<N>()?;
        self.bytes = rest;
        let mut b = *head;
        if self.big_endian {
            b.reverse();
        }
        Some(b)
    }

    /// The next scalar of type `t`, as `f64` (exact for every PLY type).
    #[inline(always)]
    fn scalar(&mut self, t: &ScalarType) -> Option<f64> {
        Some(match t {
            ScalarType::Char => i8::from_le_bytes(self.take()?).into(),
            ScalarType::UChar => u8::from_le_bytes(self.take()?).into(),
            ScalarType::Short => i16::from_le_bytes(self.take()?).into(),
            ScalarType::UShort => u16::from_le_bytes(self.take()?).into(),
            ScalarType::Int => i32::from_le_bytes(self.take()?).into(),
            ScalarType::UInt => u32::from_le_bytes(self.take()?).into(),
            ScalarType::Float => f32::from_le_bytes(self.take()?).into(),
            ScalarType::Double => f64::from_le_bytes(self.take()?),
        })
    }

    /// A list's length (of integer type `t`).
    fn count(&mut self, t: &ScalarType) -> Result<usize, String> {
        let v = self.scalar(t).ok_or_else(ends)?;
        if matches!(t, ScalarType::Float | ScalarType::Double) || v < 0.0 {
            return Err(format!("list length {v} is not a count"));
        }
        Ok(v as usize)
    }

    /// Reads item `i` of an element, calling `scalar(k, value)` for its `k`th property
    /// when a scalar and `list(k, values)` when a list (`values` reused between calls).
    fn item(
        &mut self,
        def: &ElementDef,
        values: &mut Vec<f64>,
        mut scalar: impl FnMut(usize, f64),
        mut list: impl FnMut(usize, &[f64]),
    ) -> Result<(), String> {
        for (k, p) in def.properties.values().enumerate() {
            match &p.data_type {
                PropertyType::Scalar(t) => scalar(k, self.scalar(t).ok_or_else(ends)?),
                PropertyType::List(ct, t) => {
                    let n = self.count(ct)?;
                    values.clear();
                    for _ in 0..n {
                        values.push(self.scalar(t).ok_or_else(ends)?);
                    }
                    list(k, values);
                }
            }
        }
        Ok(())
    }

    /// Reads the `vertex` element into `mesh` (normals and uvs when `normals`, `uvs`).
    pub(super) fn vertices(
        &mut self,
        def: &ElementDef,
        normals: bool,
        uvs: bool,
        mesh: &mut TriangleMesh,
    ) -> Result<(), ItemError> {
        let slots: Vec<Option<usize>> = def.properties.keys().map(|n| vertex_slot(n)).collect();
        mesh.positions.reserve(def.count);
        mesh.normals.reserve(if normals { def.count } else { 0 });
        mesh.uvs.reserve(if uvs { def.count } else { 0 });
        let mut push = |row: &[f32; 8]| {
            mesh.positions.push(Vec3::new(row[0], row[1], row[2]));
            if normals {
                mesh.normals.push(Vec3::new(row[3], row[4], row[5]));
            }
            if uvs {
                mesh.uvs.push(Vec2::new(row[6], row[7]));
            }
        };
        if let Some(fixed) = self.fixed_rows(def, &slots) {
            fixed.for_each(|row| push(&row));
            return Ok(());
        }
        let mut values = Vec::new();
        for i in 0..def.count {
            let mut row = [0.0f32; 8];
            self.item(
                def,
                &mut values,
                |k, v| {
                    if let Some(s) = slots[k] {
                        row[s] = v as f32;
                    }
                },
                |_, _| {},
            )
            .map_err(|m| (i, m))?;
            push(&row);
        }
        Ok(())
    }

    /// When every property of `def` is a scalar and all its items are there: the items'
    /// values by slot ([`vertex_slot`]), each row decoded from its own bytes (a fixed
    /// stride), and the payload moved past them.
    fn fixed_rows(
        &mut self,
        def: &ElementDef,
        slots: &[Option<usize>],
    ) -> Option<impl Iterator<Item = [f32; 8]> + 'a> {
        let mut fields = Vec::new(); // (offset, type, slot)
        let mut stride = 0;
        for (p, slot) in def.properties.values().zip(slots) {
            let PropertyType::Scalar(t) = &p.data_type else {
                return None;
            };
            if let Some(s) = slot {
                fields.push((stride, t.clone(), *s));
            }
            stride += scalar_size(t);
        }
        let len = stride.checked_mul(def.count)?;
        if stride == 0 || len > self.bytes.len() {
            return None;
        }
        let (rows, rest) = self.bytes.split_at(len);
        self.bytes = rest;
        let big_endian = self.big_endian;
        Some(rows.chunks_exact(stride).map(move |r| {
            let mut row = [0.0f32; 8];
            for (offset, t, s) in &fields {
                let mut p = Payload {
                    bytes: &r[*offset..],
                    big_endian,
                };
                row[*s] = p.scalar(t).unwrap_or(0.0) as f32;
            }
            row
        }))
    }

    /// Reads the `face` element's index lists into `mesh`, fan-triangulated.
    pub(super) fn faces(
        &mut self,
        def: &ElementDef,
        mesh: &mut TriangleMesh,
    ) -> Result<(), ItemError> {
        let is_index: Vec<bool> = def
            .properties
            .keys()
            .map(|n| n == "vertex_indices" || n == "vertex_index")
            .collect();
        mesh.indices.reserve(def.count);
        let (mut values, mut corners) = (Vec::new(), Vec::new());
        // The usual layout: only the index list, its length a byte, 4-byte indices.
        let mut props = def.properties.values();
        let plain = match (props.next().map(|p| &p.data_type), props.next()) {
            (Some(PropertyType::List(ScalarType::UChar, t)), None) if is_index[0] => match t {
                ScalarType::Int => Some(true),
                ScalarType::UInt => Some(false),
                _ => None,
            },
            _ => None,
        };
        for i in 0..def.count {
            if let Some(signed) = plain {
                if let Some(t) = self.plain_triangle(signed) {
                    mesh.indices.push(t);
                    continue;
                }
            }
            let mut negative = false;
            corners.clear();
            self.item(
                def,
                &mut values,
                |_, _| {},
                |k, vs| {
                    if is_index[k] {
                        corners.clear();
                        for &v in vs {
                            if v < 0.0 {
                                negative = true;
                            } else {
                                corners.push(v as u32);
                            }
                        }
                    }
                },
            )
            .map_err(|m| (i, m))?;
            if negative {
                return Err((i, "negative index".into()));
            }
            if corners.len() < 3 {
                return Err((
                    i,
                    format!("a face needs 3 corners, found {}", corners.len()),
                ));
            }
            push_fan(&mut mesh.indices, &corners);
        }
        Ok(())
    }

    /// A face of three nonnegative 4-byte indices (`signed`: as `int`, else `uint`) after
    /// a length byte, read and passed; `None` (nothing read) for any other face.
    #[inline(always)]
    fn plain_triangle(&mut self, signed: bool) -> Option<[u32; 3]> {
        let (&[3], rest) = self.bytes.split_first_chunk::<1>()? else {
            return None;
        };
        let b: [u8; 12] = *rest.first_chunk()?;
        let t = [0, 4, 8].map(|k| {
            let v = [b[k], b[k + 1], b[k + 2], b[k + 3]];
            if self.big_endian {
                u32::from_be_bytes(v)
            } else {
                u32::from_le_bytes(v)
            }
        });
        if signed && t.iter().any(|&v| v > i32::MAX as u32) {
            return None;
        }
        self.bytes = &rest[12..];
        Some(t)
    }

    /// Reads past an element.
    pub(super) fn skip(&mut self, def: &ElementDef) -> Result<(), ItemError> {
        let mut values = Vec::new();
        for i in 0..def.count {
            self.item(def, &mut values, |_, _| {}, |_, _| {})
                .map_err(|m| (i, m))?;
        }
        Ok(())
    }
}

/// The bytes of a scalar of type `t`.
pub(super) fn scalar_size(t: &ScalarType) -> usize {
    match t {
        ScalarType::Char | ScalarType::UChar => 1,
        ScalarType::Short | ScalarType::UShort => 2,
        ScalarType::Int | ScalarType::UInt | ScalarType::Float => 4,
        ScalarType::Double => 8,
    }
}

fn ends() -> String {
    "the file ends inside it".into()
}
