//! The low-discrepancy sampler: padded Owen-scrambled Sobol points, bit-identical to
//! `sobol_burley`'s, computed by a scalar path for the two dimensions padding uses.

use glam::Vec2;

mod burley;
mod four_d;

pub use four_d::Sobol4dSampler;

use super::hash::{combine, mix64, pixel_key_of_mixed};
use super::{check_spp, stream_dimension, SampleSource, Sampler};
use crate::sampling::SamplingError;

/// Sample indices per Sobol block: `sobol_burley` supports indices below 2¹⁶.
const BLOCK_BITS: u32 = 16;

/// Owen-scrambled Sobol sample values (Burley 2020, "Practical Hash-based Owen Scrambling",
/// Journal of Computer Graphics Techniques 9(4)), bit-identical to the `sobol_burley` crate's.
///
/// Every dimension the sampler hands out is a separately seeded scramble of the first two Sobol
/// dimensions (the first for a 1D value), with a scramble seed of its own per (seed, pixel,
/// dimension): the padding Burley recommends. So the first `2^k` samples of a pixel form a
/// (0,k,2)-net in each 2D dimension (each elementary interval of area `2^-k`, of any shape
/// `2^-a × 2^-b`, holds exactly one point), each 1D dimension holds one point per interval of
/// length `2^-k`, different dimensions and different pixels are decorrelated, and the sequence
/// is progressive: any sample count works, and a power of two is stratified best.
///
/// Exactly: let `i` be the sample index modulo 2¹⁶, `k` a 64-bit hash of (seed, pixel,
/// `⌊index / 2¹⁶⌋`), and `s_d = (k ⊕ (k >> 32)) + d · 0x9e3779b9 mod 2³²` the 32-bit scramble
/// seed of dimension `d` (1D and 2D calls since [`Sampler::start_pixel_sample`] both count).
/// Then [`SampleSource::next_2d`](super::SampleSource::next_2d) returns
/// `(sobol_burley::sample(i, 0, s_d), sobol_burley::sample(i, 1, s_d))` and
/// [`SampleSource::next_1d`](super::SampleSource::next_1d) returns
/// `sobol_burley::sample(i, 0, s_d)` (crate version 0.5). The crate hashes the seed again for
/// its index shuffle and for each Owen scramble, so one full hash per pixel sample plus a Weyl
/// step per dimension decorrelates the dimensions (the crate's own padding example steps the
/// seed by one). The values are computed by a scalar path for those two dimensions (identity
/// and Pascal generator matrices, one 64-bit reversal for both outputs) instead of the crate's
/// table walk or 4-lane SIMD; unit tests pin them to the crate's for every index.
///
/// Limits of `sobol_burley`'s sequence and what this type does about them: we use only its
/// dimensions 0 and 1, so any number of dimensions per path works; it has indices below 2¹⁶,
/// so index `i ≥ 2¹⁶` is drawn as index `i mod 2¹⁶` of a sequence scrambled with another seed
/// (each block of 2¹⁶ samples is a net on its own; the blocks are independent of each other).
/// Values lie in `[0, 1)` (multiples of 2⁻²³). Mitsuba 3's `ldsampler` maps here.
///
/// ```
/// use mcrt::sampling::sampler::{SampleSource, Sampler, SobolSampler};
///
/// let mut s = SobolSampler::new(16, 1).unwrap();
/// let mut cells = [0; 16];
/// for i in 0..16 {
///     s.start_pixel_sample([7, 3], i);
///     let u = s.next_2d();
///     cells[(u.y * 4.0) as usize * 4 + (u.x * 4.0) as usize] += 1;
/// }
/// assert_eq!(cells, [1; 16]); // one sample in each 1/4 × 1/4 cell
/// ```
#[derive(Debug, Clone)]
pub struct SobolSampler {
    spp: u32,
    seed: u64,
    /// `mix64(seed)`, the part of every pixel key that depends on the seed alone.
    mixed_seed: u64,
    /// The sample index modulo 2¹⁶ with its 32 bits reversed (what the scramble works on).
    index_rev: u32,
    /// The scramble seed of the next dimension.
    next_seed: u32,
    /// The scramble seed of dimension 0 of the current pixel sample.
    first_seed: u32,
}

impl SobolSampler {
    /// A sampler for `spp` samples per pixel (at least 1; a power of two stratifies best) and
    /// a `seed`.
    pub fn new(spp: u32, seed: u64) -> Result<Self, SamplingError> {
        Ok(Self {
            spp: check_spp(spp)?,
            seed,
            mixed_seed: mix64(seed),
            index_rev: 0,
            next_seed: 0,
            first_seed: 0,
        })
    }

