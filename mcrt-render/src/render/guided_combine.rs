//! The guided path tracer's image from several passes: each pass's image weighted by the
//! inverse of its variance (Müller 2019, "Practical Path Guiding in Production", SIGGRAPH
//! course notes, §10: the training passes' images are not thrown away), with the weights of
//! one half of the pixels estimated from the other half, so that the combination stays
//! unbiased. Derivation: `docs/renderer.md`, "Path guiding".
//!
//! Each pass's image is unbiased whatever guide it was rendered with. Pixels are split like a
//! checkerboard into two classes, `(x + y)` even and odd. A pass's variance is estimated on
//! each class (the mean over its pixels of the variance of the pixel estimate, channels
//! averaged), and a pixel of one class takes the weights `w_k ∝ 1 / V_k` estimated on the
//! other class. Its passes' samples are independent of the other class's, so
//! `E[Σ w_k I_k] = Σ E[w_k] E[I_k] = I`: no bias from weights that depend on the data,
//! as there would be if a pass were weighted by its own noise.

use crate::film::{Film, PixelAccum};
use glam::Vec3;

/// The film whose pixel `i` is `Σ_k w_k · mean_k(i)` over `passes` (all of one size), with
/// the weights described above, renormalised over the passes that have at least one
/// sample in the pixel; its variance is `Σ w_k² · var_k(i)` and its count the passes'
/// counts summed. A class whose variance estimates are not all positive and finite (a
/// black image, passes of one sample) weights the passes by their sample counts instead,
/// which is the plain mean of all samples.
pub(crate) fn combine(passes: &[Film]) -> Film {
    let (width, height) = passes.first().map_or((0, 0), |f| (f.width(), f.height()));
    let mut out = Film::new(width, height);
    let means: Vec<Vec<Vec3>> = passes.iter().map(Film::mean).collect();
    let vars: Vec<Vec<Vec3>> = passes.iter().map(Film::variance).collect();
    let class = |i: usize| ((i % width as usize) + (i / width as usize)) % 2;
    // The weights that pixels of class c take: estimated on class 1 − c.
    let weights: [Vec<f64>; 2] =
        std::array::from_fn(|c| class_weights(passes, &vars, |i| class(i) != c));
    for i in 0..(width as usize * height as usize) {
        let w = &weights[class(i)];
        let present: f64 = (0..passes.len())
            .filter(|&k| passes[k].count(i) > 0)
            .map(|k| w[k])
            .sum();
        let n: u32 = passes.iter().map(|f| f.count(i)).sum();
        if n == 0 || present.is_nan() || present <= 0.0 {
            continue;
        }
        let mut mean = [0.0f64; 3];
        let mut var = [0.0f64; 3];
        for k in (0..passes.len()).filter(|&k| passes[k].count(i) > 0) {
            let wk = w[k] / present;
            let (m, v) = (means[k][i], vars[k][i]);
            for c in 0..3 {
                mean[c] += wk * f64::from(m[c]);
                var[c] += wk * wk * f64::from(v[c]);
            }
        }
        let nf = f64::from(n);
        // The sums whose mean and variance (`Film::mean`, `Film::variance`) are the above.
        let acc = PixelAccum {
            sum: mean.map(|m| m * nf),
            sum_sq: std::array::from_fn(|c| nf * (mean[c] * mean[c] + (nf - 1.0) * var[c])),
            count: n,
        };
        let merged = out.merge(i, &acc);
        debug_assert!(merged.is_ok());
    }
    out
}

/// Each pass's weight from the pixels `in_class`: `1 / V_k`, normalised; by sample counts if
/// some `V_k` is not positive and finite.
fn class_weights(
    passes: &[Film],
    vars: &[Vec<Vec3>],
    in_class: impl Fn(usize) -> bool,
) -> Vec<f64> {
    let inverse: Vec<f64> = vars
        .iter()
        .zip(passes)
        .map(|(v, f)| {
            let (mut sum, mut n) = (0.0f64, 0u64);
            for (i, x) in v.iter().enumerate() {
                if in_class(i) && f.count(i) >= 2 {
                    sum += f64::from(x.element_sum()) / 3.0;
                    n += 1;
                }
            }
            let mean = sum / n as f64;
            1.0 / mean
        })
        .collect();
    let raw = if inverse.iter().all(|w| *w > 0.0 && w.is_finite()) {
        inverse
    } else {
        passes
            .iter()
            .map(|f| {
                let n: u64 = (0..f.width() as usize * f.height() as usize)
                    .map(|i| u64::from(f.count(i)))
                    .sum();
                n as f64
            })
            .collect()
    };
    let total: f64 = raw.iter().sum();
    raw.iter()
        .map(|w| if total > 0.0 { w / total } else { 0.0 })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A film whose every pixel has the samples `values`.
    fn film(w: u32, h: u32, values: impl Fn(usize) -> Vec<f32>) -> Film {
        let mut f = Film::new(w, h);
        for i in 0..(w * h) as usize {
            let mut a = PixelAccum::default();
            for v in values(i) {
                a.add(Vec3::splat(v));
            }
            f.merge(i, &a).unwrap();
        }
        f
    }

    #[test]
    fn equal_passes_average_and_a_noisy_pass_weighs_little() {
        // Two passes of equal noise: the plain mean.
        let a = film(4, 4, |_| vec![1.0, 3.0]);
        let b = film(4, 4, |_| vec![2.0, 4.0]);
        let c = combine(&[a.clone(), b]);
        let m = c.mean();
        assert!(
            m.iter().all(|v| v.is_finite() && (v.x - 2.5).abs() < 1e-6),
            "{m:?}"
        );
        assert_eq!(c.count(0), 4);
        // A pass 100× noisier (variance 10⁴×) gets about 10⁻⁴ of the weight.
        let noisy = film(4, 4, |_| vec![-98.0, 102.0]);
        let m = combine(&[a, noisy]).mean();
        assert!(
            m.iter().all(|v| v.is_finite() && (v.x - 2.0).abs() < 1e-3),
            "{m:?}"
        );
    }

    #[test]
    fn a_pixel_takes_the_weights_of_the_other_class() {
        // Pass `a` is noisy on even pixels only, pass `b` on odd ones: an odd pixel is
        // weighted by the even pixels' noise, so it leans on `b` although `b` is the noisy
        // one there.
        let even = |i: usize| ((i % 4) + (i / 4)).is_multiple_of(2);
        let a = film(4, 4, |i| {
            if even(i) {
                vec![-9.0, 11.0]
            } else {
                vec![0.9, 1.1]
            }
        });
        let b = film(4, 4, |i| {
            if even(i) {
                vec![2.9, 3.1]
            } else {
                vec![-7.0, 13.0]
            }
        });
        let m = combine(&[a, b]).mean();
        let odd = m[1].x; // pixel (1, 0)
        let even_px = m[0].x; // pixel (0, 0)
        assert!(odd.is_finite() && (odd - 3.0).abs() < 0.01, "{odd}");
        assert!(
            even_px.is_finite() && (even_px - 1.0).abs() < 0.01,
            "{even_px}"
        );
    }

    #[test]
    fn black_passes_fall_back_to_the_mean_of_all_samples() {
        let a = film(2, 2, |_| vec![0.0, 0.0]);
        let b = film(2, 2, |_| vec![0.0; 4]);
        let c = combine(&[a, b]);
        assert!(c.mean().iter().all(|v| *v == Vec3::ZERO));
        assert_eq!(c.count(3), 6);
        assert!(c
            .variance()
            .iter()
            .all(|v| v.is_finite() && *v == Vec3::ZERO));
    }
}
