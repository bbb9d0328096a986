//! The correlated multi-jittered sampler: Kensler's 2D patterns, padded across dimensions.

use glam::Vec2;

use super::hash::{in_stratum, mix64, permute, unit_f32};
use super::padded::PaddedKeys;
use super::{check_spp, stream_dimension, SampleSource, Sampler};
use crate::sampling::SamplingError;

/// Tags that keep the 1D and 2D keys of one dimension apart.
const TAG_1D: u64 = 0x1d;
const TAG_2D: u64 = 0x2d;

/// Salts deriving the three permutation keys of a 2D pattern from its key (words of the
/// SHA-512 initial value: any distinct constants do, since the key is hashed again).
const SALT_ORDER: u64 = 0x3c6e_f372_fe94_f82b;
const SALT_COLUMNS: u64 = 0xa54f_f53a_5f1d_36f1;
const SALT_ROWS: u64 = 0x510e_527f_ade6_82d1;

/// Correlated multi-jittered sample values (Kensler 2013, "Correlated Multi-Jittered
/// Sampling", Pixar Technical Memo 13-01), padded across dimensions; Mitsuba 3's
/// `multijitter` is this kind of sampler.
///
/// The sample count `N` is rounded up to `m × n` with `m = ⌊√N⌋` and `n = ⌈N / m⌉`, as
/// Mitsuba 3's `multijitter` does (5 → 6, 10 → 12, 17 → 20; squares stay). In each 2D
/// dimension the `N` samples of a pixel fall one in each cell of the `m × n` grid *and* one in
/// each of the `N` columns and `N` rows of the fine `N × N` grid (multi-jittering: Chiu,
/// Shirley & Wang 1994, "Multi-jittered sampling", Graphics Gems IV); the fine offsets are
/// one permutation shared by all columns and one shared by all rows (Kensler's *correlated*
/// variant), which spreads the points more evenly than independent permutations. Each 1D
/// dimension puts one value in each interval `[k/N, (k+1)/N)`. Which sample gets which cell
/// is shuffled afresh for every (pixel, dimension): the padding that decorrelates dimensions
/// (Kollig & Keller 2002, "Efficient multidimensional sampling", Computer Graphics Forum
/// 21(3)). Inside its fine cell a value is placed uniformly at random (`jitter = true`) or at
/// the centre.
///
/// Sample indices at or beyond [`Sampler::samples_per_pixel`] start a new round with fresh
/// permutations: each complete round of `N` samples is stratified on its own. All values lie
/// in `[0, 1 − 2⁻²⁴]`: never 1.0.
///
/// ```
/// use mcrt::sampling::sampler::{CmjSampler, SampleSource, Sampler};
///
/// let mut s = CmjSampler::new(16, 1, true).unwrap();
/// let (mut cells, mut columns) = ([0; 16], [0; 16]);
/// for i in 0..16 {
///     s.start_pixel_sample([4, 2], i);
///     let u = s.next_2d();
///     cells[(u.y * 4.0) as usize * 4 + (u.x * 4.0) as usize] += 1;
///     columns[(u.x * 16.0) as usize] += 1;
/// }
/// assert_eq!(cells, [1; 16]); // one sample per 1/4 × 1/4 cell
/// assert_eq!(columns, [1; 16]); // and one per 1/16 column
/// ```
#[derive(Debug, Clone)]
pub struct CmjSampler {
    /// Cells along x (`m`) and along y (`n`).
    grid: (u32, u32),
    spp: u32,
    seed: u64,
    jitter: bool,
    keys: PaddedKeys,
}

impl CmjSampler {
    /// A sampler for `spp` samples per pixel (at least 1; rounded up to `m × n` as
    /// described above), a `seed`, and whether to jitter within the fine cells (`false`
    /// places values at their centres).
    pub fn new(spp: u32, seed: u64, jitter: bool) -> Result<Self, SamplingError> {
        let (m, n) = Self::grid_for(check_spp(spp)?);
        // m·n ≤ 65535 · 65537 = 2³² − 1 for every u32 count; checked all the same.
        let spp = m.checked_mul(n).ok_or(SamplingError::InvalidParameter {
            name: "spp",
            value: f64::from(spp),
            expected: "at most 65535 × 65537",
        })?;
        Ok(Self {
            grid: (m, n),
            spp,
            seed,
            jitter,
            keys: PaddedKeys::default(),
        })
    }

    /// The grid a request for `spp ≥ 1` samples becomes: `(⌊√spp⌋, ⌈spp / ⌊√spp⌋⌉)`.
    fn grid_for(spp: u32) -> (u32, u32) {
        let mut m = (f64::from(spp)).sqrt() as u32;
        while u64::from(m + 1) * u64::from(m + 1) <= u64::from(spp) {
            m += 1;
        }
        while u64::from(m) * u64::from(m) > u64::from(spp) {
            m -= 1;
        }
        (m, spp.div_ceil(m))
    }

