//! Per-sample random numbers: a PCG32 stream seeded from (seed, pixel, sample index), so a
//! render is the same whatever the thread count or tile order.

use crate::integrator::SampleSource;
use rand_core::RngCore;
use rand_pcg::Pcg32;

/// SplitMix64 finaliser (Steele, Lea, Flood 2014, "Fast Splittable Pseudorandom Number
/// Generators", OOPSLA).
#[inline]
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Independent uniform numbers for one pixel sample (O'Neill 2014, "PCG: A Family of Simple
/// Fast Space-Efficient Statistically Good Algorithms for Random Number Generation").
pub struct PixelRng(Pcg32);

impl PixelRng {
    /// The stream for sample `index` of pixel `pixel` under `seed`.
    #[inline]
    pub fn new(seed: u64, pixel: u64, index: u64) -> Self {
        let state = mix(seed ^ mix(pixel.wrapping_add(0x9e37_79b9_7f4a_7c15)));
        let stream = mix(index ^ state.rotate_left(17));
        Self(Pcg32::new(state, stream))
    }
}

impl SampleSource for PixelRng {
    #[inline]
    fn next_1d(&mut self) -> f32 {
        (self.0.next_u32() >> 8) as f32 * (1.0 / 16_777_216.0)
    }
}
