//! Reference images (OpenEXR, linear RGB) and the relative MSE the rendering study reports.

use std::path::Path;

/// A linear RGB image, row-major from the top-left.
#[derive(Debug, Clone, PartialEq)]
pub struct Rgb {
    /// Columns.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// Pixels.
    pub pixels: Vec<[f32; 3]>,
}

/// Reads the first RGB(A) layer of an EXR file (alpha is ignored).
pub fn read_exr(path: &Path) -> Result<Rgb, String> {
    type Buf = (usize, Vec<[f32; 3]>);
    let img = exr::prelude::read_first_rgba_layer_from_file(
        path,
        |size, _| -> Buf { (size.width(), vec![[0.0; 3]; size.width() * size.height()]) },
        |buf: &mut Buf, at, (r, g, b, _): (f32, f32, f32, f32)| {
            buf.1[at.y() * buf.0 + at.x()] = [r, g, b];
        },
    )
    .map_err(|e| format!("{}: {e}", path.display()))?;
    let size = img.layer_data.size;
    Ok(Rgb {
        width: size.width(),
        height: size.height(),
        pixels: img.layer_data.channel_data.pixels.1,
    })
}

/// Writes an RGB EXR (for the round-trip test).
#[cfg(test)]
pub fn write_exr(path: &Path, img: &Rgb) -> Result<(), String> {
    exr::prelude::write_rgb_file(path, img.width, img.height, |x, y| {
        let p = img.pixels[y * img.width + x];
        (p[0], p[1], p[2])
    })
    .map_err(|e| format!("{}: {e}", path.display()))
}

/// relMSE = mean over pixels and channels of (img − ref)² / (ref² + 0.01); a non-finite
/// pixel makes it infinite.
pub fn rel_mse(img: &Rgb, reference: &Rgb) -> Result<f64, String> {
    if (img.width, img.height) != (reference.width, reference.height) {
        return Err(format!(
            "image {}×{} against reference {}×{}",
            img.width, img.height, reference.width, reference.height
        ));
    }
    let mut sum = 0.0;
    for (a, b) in img.pixels.iter().zip(&reference.pixels) {
        for c in 0..3 {
            let (x, r) = (f64::from(a[c]), f64::from(b[c]));
            sum += (x - r) * (x - r) / (r * r + 0.01);
        }
    }
    let n = 3 * img.pixels.len();
    Ok(if sum.is_nan() {
        f64::INFINITY
    } else {
        sum / n.max(1) as f64
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tiny() -> Rgb {
        Rgb {
            width: 3,
            height: 2,
            pixels: (0..6).map(|i| [i as f32, 0.5, 2.0 * i as f32]).collect(),
        }
    }

    #[test]
    fn exr_round_trip() {
        let dir = std::env::temp_dir().join("mcrt-convergence-image-test");
        std::fs::create_dir_all(&dir).expect("temp dir");
        let path = dir.join("tiny.exr");
        write_exr(&path, &tiny()).expect("written");
        assert_eq!(read_exr(&path).expect("read back"), tiny());
    }

    #[test]
    fn reads_the_shipped_reference() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/cornell-box.exr");
        let img = read_exr(&path).expect("reference image");
        assert_eq!((img.width, img.height), (256, 256));
        let mean: f64 = img.pixels.iter().map(|p| f64::from(p[0])).sum::<f64>() / 65536.0;
        // REFERENCES.md gives the red mean as 0.24443.
        assert!(mean.is_finite() && (mean - 0.24443).abs() < 1e-4, "{mean}");
    }

    #[test]
    fn rel_mse_by_hand() {
        let r = tiny();
        assert_eq!(rel_mse(&r, &r), Ok(0.0));
        let mut a = r.clone();
        a.pixels[0][0] += 0.1; // reference 0: 0.01 / 0.01 = 1
        a.pixels[1][2] += 1.0; // reference 2: 1 / 4.01
        let want = (1.0 + 1.0 / 4.01) / 18.0;
        let got = rel_mse(&a, &r).expect("same size");
        assert!(got.is_finite() && (got - want).abs() < 1e-6, "{got} {want}");
        a.pixels[2][1] = f32::NAN;
        assert_eq!(rel_mse(&a, &r), Ok(f64::INFINITY));
        let small = Rgb {
            width: 1,
            height: 1,
            pixels: vec![[0.0; 3]],
        };
        assert!(rel_mse(&small, &r).is_err());
    }
}
