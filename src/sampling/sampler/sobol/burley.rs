//! Dimensions 0 and 1 of `sobol_burley`'s seeded Owen-scrambled Sobol sequence in scalar code.
//!
//! `sobol_burley::sample_4d` computes four dimensions with 4-lane integer SIMD, whose 32-bit
//! multiplies are emulated on baseline x86-64 (no SSE4.1), and `sobol_burley::sample` walks
//! the index bits through a direction-vector table. The padded sampler only ever needs
//! dimensions 0 and 1, whose generator matrices have closed forms: the identity (dimension 0,
//! the van der Corput sequence) and Pascal's triangle modulo 2 (dimension 1). So this module
//! composes `sobol_burley::parts` (the hash and the hash-based Owen scramble) with those two
//! matrices, and reverses the bits of both outputs with one 64-bit reversal. The values are
//! bit-identical to `sobol_burley::sample(index, 0 | 1, seed)`; the tests below pin that for
//! every index and several seeds.
//!
//! The method is Burley's (2020, "Practical Hash-based Owen Scrambling", Journal of Computer
//! Graphics Techniques 9(4)): shuffle the index with a nested-uniform scramble, evaluate the
//! Sobol point, Owen-scramble it; both scrambles work on bit-reversed integers.

use sobol_burley::parts::{hash, owen_scramble_rev, u32_to_f32_norm};

/// Mixed into the seed before hashing it into the index shuffle (as `sobol_burley` does).
const INDEX_SALT: u32 = 0x79c6_8e4a;

/// Multiplier applied to the seed of the per-dimension scramble (as `sobol_burley` does).
const SEED_MULTIPLIER: u32 = 0x9c8f_2d3b;

/// Salts of the Owen scrambles of dimensions 0 and 1 (as `sobol_burley` does).
const DIMENSION_SALT: [u32; 2] = [0x912f_69ba, 0x174f_18ab];

/// The shuffled 16-bit sample index, in natural bit order, for `index_rev`, the sample index
/// (below 2¹⁶) with its 32 bits reversed.
#[inline(always)]
fn shuffled_index(index_rev: u32, seed: u32) -> u32 {
    let shuffled_rev = owen_scramble_rev(index_rev, hash(seed ^ INDEX_SALT));
    // Only the top 16 bits of the reversed index count (the sequence has 2¹⁶ points); two
    // byte lookups reverse them in fewer instructions than the shift-and-mask reversal.
    let [_, _, b2, b3] = shuffled_rev.to_le_bytes();
    u32::from(REVERSED_BYTE[usize::from(b2)]) << 8 | u32::from(REVERSED_BYTE[usize::from(b3)])
}

/// `REVERSED_BYTE[b]` is `b` with its 8 bits reversed.
const REVERSED_BYTE: [u8; 256] = {
    let mut table = [0; 256];
    let mut b = 0;
    while b < 256 {
        table[b] = (b as u8).reverse_bits();
        b += 1;
    }
    table
};

/// Sobol dimension 1 of the 16-bit index `n`, with the result's bits reversed.
///
/// Its generator matrix is Pascal's triangle modulo 2: digit `i` (from the most significant)
/// of the point is the parity of the index bits `k` with `binomial(k, i)` odd, i.e. (Lucas'
/// theorem) with `k ⊇ i` as bit sets. Bit `i` of the reversed result is that digit; the sum
/// over supersets is four butterfly steps, one per bit of `i`.
#[inline(always)]
fn pascal_rev(n: u32) -> u32 {
    let mut y = n;
    y ^= (y >> 1) & 0x5555;
    y ^= (y >> 2) & 0x3333;
    y ^= (y >> 4) & 0x0f0f;
    y ^= (y >> 8) & 0x00ff;
    y
}

/// The Owen-scramble key of `dimension` (0 or 1) for `seed`.
#[inline(always)]
fn dimension_key(seed: u32, dimension: usize) -> u32 {
    hash(seed.wrapping_mul(SEED_MULTIPLIER) ^ DIMENSION_SALT[dimension])
}

/// `[sobol_burley::sample(i, 0, seed), sobol_burley::sample(i, 1, seed)]` for the index `i`
/// (below 2¹⁶) whose 32 bits reversed are `index_rev`.
#[inline(always)]
pub(super) fn sample_2d(index_rev: u32, seed: u32) -> [f32; 2] {
    let n = shuffled_index(index_rev, seed);
    // Dimension 0's generator matrix is the identity: its reversed point is the index itself.
    let x_rev = owen_scramble_rev(n, dimension_key(seed, 0));
    let y_rev = owen_scramble_rev(pascal_rev(n), dimension_key(seed, 1));
    // One 64-bit reversal un-reverses both: the low word lands reversed in the high word.
    let both = (u64::from(y_rev) << 32 | u64::from(x_rev)).reverse_bits();
    [
        u32_to_f32_norm((both >> 32) as u32),
        u32_to_f32_norm(both as u32),
    ]
}

/// `sobol_burley::sample(i, 0, seed)` for the index `i` (below 2¹⁶) whose 32 bits reversed
/// are `index_rev`.
#[inline(always)]
pub(super) fn sample_1d(index_rev: u32, seed: u32) -> f32 {
    let x_rev = owen_scramble_rev(shuffled_index(index_rev, seed), dimension_key(seed, 0));
    u32_to_f32_norm(x_rev.reverse_bits())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Seeds with few, many and patterned bits set.
    const SEEDS: [u32; 6] = [0, 1, 0x8000_0000, 0xdead_beef, u32::MAX, 0x1234_5678];

    #[test]
    fn matches_sobol_burley_for_every_index() {
        for seed in SEEDS {
            for i in 0..(1u32 << 16) {
                let want = [
                    sobol_burley::sample(i, 0, seed),
                    sobol_burley::sample(i, 1, seed),
                ];
                let got = sample_2d(i.reverse_bits(), seed);
                assert_eq!(got, want, "index {i} seed {seed:#x}");
                assert_eq!(sample_1d(i.reverse_bits(), seed), want[0]);
            }
        }
    }

    #[test]
    fn matches_sobol_burley_for_many_seeds() {
        for k in 0..20_000u32 {
            let seed = k.wrapping_mul(0x9e37_79b9) ^ (k >> 3);
            let i = k.wrapping_mul(40_503) & 0xffff;
            let want = sobol_burley::sample_4d(i, 0, seed);
            assert_eq!(sample_2d(i.reverse_bits(), seed), [want[0], want[1]]);
        }
    }

    #[test]
    fn pascal_rev_is_the_sobol_dimension_one_matrix() {
        // Without scrambling, direction vector k of dimension 1 (index 2^k) reversed.
        for k in 0..16 {
            let want = sobol_burley::parts::sobol_rev((1u32 << k).reverse_bits(), 1);
            assert_eq!(pascal_rev(1 << k), want, "bit {k}");
        }
    }
}
