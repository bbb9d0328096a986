//! Image files: linear float RGB EXR (read and write) and 8-bit sRGB PNG (write).

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

fn err(path: &Path, e: impl std::fmt::Display) -> ImageError {
    ImageError {
        path: path.to_path_buf(),
        message: e.to_string(),
    }
}

fn check_len(path: &Path, w: u32, h: u32, px: &[Vec3]) -> Result<(), ImageError> {
    if px.len() != w as usize * h as usize {
        return Err(err(
            path,
            format!("{} pixels for a {w}×{h} image", px.len()),
        ));
    }
    Ok(())
}

/// Writes linear float RGB pixels (row-major from the top-left) to an OpenEXR file.
pub fn write_exr(path: &Path, width: u32, height: u32, pixels: &[Vec3]) -> Result<(), ImageError> {
    check_len(path, width, height, pixels)?;
    let w = width as usize;
    exr::prelude::write_rgb_file(path, w, height as usize, |x, y| {
        let p = pixels[y * w + x];
        (p.x, p.y, p.z)
    })
    .map_err(|e| err(path, e))
}

/// Reads the first RGB(A) layer of an OpenEXR file as linear float RGB, row-major from the
/// top-left: `(width, height, pixels)`.
pub fn read_exr(path: &Path) -> Result<(u32, u32, Vec<Vec3>), ImageError> {
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

/// The sRGB transfer function of a linear value, clamped to `[0, 1]`.
fn srgb(x: f32) -> u8 {
    let x = if x.is_finite() {
        x.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let v = if x <= 0.003_130_8 {
        12.92 * x
    } else {
        1.055 * x.powf(1.0 / 2.4) - 0.055
    };
    (v * 255.0 + 0.5) as u8
}

/// Writes pixels as an 8-bit sRGB PNG (values clamped to `[0, 1]`).
pub fn write_png(path: &Path, width: u32, height: u32, pixels: &[Vec3]) -> Result<(), ImageError> {
    check_len(path, width, height, pixels)?;
    let file = std::fs::File::create(path).map_err(|e| err(path, e))?;
    let mut enc = png::Encoder::new(std::io::BufWriter::new(file), width, height);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    let mut writer = enc.write_header().map_err(|e| err(path, e))?;
    let data: Vec<u8> = pixels
        .iter()
        .flat_map(|p| [srgb(p.x), srgb(p.y), srgb(p.z)])
        .collect();
    writer.write_image_data(&data).map_err(|e| err(path, e))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exr_round_trip_and_png() {
        let dir = std::env::temp_dir().join(format!("mcrt-film-io-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        let px: Vec<Vec3> = (0..6)
            .map(|i| Vec3::new(i as f32, 0.5, 1e-3 * i as f32))
            .collect();
        let p = dir.join("t.exr");
        write_exr(&p, 3, 2, &px).expect("write exr");
        let (w, h, back) = read_exr(&p).expect("read exr");
        assert_eq!((w, h), (3, 2));
        assert_eq!(back, px);
        write_png(&dir.join("t.png"), 3, 2, &px).expect("write png");
        assert!(write_png(&dir.join("u.png"), 2, 2, &px).is_err());
        assert_eq!((srgb(0.0), srgb(1.0), srgb(f32::NAN)), (0, 255, 0));
        std::fs::remove_dir_all(&dir).ok();
    }
}
