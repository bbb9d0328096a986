//! The film: per-pixel accumulation of radiance samples (mean and variance of the mean),
//! the pixel reconstruction filters, EXR/PNG output, and the parts of a distributed render
//! ([`write_part`], [`read_part`], [`merge_parts`]; `docs/distributed.md`).
//!
//! Filters are applied by *filter importance sampling*: a pixel sample's position is drawn
//! from the filter's density around the pixel centre, and the pixel value is the plain mean
//! of its samples. For the box filter that is exactly Mitsuba's estimate; for the Gaussian it
//! has the same expectation as Mitsuba's weighted splatting, keeps pixels independent (so
//! tiles need no shared borders), and makes the per-pixel variance a plain sample variance.
//! Ernst, Stamminger, Greiner 2006, "Filter Importance Sampling", IEEE Symposium on
//! Interactive Ray Tracing.

mod compare;
mod filter;
mod merge;
mod moment;
mod output;
mod part;
mod window;
mod write;

pub(crate) use moment::xyz_squared;

pub use crate::io::{read_exr, read_exr_at_most, ImageError};
pub use compare::{compare_blocks, z_two_sided, BlockReport};
pub use filter::PixelFilter;
pub use merge::{merge_parts, MergeError};
pub use output::{OutputError, OutputPlan, DEFAULT_FOLDER, EXIT_INTERRUPTED};
pub use part::{read_part, write_part, Part, PartInfo, PartMoment};
pub use window::{Crop, SampleRange, WindowError};
pub use write::{write_exr, write_exr_with_channels, write_png};

use glam::Vec3;

/// The factor by which light tracing's splat sums enter the image: 1 / the pixel samples
/// taken per pixel (`samples` over `pixels`), each of which traced one light subpath; 0 if
/// none. A render and the merge of its parts compute it alike, so they agree bit for bit.
pub(crate) fn splat_scale(samples: u64, pixels: u64) -> f64 {
    let taken = samples as f64 / pixels as f64;
    if taken > 0.0 {
        1.0 / taken
    } else {
        0.0
    }
}

/// Accumulated samples for every pixel: sums of values and of squares in f64, and counts.
#[derive(Debug, Clone, PartialEq)]
pub struct Film {
    width: u32,
    height: u32,
    sum: Vec<[f64; 3]>,
    sum_sq: Vec<[f64; 3]>,
    count: Vec<u32>,
    /// Contributions splatted onto the film from elsewhere (light tracing, Metropolis),
    /// summed per pixel; the image adds them times `splat_scale`.
    splat: Vec<[f64; 3]>,
    splat_scale: f64,
    /// The `moment` integrator's sums, if the scene asks for its channels.
    moment: Option<moment::Moment>,
}

/// [`Film::merge`] was given a pixel index past the end of the film.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PixelOutOfRange {
    /// The index given.
    pub index: usize,
    /// The film's pixel count.
    pub pixels: usize,
}

impl std::fmt::Display for PixelOutOfRange {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "pixel index {} is outside a film of {} pixels",
            self.index, self.pixels
        )
    }
}

impl std::error::Error for PixelOutOfRange {}

/// One pixel's accumulated samples (what a render tile hands back).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PixelAccum {
    /// Sum of the sample values.
    pub sum: [f64; 3],
    /// Sum of their squares.
    pub sum_sq: [f64; 3],
    /// Number of samples.
    pub count: u32,
}

impl PixelAccum {
    /// Adds one sample.
    #[inline]
    pub fn add(&mut self, v: Vec3) {
        for (c, x) in [v.x, v.y, v.z].into_iter().enumerate() {
            let x = x as f64;
            self.sum[c] += x;
            self.sum_sq[c] += x * x;
        }
        self.count += 1;
    }
}

impl Film {
    /// An empty film.
    pub fn new(width: u32, height: u32) -> Self {
        let n = width as usize * height as usize;
        Self {
            width,
            height,
            sum: vec![[0.0; 3]; n],
            sum_sq: vec![[0.0; 3]; n],
            count: vec![0; n],
            splat: Vec::new(),
            splat_scale: 0.0,
            moment: None,
        }
    }

    /// This film, keeping the sums for Mitsuba 3's `moment` channels (named after the nested
    /// integrator `name`: `NAME.X` … `m2_NAME.Z`), which the EXR then holds beside the image.
    pub fn with_moment(mut self, name: &str) -> Self {
        self.moment = Some(moment::Moment {
            name: name.to_string(),
            sum_sq_xyz: vec![[0.0; 3]; self.count.len()],
            more: Vec::new(),
        });
        self
    }