    /// The seed given to [`SobolSampler::new`].
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// Returns the scramble seed of the next dimension and steps to the one after it.
    #[inline]
    fn take_seed(&mut self) -> u32 {
        let seed = self.next_seed;
        self.next_seed = seed.wrapping_add(DIMENSION_STEP);
        seed
    }
}

/// The step between the scramble seeds of successive dimensions: 2³² divided by the golden
/// ratio, odd, so the first 2³² dimensions of a pixel sample get distinct seeds.
const DIMENSION_STEP: u32 = 0x9e37_79b9;

/// The scramble seed of dimension 0 of (seed, pixel, index block), from `mix64(seed)`: a
/// 64-bit hash folded to 32 bits.
#[inline]
fn first_seed(mixed_seed: u64, pixel: [u32; 2], block: u32) -> u32 {
    let k = pixel_key_of_mixed(mixed_seed, pixel);
    let k = if block == 0 {
        k
    } else {
        combine(k, u64::from(block))
    };
    (k ^ (k >> 32)) as u32
}

impl Sampler for SobolSampler {
    #[inline]
    fn start_pixel_sample(&mut self, pixel: [u32; 2], sample_index: u32) {
        self.index_rev = (sample_index & ((1 << BLOCK_BITS) - 1)).reverse_bits();
        self.next_seed = first_seed(self.mixed_seed, pixel, sample_index >> BLOCK_BITS);
        self.first_seed = self.next_seed;
    }

    #[inline]
    fn skip_to_dimension(&mut self, dim: u32) {
        self.next_seed = self
            .first_seed
            .wrapping_add(dim.wrapping_mul(DIMENSION_STEP));
    }

    fn samples_per_pixel(&self) -> u32 {
        self.spp
    }
}

impl SampleSource for SobolSampler {
    #[inline]
    fn next_1d(&mut self) -> f32 {
        let seed = self.take_seed();
        burley::sample_1d(self.index_rev, seed)
    }

    #[inline]
    fn next_2d(&mut self) -> Vec2 {
        let seed = self.take_seed();
        let [x, y] = burley::sample_2d(self.index_rev, seed);
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

    #[test]
    fn large_indices_do_not_panic_and_stay_in_range() {
        let mut s = SobolSampler::new(1, 0).unwrap();
        for i in [65_535u32, 65_536, 1 << 20, u32::MAX] {
            s.start_pixel_sample([0, 0], i);
            let u = s.next_2d();
            let v = s.next_1d();
            for x in [u.x, u.y, v] {
                assert!(x.is_finite() && (0.0..1.0).contains(&x), "index {i}: {x}");
            }
        }
    }

    #[test]
    fn blocks_beyond_two_to_the_sixteen_differ_from_the_first() {
        let mut s = SobolSampler::new(1, 0).unwrap();
        s.start_pixel_sample([0, 0], 5);
        let a = s.next_2d();
        s.start_pixel_sample([0, 0], 5 + (1 << 16));
        assert_ne!(a, s.next_2d());
    }

    /// The documented definition, value by value: dimension `d` of a pixel sample is
    /// `sobol_burley::sample(i mod 2¹⁶, 0 | 1, s₀ + d · 0x9e3779b9)`, 1D and 2D calls mixed.
    #[test]
    fn values_are_sobol_burley_samples_with_a_weyl_seed_per_dimension() {
        let mut s = SobolSampler::new(1, 9).unwrap();
        for (pixel, i) in [
            ([2, 3], 0u32),
            ([2, 3], 63),
            ([700, 1], 12_345),
            ([5, 5], 70_000),
        ] {
            s.start_pixel_sample(pixel, i);
            let (i, mut seed) = (i & 0xffff, first_seed(mix64(9), pixel, i >> 16));
            for d in 0..40u32 {
                if d % 3 == 2 {
                    assert_eq!(s.next_1d(), sobol_burley::sample(i, 0, seed), "dim {d}");
                } else {
                    let want = Vec2::new(
                        sobol_burley::sample(i, 0, seed),
                        sobol_burley::sample(i, 1, seed),
                    );
                    assert_eq!(s.next_2d(), want, "pixel {pixel:?} index {i} dim {d}");
                }
                seed = seed.wrapping_add(DIMENSION_STEP);
            }
        }
    }

    #[test]
    fn skipping_to_a_dimension_gives_its_value() {
        let mut a = SobolSampler::new(16, 4).unwrap();
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
    fn many_dimensions_work() {
        let mut s = SobolSampler::new(1, 0).unwrap();
        s.start_pixel_sample([1, 1], 0);
        for _ in 0..1000 {
            let u = s.next_2d();
            assert!(u.x.is_finite() && u.x < 1.0 && u.y < 1.0);
        }
    }
}
