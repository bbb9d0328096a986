//! Reading OpenEXR images (linear float RGB), with a bound on the pixels a file from a user
//! may claim, and the error of every image file read or written.

use glam::Vec3;
use std::path::Path;

/// An image could not be read or written.
#[derive(Debug)]
pub struct ImageError {
    /// The file.
    pub path: std::path::PathBuf,
    /// What went wrong.
    pub message: String,
}

impl std::fmt::Display for ImageError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.path.display(), self.message)
    }
}

impl std::error::Error for ImageError {}

pub(crate) fn err(path: &Path, e: impl std::fmt::Display) -> ImageError {
    ImageError {
        path: path.to_path_buf(),
        message: e.to_string(),
    }
}

/// Reads the first RGB(A) layer of an OpenEXR file as linear float RGB, row-major from the
/// top-left: `(width, height, pixels)`.
pub fn read_exr(path: &Path) -> Result<(u32, u32, Vec<Vec3>), ImageError> {
    read_exr_at_most(path, u64::MAX)
}

/// [`read_exr`] for files from users: the headers are read first, and a layer of more than
/// `max_pixels` pixels is an error before any pixel storage is allocated (a 40-byte header
/// can claim 2³¹ × 2³¹ pixels).
pub fn read_exr_at_most(path: &Path, max_pixels: u64) -> Result<(u32, u32, Vec<Vec3>), ImageError> {
    let meta = exr::meta::MetaData::read_from_file(path, false).map_err(|e| err(path, e))?;
    for header in meta.headers.iter() {
        let (w, h) = (header.layer_size.width(), header.layer_size.height());
        if (w as u64).saturating_mul(h as u64) > max_pixels {
            return Err(err(
                path,
                format!("a layer of {w} × {h} pixels is more than the {max_pixels} allowed"),
            ));
        }
    }
    let img = exr::prelude::read_first_rgba_layer_from_file(
        path,
        |res, _| (res.width(), vec![Vec3::ZERO; res.width() * res.height()]),
        |(w, px): &mut (usize, Vec<Vec3>), pos, (r, g, b, _a): (f32, f32, f32, f32)| {
            px[pos.y() * *w + pos.x()] = Vec3::new(r, g, b);
        },
    )
    .map_err(|e| err(path, e))?;
    let size = img.layer_data.size;
    let (_, px) = img.layer_data.channel_data.pixels;
    Ok((size.width() as u32, size.height() as u32, px))
}
