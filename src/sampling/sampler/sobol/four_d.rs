//! The 4D low-discrepancy sampler: Owen-scrambled Sobol points padded in 4D sets, so that
//! two successive dimensions are stratified jointly.

use glam::Vec2;

use super::burley;
use super::{first_seed, BLOCK_BITS, DIMENSION_STEP};
use crate::sampling::sampler::hash::mix64;
use crate::sampling::sampler::{check_spp, stream_dimension, SampleSource, Sampler};
use crate::sampling::SamplingError;

/// Owen-scrambled Sobol sample values padded in 4D sets: dimensions `2k` and `2k + 1` of a
/// pixel sample are the two halves of one 4D point (Sobol dimensions 0–1 and 2–3 under one
/// index shuffle), and each such pair has a scramble seed of its own (Burley 2020,
/// "Practical Hash-based Owen Scrambling", Journal of Computer Graphics Techniques 9(4),
/// recommends padding 4D sets this way).
///
/// What that buys over [`SobolSampler`](super::SobolSampler), which pads every 2D dimension:
/// an integrand that couples two successive draws is stratified in 4D, not only in each 2D
/// projection. A path tracer's first two draws are the position in the pixel and the first
/// light sample; on glossy surfaces the reflected highlight couples them strongly
/// (`docs/sampler-error.md` has the measurements). The first `2^k` samples of a pixel form a
/// (0,k,2)-net in every even dimension and a (3,k,4)-net in each pair, in 4D; the price is the
/// odd dimensions, whose Sobol dimensions 2–3 form only a (2,k,2)-net (checked for k ≤ 14:
/// each elementary interval of area `2^(2-k)` holds four points, so a 2 × 2 grid is not
/// filled evenly before 16 samples; no pair among Sobol dimensions 2 to 7 does better). 1D
/// values are Sobol dimension 0 (even) or 2 (odd): one point in each interval of length
/// `2^-k`.
///
/// Exactly: with `i`, `s_0` and the step `0x9e3779b9` as for `SobolSampler`, dimension `d`
/// (1D and 2D calls both count) is `sobol_burley::sample(i, 2 (d mod 2) + {0, 1}, s_0 + ⌊d/2⌋ ·
/// 0x9e3779b9)` (crate version 0.5), computed by the scalar paths of the `burley` module. Index
/// `i ≥ 2¹⁶` is drawn as index `i mod 2¹⁶` of a sequence scrambled with another seed, as for
/// `SobolSampler`. Values lie in `[0, 1)`.
///
/// ```
/// use mcrt::sampling::sampler::{SampleSource, Sampler, Sobol4dSampler};
///
/// let mut s = Sobol4dSampler::new(16, 1).unwrap();
/// let mut cells = [0; 16];
/// for i in 0..16 {
///     s.start_pixel_sample([7, 3], i);
///     let (a, b) = (s.next_2d(), s.next_2d());
///     // The x coordinates of dimensions 0 and 1 jointly: one sample per 1/4 × 1/4 cell.
///     cells[(b.x * 4.0) as usize * 4 + (a.x * 4.0) as usize] += 1;
/// }
/// assert_eq!(cells, [1; 16]);
/// ```
#[derive(Debug, Clone)]
pub struct Sobol4dSampler {
    spp: u32,
    seed: u64,
    /// `mix64(seed)`, the part of every pixel key that depends on the seed alone.
    mixed_seed: u64,
    /// The sample index modulo 2¹⁶ with its 32 bits reversed.
    index_rev: u32,
    /// The scramble seed of dimensions 0 and 1 of the current pixel sample.
    first_seed: u32,
    /// The next dimension.
    dimension: u32,
}

impl Sobol4dSampler {
    /// A sampler for `spp` samples per pixel (at least 1; a power of two stratifies best) and
    /// a `seed`.
    pub fn new(spp: u32, seed: u64) -> Result<Self, SamplingError> {
        Ok(Self {
            spp: check_spp(spp)?,
            seed,
            mixed_seed: mix64(seed),
            index_rev: 0,
            first_seed: 0,
            dimension: 0,
        })
    }

