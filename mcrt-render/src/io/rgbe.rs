//! Reading Radiance RGBE (`.hdr`) images as linear float RGB, through the `image` crate's
//! decoder, with the pixel count checked before any pixel storage is allocated.

use glam::Vec3;
use image::codecs::hdr::HdrDecoder;

/// Whether `head`, a file's first bytes, starts a Radiance RGBE image (`#?RADIANCE`,
/// `#?RGBE` and the other programs' `#?` signatures).
pub(crate) fn is_rgbe(head: &[u8]) -> bool {
    head.starts_with(b"#?")
}

/// Decodes a Radiance RGBE image held in `bytes`: `(width, height, pixels)`, row-major
/// from the top-left, each channel `m · 2^(e − 136)` of its mantissa byte `m` and shared
/// exponent `e` (0 for `e = 0`), as Mitsuba 3 decodes them; the header's `EXPOSURE` is
/// ignored, as Mitsuba ignores it. `room(w, h, bytes per pixel)` is asked before the
/// pixels are decoded (the memory budget); more than `max_pixels` pixels are refused.
pub(crate) fn read_rgbe(
    bytes: &[u8],
    max_pixels: u64,
    room: impl Fn(u32, u32, usize) -> Result<(), String>,
) -> Result<(u32, u32, Vec<Vec3>), String> {
    let bad = |e: image::ImageError| format!("undecodable Radiance RGBE image: {e}");
    // Not strict: the strict reader wants `#?RADIANCE`, and Mitsuba writes `#?RGBE` (the
    // lenient one skips the signature as a comment line; the caller has checked `#?`).
    let decoder = HdrDecoder::with_strictness(bytes, false).map_err(bad)?;
    let meta = decoder.metadata();
    let (w, h) = (meta.width, meta.height);
    if w == 0 || h == 0 {
        return Err("an empty image".into());
    }
    if u64::from(w) * u64::from(h) > max_pixels {
        return Err(format!(
            "{w} × {h} pixels is more than the {max_pixels} an image may have"
        ));
    }
    // The pixels and the decoder's one scanline of RGBE bytes.
    room(w, h, 12 + 4)?;
    let mut px = vec![Vec3::ZERO; w as usize * h as usize];
    decoder
        .read_image_transform(
            |p| {
                let c = p.to_hdr().0;
                Vec3::new(c[0], c[1], c[2])
            },
            &mut px,
        )
        .map_err(bad)?;
    Ok((w, h, px))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat (uncompressed) RGBE file of `w × h` pixels.
    fn flat(w: u32, h: u32, px: &[[u8; 4]]) -> Vec<u8> {
        let mut b = format!("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {h} +X {w}\n").into_bytes();
        px.iter().for_each(|p| b.extend_from_slice(p));
        b
    }

    /// Mantissas and exponents as Mitsuba 3.9.1 decodes them (`mi.Bitmap` of the same
    /// bytes): 128·2^(129−136) = 1, 255·2^(129−136) = 1.9921875, 2·2^(140−136) = 32;
    /// exponent 0 is black whatever the mantissas.
    #[test]
    fn values_and_layout() {
        let px = [
            [128, 64, 255, 129],
            [7, 7, 7, 0],
            [128, 0, 0, 128],
            [0, 1, 2, 140],
        ];
        let (w, h, got) = read_rgbe(&flat(2, 2, &px), 100, |_, _, _| Ok(())).unwrap();
        assert_eq!((w, h), (2, 2));
        let want = [
            Vec3::new(1.0, 0.5, 1.992_187_5),
            Vec3::ZERO,
            Vec3::new(0.5, 0.0, 0.0),
            Vec3::new(0.0, 16.0, 32.0),
        ];
        assert_eq!(got, want);
        assert!(is_rgbe(b"#?RGBE\n") && !is_rgbe(b"\x76\x2f\x31\x01"));
    }

    /// Refusals: too many pixels, a budget that says no, a truncated file; never a panic.
    #[test]
    fn refusals() {
        let f = flat(2, 2, &[[1, 1, 1, 128]; 4]);
        assert!(read_rgbe(&f, 3, |_, _, _| Ok(()))
            .unwrap_err()
            .contains("more than"));
        let no = read_rgbe(&f, 100, |_, _, _| Err("over budget".into()));
        assert_eq!(no.unwrap_err(), "over budget");
        assert!(read_rgbe(&f[..f.len() - 3], 100, |_, _, _| Ok(())).is_err());
        let huge = b"#?RADIANCE\n\n-Y 100000 +X 100000\n".to_vec();
        assert!(read_rgbe(&huge, 1 << 26, |_, _, _| Ok(())).is_err());
        assert!(read_rgbe(b"#?RADIANCE\n", 100, |_, _, _| Ok(())).is_err());
    }
}