    /// This film, keeping the sums of further integrators nested in `moment`, named `names`
    /// in file order (their channels follow the first one's; nothing unless the film was
    /// made [`with_moment`](Self::with_moment)).
    pub(crate) fn with_moment_more(mut self, names: &[&str]) -> Self {
        let n = self.count.len();
        if let Some(m) = &mut self.moment {
            m.more = names
                .iter()
                .map(|name| moment::MoreSums {
                    name: name.to_string(),
                    sum: vec![[0.0; 3]; n],
                    sum_sq_xyz: vec![[0.0; 3]; n],
                })
                .collect();
        }
        self
    }

    /// Whether the film keeps the sums of more than one integrator nested in `moment`.
    pub(crate) fn has_moment_more(&self) -> bool {
        self.moment.as_ref().is_some_and(|m| !m.more.is_empty())
    }

    /// The `moment` channels beside the image `mean` (the pixel estimates), `unsampled`
    /// where a pixel has no sample; none unless the film was made [`with_moment`](Self::with_moment).
    pub fn extra_channels(&self, mean: &[Vec3], unsampled: f32) -> Vec<(String, Vec<f32>)> {
        self.moment
            .as_ref()
            .map(|m| m.channels(mean, &self.count, unsampled))
            .unwrap_or_default()
    }

    /// The bytes a film of `width × height` pixels takes at most (sums, squares, counts and
    /// splats), for the memory budget ([`crate::memory`]).
    pub fn bytes_for(width: u64, height: u64) -> u64 {
        crate::memory::bytes(width.saturating_mul(height), 3 * 24 + 4)
    }

    /// Adds `v` to the splat sum of pixel `index` (ignored past the end).
    pub fn add_splat(&mut self, index: usize, v: Vec3) {
        self.add_splat_sum(index, [v.x as f64, v.y as f64, v.z as f64]);
    }

    /// Adds a sum of splats, kept in f64, to pixel `index` (ignored past the end): how
    /// [`merge_parts`] adds the splats of the parts of a render.
    pub fn add_splat_sum(&mut self, index: usize, v: [f64; 3]) {
        if self.splat.is_empty() {
            self.splat = vec![[0.0; 3]; self.count.len()];
        }
        if let Some(s) = self.splat.get_mut(index) {
            for (s, v) in s.iter_mut().zip(v) {
                *s += v;
            }
        }
    }

    /// The splat sum of pixel `index`, before the splat scale (0 where nothing was splatted
    /// and past the end).
    pub fn splat_sum(&self, index: usize) -> [f64; 3] {
        self.splat.get(index).copied().unwrap_or([0.0; 3])
    }

    /// The samples accumulated in pixel `index` (none past the end).
    pub fn pixel(&self, index: usize) -> PixelAccum {
        match (
            self.sum.get(index),
            self.sum_sq.get(index),
            self.count.get(index),
        ) {
            (Some(&sum), Some(&sum_sq), Some(&count)) => PixelAccum { sum, sum_sq, count },
            _ => PixelAccum::default(),
        }
    }

    /// Sets the factor by which the splat sums enter the image (for light tracing,
    /// 1 / samples per pixel; for Metropolis sampling, `b` / mutations per pixel).
    pub fn set_splat_scale(&mut self, scale: f64) {
        self.splat_scale = scale;
    }

