//! Image files for `bitmap` textures: PNG, JPEG, OpenEXR and Radiance RGBE (`.hdr`), told
//! apart by their first bytes, decoded to linear RGB as Mitsuba 3 decodes them: 8- and
//! 16-bit PNG and JPEG values are sRGB-encoded and go through the sRGB curve unless `raw`
//! is set; EXR and RGBE values are linear as stored. Grey images are replicated to three channels; alpha is ignored
//! (Mitsuba 3's `bitmap` evaluates colour only).

use super::image::Image;
use super::texels::Texels;
use exr::prelude::f16;
use glam::Vec3;
use std::path::Path;

/// Most pixels a texture may have (2²⁶, 768 MiB as linear RGB floats).
pub const MAX_TEXTURE_PIXELS: u64 = 1 << 26;

/// Most bytes a PNG or JPEG texture file may have.
const MAX_FILE_BYTES: u64 = 1 << 30;

/// The sRGB decoding curve (IEC 61966-2-1): an encoded value in [0, 1] to linear.
#[inline]
pub fn srgb_to_linear(x: f32) -> f32 {
    if x <= 0.040_45 {
        x / 12.92
    } else {
        ((x + 0.055) / 1.055).powf(2.4)
    }
}

/// Reads the image at `path`; `raw` skips the sRGB curve of PNG and JPEG files. The error
/// says what is wrong with the file (the caller names it). 8-bit values are kept as bytes
/// and half-float EXR values as halves (see `texels.rs`). The image's size, read from its
/// header, is checked against the memory budget ([`crate::memory`]) before its pixels are.
pub fn read_image(path: &Path, raw: bool) -> Result<Image, String> {
    read_image_beside(path, raw, 0)
}

/// [`read_image`] beside `used` bytes of images read before, which count against the
/// memory budget with it.
pub fn read_image_beside(path: &Path, raw: bool, used: u64) -> Result<Image, String> {
    let len = crate::io::open_regular(path)
        .and_then(|f| f.metadata())
        .map_err(|e| e.to_string())?
        .len();
    let room = |w: u32, h: u32, per_pixel: usize, file: u64| {
        let need = crate::memory::bytes(u64::from(w) * u64::from(h), per_pixel)
            .saturating_add(file)
            .saturating_add(used);
        let what = if used == 0 {
            format!("decoding this {w} × {h} image")
        } else {
            format!("decoding this {w} × {h} image beside the {used} bytes of images before it")
        };
        crate::memory::check(&what, need)
    };
    crate::memory::check(
        "reading this image file",
        len.min(MAX_FILE_BYTES).saturating_add(used),
    )?;
    let bytes = crate::io::read_capped(path, MAX_FILE_BYTES).map_err(|e| e.to_string())?;
    if bytes.starts_with(&[0x76, 0x2f, 0x31, 0x01]) {
        drop(bytes);
        return read_exr_texture(path, |w, h, per_pixel| room(w, h, per_pixel, 0));
    }
    let file = bytes.len() as u64;
    if crate::io::is_rgbe(&bytes) {
        let (w, h, px) = crate::io::read_rgbe(&bytes, MAX_TEXTURE_PIXELS, |w, h, per| {
            room(w, h, per, file)
        })?;
        return Image::new(w, h, px).ok_or_else(|| "an empty image".to_string());
    }
    let (w, h, channels, values) = if bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
        png_values(&bytes, |w, h, per| room(w, h, per, file))?
    } else if bytes.starts_with(&[0xff, 0xd8, 0xff]) {
        jpeg_values(&bytes, |w, h, per| room(w, h, per, file))?
    } else {
        return Err("not a PNG, JPEG or OpenEXR image (nor a Radiance RGBE one)".into());
    };
    let decode = |x: f32| if raw { x } else { srgb_to_linear(x) };
    let texels = match values {
        Samples::Bytes(b) => {
            let data = b
                .chunks_exact(channels)
                .map(|c| match channels {
                    1 | 2 => [c[0]; 3],
                    _ => [c[0], c[1], c[2]],
                })
                .collect();
            Texels::bytes(data, decode)
        }
        Samples::Floats(values) => Texels::Linear(
            values
                .chunks_exact(channels)
                .map(|c| match channels {
                    1 | 2 => Vec3::splat(decode(c[0])),
                    _ => Vec3::new(decode(c[0]), decode(c[1]), decode(c[2])),
                })
                .collect(),
        ),
    };
    Image::from_texels(w, h, texels).ok_or_else(|| "an empty image".to_string())
}

