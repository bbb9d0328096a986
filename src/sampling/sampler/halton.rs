//! The Halton sampler: bases 2 and 3 with random digit permutations, padded across
//! dimensions.

use glam::Vec2;

use super::hash::mix64;
use super::padded::ShuffledRound;
use super::{check_spp, stream_dimension, SampleSource, Sampler};
use crate::sampling::SamplingError;

/// Base-3 digits used: 3⁻¹⁶ ≈ 2.3·10⁻⁸ is below the `f32` spacing near 1.
const BASE3_DIGITS: u32 = 16;

/// Separates the index-shuffle key from the digit-permutation key of a dimension.
const SHUFFLE_TAG: u64 = 0x5a5a_0f0f_3c3c_9696;

/// The six permutations of {0, 1, 2}.
const PERMS3: [[u8; 3]; 6] = [
    [0, 1, 2],
    [0, 2, 1],
    [1, 0, 2],
    [1, 2, 0],
    [2, 0, 1],
    [2, 1, 0],
];

/// Halton sample values with random digit permutations (Faure & Tezuka's scrambling as pbrt
/// uses it), padded across dimensions.
///
/// Every 2D dimension is the Halton point of bases 2 and 3 for the sample index `i`, with
/// each digit position of each base remapped by a random permutation of the digits; every 1D
/// dimension is the base-2 coordinate alone. The permutations are drawn afresh per (seed,
/// pixel, dimension) from a hash, and each dimension also visits the Halton indices of the
/// current round of `spp` samples in its own random order (a stateless permutation of the
/// round), so dimensions and pixels are decorrelated (the padding of Kollig & Keller): digit
/// permutations alone would leave successive dimensions functions of each other (in base 2,
/// `x_{d+1} = x_d ⊕ c`). A round of `spp` consecutive Halton indices is stratified like the
/// first (any `2^a 3^b` consecutive integers run through every combination of their low
/// `a` base-2 and `b` base-3 digits), so the shuffle keeps the stratification of each full
/// round. In base 2 a digit permutation is a random bit flip, so the base-2
/// coordinate is `reverse(i) ⊕ mask`; in base 3 each of 16 digit positions takes one of the
/// six permutations of {0, 1, 2}. Since a permutation of digits maps elementary intervals to
/// elementary intervals, the first `2^a · 3^b` samples of a pixel put exactly one point in
/// each cell of a `2^a × 3^b` grid in every 2D dimension, and the first `2^a` samples one
/// point in each interval `[k/2^a, (k+1)/2^a)` in every 1D dimension (the stratification
/// tests check both), for `spp = 2^a 3^b`. Any sample count works; `2^a 3^b` counts (6, 12,
/// 36, 72, 144, …) stratify best, and only full rounds of `spp` are stratified (a prefix of a
/// round is a random subset of it). Values are rounded down to `f32`, so they lie in `[0, 1)` and never cross
/// into the next stratum. Indices are taken modulo 2²⁴ (the base-2 digits `f32` can hold).
///
/// Citation: J. H. Halton, 1964, "Algorithm 247: Radical-inverse quasi-random point
/// sequence", Communications of the ACM 7(12); H. Faure, S. Tezuka, 2002, "Another Random
/// Scrambling of Digital (t, s)-Sequences", Monte Carlo and Quasi-Monte Carlo Methods 2000.
///
/// ```
/// use mcrt::sampling::sampler::{HaltonSampler, SampleSource, Sampler};
///
/// let mut s = HaltonSampler::new(6, 1).unwrap();
/// let mut cells = [0; 6];
/// for i in 0..6 {
///     s.start_pixel_sample([7, 3], i);
///     let u = s.next_2d();
///     cells[(u.y * 3.0) as usize * 2 + (u.x * 2.0) as usize] += 1;
/// }
/// assert_eq!(cells, [1; 6]); // one sample in each 1/2 × 1/3 cell
/// ```
#[derive(Debug, Clone)]
pub struct HaltonSampler {
    spp: u32,
    seed: u64,
    mixed_seed: u64,
    round: ShuffledRound,
}

impl HaltonSampler {
    /// A sampler for `spp` samples per pixel (at least 1; `2^a 3^b` counts stratify best)
    /// and a `seed`.
    pub fn new(spp: u32, seed: u64) -> Result<Self, SamplingError> {
        Ok(Self {
            spp: check_spp(spp)?,
            seed,
            mixed_seed: mix64(seed),
            round: ShuffledRound::default(),
        })
    }

    /// The seed given to [`HaltonSampler::new`].
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// The key of the next dimension and the (shuffled) Halton index it uses.
    fn take(&mut self) -> (u64, u32) {
        let (key, round_start, shuffled) = self.round.take(self.spp, SHUFFLE_TAG);
        // Wrapping: the last round of u32 indices may run past u32::MAX; only 24 bits are used.
        let index = round_start.wrapping_add(shuffled);
        (key, index & 0x00ff_ffff)
    }
}

