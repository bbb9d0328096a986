//! Hashing helpers shared by the samplers: a 64-bit mixer, keys for (seed, pixel, index),
//! conversion of random bits to `[0, 1)`, and a stateless random permutation.

/// The SplitMix64 finaliser: a bijective 64-bit mix with full avalanche.
/// Steele, Lea & Flood 2014, "Fast splittable pseudorandom number generators", OOPSLA.
#[inline]
pub fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Golden-ratio increment of SplitMix64; separates successive words before mixing.
const GOLDEN: u64 = 0x9e37_79b9_7f4a_7c15;

/// Folds `word` into the running hash `h`.
#[inline]
pub fn combine(h: u64, word: u64) -> u64 {
    mix64(h.wrapping_add(GOLDEN) ^ mix64(word.wrapping_add(GOLDEN)))
}

/// A key for (seed, pixel): what every value of one pixel shares.
#[inline]
pub fn pixel_key(seed: u64, pixel: [u32; 2]) -> u64 {
    pixel_key_of_mixed(mix64(seed), pixel)
}

/// [`pixel_key`] from `mix64(seed)`, which a sampler computes once at construction.
#[inline]
pub fn pixel_key_of_mixed(mixed_seed: u64, pixel: [u32; 2]) -> u64 {
    let p = u64::from(pixel[0]) | (u64::from(pixel[1]) << 32);
    combine(mixed_seed, p)
}

