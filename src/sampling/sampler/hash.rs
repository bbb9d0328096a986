//! Hashing helpers shared by the samplers: a 64-bit mixer, keys for (seed, pixel, index),
//! conversion of random bits to `[0, 1)`, and a stateless random permutation.

use super::ONE_MINUS_EPSILON;

/// The SplitMix64 finaliser: a bijective 64-bit mix with full avalanche.
/// Steele, Lea & Flood 2014, "Fast splittable pseudorandom number generators", OOPSLA.
#[inline]
pub(crate) fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Golden-ratio increment of SplitMix64; separates successive words before mixing.
const GOLDEN: u64 = 0x9e37_79b9_7f4a_7c15;

/// Folds `word` into the running hash `h`.
#[inline]
pub(crate) fn combine(h: u64, word: u64) -> u64 {
    mix64(h.wrapping_add(GOLDEN) ^ mix64(word.wrapping_add(GOLDEN)))
}

/// A key for (seed, pixel): what every value of one pixel shares.
#[inline]
pub(crate) fn pixel_key(seed: u64, pixel: [u32; 2]) -> u64 {
    let p = u64::from(pixel[0]) | (u64::from(pixel[1]) << 32);
    combine(mix64(seed), p)
}

/// The 24 high bits of `bits` as an `f32` in `[0, 1)` with spacing 2⁻²⁴ (never 1.0).
#[inline]
pub(crate) fn unit_f32(bits: u32) -> f32 {
    (bits >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// `(stratum + offset) / count` in `[0, 1)`, rounded in f64 and clamped below 1.
#[inline]
pub(crate) fn in_stratum(stratum: u32, offset: f32, count: u32) -> f32 {
    let v = (f64::from(stratum) + f64::from(offset)) / f64::from(count);
    (v as f32).min(ONE_MINUS_EPSILON)
}

/// Element `i` of a random permutation of `0..n` chosen by `key`, without storing it.
///
/// A seeded bijection on the `k`-bit integers (`2^k ≥ n`) built from invertible steps
/// (xor with a key, multiplication by an odd key, xorshifts), applied repeatedly until the
/// value falls below `n` ("cycle walking"; the idea of Kensler 2013, "Correlated Multi-Jittered
/// Sampling", Pixar Technical Memo 13-01). Fewer than two rounds are needed on average.
pub(crate) fn permute(i: u32, n: u32, key: u64) -> u32 {
    debug_assert!(n > 0 && i < n);
    if n <= 1 {
        return 0;
    }
    let bits = 32 - (n - 1).leading_zeros();
    let mask = u32::MAX >> (32 - bits);
    let k1 = key as u32;
    let k2 = (key >> 32) as u32 | 1;
    let k3 = mix64(key) as u32;
    let mut x = i;
    loop {
        x = bijection(x, bits, mask, [k1, k2, k3]);
        if x < n {
            return x;
        }
    }
}

/// One seeded bijection of the `bits`-bit integers (all steps invertible modulo `2^bits`).
#[inline]
fn bijection(mut x: u32, bits: u32, mask: u32, k: [u32; 3]) -> u32 {
    let half = bits.div_ceil(2);
    x ^= k[0] & mask;
    x = x.wrapping_mul(k[1]) & mask;
    x ^= x >> half;
    x = x.wrapping_add(k[2]) & mask;
    x = x.wrapping_mul(k[1].wrapping_mul(0x2c1b_3c6d) | 1) & mask;
    x ^= (x >> (bits / 3).max(1)) & mask;
    x = x.wrapping_mul(0x297a_2d39) & mask;
    x ^ (x >> half)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_f32_covers_zero_to_one_minus_epsilon() {
        assert_eq!(unit_f32(0), 0.0);
        assert_eq!(unit_f32(u32::MAX), ONE_MINUS_EPSILON);
    }

    #[test]
    fn in_stratum_never_reaches_one() {
        let v = in_stratum(6, ONE_MINUS_EPSILON, 7);
        assert!(v.is_finite() && v < 1.0);
        assert_eq!(in_stratum(0, 0.0, 7), 0.0);
    }

    #[test]
    fn permute_is_a_bijection_for_many_sizes_and_keys() {
        for n in [1u32, 2, 3, 4, 5, 7, 16, 17, 100, 256, 1000] {
            for key in [0u64, 1, 42, u64::MAX, 0x1234_5678_9abc_def0] {
                let mut seen = vec![false; n as usize];
                for i in 0..n {
                    let p = permute(i, n, key);
                    assert!(p < n, "n {n} key {key}: {p}");
                    assert!(!seen[p as usize], "n {n} key {key}: {p} twice");
                    seen[p as usize] = true;
                }
            }
        }
    }

    #[test]
    fn permute_depends_on_the_key() {
        let a: Vec<u32> = (0..64).map(|i| permute(i, 64, 1)).collect();
        let b: Vec<u32> = (0..64).map(|i| permute(i, 64, 2)).collect();
        assert_ne!(a, b);
        let identity: Vec<u32> = (0..64).collect();
        assert_ne!(a, identity);
    }

    #[test]
    fn pixel_keys_differ_between_neighbours() {
        let k = pixel_key(0, [0, 0]);
        assert_ne!(k, pixel_key(0, [1, 0]));
        assert_ne!(k, pixel_key(0, [0, 1]));
        assert_ne!(k, pixel_key(1, [0, 0]));
    }
}
