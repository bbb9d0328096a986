//! An environment-like test function on `[0,1]²` — a smooth sky and a small bright sun disc —
//! times a cosine-like lobe, with its integral computed by fine quadrature, and the images the
//! importance tables are built from.

/// Sun centre in `[0,1]²`.
const SUN: (f64, f64) = (0.62, 0.3);
/// Sun radius (in units of the square).
const SUN_RADIUS: f64 = 0.02;
/// Sun radiance (the sun carries about two thirds of the function's integral).
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

/// The environment: sky plus sun (what the tables are built from).
pub fn env(x: f64, y: f64) -> f64 {
    sky(x, y) + sun(x, y)
}

/// The lobe the environment is multiplied by: 1 − d²/R² clamped at 0, like a cosine.
pub fn lobe(x: f64, y: f64) -> f64 {
    let (dx, dy) = (x - LOBE.0, y - LOBE.1);
    (1.0 - (dx * dx + dy * dy) / LOBE.2).max(0.0)
}

/// The integrand of the estimate: environment × lobe.
pub fn integrand(x: f64, y: f64) -> f64 {
    env(x, y) * lobe(x, y)
}

/// Midpoint rule of `f` over `[x0,x1]×[y0,y1]` with `n × n` points.
fn midpoint(
    f: impl Fn(f64, f64) -> f64,
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
    n: usize,
) -> f64 {
    let (hx, hy) = ((x1 - x0) / n as f64, (y1 - y0) / n as f64);
    let mut sum = 0.0;
    for j in 0..n {
        let y = y0 + (j as f64 + 0.5) * hy;
        let row: f64 = (0..n).map(|i| f(x0 + (i as f64 + 0.5) * hx, y)).sum();
        sum += row;
    }
    sum * hx * hy
}

/// ∫ integrand over `[0,1]²`: the smooth part on an `n × n` grid, the sun on an `n × n` grid
/// of its bounding box (relative error well below 10⁻⁴ for `n ≥ 1024`).
pub fn reference_integral(n: usize) -> f64 {
    let smooth = midpoint(|x, y| sky(x, y) * lobe(x, y), (0.0, 1.0), (0.0, 1.0), n);
    let r = SUN_RADIUS;
    let bx = (SUN.0 - r, SUN.0 + r);
    let by = (SUN.1 - r, SUN.1 + r);
    smooth + midpoint(|x, y| sun(x, y) * lobe(x, y), bx, by, n)
}

/// The environment sampled at the centres of a `width × height` grid, row-major.
pub fn image(width: usize, height: usize) -> Vec<f64> {
    let mut img = Vec::with_capacity(width * height);
    for y in 0..height {
        let v = (y as f64 + 0.5) / height as f64;
        img.extend((0..width).map(|x| env((x as f64 + 0.5) / width as f64, v)));
    }
    img
}

/// Box-filters a row-major image down by integer factors to `width × height` (cell means).
pub fn downsample(img: &[f64], iw: usize, ih: usize, width: usize, height: usize) -> Vec<f32> {
    let (fx, fy) = (iw / width, ih / height);
    debug_assert!(fx * width == iw && fy * height == ih);
    let mut out = vec![0.0f64; width * height];
    for (y, row) in img.chunks_exact(iw).enumerate() {
        let o = &mut out[(y / fy) * width..(y / fy + 1) * width];
        for (x, v) in row.iter().enumerate() {
            o[x / fx] += v;
        }
    }
    let norm = 1.0 / (fx * fy) as f64;
    out.iter().map(|v| (v * norm) as f32).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reference_integral_converges() {
        let a = reference_integral(512);
        let b = reference_integral(1024);
        assert!(
            a.is_finite() && b.is_finite() && ((a - b) / b).abs() < 1e-4,
            "{a} {b}"
        );
        let sun_only = midpoint(sun, (0.0, 1.0), (0.0, 1.0), 2000);
        let expect = SUN_RADIANCE * std::f64::consts::PI * SUN_RADIUS * SUN_RADIUS;
        assert!(((sun_only - expect) / expect).abs() < 1e-2);
    }

    #[test]
    fn downsample_keeps_the_mean() {
        let img = image(64, 32);
        let small = downsample(&img, 64, 32, 8, 4);
        let mean_big: f64 = img.iter().sum::<f64>() / img.len() as f64;
        let mean_small: f64 = small.iter().map(|&v| f64::from(v)).sum::<f64>() / 32.0;
        assert!(((mean_big - mean_small) / mean_big).abs() < 1e-6);
        assert_eq!(downsample(&[1.0, 3.0, 5.0, 7.0], 2, 2, 1, 1), vec![4.0]);
    }
}