/// The 24 high bits of `bits` as an `f32` in `[0, 1)` with spacing 2⁻²⁴ (never 1.0).
#[inline]
pub fn unit_f32(bits: u32) -> f32 {
    (bits >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// `(stratum + offset) / count` for `offset ∈ [0, 1)`: computed in f64 and rounded *down* to
/// f32, so the value never rounds up onto the next stratum's lower edge (nor onto 1.0).
#[inline]
pub fn in_stratum(stratum: u32, offset: f32, count: u32) -> f32 {
    let v = (f64::from(stratum) + f64::from(offset)) / f64::from(count);
    let f = v as f32;
    if f64::from(f) > v {
        f.next_down()
    } else {
        f
    }
}

/// Element `i` of a random permutation of `0..n` chosen by `key`, without storing it.
///
/// A seeded bijection of the `b`-bit integers (`2^b ≥ n`): three rounds of invertible
/// steps (xor with a round key, multiplication by an odd round key, xorshifts both ways, a
/// keyed rotation), applied repeatedly until the value falls below `n` ("cycle walking"; the
/// idea of Kensler 2013, "Correlated Multi-Jittered Sampling", Pixar Technical Memo 13-01),
/// then a keyed cyclic shift modulo `n`. Fewer than two walks are needed on average. Over
/// random keys each element's image is uniform on `0..n` (exactly, up to the 2⁻³² resolution
/// of the shift), so a value of a partial round of samples is uniform too; the permutations
/// of small sets come out close to uniform (unit tests check both).
pub fn permute(i: u32, n: u32, key: u64) -> u32 {
    debug_assert!(n > 0 && i < n);
    if n <= 1 {
        return 0;
    }
    let bits = 32 - (n - 1).leading_zeros();
    // `key` is already a full-avalanche hash: one multiply per derived key is enough.
    let folded = key ^ (key >> 31);
    let round_keys = ROUND_MULTIPLIERS.map(|m| folded.wrapping_mul(m));
    let mut x = i;
    loop {
        for &rk in &round_keys {
            x = round(x, bits, rk);
        }
        if x < n {
            break;
        }
    }
    // A keyed cyclic shift on top makes each element exactly uniform over keys, whatever the
    // bijection's quality: P(result = s) = Σₜ P(x = t) · P(shift = s − t) = 1/n.
    let shift_bits = (key.rotate_left(17) ^ folded).wrapping_mul(SHIFT_MULTIPLIER) >> 32;
    let shift = ((shift_bits * u64::from(n)) >> 32) as u32;
    // In u64: for n above 2³¹ the sum can pass u32::MAX.
    let y = u64::from(x) + u64::from(shift);
    (if y >= u64::from(n) {
        y - u64::from(n)
    } else {
        y
    }) as u32
}

/// Rounds of [`round`] per walk of [`permute`].
const ROUNDS: usize = 3;

/// Odd multipliers deriving the round keys of [`permute`] from its key.
const ROUND_MULTIPLIERS: [u64; ROUNDS] = [
    0xd1b5_4a32_d192_ed03,
    0xaef1_7502_108e_f2d9,
    0x8cb9_2ba7_2f3d_8dd7,
];

/// Odd multiplier deriving the cyclic shift of [`permute`] from its key.
const SHIFT_MULTIPLIER: u64 = 0xf135_7aea_2e62_a9c5;

/// One keyed bijection of the `bits`-bit integers (every step invertible modulo `2^bits`).
#[inline]
fn round(mut x: u32, bits: u32, key: u64) -> u32 {
    let mask = u32::MAX >> (32 - bits);
    let half = bits.div_ceil(2);
    x ^= key as u32 & mask;
    x = x.wrapping_mul((key >> 32) as u32 | 1) & mask;
    x ^= x >> half;
    x ^= (x << half) & mask;
    let r = (((key >> 59) as u32) * bits) >> 5; // in 0..bits, without a division
    if r != 0 {
        x = ((x << r) | (x >> (bits - r))) & mask;
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::ONE_MINUS_EPSILON;

    #[test]
    fn unit_f32_covers_zero_to_one_minus_epsilon() {
        assert_eq!(unit_f32(0), 0.0);
        assert_eq!(unit_f32(u32::MAX), ONE_MINUS_EPSILON);
    }

    #[test]
    fn in_stratum_stays_below_the_next_stratum() {
        // Rounded to nearest, (3 + 1 − 2⁻²⁴)/5 would give 0.8, the lower edge of stratum 4.
        for count in [3u32, 5, 7, 9, 11, 13, 100, 1000, 12345] {
            for stratum in [0, 1, count / 2, count - 2, count - 1] {
                let v = in_stratum(stratum, ONE_MINUS_EPSILON, count);
                let upper = f64::from(stratum + 1) / f64::from(count);
                assert!(
                    v.is_finite() && f64::from(v) < upper,
                    "{stratum}/{count}: {v}"
                );
                let low = in_stratum(stratum, 0.0, count);
                assert!(f64::from(low) <= f64::from(stratum) / f64::from(count));
                let edge = f64::from(stratum) / f64::from(count);
                assert!(f64::from(low) >= edge * (1.0 - f64::from(f32::EPSILON)));
            }
        }
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

    /// Sizes above 2³¹ (a stratified or multi-jittered round of up to 2³² − 1 samples): the
    /// shifted value stays below `n` without overflowing, and distinct inputs stay distinct.
    #[test]
    fn permute_handles_sizes_near_u32_max() {
        for n in [(1u32 << 31) + 1, 4_294_836_225, u32::MAX] {
            for key in [0u64, 7, u64::MAX, 0x1234_5678_9abc_def0] {
                let inputs = [0, 1, n / 2, n - 2, n - 1];
                let outputs = inputs.map(|i| permute(i, n, key));
                for (k, &p) in outputs.iter().enumerate() {
                    assert!(p < n, "n {n} key {key}: {p}");
                    assert!(!outputs[..k].contains(&p), "n {n} key {key}: {p} twice");
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

#[cfg(test)]
mod permutation_quality {
    use super::*;
    use std::collections::HashMap;

    /// Over many keys, every permutation of a small set appears, each about equally often.
    #[test]
    fn small_permutations_are_close_to_uniform() {
        for n in [3u32, 4] {
            let mut counts: HashMap<Vec<u32>, u32> = HashMap::new();
            let keys = 24_000u64;
            for k in 0..keys {
                let key = mix64(k);
                let p: Vec<u32> = (0..n).map(|i| permute(i, n, key)).collect();
                *counts.entry(p).or_default() += 1;
            }
            let perms: u32 = if n == 3 { 6 } else { 24 };
            assert_eq!(counts.len(), perms as usize, "n {n}: {counts:?}");
            let expected = keys as f64 / f64::from(perms);
            for (p, &c) in &counts {
                let dev = (f64::from(c) - expected).abs() / expected;
                assert!(
                    dev < 0.15,
                    "n {n}: {p:?} drawn {c} times, expected {expected}"
                );
            }
        }
    }

    /// For each `i`, `permute(i, n, key)` is uniform over `0..n` across keys (so every sample
    /// of a partial round is uniform too): a chi-square test with n − 1 degrees of freedom for
    /// `i` at the start, middle and end, bound dof + 5·sqrt(2 dof) + 10 (p < 10⁻⁴ for every n
    /// here).
    #[test]
    fn each_element_is_uniform_over_keys() {
        for n in [2u32, 3, 5, 6, 7, 9, 10, 12, 17, 24, 33] {
            let keys = 20_000 * u64::from(n);
            for i in [0, n / 2, n - 1] {
                let mut counts = vec![0u32; n as usize];
                for k in 0..keys {
                    counts[permute(i, n, mix64(k)) as usize] += 1;
                }
                let e = keys as f64 / f64::from(n);
                let chi2: f64 = counts.iter().map(|&c| (f64::from(c) - e).powi(2) / e).sum();
                let dof = f64::from(n - 1);
                let bound = dof + 5.0 * (2.0 * dof).sqrt() + 10.0;
                assert!(
                    chi2.is_finite() && chi2 < bound,
                    "n {n} i {i}: chi-square {chi2:.1}"
                );
            }
        }
    }
}
