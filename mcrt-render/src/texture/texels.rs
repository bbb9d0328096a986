//! A texture's pixels kept in the precision of its file, converted to linear RGB at lookup
//! (as Mitsuba and pbrt keep them): 8-bit PNG and JPEG values as bytes, decoded through a
//! 256-entry table (the sRGB curve, or `/255` when `raw`), so a lookup returns exactly the
//! floats a decode to linear RGB would have stored; half-float OpenEXR values as halves
//! (exact in `f32`); anything else as linear `f32` RGB.

use exr::prelude::f16;
use glam::Vec3;

/// The pixels of an [`Image`](super::Image), row-major from the top-left.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Texels {
    /// Linear RGB floats (16-bit PNG, float EXR, images built in code).
    Linear(Vec<Vec3>),
    /// 8-bit RGB and the linear value of each byte.
    Bytes {
        /// The bytes, three per pixel.
        data: Vec<[u8; 3]>,
        /// The linear value of each byte value.
        table: Box<[f32; 256]>,
    },
    /// Half-float linear RGB.
    Half(Vec<[f16; 3]>),
}

impl Texels {
    /// Bytes with the table `decode(b / 255)`.
    pub(crate) fn bytes(data: Vec<[u8; 3]>, decode: impl Fn(f32) -> f32) -> Self {
        let mut table = Box::new([0.0f32; 256]);
        for (b, t) in table.iter_mut().enumerate() {
            *t = decode(f32::from(b as u8) / 255.0);
        }
        Self::Bytes { data, table }
    }

    /// Number of pixels.
    pub(crate) fn len(&self) -> usize {
        match self {
            Self::Linear(v) => v.len(),
            Self::Bytes { data, .. } => data.len(),
            Self::Half(v) => v.len(),
        }
    }

    /// Bytes held per pixel.
    pub(crate) fn pixel_bytes(&self) -> usize {
        match self {
            Self::Linear(_) => 12,
            Self::Bytes { .. } => 3,
            Self::Half(_) => 6,
        }
    }

    /// Pixel `i` in linear RGB.
    #[inline]
    pub(crate) fn get(&self, i: usize) -> Vec3 {
        match self {
            Self::Linear(v) => v[i],
            Self::Bytes { data, table } => {
                let [r, g, b] = data[i];
                Vec3::new(
                    table[usize::from(r)],
                    table[usize::from(g)],
                    table[usize::from(b)],
                )
            }
            Self::Half(v) => {
                let [r, g, b] = v[i];
                Vec3::new(r.to_f32(), g.to_f32(), b.to_f32())
            }
        }
    }
}
