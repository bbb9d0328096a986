//! Block comparison of a render against a reference beyond a relative allowance, shared by
//! the reference-match tests.

use mcrt::glam::Vec3;

/// The largest `(|mean − ref| − allowance·ref) / σ` over bright blocks and channels (the
/// blocks and σ of `compare_blocks`).
#[allow(clippy::too_many_arguments)]
pub fn worst_z_beyond(
    img: &[Vec3],
    var: &[Vec3],
    reference: &[Vec3],
    ref_var: &[Vec3],
    w: u32,
    h: u32,
    b: u32,
    allowance: f64,
) -> f64 {
    let n = img.len() as f64;
    let ref_mean = reference
        .iter()
        .map(|v| v.element_sum() as f64)
        .sum::<f64>()
        / (3.0 * n);
    let mut worst = 0.0f64;
    for by in 0..h / b {
        for bx in 0..w / b {
            let (mut m, mut r, mut v) = ([0.0f64; 3], [0.0f64; 3], [0.0f64; 3]);
            for y in by * b..(by + 1) * b {
                for x in bx * b..(bx + 1) * b {
                    let i = (y * w + x) as usize;
                    for c in 0..3 {
                        m[c] += f64::from(img[i][c]);
                        r[c] += f64::from(reference[i][c]);
                        v[c] += f64::from(var[i][c] + ref_var[i][c]);
                    }
                }
            }
            let k = f64::from(b * b);
            if r.iter().sum::<f64>() / (3.0 * k) <= 0.05 * ref_mean {
                continue;
            }
            for c in 0..3 {
                let dev = ((m[c] - r[c]).abs() - allowance * r[c].abs()).max(0.0) / k;
                // Within the allowance is z = 0 even without noise (a block of constant
                // sky has no variance); a NaN deviation still fails below.
                let z = if dev == 0.0 {
                    0.0
                } else {
                    dev / (v[c] / (k * k)).sqrt()
                };
                worst = if z.is_nan() {
                    f64::INFINITY
                } else {
                    worst.max(z)
                };
            }
        }
    }
    worst
}
