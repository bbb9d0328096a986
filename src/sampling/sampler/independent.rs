//! The independent sampler: uniform pseudo-random values from PCG32.

use glam::Vec2;
use rand_core::RngCore;
use rand_pcg::Pcg32;

use super::hash::{combine, mix64, pixel_key_of_mixed, unit_f32};
use super::{check_spp, stream_dimension, SampleSource, Sampler};
use crate::sampling::SamplingError;

/// Independent uniform sample values: a PCG32 generator seeded, at each pixel sample, by a hash
/// of (seed, pixel, sample index).
///
/// PCG32 is O'Neill 2014, "PCG: A Family of Simple Fast Space-Efficient Statistically Good
/// Algorithms for Random Number Generation", Harvey Mudd College HMC-CS-2014-0905. Its state
/// and stream are two SplitMix64 hashes of (seed, pixel, sample index), so neighbouring pixels
/// and samples draw from unrelated streams. Values have 24-bit resolution (spacing 2⁻²⁴) and
/// lie in `[0, 1 − 2⁻²⁴]`: never 1.0. Every sample index is valid, including those at or beyond
/// [`Sampler::samples_per_pixel`]. Mitsuba 3's `independent` maps here.
///
/// ```
/// use mcrt::sampling::sampler::{IndependentSampler, SampleSource, Sampler};
///
/// let mut s = IndependentSampler::new(4, 1).unwrap();
/// s.start_pixel_sample([0, 0], 0);
/// let u = s.next_2d();
/// assert!(u.x < 1.0 && u.y < 1.0);
/// ```
#[derive(Debug, Clone)]
pub struct IndependentSampler {
    spp: u32,
    seed: u64,
    /// `mix64(seed)`, the part of every pixel key that depends on the seed alone.
    mixed_seed: u64,
    rng: Pcg32,
}

impl IndependentSampler {
    /// A sampler for `spp` samples per pixel (at least 1) and a `seed`.
    pub fn new(spp: u32, seed: u64) -> Result<Self, SamplingError> {
        Ok(Self {
            spp: check_spp(spp)?,
            seed,
            mixed_seed: mix64(seed),
            rng: Pcg32::new(mix64(seed), 0),
        })
    }

    /// The seed given to [`IndependentSampler::new`].
    pub fn seed(&self) -> u64 {
        self.seed
    }
}

impl Sampler for IndependentSampler {
    #[inline]
    fn start_pixel_sample(&mut self, pixel: [u32; 2], sample_index: u32) {
        let key = combine(
            pixel_key_of_mixed(self.mixed_seed, pixel),
            u64::from(sample_index),
        );
        self.rng = Pcg32::new(key, mix64(key ^ 0x5851_f42d_4c95_7f2d));
    }

    fn samples_per_pixel(&self) -> u32 {
        self.spp
    }
}

impl SampleSource for IndependentSampler {
    #[inline]
    fn next_1d(&mut self) -> f32 {
        unit_f32(self.rng.next_u32())
    }

    #[inline]
    fn next_2d(&mut self) -> Vec2 {
        let x = unit_f32(self.rng.next_u32());
        Vec2::new(x, unit_f32(self.rng.next_u32()))
    }

    #[inline]
    fn start_stream(&mut self, stream: u32) {
        self.skip_to_dimension(stream_dimension(stream));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn draw(s: &mut IndependentSampler, pixel: [u32; 2], index: u32) -> Vec<f32> {
        s.start_pixel_sample(pixel, index);
        (0..8).map(|_| s.next_1d()).collect()
    }

    #[test]
    fn same_pixel_sample_gives_same_values() {
        let mut a = IndependentSampler::new(16, 3).unwrap();
        let mut b = IndependentSampler::new(16, 3).unwrap();
        draw(&mut b, [9, 9], 5); // the history of a sampler does not matter
        assert_eq!(draw(&mut a, [1, 2], 3), draw(&mut b, [1, 2], 3));
    }

    #[test]
    fn seed_pixel_and_index_each_change_the_values() {
        let mut s = IndependentSampler::new(16, 3).unwrap();
        let base = draw(&mut s, [1, 2], 3);
        assert_ne!(base, draw(&mut s, [2, 2], 3));
        assert_ne!(base, draw(&mut s, [1, 3], 3));
        assert_ne!(base, draw(&mut s, [1, 2], 4));
        let mut t = IndependentSampler::new(16, 4).unwrap();
        assert_ne!(base, draw(&mut t, [1, 2], 3));
    }

    #[test]
    fn values_are_in_unit_interval() {
        let mut s = IndependentSampler::new(1, 0).unwrap();
        for i in 0..1000 {
            s.start_pixel_sample([i, 0], 0);
            let u = s.next_2d();
            let v = s.next_1d();
            for x in [u.x, u.y, v] {
                assert!(x.is_finite() && (0.0..1.0).contains(&x));
            }
        }
    }

    #[test]
    fn zero_spp_is_an_error() {
        assert!(IndependentSampler::new(0, 0).is_err());
    }
}