    /// The cells of the coarse grid along x and y (`m`, `n`).
    pub fn grid(&self) -> (u32, u32) {
        self.grid
    }

    /// Whether values are jittered within their fine cells.
    pub fn jitter(&self) -> bool {
        self.jitter
    }
}

impl Sampler for CmjSampler {
    fn start_pixel_sample(&mut self, pixel: [u32; 2], sample_index: u32) {
        self.keys.start(self.seed, self.spp, pixel, sample_index);
    }

    #[inline]
    fn skip_to_dimension(&mut self, dim: u32) {
        self.keys.dimension = u64::from(dim);
    }

    fn samples_per_pixel(&self) -> u32 {
        self.spp
    }
}

impl SampleSource for CmjSampler {
    #[inline]
    fn next_1d(&mut self) -> f32 {
        let stratum = permute(
            self.keys.index_in_round,
            self.spp,
            self.keys.pattern_key(TAG_1D),
        );
        let offset = if self.jitter {
            unit_f32(self.keys.jitter_bits() as u32)
        } else {
            0.5
        };
        self.keys.dimension += 1;
        in_stratum(stratum, offset, self.spp)
    }

    #[inline]
    fn next_2d(&mut self) -> Vec2 {
        let key = self.keys.pattern_key(TAG_2D);
        let (m, n) = self.grid;
        // Which coarse cell (column c, row r) this sample takes in this dimension.
        let s = permute(self.keys.index_in_round, self.spp, mix64(key ^ SALT_ORDER));
        let (c, r) = (s % m, s / m);
        // The fine offsets: one permutation of the rows shared by every column (x), one of
        // the columns shared by every row (y).
        let fine_x = permute(r, n, mix64(key ^ SALT_ROWS));
        let fine_y = permute(c, m, mix64(key ^ SALT_COLUMNS));
        let (jx, jy) = if self.jitter {
            let bits = self.keys.jitter_bits();
            (unit_f32(bits as u32), unit_f32((bits >> 32) as u32))
        } else {
            (0.5, 0.5)
        };
        self.keys.dimension += 1;
        // x = (c + (fine_x + jx) / n) / m and y = (r + (fine_y + jy) / m) / n, each in one
        // of the N fine strata.
        Vec2::new(
            in_stratum(c * n + fine_x, jx, self.spp),
            in_stratum(r * m + fine_y, jy, self.spp),
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

    /// Mitsuba 3.9.1's `multijitter` sample counts (read back from `sample_count()`).
    #[test]
    fn counts_round_as_mitsuba_does() {
        for (asked, got) in [
            (1, 1),
            (2, 2),
            (3, 3),
            (5, 6),
            (7, 8),
            (10, 12),
            (17, 20),
            (64, 64),
            (100, 100),
            (256, 256),
            (1000, 1023),
        ] {
            let s = CmjSampler::new(asked, 0, true).unwrap();
            assert_eq!(s.samples_per_pixel(), got, "asked {asked}");
        }
    }

    #[test]
    fn extreme_and_zero_counts_are_errors_not_panics() {
        assert!(CmjSampler::new(0, 0, true).is_err());
        let s = CmjSampler::new(u32::MAX, 0, true).unwrap();
        assert_eq!(s.grid(), (65535, 65537));
        let mut s = CmjSampler::new(u32::MAX - 1, 0, true).unwrap();
        s.start_pixel_sample([1, 2], u32::MAX);
        let u = s.next_2d();
        assert!(u.x.is_finite() && u.x < 1.0 && u.y < 1.0);
    }

    #[test]
    fn unjittered_values_are_fine_cell_centres() {
        let mut s = CmjSampler::new(4, 9, false).unwrap();
        let mut xs: Vec<f32> = (0..4)
            .map(|i| {
                s.start_pixel_sample([0, 0], i);
                s.next_2d().x
            })
            .collect();
        xs.sort_by(f32::total_cmp);
        assert_eq!(xs, [0.125, 0.375, 0.625, 0.875]);
    }

    #[test]
    fn skipping_to_a_dimension_gives_its_value() {
        let mut a = CmjSampler::new(16, 4, true).unwrap();
        let mut b = a.clone();
        a.start_pixel_sample([3, 9], 5);
        let values: Vec<Vec2> = (0..12).map(|_| a.next_2d()).collect();
        b.start_pixel_sample([3, 9], 5);
        for d in [7u32, 0, 11, 3] {
            b.skip_to_dimension(d);
            assert_eq!(b.next_2d(), values[d as usize], "dimension {d}");
        }
    }
}
