//! The R2 sampler: the Kronecker sequence of the plastic number with a Cranley–Patterson
//! rotation, padded across dimensions.

use glam::Vec2;

use super::hash::mix64;
use super::padded::ShuffledRound;
use super::{check_spp, stream_dimension, SampleSource, Sampler};
use crate::sampling::SamplingError;

/// `2⁶⁴/φ₂` and `2⁶⁴/φ₂²` rounded to odd integers, φ₂ ≈ 1.3247 the plastic number (the real
/// root of x³ = x + 1): the R2 step in 64-bit fixed point.
const ALPHA_2D: [u64; 2] = [0xc13f_a9a9_02a6_328f, 0x91e1_0da5_c79e_7b1d];

/// Separates the index-shuffle key from the rotation of a dimension.
const SHUFFLE_TAG: u64 = 0x3c3c_9696_5a5a_0f0f;

/// `2⁶⁴/φ`, φ the golden ratio, odd: the R1 step (1D dimensions).
const ALPHA_1D: u64 = 0x9e37_79b9_7f4a_7c15;

/// R2 sample values (Roberts 2018): `frac(s + i α)` with `α = (1/φ₂, 1/φ₂²)`, a rank-1
/// Kronecker lattice that is progressive (any sample count works) and has low discrepancy in
/// 2D, with a random Cranley–Patterson rotation `s` drawn per (seed, pixel, dimension), so
/// that dimensions and pixels are decorrelated and each pixel's estimate is unbiased (a random
/// shift makes every point uniform on the square). 1D dimensions use the golden-ratio sequence
/// `frac(s + i/φ)`, whose `n` first points leave gaps of at most three lengths (the
/// three-distance theorem), none longer than about `2.6/n`.
///
/// Computed in 64-bit fixed point (`i α` wraps modulo 2⁶⁴ exactly), so the sequence does not
/// lose precision for large indices; values are the top 24 bits, in `[0, 1 − 2⁻²⁴]`.
/// Unlike the other samplers its points are not stratified cell by cell; its strength is the
/// even spread of any prefix (the tests bound the occupancy of grid cells and the largest 1D
/// gap, and the integration error against the independent sampler's).
///
/// Citation: M. Roberts, 2018, "The Unreasonable Effectiveness of Quasirandom Sequences"
/// (extreme learning blog); R. Cranley, T. N. L. Patterson, 1976, "Randomization of number
/// theoretic methods for multiple integration", SIAM Journal on Numerical Analysis 13(6).
///
/// ```
/// use mcrt::sampling::sampler::{R2Sampler, SampleSource, Sampler};
///
/// let mut s = R2Sampler::new(64, 1).unwrap();
/// s.start_pixel_sample([3, 4], 10);
/// let u = s.next_2d();
/// assert!(u.x < 1.0 && u.y < 1.0);
/// ```
#[derive(Debug, Clone)]
pub struct R2Sampler {
    spp: u32,
    seed: u64,
    mixed_seed: u64,
    round: ShuffledRound,
}

impl R2Sampler {
    /// A sampler for `spp` samples per pixel (at least 1) and a `seed`.
    pub fn new(spp: u32, seed: u64) -> Result<Self, SamplingError> {
        Ok(Self {
            spp: check_spp(spp)?,
            seed,
            mixed_seed: mix64(seed),
            round: ShuffledRound::default(),
        })
    }

    /// The seed given to [`R2Sampler::new`].
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// The rotation of the next dimension and the (shuffled) lattice index it uses.
    fn take(&mut self) -> (u64, u64) {
        let (key, round_start, shuffled) = self.round.take(self.spp, SHUFFLE_TAG);
        // In u64: the last round of u32 indices may run past u32::MAX.
        let index = u64::from(round_start) + u64::from(shuffled);
        (key, index)
    }
}

/// The top 24 bits of a 64-bit fixed-point fraction, as an `f32` in `[0, 1)`.
#[inline]
fn to_unit(x: u64) -> f32 {
    (x >> 40) as f32 * (1.0 / 16_777_216.0)
}

impl Sampler for R2Sampler {
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

impl SampleSource for R2Sampler {
    #[inline]
    fn next_1d(&mut self) -> f32 {
        let (shift, i) = self.take();
        to_unit(shift.wrapping_add(i.wrapping_mul(ALPHA_1D)))
    }

    #[inline]
    fn next_2d(&mut self) -> Vec2 {
        let (shift, i) = self.take();
        let other = mix64(shift);
        Vec2::new(
            to_unit(shift.wrapping_add(i.wrapping_mul(ALPHA_2D[0]))),
            to_unit(other.wrapping_add(i.wrapping_mul(ALPHA_2D[1]))),
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
    fn steps_are_the_plastic_and_golden_fractions() {
        let plastic = 1.324_717_957_244_746_f64;
        let scale = 2f64.powi(64);
        let a = [ALPHA_2D[0] as f64 / scale, ALPHA_2D[1] as f64 / scale];
        assert!((a[0] - 1.0 / plastic).abs() < 1e-15, "{}", a[0]);
        assert!((a[1] - 1.0 / (plastic * plastic)).abs() < 1e-15, "{}", a[1]);
        let golden = (1.0 + 5f64.sqrt()) / 2.0;
        assert!((ALPHA_1D as f64 / scale - 1.0 / golden).abs() < 1e-15);
    }
}