/// An OpenEXR texture: halves when its R, G and B channels are all half floats, else
/// linear floats. `room(w, h, bytes per pixel)` checks the budget before any pixel is read.
fn read_exr_texture(
    path: &Path,
    room: impl Fn(u32, u32, usize) -> Result<(), String>,
) -> Result<Image, String> {
    use exr::meta::attribute::SampleType;
    let meta = exr::meta::MetaData::read_from_file(path, false).map_err(|e| e.to_string())?;
    let half = meta.headers.iter().all(|h| {
        h.channels
            .list
            .iter()
            .filter(|c| ["R", "G", "B"].contains(&c.name.to_string().as_str()))
            .all(|c| c.sample_type == SampleType::F16)
    });
    for header in meta.headers.iter() {
        let (w, h) = (header.layer_size.width(), header.layer_size.height());
        // The text `read_exr_at_most` gives, for the same refusal.
        if (w as u64).saturating_mul(h as u64) > MAX_TEXTURE_PIXELS {
            return Err(format!(
                "{}: a layer of {w} × {h} pixels is more than the {MAX_TEXTURE_PIXELS} allowed",
                path.display()
            ));
        }
        check_size(w as u64, h as u64)?;
        room(w as u32, h as u32, if half { 6 } else { 12 })?;
    }
    if !half {
        let (w, h, px) =
            crate::io::read_exr_at_most(path, MAX_TEXTURE_PIXELS).map_err(|e| e.to_string())?;
        return Image::new(w, h, px).ok_or_else(|| "an empty image".to_string());
    }
    let img = exr::prelude::read_first_rgba_layer_from_file(
        path,
        |res, _| {
            (
                res.width(),
                vec![[f16::ZERO; 3]; res.width() * res.height()],
            )
        },
        |(w, px): &mut (usize, Vec<[f16; 3]>), pos, (r, g, b, _a): (f16, f16, f16, f16)| {
            px[pos.y() * *w + pos.x()] = [r, g, b];
        },
    )
    .map_err(|e| e.to_string())?;
    let size = img.layer_data.size;
    let (_, px) = img.layer_data.channel_data.pixels;
    Image::from_texels(size.width() as u32, size.height() as u32, Texels::Half(px))
        .ok_or_else(|| "an empty image".to_string())
}

fn check_size(w: u64, h: u64) -> Result<(), String> {
    if w == 0 || h == 0 {
        return Err("an empty image".into());
    }
    if w * h > MAX_TEXTURE_PIXELS {
        return Err(format!(
            "{w} × {h} pixels is more than the {MAX_TEXTURE_PIXELS} a texture may have"
        ));
    }
    Ok(())
}

/// Decoded samples: 8-bit values as they are, or 16-bit ones as floats in [0, 1].
enum Samples {
    Bytes(Vec<u8>),
    Floats(Vec<f32>),
}

/// `(width, height, channels, values in [0, 1])` of a PNG.
fn png_values(
    bytes: &[u8],
    room: impl Fn(u32, u32, usize) -> Result<(), String>,
) -> Result<(u32, u32, usize, Samples), String> {
    let bad = |e: png::DecodingError| format!("undecodable PNG: {e}");
    let mut decoder = png::Decoder::new(bytes);
    // Palettes, low bit depths and transparency chunks expand to 8-bit grey or RGB(A).
    decoder.set_transformations(png::Transformations::EXPAND);
    let mut reader = decoder.read_info().map_err(bad)?;
    let (w, h) = (reader.info().width, reader.info().height);
    check_size(u64::from(w), u64::from(h))?;
    // The decoded rows, and the bytes (8-bit) or floats and linear RGB (16-bit) from them.
    let sixteen = reader.info().bit_depth == png::BitDepth::Sixteen;
    room(w, h, if sixteen { 8 + 16 + 12 } else { 4 + 3 })?;
    let mut buf = vec![0u8; reader.output_buffer_size()];
    let frame = reader.next_frame(&mut buf).map_err(bad)?;
    buf.truncate(frame.buffer_size());
    let channels = frame.color_type.samples();
    let values = match frame.bit_depth {
        png::BitDepth::Sixteen => Samples::Floats(
            buf.chunks_exact(2)
                .map(|b| f32::from(u16::from_be_bytes([b[0], b[1]])) / 65535.0)
                .collect(),
        ),
        _ => Samples::Bytes(buf),
    };
    Ok((w, h, channels, values))
}

