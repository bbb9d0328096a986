//! Failure images: the observed and expected histograms and their standardised difference,
//! as binary PPM files (no dependency; most image viewers open them), or as PNG with the
//! feature `report-png`.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// Widest image grid; wider histograms are summed into this many columns.
const MAX_COLUMNS: usize = 1024;

/// The image files' extension: `png` with the feature `report-png`, else `ppm`.
pub(crate) const EXTENSION: &str = if cfg!(feature = "report-png") {
    "png"
} else {
    "ppm"
};

/// Writes `<name>-observed.EXT`, `<name>-expected.EXT` and `<name>-difference.EXT` into
/// `dir` (created if needed) and returns their paths; errors are printed, not raised (a
/// failing test should report its statistics even when the disk is read-only).
pub(crate) fn write_images(
    dir: &Path,
    name: &str,
    grid: (usize, usize),
    observed: &[u64],
    expected: &[f64],
) -> Vec<PathBuf> {
    let obs: Vec<f64> = observed.iter().map(|&o| o as f64).collect();
    let (cols, rows, obs) = regrid(grid, &obs);
    let (_, _, exp) = regrid(grid, expected);
    let max = obs.iter().chain(&exp).fold(0.0f64, |m, &v| m.max(v));
    let heat = |v: &f64| ramp(if max > 0.0 { v / max } else { 0.0 });
    let diff: Vec<[u8; 3]> = obs
        .iter()
        .zip(&exp)
        .map(|(o, e)| signed((o - e) / e.max(1.0).sqrt() / 4.0))
        .collect();
    let safe: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect();
    let images = [
        ("observed", obs.iter().map(heat).collect::<Vec<_>>()),
        ("expected", exp.iter().map(heat).collect()),
        ("difference", diff),
    ];
    let mut paths = Vec::new();
    for (kind, px) in images {
        let path = dir.join(format!("{safe}-{kind}.{EXTENSION}"));
        match write_image(&path, cols, rows, &px) {
            Ok(()) => paths.push(path),
            Err(e) => eprintln!("mcrt::stats: could not write {}: {e}", path.display()),
        }
    }
    paths
}

/// The first `cols · rows` values as a grid of at most [`MAX_COLUMNS`] columns.
fn regrid((cols, rows): (usize, usize), values: &[f64]) -> (usize, usize, Vec<f64>) {
    let group = cols.div_ceil(MAX_COLUMNS).max(1);
    let new_cols = cols.div_ceil(group);
    let mut out = vec![0.0; new_cols * rows];
    for r in 0..rows {
        for c in 0..cols {
            out[r * new_cols + c / group] += values.get(r * cols + c).copied().unwrap_or(0.0);
        }
    }
    (new_cols, rows, out)
}

/// Black → red → yellow → white for `t ∈ [0, 1]`.
fn ramp(t: f64) -> [u8; 3] {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0) * 3.0
    } else {
        0.0
    };
    let ch = |x: f64| (x.clamp(0.0, 1.0) * 255.0).round() as u8;
    [ch(t), ch(t - 1.0), ch(t - 2.0)]
}

/// Blue (negative) → white (0) → red (positive) for `t ∈ [-1, 1]`.
fn signed(t: f64) -> [u8; 3] {
    let t = if t.is_finite() {
        t.clamp(-1.0, 1.0)
    } else {
        0.0
    };
    let fade = ((1.0 - t.abs()) * 255.0).round() as u8;
    if t >= 0.0 {
        [255, fade, fade]
    } else {
        [fade, fade, 255]
    }
}

/// Writes an RGB image, each cell drawn as a block so the image is about 512 pixels wide
/// (rows of one-row grids are 32 pixels tall).
fn write_image(path: &Path, cols: usize, rows: usize, px: &[[u8; 3]]) -> std::io::Result<()> {
    if let Some(parent) = path.parent() {
        std::fs::create_dir_all(parent)?;
    }
    let sx = (512 / cols.max(1)).clamp(1, 16);
    let sy = if rows == 1 {
        32
    } else {
        (512 / rows).clamp(1, 16).min(sx.max(1))
    };
    let (w, h) = (cols * sx, rows * sy);
    let mut data = Vec::with_capacity(w * h * 3);
    for y in 0..h {
        let r = rows - 1 - y / sy; // first row at the bottom
        for x in 0..w {
            data.extend_from_slice(&px[r * cols + x / sx]);
        }
    }
    encode(BufWriter::new(File::create(path)?), w, h, &data)
}

/// Binary PPM (netpbm `P6`): a text header, then the RGB bytes row by row from the top.
#[cfg(not(feature = "report-png"))]
fn encode(mut out: impl Write, w: usize, h: usize, rgb: &[u8]) -> std::io::Result<()> {
    write!(out, "P6\n{w} {h}\n255\n")?;
    out.write_all(rgb)?;
    out.flush()
}

/// PNG, 8-bit RGB.
#[cfg(feature = "report-png")]
fn encode(out: impl Write, w: usize, h: usize, rgb: &[u8]) -> std::io::Result<()> {
    let too_big = |v: usize| std::io::Error::other(format!("image dimension {v} too large"));
    let w32 = u32::try_from(w).map_err(|_| too_big(w))?;
    let h32 = u32::try_from(h).map_err(|_| too_big(h))?;
    let mut enc = png::Encoder::new(out, w32, h32);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    let mut writer = enc.write_header().map_err(std::io::Error::other)?;
    writer.write_image_data(rgb).map_err(std::io::Error::other)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wide_grids_are_summed() {
        let v = vec![1.0; 3000];
        let (c, r, out) = regrid((3000, 1), &v);
        assert_eq!((c, r), (1000, 1));
        assert!(out.iter().all(|&x| x == 3.0));
    }

    #[test]
    fn images_are_written() {
        let dir = std::env::temp_dir().join("mcrt-stats-report-test");
        let paths = write_images(&dir, "t/x", (4, 2), &[1, 2, 3, 4, 5, 6, 7, 8], &[4.0; 8]);
        assert_eq!(paths.len(), 3);
        assert!(paths.iter().all(|p| p.exists()));
    }

    #[cfg(not(feature = "report-png"))]
    #[test]
    fn ppm_header_and_size() {
        let mut out = Vec::new();
        encode(&mut out, 2, 1, &[1, 2, 3, 4, 5, 6]).expect("written");
        assert_eq!(out, b"P6\n2 1\n255\n\x01\x02\x03\x04\x05\x06");
    }
}
