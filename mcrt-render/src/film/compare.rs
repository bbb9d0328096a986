//! Comparing a render with a reference image by block means: a z-test that uses the
//! render's own per-pixel variance (Šidák-corrected over the blocks and channels) and the
//! relative error of every block brighter than a threshold.

use glam::Vec3;

/// The outcome of [`compare_blocks`].
#[derive(Debug, Clone, PartialEq)]
pub struct BlockReport {
    /// Block edge in pixels.
    pub block: u32,
    /// Blocks compared (those whose reference mean exceeds the brightness threshold).
    pub blocks: usize,
    /// Largest relative error of a compared block's mean (over channels), e.g. 0.03 = 3%.
    pub worst_relative: f64,
    /// Largest |z| over compared blocks and channels.
    pub worst_z: f64,
    /// The two-sided critical |z| at the requested level after the Šidák correction over
    /// `3 · blocks` tests.
    pub z_critical: f64,
    /// Image mean over reference mean, per channel.
    pub mean_ratio: Vec3,
    /// Pixels that are NaN or infinite in the render.
    pub non_finite: usize,
}

impl BlockReport {
    /// Whether every block passes the z-test.
    pub fn z_test_passes(&self) -> bool {
        self.worst_z.is_finite() && self.worst_z <= self.z_critical
    }
}

/// Complementary error function, relative error below 1.2·10⁻⁷ (Press, Teukolsky,
/// Vetterling, Flannery 2007, "Numerical Recipes", 3rd ed., section 6.2, `erfccheb`'s
/// simpler predecessor `erfcc`).
fn erfc(x: f64) -> f64 {
    let z = x.abs();
    let t = 1.0 / (1.0 + 0.5 * z);
    let poly = -z * z - 1.265_512_23
        + t * (1.000_023_68
            + t * (0.374_091_96
                + t * (0.096_784_18
                    + t * (-0.186_288_06
                        + t * (0.278_868_07
                            + t * (-1.135_203_98
                                + t * (1.488_515_87 + t * (-0.822_152_23 + t * 0.170_872_77))))))));
    let r = t * poly.exp();
    if x >= 0.0 {
        r
    } else {
        2.0 - r
    }
}

/// The |z| whose two-sided tail probability is `alpha`, by bisection.
pub fn z_two_sided(alpha: f64) -> f64 {
    let (mut lo, mut hi) = (0.0f64, 40.0f64);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if erfc(mid / std::f64::consts::SQRT_2) > alpha {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

fn block_sums(px: &[Vec3], w: u32, h: u32, b: u32) -> Vec<[f64; 3]> {
    let (bw, bh) = (w / b, h / b);
    let mut out = vec![[0.0f64; 3]; (bw * bh) as usize];
    for y in 0..bh * b {
        for x in 0..bw * b {
            let p = px[(y * w + x) as usize];
            let o = &mut out[((y / b) * bw + x / b) as usize];
            o[0] += p.x as f64;
            o[1] += p.y as f64;
            o[2] += p.z as f64;
        }
    }
    out
}

fn image_mean(px: &[Vec3]) -> [f64; 3] {
    let mut s = [0.0f64; 3];
    for p in px {
        s[0] += p.x as f64;
        s[1] += p.y as f64;
        s[2] += p.z as f64;
    }
    s.map(|v| v / px.len().max(1) as f64)
}

/// Compares `img` (with per-pixel `variance` of its estimate) against `reference` (with its
/// own variance when it is a render too, else `None`), all `w × h` row-major, over `block × block` blocks (partial blocks at the edges are left
/// out). Blocks whose reference mean (over channels) is below `min_brightness` times the
/// reference image mean are skipped. `alpha` is the family-wise level of the z-test.
#[allow(clippy::too_many_arguments)]
pub fn compare_blocks(
    img: &[Vec3],
    variance: &[Vec3],
    reference: &[Vec3],
    reference_variance: Option<&[Vec3]>,
    w: u32,
    h: u32,
    block: u32,
    min_brightness: f64,
    alpha: f64,
) -> BlockReport {
    let n = (block * block) as f64;
    let (si, sv, sr) = (
        block_sums(img, w, h, block),
        block_sums(variance, w, h, block),
        block_sums(reference, w, h, block),
    );
    let srv = reference_variance.map(|v| block_sums(v, w, h, block));
    let rm = image_mean(reference);
    let im = image_mean(img);
    let thresh = min_brightness * (rm[0] + rm[1] + rm[2]) / 3.0;
    let (mut blocks, mut worst_rel, mut worst_z) = (0usize, 0.0f64, 0.0f64);
    for k in 0..si.len() {
        let r = sr[k].map(|v| v / n);
        if (r[0] + r[1] + r[2]) / 3.0 <= thresh {
            continue;
        }
        blocks += 1;
        for c in 0..3 {
            let m = si[k][c] / n;
            let var = (sv[k][c] + srv.as_ref().map_or(0.0, |v| v[k][c])) / (n * n);
            if r[c] > 0.0 && r[c] > 0.05 * thresh {
                worst_rel = worst_rel.max(((m - r[c]) / r[c]).abs());
            }
            let z = if var > 0.0 {
                (m - r[c]).abs() / var.sqrt()
            } else if (m - r[c]).abs() > 1e-6 * r[c].abs().max(1e-6) {
                f64::INFINITY
            } else {
                0.0
            };
            if !z.is_finite() || z > worst_z || z.is_nan() {
                worst_z = if z.is_nan() {
                    f64::INFINITY
                } else {
                    worst_z.max(z)
                };
            }
        }
    }
    let tests = (3 * blocks).max(1) as f64;
    let alpha_each = 1.0 - (1.0 - alpha).powf(1.0 / tests);
    BlockReport {
        block,
        blocks,
        worst_relative: worst_rel,
        worst_z,
        z_critical: z_two_sided(alpha_each),
        mean_ratio: Vec3::new(
            (im[0] / rm[0]) as f32,
            (im[1] / rm[1]) as f32,
            (im[2] / rm[2]) as f32,
        ),
        non_finite: img.iter().filter(|p| !p.is_finite()).count(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normal_quantiles() {
        for (a, z) in [(0.05, 1.959_964), (0.01, 2.575_829), (1e-4, 3.890_592)] {
            let q = z_two_sided(a);
            assert!(q.is_finite() && (q - z).abs() < 1e-4, "{a}: {q}");
        }
    }

    #[test]
    fn identical_images_pass_and_a_scaled_one_fails() {
        let img: Vec<Vec3> = (0..64).map(|i| Vec3::splat(1.0 + (i % 7) as f32)).collect();
        let var = vec![Vec3::splat(1e-4); 64];
        let r = compare_blocks(&img, &var, &img, None, 8, 8, 4, 0.05, 0.01);
        assert!(r.z_test_passes() && r.worst_relative == 0.0 && r.blocks == 4);
        let scaled: Vec<Vec3> = img.iter().map(|p| *p * 1.05).collect();
        let r = compare_blocks(&scaled, &var, &img, Some(&var), 8, 8, 4, 0.05, 0.01);
        assert!(!r.z_test_passes());
        assert!((r.worst_relative - 0.05).abs() < 1e-5);
        assert!((r.mean_ratio.x - 1.05).abs() < 1e-5);
    }
}