/// `(width, height, channels, values in [0, 1])` of a baseline or progressive JPEG.
fn jpeg_values(
    bytes: &[u8],
    room: impl Fn(u32, u32, usize) -> Result<(), String>,
) -> Result<(u32, u32, usize, Samples), String> {
    let bad = |e: jpeg_decoder::Error| format!("undecodable JPEG: {e}");
    let mut decoder = jpeg_decoder::Decoder::new(bytes);
    decoder.read_info().map_err(bad)?;
    let info = decoder
        .info()
        .ok_or_else(|| "undecodable JPEG: no frame header".to_string())?;
    check_size(u64::from(info.width), u64::from(info.height))?;
    room(u32::from(info.width), u32::from(info.height), 3 + 3)?;
    let channels = match info.pixel_format {
        jpeg_decoder::PixelFormat::L8 => 1,
        jpeg_decoder::PixelFormat::RGB24 => 3,
        other => {
            return Err(format!(
                "unsupported JPEG pixel format {other:?} (grey or RGB only)"
            ))
        }
    };
    let values = decoder.decode().map_err(bad)?;
    if values.len() != usize::from(info.width) * usize::from(info.height) * channels {
        return Err("undecodable JPEG: truncated pixel data".into());
    }
    Ok((
        u32::from(info.width),
        u32::from(info.height),
        channels,
        Samples::Bytes(values),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Writes a `w × h` PNG of `color` type and `depth` with the raw sample bytes `data`.
    fn png_file(
        name: &str,
        w: u32,
        h: u32,
        color: png::ColorType,
        depth: png::BitDepth,
        data: &[u8],
    ) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("mcrt-decode-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(name);
        let mut enc = png::Encoder::new(std::fs::File::create(&path).unwrap(), w, h);
        enc.set_color(color);
        enc.set_depth(depth);
        enc.write_header().unwrap().write_image_data(data).unwrap();
        path
    }

    /// 16-bit grey, 8-bit grey + alpha and RGBA, decoded as Mitsuba 3.9.1 reads them: grey
    /// replicated, alpha ignored, 16-bit values (big-endian) through the sRGB curve, `raw`
    /// skipping it.
    #[test]
    fn png_layouts() {
        use png::{BitDepth, ColorType};
        let close = |a: Vec3, b: Vec3| a.is_finite() && (a - b).abs().max_element() < 1e-6;
        let g16 = png_file(
            "g16.png",
            2,
            1,
            ColorType::Grayscale,
            BitDepth::Sixteen,
            &[0x80, 0x00, 0xff, 0xff],
        );
        let im = read_image(&g16, false).unwrap();
        assert!(close(
            im.pixels()[0],
            Vec3::splat(srgb_to_linear(32768.0 / 65535.0))
        ));
        assert!(close(im.pixels()[1], Vec3::ONE));
        let im = read_image(&g16, true).unwrap();
        assert!(close(im.pixels()[0], Vec3::splat(32768.0 / 65535.0)));
        let ga = png_file(
            "ga.png",
            1,
            1,
            ColorType::GrayscaleAlpha,
            BitDepth::Eight,
            &[128, 7],
        );
        let im = read_image(&ga, false).unwrap();
        assert!(close(
            im.pixels()[0],
            Vec3::splat(srgb_to_linear(128.0 / 255.0))
        ));
        let rgba = png_file(
            "rgba.png",
            2,
            1,
            ColorType::Rgba,
            BitDepth::Eight,
            &[128, 128, 128, 0, 255, 0, 0, 128],
        );
        let im = read_image(&rgba, false).unwrap();
        assert!(
            close(im.pixels()[0], Vec3::splat(0.215_860_5)),
            "{}",
            im.pixels()[0]
        );
        assert!(close(im.pixels()[1], Vec3::X));
        std::fs::remove_dir_all(g16.parent().unwrap()).unwrap();
    }

    /// Mitsuba 3.9.1 decodes 8-bit 128 to 0.21586 (exact) and 16-bit 32768 to 0.213989
    /// (its 16-bit curve is an approximation, 5·10⁻⁵ below the exact 0.214041).
    #[test]
    fn srgb_curve() {
        let a = srgb_to_linear(128.0 / 255.0);
        let b = srgb_to_linear(32768.0 / 65535.0);
        assert!(a.is_finite() && (a - 0.215_86).abs() < 2e-5, "{a}");
        assert!(b.is_finite() && (b - 0.213_989).abs() < 1e-4, "{b}");
        assert_eq!((srgb_to_linear(0.0), srgb_to_linear(1.0)), (0.0, 1.0));
        // The linear toe: 10/255 is below the 0.04045 knee.
        let t = srgb_to_linear(10.0 / 255.0);
        assert!(t.is_finite() && (t - 10.0 / 255.0 / 12.92).abs() < 1e-7);
    }
}
