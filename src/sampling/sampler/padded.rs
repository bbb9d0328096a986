//! Where the padded samplers are within a pixel sample: the keys of the stratified and
//! correlated multi-jittered samplers (one random pattern per pixel, dimension and round of
//! `spp` samples, one jitter per pixel sample and dimension), and the shuffled round of the
//! Halton and R2 samplers (one index permutation per pixel, dimension and round).

use super::hash::{combine, permute, pixel_key, pixel_key_of_mixed};

/// Where a padded sampler is: the keys of the current pixel sample and its dimension.
#[derive(Debug, Clone, Default)]
pub(super) struct PaddedKeys {
    /// The key of the current round of `spp` samples in this pixel.
    round_key: u64,
    /// The key of the current pixel sample.
    sample_key: u64,
    /// The sample index within its round.
    pub(super) index_in_round: u32,
    /// The next dimension.
    pub(super) dimension: u64,
}

impl PaddedKeys {
    /// Starts sample `sample_index` of `pixel` for a sampler of `spp` samples per round and
    /// `seed`, at dimension 0.
    #[inline]
    pub(super) fn start(&mut self, seed: u64, spp: u32, pixel: [u32; 2], sample_index: u32) {
        let pixel_key = pixel_key(seed, pixel);
        self.sample_key = combine(pixel_key, u64::from(sample_index));
        self.index_in_round = sample_index % spp;
        let round = sample_index / spp;
        // Round 0 (the usual case) skips one hash.
        self.round_key = if round == 0 {
            pixel_key
        } else {
            combine(pixel_key, u64::from(round))
        };
        self.dimension = 0;
    }

    /// The key of the current dimension's pattern in this pixel and round; `tag` keeps the
    /// patterns of different kinds (1D, 2D) of one dimension apart.
    #[inline]
    pub(super) fn pattern_key(&self, tag: u64) -> u64 {
        combine(self.round_key, (self.dimension << 8) | tag)
    }

    /// 64 random bits for the jitter of the current dimension and pixel sample.
    #[inline]
    pub(super) fn jitter_bits(&self) -> u64 {
        combine(self.sample_key, self.dimension)
    }
}

/// Where a sampler that shuffles one sequence's indices per dimension is (Halton, R2): the
/// pixel's key, the round of `spp` samples and the offset in it, and the dimension.
#[derive(Debug, Clone, Default)]
pub(super) struct ShuffledRound {
    pixel_key: u64,
    /// The first index of the current round of `spp` samples.
    round_start: u32,
    /// The sample's offset in its round.
    offset: u32,
    /// The next dimension.
    pub(super) dimension: u64,
}

impl ShuffledRound {
    /// Starts sample `sample_index` of `pixel` (`mixed_seed = mix64(seed)`) for `spp`
    /// samples per round, at dimension 0.
    #[inline]
    pub(super) fn start(&mut self, mixed_seed: u64, spp: u32, pixel: [u32; 2], sample_index: u32) {
        self.pixel_key = pixel_key_of_mixed(mixed_seed, pixel);
        self.offset = sample_index % spp;
        self.round_start = sample_index - self.offset;
        self.dimension = 0;
    }

    /// The key of the next dimension, the round's first index and the sample's offset in
    /// the round shuffled by that key (salted with `tag`); steps to the dimension after.
    #[inline]
    pub(super) fn take(&mut self, spp: u32, tag: u64) -> (u64, u32, u32) {
        let key = combine(self.pixel_key, self.dimension);
        self.dimension += 1;
        (key, self.round_start, permute(self.offset, spp, key ^ tag))
    }
}
