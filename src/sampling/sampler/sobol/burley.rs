//! Dimensions 0 to 3 of `sobol_burley`'s seeded Owen-scrambled Sobol sequence in scalar code.
//!
//! `sobol_burley::sample_4d` computes four dimensions with 4-lane integer SIMD, whose 32-bit
//! multiplies are emulated on baseline x86-64 (no SSE4.1), and `sobol_burley::sample` walks
//! the index bits through a direction-vector table. The padded sampler only ever needs
//! dimensions 0 and 1, whose generator matrices have closed forms: the identity (dimension 0,
//! the van der Corput sequence) and Pascal's triangle modulo 2 (dimension 1). So this module
//! composes `sobol_burley::parts` (the hash and the hash-based Owen scramble) with those two
//! matrices, and reverses the bits of both outputs with one 64-bit reversal. The values are
//! bit-identical to `sobol_burley::sample(index, 0 | 1, seed)`; the tests below pin that for
//! every index and several seeds. Dimensions 2 and 3 (for the 4D sampler) have no such closed
//! form: their generator matrices are applied a byte of the index at a time from tables built
//! at compile time from the crate's direction numbers, again bit-identical to the crate. The
//! byte tables are indexed by the bytes of the bit-reversed shuffled index as they are (the
//! tables hold the reversal), and dimension 1's tables hold its matrix product as well.
//!
//! The method is Burley's (2020, "Practical Hash-based Owen Scrambling", Journal of Computer
//! Graphics Techniques 9(4)): shuffle the index with a nested-uniform scramble, evaluate the
//! Sobol point, Owen-scramble it; both scrambles work on bit-reversed integers.

use sobol_burley::parts::{hash, owen_scramble_rev, u32_to_f32_norm};

/// Mixed into the seed before hashing it into the index shuffle (as `sobol_burley` does).
const INDEX_SALT: u32 = 0x79c6_8e4a;

/// Multiplier applied to the seed of the per-dimension scramble (as `sobol_burley` does).
const SEED_MULTIPLIER: u32 = 0x9c8f_2d3b;

/// Salts of the Owen scrambles of dimensions 0 to 3 (as `sobol_burley` does).
const DIMENSION_SALT: [u32; 4] = [0x912f_69ba, 0x174f_18ab, 0x691e_72ca, 0xb40c_c1b8];

/// `sobol_burley`'s direction numbers of Sobol dimensions 2 and 3, bits reversed: entry `k`
/// is `sobol_burley::parts::sobol_rev((1 << k).reverse_bits(), 2 | 3)` (a unit test checks).
const DIRECTIONS_2: [u32; 16] = [
    0x0001, 0x0003, 0x0006, 0x0009, 0x0017, 0x003a, 0x0071, 0x00a3, 0x0116, 0x0339, 0x0677, 0x09aa,
    0x1601, 0x3903, 0x7706, 0xaa09,
];
const DIRECTIONS_3: [u32; 16] = [
    0x0001, 0x0003, 0x0004, 0x000a, 0x001f, 0x002e, 0x0045, 0x00c9, 0x011b, 0x02a4, 0x079a, 0x0b67,
    0x101e, 0x302d, 0x4041, 0xa0c3,
];

/// `UPPER_OF_BYTE[k][b]`: the reversed points of Sobol dimensions 2 (low 16 bits) and 3
/// (high 16 bits) for the 16-bit index whose only set bits are the byte `b` reversed, at bits
/// `8..16` for `k = 0` and `0..8` for `k = 1`: the shuffled index's bytes, as
/// [`shuffled_index_bytes`] returns them, index it directly.
const UPPER_OF_BYTE: [[u32; 256]; 2] = {
    let mut table = [[0; 256]; 2];
    let mut b = 0;
    while b < 256 {
        let reversed = (b as u8).reverse_bits() as u32;
        table[0][b] = upper_of_index(reversed << 8);
        table[1][b] = upper_of_index(reversed);
        b += 1;
    }
    table
};