    /// The seed given to [`Sobol4dSampler::new`].
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// The scramble seed of the next dimension's 4D set, whether it is the set's upper half,
    /// and a step to the dimension after it.
    #[inline]
    fn take(&mut self) -> (u32, bool) {
        let d = self.dimension;
        self.dimension = d.wrapping_add(1);
        let seed = self
            .first_seed
            .wrapping_add((d >> 1).wrapping_mul(DIMENSION_STEP));
        (seed, d & 1 == 1)
    }
}

impl Sampler for Sobol4dSampler {
    #[inline]
    fn start_pixel_sample(&mut self, pixel: [u32; 2], sample_index: u32) {
        self.index_rev = (sample_index & ((1 << BLOCK_BITS) - 1)).reverse_bits();
        self.first_seed = first_seed(self.mixed_seed, pixel, sample_index >> BLOCK_BITS);
        self.dimension = 0;
    }

    #[inline]
    fn skip_to_dimension(&mut self, dim: u32) {
        self.dimension = dim;
    }

    fn samples_per_pixel(&self) -> u32 {
        self.spp
    }
}

impl SampleSource for Sobol4dSampler {
    #[inline]
    fn next_1d(&mut self) -> f32 {
        match self.take() {
            (seed, false) => burley::sample_1d(self.index_rev, seed),
            (seed, true) => burley::sample_1d_upper(self.index_rev, seed),
        }
    }

    #[inline]
    fn next_2d(&mut self) -> Vec2 {
        let [x, y] = match self.take() {
            (seed, false) => burley::sample_2d(self.index_rev, seed),
            (seed, true) => burley::sample_2d_upper(self.index_rev, seed),
        };
        Vec2::new(x, y)
    }

    #[inline]
    fn start_stream(&mut self, stream: u32) {
        self.skip_to_dimension(stream_dimension(stream));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The documented definition, value by value, 1D and 2D calls mixed.
    #[test]
    fn values_are_sobol_burley_4d_points_with_a_weyl_seed_per_pair() {
        let mut s = Sobol4dSampler::new(1, 9).unwrap();
        for (pixel, i) in [([2, 3], 0u32), ([700, 1], 12_345), ([5, 5], 70_000)] {
            s.start_pixel_sample(pixel, i);
            let (i, s0) = (i & 0xffff, first_seed(mix64(9), pixel, i >> 16));
            for d in 0..40u32 {
                let seed = s0.wrapping_add((d / 2).wrapping_mul(DIMENSION_STEP));
                let base = 2 * (d % 2);
                if d % 3 == 2 {
                    assert_eq!(s.next_1d(), sobol_burley::sample(i, base, seed), "dim {d}");
                } else {
                    let want = Vec2::new(
                        sobol_burley::sample(i, base, seed),
                        sobol_burley::sample(i, base + 1, seed),
                    );
                    assert_eq!(s.next_2d(), want, "pixel {pixel:?} index {i} dim {d}");
                }
            }
        }
    }

    #[test]
    fn skipping_to_a_dimension_gives_its_value() {
        let mut a = Sobol4dSampler::new(16, 4).unwrap();
        let mut b = a.clone();
        a.start_pixel_sample([3, 9], 5);
        let values: Vec<Vec2> = (0..12).map(|_| a.next_2d()).collect();
        b.start_pixel_sample([3, 9], 5);
        for d in [7u32, 0, 11, 3] {
            b.skip_to_dimension(d);
            assert_eq!(b.next_2d(), values[d as usize], "dimension {d}");
        }
    }

    #[test]
    fn large_indices_and_dimensions_stay_in_range() {
        let mut s = Sobol4dSampler::new(1, 0).unwrap();
        for i in [65_535u32, 65_536, u32::MAX] {
            s.start_pixel_sample([0, 0], i);
            s.skip_to_dimension(u32::MAX);
            let (u, v) = (s.next_2d(), s.next_1d());
            for x in [u.x, u.y, v] {
                assert!(x.is_finite() && (0.0..1.0).contains(&x), "index {i}: {x}");
            }
        }
    }
}
