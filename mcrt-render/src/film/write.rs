//! Image files: linear float RGB EXR and 8-bit sRGB PNG, written (reading EXR is
//! [`crate::io`]'s).
//!
//! Writes are atomic: the image goes to a temporary file in the same folder, which is
//! flushed to disk and then renamed over the target, so a kill during the write leaves
//! either the old file or the new one, never a truncated one. EXR chunks are written in
//! increasing line order, so the same pixels always give the same bytes.

use crate::io::{err, ImageError};
use glam::Vec3;
use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};

fn check_len(path: &Path, w: u32, h: u32, px: &[Vec3]) -> Result<(), ImageError> {
    if px.len() != w as usize * h as usize {
        return Err(err(
            path,
            format!("{} pixels for a {w}×{h} image", px.len()),
        ));
    }
    Ok(())
}

/// The temporary name `path` is written under before the rename: hidden, in the same
/// folder (so the rename stays on one file system), and unique to this process.
fn temporary_name(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.{}.tmp", std::process::id()))
}

/// Writes `path` atomically: `fill` writes into a new temporary file beside it, which is
/// synced and renamed over `path`; on any error the temporary file is removed.
pub(super) fn write_atomically(
    path: &Path,
    fill: impl FnOnce(&mut File) -> Result<(), String>,
) -> Result<(), ImageError> {
    let tmp = temporary_name(path);
    let result = (|| {
        let mut f = std::fs::OpenOptions::new()
            .write(true)
            .create(true)
            .truncate(true)
            .open(&tmp)
            .map_err(|e| e.to_string())?;
        fill(&mut f)?;
        f.flush().map_err(|e| e.to_string())?;
        f.sync_all().map_err(|e| e.to_string())?;
        drop(f);
        std::fs::rename(&tmp, path).map_err(|e| e.to_string())
    })();
    if result.is_err() {
        std::fs::remove_file(&tmp).ok();
    }
    result.map_err(|m| err(path, m))
}

/// Writes linear float RGB pixels (row-major from the top-left) to an OpenEXR file
/// (RLE-compressed 64×64 tiles in increasing line order), atomically.
pub fn write_exr(path: &Path, width: u32, height: u32, pixels: &[Vec3]) -> Result<(), ImageError> {
    use exr::prelude::*;
    check_len(path, width, height, pixels)?;
    let w = width as usize;
    let channels = SpecificChannels::rgb(|Vec2(x, y): Vec2<usize>| {
        let p = pixels[y * w + x];
        (p.x, p.y, p.z)
    });
    let encoding = Encoding {
        line_order: LineOrder::Increasing,
        ..Encoding::FAST_LOSSLESS
    };
    let image = Image::from_encoded_channels((w, height as usize), encoding, channels);
    write_atomically(path, |f| {
        image.write().to_unbuffered(&*f).map_err(|e| e.to_string())
    })
}

/// Writes linear float RGB pixels with the named `extra` channels (each a full image,
/// row-major) beside them, as [`write_exr`] does; with no extra channel, exactly the file of
/// [`write_exr`].
pub fn write_exr_with_channels(
    path: &Path,
    width: u32,
    height: u32,
    pixels: &[Vec3],
    extra: &[(String, Vec<f32>)],
) -> Result<(), ImageError> {
    use exr::prelude::traits::WritableImage;
    use exr::prelude::{
        AnyChannel, AnyChannels, Encoding, FlatSamples, Image, Layer, LayerAttributes, LineOrder,
        SmallVec, Text,
    };
    if extra.is_empty() {
        return write_exr(path, width, height, pixels);
    }
    check_len(path, width, height, pixels)?;
    let n = pixels.len();
    let mut channels = Vec::with_capacity(3 + extra.len());
    for (c, name) in ["R", "G", "B"].into_iter().enumerate() {
        let v = pixels.iter().map(|p| p[c]).collect();
        channels.push(AnyChannel::new(Text::from(name), FlatSamples::F32(v)));
    }
    for (name, v) in extra {
        if v.len() != n {
            return Err(err(
                path,
                format!("channel \"{name}\": {} values for {n} pixels", v.len()),
            ));
        }
        let text = Text::new_or_none(name.as_str())
            .ok_or_else(|| err(path, format!("channel name \"{name}\" is not ASCII")))?;
        channels.push(AnyChannel::new(text, FlatSamples::F32(v.clone())));
    }
    let encoding = Encoding {
        line_order: LineOrder::Increasing,
        ..Encoding::FAST_LOSSLESS
    };
    let size = (width as usize, height as usize);
    let channels = AnyChannels::sort(SmallVec::from_vec(channels));
    let image = Image::from_layer(Layer::new(
        size,
        LayerAttributes::default(),
        encoding,
        channels,
    ));
    write_atomically(path, |f| {
        image.write().to_unbuffered(&*f).map_err(|e| e.to_string())
    })
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

/// Writes pixels as an 8-bit sRGB PNG (values clamped to `[0, 1]`, NaN black),
/// atomically.
pub fn write_png(path: &Path, width: u32, height: u32, pixels: &[Vec3]) -> Result<(), ImageError> {
    check_len(path, width, height, pixels)?;
    let data: Vec<u8> = pixels
        .iter()
        .flat_map(|p| [srgb(p.x), srgb(p.y), srgb(p.z)])
        .collect();
    write_atomically(path, |f| {
        let mut enc = png::Encoder::new(std::io::BufWriter::new(f), width, height);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut writer = enc.write_header().map_err(|e| e.to_string())?;
        writer.write_image_data(&data).map_err(|e| e.to_string())?;
        writer.finish().map_err(|e| e.to_string())
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::read_exr;

    #[test]
    fn exr_round_trip_and_png() {
        let dir = std::env::temp_dir().join(format!("mcrt-film-io-{}", std::process::id()));
        std::fs::remove_dir_all(&dir).ok();
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
        // A rewrite replaces the file by a rename: a hard link to the old file keeps the
        // old bytes (writing in place would change them), and no temporary file is left.
        let before = std::fs::read(&p).expect("exr bytes");
        let link = dir.join("link.exr");
        std::fs::hard_link(&p, &link).expect("hard link");
        let brighter: Vec<Vec3> = px.iter().map(|v| *v + Vec3::ONE).collect();
        write_exr(&p, 3, 2, &brighter).expect("rewrite");
        assert_eq!(std::fs::read(&link).expect("link bytes"), before);
        assert_ne!(std::fs::read(&p).expect("new bytes"), before);
        assert!(write_exr(&p, 2, 2, &px).is_err());
        assert!(write_exr(&dir.join("no/such/dir.exr"), 3, 2, &px).is_err());
        let mut names: Vec<_> = std::fs::read_dir(&dir)
            .expect("dir")
            .map(|e| e.expect("entry").file_name())
            .collect();
        names.sort();
        assert_eq!(names, ["link.exr", "t.exr", "t.png"]);
        std::fs::remove_dir_all(&dir).ok();
    }
}