/// The reversed points of Sobol dimensions 2 (low 16 bits) and 3 (high 16 bits) of the
/// 16-bit index `n`: the XOR of the direction numbers of its set bits.
const fn upper_of_index(n: u32) -> u32 {
    let mut both = 0;
    let mut k = 0;
    while k < 16 {
        if n >> k & 1 == 1 {
            both ^= DIRECTIONS_3[k] << 16 | DIRECTIONS_2[k];
        }
        k += 1;
    }
    both
}

/// `LOWER_OF_BYTE[k][b]`: the shuffled index's contribution (low 16 bits) and its image under
/// the dimension-1 matrix, [`pascal_rev`] (high 16 bits), for the byte `b` of
/// [`shuffled_index_bytes`], `k` as for [`UPPER_OF_BYTE`]. Both maps are linear over GF(2)
/// and the two bytes' bits are disjoint, so the two entries' XOR is `n | pascal_rev(n) << 16`.
const LOWER_OF_BYTE: [[u32; 256]; 2] = {
    let mut table = [[0; 256]; 2];
    let mut b = 0;
    while b < 256 {
        let reversed = (b as u8).reverse_bits() as u32;
        let (high, low) = (reversed << 8, reversed);
        table[0][b] = high | pascal_rev(high) << 16;
        table[1][b] = low | pascal_rev(low) << 16;
        b += 1;
    }
    table
};

/// The two bytes of the reversed shuffled index that hold the 16-bit shuffled index (bits
/// 16..24 and 24..32), for `index_rev`, the sample index (below 2¹⁶) with its 32 bits
/// reversed. Only those bits count (the sequence has 2¹⁶ points); the byte tables
/// [`LOWER_OF_BYTE`] and [`UPPER_OF_BYTE`] take them as they are, which saves reversing them.
#[inline(always)]
fn shuffled_index_bytes(index_rev: u32, seed: u32) -> [usize; 2] {
    let shuffled_rev = owen_scramble_rev(index_rev, hash(seed ^ INDEX_SALT));
    let [_, _, b2, b3] = shuffled_rev.to_le_bytes();
    [usize::from(b2), usize::from(b3)]
}

/// The shuffled 16-bit index `n` (low 16 bits) and `pascal_rev(n)` (high 16 bits).
#[inline(always)]
fn lower_inputs(index_rev: u32, seed: u32) -> u32 {
    let [b2, b3] = shuffled_index_bytes(index_rev, seed);
    LOWER_OF_BYTE[0][b2] ^ LOWER_OF_BYTE[1][b3]
}

/// The reversed points of Sobol dimensions 2 (low 16 bits) and 3 (high 16 bits) of the
/// shuffled index.
#[inline(always)]
fn upper_points(index_rev: u32, seed: u32) -> u32 {
    let [b2, b3] = shuffled_index_bytes(index_rev, seed);
    UPPER_OF_BYTE[0][b2] ^ UPPER_OF_BYTE[1][b3]
}

/// Sobol dimension 1 of the 16-bit index `n`, with the result's bits reversed.
///
/// Its generator matrix is Pascal's triangle modulo 2: digit `i` (from the most significant)
/// of the point is the parity of the index bits `k` with `binomial(k, i)` odd, i.e. (Lucas'
/// theorem) with `k ⊇ i` as bit sets. Bit `i` of the reversed result is that digit; the sum
/// over supersets is four butterfly steps, one per bit of `i`.
const fn pascal_rev(n: u32) -> u32 {
    let mut y = n;
    y ^= (y >> 1) & 0x5555;
    y ^= (y >> 2) & 0x3333;
    y ^= (y >> 4) & 0x0f0f;
    y ^= (y >> 8) & 0x00ff;
    y
}

/// The Owen-scramble key of `dimension` (0 to 3) for `seed`.
#[inline(always)]
fn dimension_key(seed: u32, dimension: usize) -> u32 {
    hash(seed.wrapping_mul(SEED_MULTIPLIER) ^ DIMENSION_SALT[dimension])
}