    /// Whether any contribution was splatted.
    pub fn has_splats(&self) -> bool {
        !self.splat.is_empty()
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Adds a pixel's accumulated samples (pixel index `y · width + x`).
    ///
    /// # Errors
    /// [`PixelOutOfRange`] if `index` is past the last pixel; the film is unchanged.
    pub fn merge(&mut self, index: usize, a: &PixelAccum) -> Result<(), PixelOutOfRange> {
        let pixels = self.count.len();
        let out = PixelOutOfRange { index, pixels };
        let (Some(sum), Some(sum_sq), Some(count)) = (
            self.sum.get_mut(index),
            self.sum_sq.get_mut(index),
            self.count.get_mut(index),
        ) else {
            return Err(out);
        };
        for c in 0..3 {
            sum[c] += a.sum[c];
            sum_sq[c] += a.sum_sq[c];
        }
        *count = count.saturating_add(a.count);
        Ok(())
    }

    /// Adds to pixel `index` a sum of the squared XYZ samples ([`xyz_squared`]) for the
    /// `moment` channels (ignored past the end, or if the film keeps no moment sums).
    pub(crate) fn add_moment(&mut self, index: usize, sum_sq_xyz: [f64; 3]) {
        if let Some(s) = self
            .moment
            .as_mut()
            .and_then(|m| m.sum_sq_xyz.get_mut(index))
        {
            for (s, x) in s.iter_mut().zip(sum_sq_xyz) {
                *s += x;
            }
        }
    }

    /// Adds to pixel `index` the samples of the further nested integrators of `moment`,
    /// each its accumulator and its sum of squared XYZ samples, in file order (ignored past
    /// the end; the counts are the film's own).
    pub(crate) fn add_moment_more(&mut self, index: usize, more: &[(PixelAccum, [f64; 3])]) {
        let Some(m) = self.moment.as_mut() else {
            return;
        };
        for (sums, (acc, sq)) in m.more.iter_mut().zip(more) {
            if let (Some(s), Some(q)) = (sums.sum.get_mut(index), sums.sum_sq_xyz.get_mut(index)) {
                for c in 0..3 {
                    s[c] += acc.sum[c];
                    q[c] += sq[c];
                }
            }
        }
    }

    /// Samples in pixel `index`.
    pub fn count(&self, index: usize) -> u32 {
        self.count[index]
    }

    /// Smallest and largest sample count over the pixels.
    pub fn count_range(&self) -> (u32, u32) {
        let min = self.count.iter().copied().min().unwrap_or(0);
        let max = self.count.iter().copied().max().unwrap_or(0);
        (min, max)
    }

    /// The pixel estimates (means, plus the scaled splats), row-major from the top-left, 0
    /// where no sample landed.
    pub fn mean(&self) -> Vec<Vec3> {
        self.mean_or(Vec3::ZERO)
    }

    /// The pixel estimates, with `unsampled` where no sample landed (a cancelled render
    /// writes NaN there, so that such pixels are marked rather than black).
    /// A film of splats alone (Metropolis sampling) has no per-pixel samples: its pixels
    /// are its splats.
    pub fn mean_or(&self, unsampled: Vec3) -> Vec<Vec3> {
        let splats_only = !self.splat.is_empty() && self.count.iter().all(|&c| c == 0);
        (0..self.count.len())
            .map(|i| {
                if self.count[i] == 0 && !splats_only {
                    return unsampled;
                }
                let n = self.count[i].max(1) as f64;
                let s = self.sum[i];
                let k = self.splat_scale;
                let sp = self.splat.get(i).copied().unwrap_or([0.0; 3]);
                Vec3::new(
                    (s[0] / n + sp[0] * k) as f32,
                    (s[1] / n + sp[1] * k) as f32,
                    (s[2] / n + sp[2] * k) as f32,
                )
            })
            .collect()
    }

    /// The variance of each pixel estimate (sample variance / count), per channel; 0 where
    /// fewer than two samples landed.
    pub fn variance(&self) -> Vec<Vec3> {
        (0..self.count.len())
            .map(|i| {
                let n = self.count[i] as f64;
                if n < 2.0 {
                    return Vec3::ZERO;
                }
                let v: [f32; 3] = std::array::from_fn(|c| {
                    let m = self.sum[i][c] / n;
                    let var = ((self.sum_sq[i][c] / n - m * m) * n / (n - 1.0)).max(0.0);
                    (var / n) as f32
                });
                Vec3::from(v)
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mean_and_variance_of_the_mean() {
        let mut f = Film::new(2, 1);
        let mut a = PixelAccum::default();
        for v in [1.0, 2.0, 3.0, 4.0] {
            a.add(Vec3::splat(v));
        }
        f.merge(1, &a).expect("inside");
        assert_eq!(
            f.merge(2, &a),
            Err(PixelOutOfRange {
                index: 2,
                pixels: 2
            })
        );
        assert_eq!(
            f.merge(usize::MAX, &a).map_err(|e| e.index),
            Err(usize::MAX)
        );
        assert!(f.mean_or(Vec3::NAN)[0].is_nan());
        let m = f.mean();
        let v = f.variance();
        assert_eq!(m[0], Vec3::ZERO);
        assert!((m[1].x - 2.5).abs() < 1e-6);
        // Sample variance 5/3, divided by n = 4.
        assert!(v[1].x.is_finite() && (v[1].x - 5.0 / 12.0).abs() < 1e-6);
        assert_eq!(f.count_range(), (0, 4));
    }
}
