//! Block means with honest error bars for estimators whose per-pixel variance the film does
//! not know (light tracing and Metropolis splat anywhere on the film): the image is rendered
//! as `R` independent replicates (different seeds), and each 32×32 block's mean is compared
//! with a Student-t test on the `R` replicate means, Šidák-corrected over the blocks and
//! channels tested to the suite's per-test level (one test of the shared budget,
//! `tests/it/common/suite.rs`).

use mcrt::glam::Vec3;
use mcrt_render::description::SceneDescription;
use mcrt_render::render::{RenderOptions, Renderer};
use statrs::distribution::{ContinuousCDF, StudentsT};
use std::sync::atomic::AtomicBool;

/// The replicate images (`replicates` renders with seeds `seed`, `seed + 1`, …).
pub fn render_replicates(
    desc: &SceneDescription,
    opts: &RenderOptions,
    replicates: u32,
    seed: u64,
) -> (u32, u32, Vec<Vec<Vec3>>) {
    let mut images = Vec::new();
    let mut size = (0, 0);
    for r in 0..replicates {
        let o = RenderOptions {
            seed: Some(seed + r as u64),
            ..opts.clone()
        };
        let out = Renderer::new(desc, &o)
            .expect("scene builds")
            .render(&|_, _| {}, &AtomicBool::new(false));
        size = (out.film.width(), out.film.height());
        images.push(out.image());
    }
    (size.0, size.1, images)
}

/// Mean of each `block`×`block` block of `img` (`w`×`h`), row-major.
pub fn block_means(img: &[Vec3], w: u32, h: u32, block: u32) -> Vec<Vec3> {
    let (bw, bh) = (w / block, h / block);
    let mut out = vec![Vec3::ZERO; (bw * bh) as usize];
    for y in 0..bh * block {
        for x in 0..bw * block {
            out[((y / block) * bw + x / block) as usize] += img[(y * w + x) as usize];
        }
    }
    let n = (block * block) as f32;
    out.iter().map(|v| *v / n).collect()
}

/// What a replicate comparison found.
#[derive(Debug)]
pub struct Comparison {
    /// Blocks compared (brighter than 5% of the reference's mean).
    pub blocks: usize,
    /// Largest |t| over blocks and channels, after the allowance for bias.
    pub worst_t: f64,
    /// The Šidák-corrected critical value.
    pub t_critical: f64,
    /// Largest relative deviation of a block mean from the reference.
    pub worst_relative: f64,
    /// Image mean over reference mean, per channel.
    pub mean_ratio: Vec3,
    /// Non-finite pixels in any replicate.
    pub non_finite: usize,
}

/// Compares the mean of the replicates with `reference` (a `w`×`h` image) on `block`×`block`
/// blocks: each block and channel passes when `|mean − ref| ≤ t·se + allowance·ref`, `se`
/// the standard error from the replicates and `allowance` the reference's own error plus
/// any bias the caller accepts (0.01 = 1%). `worst_t` is the largest
/// `(|mean − ref| − allowance·ref)/se`.
pub fn compare(
    images: &[Vec<Vec3>],
    reference: &[Vec3],
    w: u32,
    h: u32,
    block: u32,
    allowance: f64,
) -> Comparison {
    let r = images.len();
    assert!(r >= 2, "need at least two replicates");
    let non_finite = images.iter().flatten().filter(|v| !v.is_finite()).count();
    let per: Vec<Vec<Vec3>> = images
        .iter()
        .map(|img| block_means(img, w, h, block))
        .collect();
    let refb = block_means(reference, w, h, block);
    let ref_mean = reference.iter().copied().sum::<Vec3>() / reference.len() as f32;
    let img_mean = images.iter().flatten().copied().sum::<Vec3>() / (r * reference.len()) as f32;
    let threshold = 0.05 * (ref_mean.x + ref_mean.y + ref_mean.z) / 3.0;
    let bright: Vec<usize> = (0..refb.len())
        .filter(|&i| (refb[i].x + refb[i].y + refb[i].z) / 3.0 > threshold)
        .collect();
    let tests = (bright.len() * 3).max(1) as f64;
    let per_test = 1.0 - (1.0 - super::per_test_alpha()).powf(1.0 / tests);
    let t_critical = StudentsT::new(0.0, 1.0, (r - 1) as f64)
        .expect("valid t distribution")
        .inverse_cdf(1.0 - per_test / 2.0);
    let (mut worst_t, mut worst_relative) = (0.0f64, 0.0f64);
    for &i in &bright {
        for c in 0..3 {
            let xs: Vec<f64> = per.iter().map(|b| b[i][c] as f64).collect();
            let m = xs.iter().sum::<f64>() / r as f64;
            let var = xs.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (r - 1) as f64;
            let se = (var / r as f64).sqrt();
            let rf = refb[i][c] as f64;
            let dev = (m - rf).abs();
            let t = (dev - allowance * rf).max(0.0) / se.max(1e-30);
            // NaN anywhere makes the comparison fail.
            worst_t = if t.is_nan() {
                f64::INFINITY
            } else {
                worst_t.max(t)
            };
            worst_relative = worst_relative.max(dev / rf.max(1e-30));
        }
    }
    Comparison {
        blocks: bright.len(),
        worst_t,
        t_critical,
        worst_relative,
        mean_ratio: img_mean / ref_mean,
        non_finite,
    }
}

impl Comparison {
    /// Fails the test with the figures unless every block passed and no pixel is NaN.
    pub fn assert_passed(&self, what: &str) {
        println!("{what}: {self:?}");
        assert_eq!(self.non_finite, 0, "{what}: non-finite pixels");
        assert!(
            self.blocks >= 4,
            "{what}: only {} blocks compared",
            self.blocks
        );
        assert!(
            self.worst_t.is_finite() && self.worst_t <= self.t_critical,
            "{what}: worst |t| {:.2} > {:.2} (worst block {:.1}%, mean ratio {})",
            self.worst_t,
            self.t_critical,
            100.0 * self.worst_relative,
            self.mean_ratio
        );
    }
}