/// `[sobol_burley::sample(i, 0, seed), sobol_burley::sample(i, 1, seed)]` for the index `i`
/// (below 2¹⁶) whose 32 bits reversed are `index_rev`.
#[inline(always)]
pub(super) fn sample_2d(index_rev: u32, seed: u32) -> [f32; 2] {
    // Dimension 0's generator matrix is the identity: its reversed point is the index itself.
    let inputs = lower_inputs(index_rev, seed);
    let x_rev = owen_scramble_rev(inputs & 0xffff, dimension_key(seed, 0));
    let y_rev = owen_scramble_rev(inputs >> 16, dimension_key(seed, 1));
    // One 64-bit reversal un-reverses both: the low word lands reversed in the high word.
    let both = (u64::from(y_rev) << 32 | u64::from(x_rev)).reverse_bits();
    [
        u32_to_f32_norm((both >> 32) as u32),
        u32_to_f32_norm(both as u32),
    ]
}

/// `[sobol_burley::sample(i, 2, seed), sobol_burley::sample(i, 3, seed)]` for the index `i`
/// (below 2¹⁶) whose 32 bits reversed are `index_rev`: the other half of the 4D point whose
/// first half [`sample_2d`] gives (same index shuffle, its own Owen scrambles).
#[inline(always)]
pub(super) fn sample_2d_upper(index_rev: u32, seed: u32) -> [f32; 2] {
    let both = upper_points(index_rev, seed);
    let x_rev = owen_scramble_rev(both & 0xffff, dimension_key(seed, 2));
    let y_rev = owen_scramble_rev(both >> 16, dimension_key(seed, 3));
    let both = (u64::from(y_rev) << 32 | u64::from(x_rev)).reverse_bits();
    [
        u32_to_f32_norm((both >> 32) as u32),
        u32_to_f32_norm(both as u32),
    ]
}

/// `sobol_burley::sample(i, 2, seed)` for the index `i` (below 2¹⁶) whose 32 bits reversed
/// are `index_rev`.
#[inline(always)]
pub(super) fn sample_1d_upper(index_rev: u32, seed: u32) -> f32 {
    let x_rev = owen_scramble_rev(
        upper_points(index_rev, seed) & 0xffff,
        dimension_key(seed, 2),
    );
    u32_to_f32_norm(x_rev.reverse_bits())
}

/// `sobol_burley::sample(i, 0, seed)` for the index `i` (below 2¹⁶) whose 32 bits reversed
/// are `index_rev`.
#[inline(always)]
pub(super) fn sample_1d(index_rev: u32, seed: u32) -> f32 {
    let n = lower_inputs(index_rev, seed) & 0xffff;
    let x_rev = owen_scramble_rev(n, dimension_key(seed, 0));
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
    fn upper_dimensions_match_sobol_burley_for_every_index() {
        for seed in SEEDS {
            for i in 0..(1u32 << 16) {
                let want = [
                    sobol_burley::sample(i, 2, seed),
                    sobol_burley::sample(i, 3, seed),
                ];
                assert_eq!(sample_2d_upper(i.reverse_bits(), seed), want, "index {i}");
                assert_eq!(sample_1d_upper(i.reverse_bits(), seed), want[0]);
            }
        }
    }

    #[test]
    fn direction_tables_are_sobol_burleys() {
        for k in 0..16 {
            let unit = (1u32 << k).reverse_bits();
            assert_eq!(
                DIRECTIONS_2[k],
                sobol_burley::parts::sobol_rev(unit, 2),
                "bit {k}"
            );
            assert_eq!(
                DIRECTIONS_3[k],
                sobol_burley::parts::sobol_rev(unit, 3),
                "bit {k}"
            );
        }
    }

    #[test]
    fn byte_tables_are_the_matrix_products_of_the_index() {
        for n in 0..(1u32 << 16) {
            let [b2, b3] = [(n >> 8) as u8, n as u8].map(|b| usize::from(b.reverse_bits()));
            let lower = LOWER_OF_BYTE[0][b2] ^ LOWER_OF_BYTE[1][b3];
            assert_eq!(lower, n | pascal_rev(n) << 16, "index {n}");
            assert_eq!(
                UPPER_OF_BYTE[0][b2] ^ UPPER_OF_BYTE[1][b3],
                upper_of_index(n)
            );
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