/// `x` in `[0, 1)` from a value in `[0, 1)` given in `f64`, rounded down to `f32`.
#[inline]
fn round_down(v: f64) -> f32 {
    let f = v as f32;
    if f64::from(f) > v {
        f.next_down()
    } else {
        f
    }
}

/// The base-2 radical inverse of `i` with every digit flipped where `mask` has a 1 bit.
#[inline]
fn scrambled_base2(i: u32, mask: u32) -> f32 {
    let bits = ((i << 8).reverse_bits() ^ mask) & 0x00ff_ffff;
    bits as f32 * (1.0 / 16_777_216.0)
}

/// The base-3 radical inverse of `i` with digit position `k` permuted by
/// `PERMS3[(key / 6^k) mod 6]`, over 16 digit positions (the trailing zero digits of `i` are
/// permuted too, as a scrambled infinite expansion requires).
#[inline]
fn scrambled_base3(mut i: u32, key: u64) -> f32 {
    // Digit k of i (least significant first) becomes digit k + 1 after the point: appending
    // each permuted digit to an integer numerator over 3^16 builds the radical inverse exactly.
    let (mut v, mut scale, mut k) = (0u64, 1u64, key);
    for _ in 0..BASE3_DIGITS {
        let digit = (i % 3) as usize;
        i /= 3;
        let perm = PERMS3[(k % 6) as usize];
        k /= 6;
        v = v * 3 + u64::from(perm[digit]);
        scale *= 3;
    }
    round_down(v as f64 / scale as f64)
}

impl Sampler for HaltonSampler {
    #[inline]
    fn start_pixel_sample(&mut self, pixel: [u32; 2], sample_index: u32) {
        self.round
            .start(self.mixed_seed, self.spp, pixel, sample_index);
    }

    #[inline]
    fn skip_to_dimension(&mut self, dim: u32) {
        self.round.dimension = u64::from(dim);
    }

    fn samples_per_pixel(&self) -> u32 {
        self.spp
    }
}

impl SampleSource for HaltonSampler {
    #[inline]
    fn next_1d(&mut self) -> f32 {
        let (key, index) = self.take();
        scrambled_base2(index, key as u32)
    }

    #[inline]
    fn next_2d(&mut self) -> Vec2 {
        let (key, index) = self.take();
        Vec2::new(
            scrambled_base2(index, key as u32),
            scrambled_base3(index, mix64(key)),
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
    fn unscrambled_values_are_the_radical_inverses() {
        // Key 0 picks the identity permutation for every base-3 digit; mask 0 for base 2.
        let want3 = [0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0 / 9.0, 4.0 / 9.0, 7.0 / 9.0];
        for (i, &w) in want3.iter().enumerate() {
            let got = scrambled_base3(i as u32, 0);
            assert!((f64::from(got) - w).abs() < 1e-7, "{i}: {got}");
            assert!(f64::from(got) <= w + 1e-12, "rounded up: {got} vs {w}");
        }
        let want2 = [0.0, 0.5, 0.25, 0.75, 0.125];
        for (i, &w) in want2.iter().enumerate() {
            assert_eq!(scrambled_base2(i as u32, 0), w);
        }
    }

    #[test]
    fn the_last_indices_do_not_overflow() {
        for spp in [1u32, 6, 7, 1000] {
            let mut s = HaltonSampler::new(spp, 3).unwrap();
            let mut r = super::super::R2Sampler::new(spp, 3).unwrap();
            for i in [u32::MAX, u32::MAX - 1, u32::MAX - 5] {
                s.start_pixel_sample([1, 2], i);
                r.start_pixel_sample([1, 2], i);
                for _ in 0..8 {
                    let (a, b) = (s.next_2d(), r.next_2d());
                    assert!(a.max_element() < 1.0 && b.max_element() < 1.0);
                    assert!(s.next_1d() < 1.0 && r.next_1d() < 1.0);
                }
            }
        }
    }

    #[test]
    fn values_stay_below_one() {
        // Key digit 3 is the permutation [1, 2, 0]: every zero digit becomes 1... and 2 by
        // [2, 0, 1] (key digit 4): the largest value, 1 − 3⁻¹⁶, must stay below 1.
        let all_twos: u64 = (0..16).fold(0, |acc, _| acc * 6 + 4);
        let top = scrambled_base3(0, all_twos);
        assert!(top < 1.0 && top > 0.999_999, "{top}");
        assert!(scrambled_base2(0, u32::MAX) < 1.0);
        for key in [0u64, 1, u64::MAX, 0x1234_5678_9abc_def0] {
            for i in [0u32, 1, 2, 1 << 20, 0x00ff_ffff] {
                let v = scrambled_base3(i, key);
                assert!(v.is_finite() && (0.0..1.0).contains(&v), "{i} {key}: {v}");
            }
        }
    }
}
