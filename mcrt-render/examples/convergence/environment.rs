//! An environment map for the distribution study: a smooth sky and a small bright sun disc,
//! rasterised at the centres of a `width × height` grid (like an HDR environment image), and
//! a cosine-like lobe it is multiplied by. The map is piecewise constant, so a table at the
//! map's own resolution is exactly proportional to it.

/// Sun centre in `[0,1]²`.
const SUN: (f64, f64) = (0.62, 0.3);
/// Sun radius (in units of the square).
const SUN_RADIUS: f64 = 0.02;
/// Sun radiance (the sun carries about two thirds of the map's integral).
const SUN_RADIANCE: f64 = 2000.0;
/// Lobe centre and squared radius.
const LOBE: (f64, f64, f64) = (0.55, 0.35, 0.09);

/// The sky: smooth, positive everywhere, brighter towards `y = 0` (the zenith).
pub fn sky(x: f64, y: f64) -> f64 {
    0.5 + 1.5 * (1.0 - y) * (1.0 - y) + 0.25 * (std::f64::consts::TAU * (x - 0.2)).cos()
}

/// The sun: a disc of constant radiance.
pub fn sun(x: f64, y: f64) -> f64 {
    let (dx, dy) = (x - SUN.0, y - SUN.1);
    if dx * dx + dy * dy <= SUN_RADIUS * SUN_RADIUS {
        SUN_RADIANCE
    } else {
        0.0
    }
}

/// The lobe the environment is multiplied by: 1 − d²/R² clamped at 0, like a cosine.
pub fn lobe(x: f64, y: f64) -> f64 {
    let (dx, dy) = (x - LOBE.0, y - LOBE.1);
    (1.0 - (dx * dx + dy * dy) / LOBE.2).max(0.0)
}

/// The rasterised environment.
#[derive(Debug, Clone, PartialEq)]
pub struct EnvMap {
    /// Columns.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// Sky + sun at pixel centres, row-major.
    pub pixels: Vec<f64>,
}

impl EnvMap {
    /// Rasterises sky + sun at the pixel centres.
    pub fn new(width: usize, height: usize) -> Self {
        let mut pixels = Vec::with_capacity(width * height);
        for y in 0..height {
            let v = (y as f64 + 0.5) / height as f64;
            pixels.extend((0..width).map(|x| {
                let u = (x as f64 + 0.5) / width as f64;
                sky(u, v) + sun(u, v)
            }));
        }
        Self {
            width,
            height,
            pixels,
        }
    }

    /// The map at `(x, y) ∈ [0,1)²` (nearest pixel).
    pub fn eval(&self, x: f64, y: f64) -> f64 {
        let i = ((x * self.width as f64) as usize).min(self.width - 1);
        let j = ((y * self.height as f64) as usize).min(self.height - 1);
        self.pixels[j * self.width + i]
    }

    /// The integrand of the estimate: map × lobe.
    pub fn integrand(&self, x: f64, y: f64) -> f64 {
        self.eval(x, y) * lobe(x, y)
    }

    /// ∫ map × lobe over `[0,1]²`: per pixel, its value times the lobe integrated by a
    /// `sub × sub` midpoint rule.
    pub fn reference_integral(&self, sub: usize) -> f64 {
        let (hx, hy) = (1.0 / self.width as f64, 1.0 / self.height as f64);
        let (sx, sy) = (hx / sub as f64, hy / sub as f64);
        let mut total = 0.0;
        for (j, row) in self.pixels.chunks_exact(self.width).enumerate() {
            for (i, v) in row.iter().enumerate() {
                let mut l = 0.0;
                for b in 0..sub {
                    let y = j as f64 * hy + (b as f64 + 0.5) * sy;
                    l += (0..sub)
                        .map(|a| lobe(i as f64 * hx + (a as f64 + 0.5) * sx, y))
                        .sum::<f64>();
                }
                total += v * l * sx * sy;
            }
        }
        total
    }

    /// Box-filtered down by integer factors to `width × height` (cell means), as f32.
    pub fn downsample(&self, width: usize, height: usize) -> Vec<f32> {
        let (fx, fy) = (self.width / width, self.height / height);
        debug_assert!(fx * width == self.width && fy * height == self.height);
        let mut out = vec![0.0f64; width * height];
        for (y, row) in self.pixels.chunks_exact(self.width).enumerate() {
            let o = &mut out[(y / fy) * width..(y / fy + 1) * width];
            for (x, v) in row.iter().enumerate() {
                o[x / fx] += v;
            }
        }
        let norm = 1.0 / (fx * fy) as f64;
        out.iter().map(|v| (v * norm) as f32).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reference_integral_converges() {
        let map = EnvMap::new(256, 128);
        let a = map.reference_integral(2);
        let b = map.reference_integral(8);
        assert!(
            a.is_finite() && b.is_finite() && ((a - b) / b).abs() < 1e-4,
            "{a} {b}"
        );
        let fine = EnvMap::new(2048, 1024);
        let sun_area =
            fine.pixels.iter().filter(|&&v| v > 100.0).count() as f64 / (2048.0 * 1024.0);
        let disc = std::f64::consts::PI * SUN_RADIUS * SUN_RADIUS;
        assert!(((sun_area - disc) / disc).abs() < 2e-2, "{sun_area} {disc}");
    }

    #[test]
    fn downsample_keeps_the_mean_and_eval_finds_pixels() {
        let map = EnvMap::new(64, 32);
        let small = map.downsample(8, 4);
        let mean_big: f64 = map.pixels.iter().sum::<f64>() / map.pixels.len() as f64;
        let mean_small: f64 = small.iter().map(|&v| f64::from(v)).sum::<f64>() / 32.0;
        assert!(((mean_big - mean_small) / mean_big).abs() < 1e-6);
        let tiny = EnvMap {
            width: 2,
            height: 2,
            pixels: vec![1.0, 3.0, 5.0, 7.0],
        };
        assert_eq!(tiny.downsample(1, 1), vec![4.0]);
        assert_eq!((tiny.eval(0.7, 0.2), tiny.eval(0.2, 0.99)), (3.0, 5.0));
    }
}
