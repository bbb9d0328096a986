//! The stratified sampler: jittered strata, padded across dimensions.

use glam::Vec2;

use super::hash::{in_stratum, permute, unit_f32};
use super::padded::PaddedKeys;
use super::{check_spp, stream_dimension, SampleSource, Sampler};
use crate::sampling::SamplingError;

/// Tags that keep the 1D and 2D permutation keys of one dimension apart.
const TAG_1D: u64 = 0x1d;
const TAG_2D: u64 = 0x2d;

/// Jittered stratified sample values, stratified per dimension and padded across dimensions.
///
/// The sample count is rounded up to a perfect square `n²` (as Mitsuba 3's `stratified`
/// plugin does: 5 becomes 9, 16 stays 16). Within a pixel, the `n²` samples of each 2D
/// dimension fall one in each cell of an `n × n` grid, and those of each 1D dimension one in
/// each interval `[k/n², (k+1)/n²)`. Which sample gets which stratum is a random permutation
/// drawn afresh for every (pixel, dimension), so different dimensions are decorrelated (the
/// padding of Kollig & Keller 2002, "Efficient multidimensional sampling", Computer Graphics
/// Forum 21(3); pbrt's and Mitsuba's stratified samplers work the same way). Inside its stratum
/// a value is placed uniformly at random (`jitter = true`) or at the centre.
///
/// Sample indices at or beyond [`Sampler::samples_per_pixel`] start a new round of strata with
/// fresh permutations: each complete round of `n²` samples is stratified on its own. All values
/// lie in `[0, 1 − 2⁻²⁴]`: never 1.0.
///
/// ```
/// use mcrt::sampling::sampler::{SampleSource, Sampler, StratifiedSampler};
///
/// let mut s = StratifiedSampler::new(5, 1, true).unwrap();
/// assert_eq!(s.samples_per_pixel(), 9); // rounded up to 3 × 3
/// let mut cells = [0; 9];
/// for i in 0..9 {
///     s.start_pixel_sample([4, 2], i);
///     let u = s.next_2d();
///     cells[(u.y * 3.0) as usize * 3 + (u.x * 3.0) as usize] += 1;
/// }
/// assert_eq!(cells, [1; 9]); // one sample per stratum
/// ```
#[derive(Debug, Clone)]
pub struct StratifiedSampler {
    resolution: u32,
    spp: u32,
    seed: u64,
    jitter: bool,
    keys: PaddedKeys,
}

impl StratifiedSampler {
    /// A sampler for `spp` samples per pixel (at least 1; rounded up to a perfect square, which
    /// must not exceed 65535²), a `seed`, and whether to jitter within strata (`false` places
    /// values at stratum centres).
    pub fn new(spp: u32, seed: u64, jitter: bool) -> Result<Self, SamplingError> {
        let resolution = Self::resolution_for(check_spp(spp)?);
        let spp = resolution
            .checked_mul(resolution)
            .ok_or(SamplingError::InvalidParameter {
                name: "spp",
                value: f64::from(spp),
                expected: "at most 65535²",
            })?;
        Ok(Self {
            resolution,
            spp,
            seed,
            jitter,
            keys: PaddedKeys::default(),
        })
    }

    /// The sample count a request for `spp` becomes: the next perfect square (Mitsuba's rule).
    pub fn rounded_sample_count(spp: u32) -> u64 {
        let n = u64::from(Self::resolution_for(spp.max(1)));
        n * n
    }

    /// The number of strata along each axis of a 2D dimension (`n` for `n²` samples).
    pub fn resolution(&self) -> u32 {
        self.resolution
    }

    /// Whether values are jittered within their strata.
    pub fn jitter(&self) -> bool {
        self.jitter
    }

    /// The smallest `n` with `n² ≥ spp`.
    fn resolution_for(spp: u32) -> u32 {
        let mut n = (f64::from(spp)).sqrt() as u32;
        while u64::from(n) * u64::from(n) < u64::from(spp) {
            n += 1;
        }
        while n > 1 && u64::from(n - 1) * u64::from(n - 1) >= u64::from(spp) {
            n -= 1;
        }
        n
    }
}

impl Sampler for StratifiedSampler {
    fn start_pixel_sample(&mut self, pixel: [u32; 2], sample_index: u32) {
        self.keys.start(self.seed, self.spp, pixel, sample_index);
    }

    fn samples_per_pixel(&self) -> u32 {
        self.spp
    }
}

impl SampleSource for StratifiedSampler {
    #[inline]
    fn next_1d(&mut self) -> f32 {
        let stratum = permute(
            self.keys.index_in_round,
            self.spp,
            self.keys.pattern_key(TAG_1D),
        );
        let offset = if self.jitter {
            unit_f32(self.keys.jitter_bits() as u32)
        } else {
            0.5
        };
        self.keys.dimension += 1;
        in_stratum(stratum, offset, self.spp)
    }

    #[inline]
    fn next_2d(&mut self) -> Vec2 {
        let stratum = permute(
            self.keys.index_in_round,
            self.spp,
            self.keys.pattern_key(TAG_2D),
        );
        let (ox, oy) = if self.jitter {
            let bits = self.keys.jitter_bits();
            (unit_f32(bits as u32), unit_f32((bits >> 32) as u32))
        } else {
            (0.5, 0.5)
        };
        self.keys.dimension += 1;
        let n = self.resolution;
        Vec2::new(
            in_stratum(stratum % n, ox, n),
            in_stratum(stratum / n, oy, n),
        )
    }

    #[inline]
    fn start_stream(&mut self, stream: u32) {
        self.skip_to_dimension(stream_dimension(stream));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_round_up_to_squares() {
        for (asked, got) in [
            (1, 1),
            (2, 4),
            (4, 4),
            (5, 9),
            (16, 16),
            (17, 25),
            (1000, 1024),
        ] {
            let s = StratifiedSampler::new(asked, 0, true).unwrap();
            assert_eq!(s.samples_per_pixel(), got, "asked {asked}");
            assert_eq!(
                StratifiedSampler::rounded_sample_count(asked),
                u64::from(got)
            );
        }
    }

    #[test]
    fn huge_and_zero_counts_are_errors_not_panics() {
        assert!(StratifiedSampler::new(0, 0, true).is_err());
        assert!(StratifiedSampler::new(u32::MAX, 0, true).is_err());
        assert!(StratifiedSampler::new(65535 * 65535, 0, true).is_ok());
    }

    #[test]
    fn unjittered_values_are_stratum_centres() {
        let mut s = StratifiedSampler::new(4, 9, false).unwrap();
        let mut xs: Vec<f32> = (0..4)
            .map(|i| {
                s.start_pixel_sample([0, 0], i);
                s.next_1d()
            })
            .collect();
        xs.sort_by(f32::total_cmp);
        assert_eq!(xs, [0.125, 0.375, 0.625, 0.875]);
    }

    #[test]
    fn dimensions_use_different_permutations() {
        let mut s = StratifiedSampler::new(64, 5, false).unwrap();
        let mut same = 0;
        for i in 0..64 {
            s.start_pixel_sample([3, 3], i);
            let (a, b) = (s.next_1d(), s.next_1d());
            same += usize::from(a == b);
        }
        assert!(
            same < 8,
            "{same} of 64 samples share strata in two dimensions"
        );
    }
}
