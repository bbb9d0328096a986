//! Vose's alias table: constant-time sampling of a discrete distribution.

use glam::Vec2;

use super::piecewise_1d::{clamp_unit, drop_underflowing, validate_table};
use crate::sampling::SamplingError;
use crate::sampling::ONE_MINUS_EPSILON;

/// One column of the table: keep the column's own index with probability `keep`, else
/// return `alias`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Column {
    keep: f64,
    alias: usize,
}

/// A discrete distribution over `0..n` with probabilities proportional to non-negative
/// weights, sampled in O(1) by the alias method (for example, choosing a light by power).
///
/// Each of the `n` equally likely columns holds its own index with probability `keep` and
/// an alias otherwise; one uniform `u` picks the column (`⌊u n⌋`) and its fractional part
/// `u n − ⌊u n⌋` is the coin. Built in `f64` in O(n). An index whose weight is zero is never
/// returned, for any `u ∈ [0,1)`; nor is one whose probability underflows `f32` (below
/// about 10⁻⁴⁵ of the total), which counts as zero.
///
/// **Resolution.** A single `f32` sample value has at most 2²⁴ distinct values, so the
/// probabilities are realised to about 2⁻²⁴ absolute: with 10⁶ entries the coin has only a
/// few bits. When that matters, use [`sample_split`](Self::sample_split) with two sample
/// values.
///
/// Reference: Vose, 1991, "A Linear Algorithm for Generating Random Numbers with a Given
/// Distribution", IEEE Transactions on Software Engineering 17(9), DOI 10.1109/32.92917.
///
/// ```
/// use mcrt::sampling::distribution::AliasTable;
///
/// let t = AliasTable::new(&[1.0, 0.0, 3.0]).unwrap();
/// assert_eq!(t.len(), 3);
/// assert!((t.pmf(2) - 0.75).abs() < 1e-7);
/// let (i, pmf) = t.sample_with_pmf(0.4);
/// assert_ne!(i, 1); // zero weight: never returned
/// assert_eq!(pmf, t.pmf(i));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct AliasTable {
    columns: Vec<Column>,
    pmf: Vec<f64>,
}

impl AliasTable {
    /// An alias table for probabilities proportional to `weights`.
    ///
    /// # Errors
    /// [`SamplingError::EmptyTable`] for no weights, [`SamplingError::InvalidEntry`] for a
    /// negative, NaN or infinite weight, [`SamplingError::ZeroTable`] when every weight is 0.
    pub fn new(weights: &[f32]) -> Result<Self, SamplingError> {
        validate_table(weights)?;
        let mut w: Vec<f64> = weights.iter().map(|&x| f64::from(x)).collect();
        let sum: f64 = w.iter().sum();
        if sum <= 0.0 {
            return Err(SamplingError::ZeroTable);
        }
        drop_underflowing(&mut w, 1.0 / sum);
        let total: f64 = w.iter().sum();
        let pmf: Vec<f64> = w.iter().map(|&x| x / total).collect();
        Ok(Self {
            columns: build_columns(&pmf),
            pmf,
        })
    }

    /// Draws an index from one sample value `u ∈ [0,1)` (clamped into it; NaN acts as 0).
    #[must_use]
    #[inline]
    pub fn sample(&self, u: f32) -> usize {
        let n = self.columns.len();
        let x = f64::from(clamp_unit(u)) * n as f64;
        let i = (x as usize).min(n - 1);
        self.pick(i, x - i as f64)
    }

    /// [`sample`](Self::sample) and the probability of the returned index.
    #[must_use]
    pub fn sample_with_pmf(&self, u: f32) -> (usize, f32) {
        let i = self.sample(u);
        (i, self.pmf(i))
    }

    /// [`sample_with_pmf`](Self::sample_with_pmf) and the sample value *reused*: the part of
    /// `u` that the choice did not consume, rescaled to `[0, 1)` (uniform there given the
    /// index), so that one sample value both chooses an entry and drives what follows
    /// (as pbrt-v4's `AliasTable::Sample` and Mitsuba 3's emitter choice do). A stratified
    /// `u` gives each entry stratified reused values, piece by piece: an entry's share of
    /// `[0, 1)` is its own column's kept part plus the aliased parts of other columns, and
    /// each piece maps onto the whole of `[0, 1)`. About `log2(n) + 1` of `u`'s 24 bits go to
    /// the choice.
    #[must_use]
    pub fn sample_reusing(&self, u: f32) -> (usize, f32, f32) {
        let n = self.columns.len();
        let x = f64::from(clamp_unit(u)) * n as f64;
        let i = (x as usize).min(n - 1);
        let (coin, c) = (x - i as f64, self.columns[i]);
        let keep = c.keep.min(1.0);
        let (j, rest) = if coin < keep {
            (i, coin / keep)
        } else {
            (c.alias, (coin - keep) / (1.0 - keep))
        };
        (j, self.pmf(j), unit_down(rest))
    }

    /// Draws an index from two sample values: `u.x` picks the column, `u.y` is the coin.
    /// Realises the probabilities to `f32` resolution whatever the table's length.
    #[must_use]
    pub fn sample_split(&self, u: Vec2) -> usize {
        let n = self.columns.len();
        let i = ((f64::from(clamp_unit(u.x)) * n as f64) as usize).min(n - 1);
        self.pick(i, f64::from(clamp_unit(u.y)))
    }

    /// The probability of index `i` (its weight over the sum of weights); 0 past the end.
    #[must_use]
    pub fn pmf(&self, i: usize) -> f32 {
        self.pmf_f64(i) as f32
    }

    /// [`pmf`](Self::pmf) in `f64`, for statistics.
    #[must_use]
    pub fn pmf_f64(&self, i: usize) -> f64 {
        self.pmf.get(i).copied().unwrap_or(0.0)
    }

    /// The number of entries.
    #[must_use]
    pub fn len(&self) -> usize {
        self.columns.len()
    }

    /// Always `false`: a table has at least one entry.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.columns.is_empty()
    }

    /// Column `i` with coin `coin ∈ [0,1)`.
    fn pick(&self, i: usize, coin: f64) -> usize {
        let c = self.columns[i];
        if coin < c.keep {
            i
        } else {
            c.alias
        }
    }
}

/// `x` rounded down to an `f32` in `[0, 1)` (so never 1.0; NaN becomes 0).
fn unit_down(x: f64) -> f32 {
    let f = x as f32;
    let f = if f64::from(f) > x { f.next_down() } else { f };
    if f >= 0.0 {
        f.min(ONE_MINUS_EPSILON)
    } else {
        0.0
    }
}

/// Vose's construction: pair each under-full column with an over-full donor.
fn build_columns(pmf: &[f64]) -> Vec<Column> {
    let n = pmf.len();
    // Any index with positive weight: the alias of columns left without a donor.
    let fallback = pmf.iter().position(|&p| p > 0.0).unwrap_or(0);
    let mut scaled: Vec<f64> = pmf.iter().map(|&p| p * n as f64).collect();
    let mut columns = vec![
        Column {
            keep: 1.0,
            alias: fallback
        };
        n
    ];
    let (mut small, mut large): (Vec<usize>, Vec<usize>) = (0..n).partition(|&i| scaled[i] < 1.0);
    while let (Some(&s), Some(&l)) = (small.last(), large.last()) {
        small.pop();
        columns[s] = Column {
            keep: scaled[s].max(0.0),
            alias: l,
        };
        scaled[l] -= 1.0 - scaled[s];
        if scaled[l] < 1.0 {
            large.pop();
            small.push(l);
        }
    }
    // Leftovers are full up to rounding, except zero weights, which must never be kept.
    for i in small.into_iter().chain(large) {
        let keep = if pmf[i] > 0.0 { 1.0 } else { 0.0 };
        columns[i] = Column {
            keep,
            alias: fallback,
        };
    }
    columns
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_bad_weights() {
        assert_eq!(AliasTable::new(&[]), Err(SamplingError::EmptyTable));
        assert_eq!(AliasTable::new(&[0.0; 3]), Err(SamplingError::ZeroTable));
        let e = AliasTable::new(&[1.0, f32::NAN]).unwrap_err();
        assert!(matches!(e, SamplingError::InvalidEntry { index: 1, .. }));
    }

    /// The probability each index receives, integrated exactly over the column/coin split.
    fn realised_pmf(t: &AliasTable) -> Vec<f64> {
        let n = t.len();
        let mut p = vec![0.0; n];
        for (i, c) in t.columns.iter().enumerate() {
            p[i] += c.keep.min(1.0) / n as f64;
            p[c.alias] += (1.0 - c.keep.min(1.0)) / n as f64;
        }
        p
    }

    #[test]
    fn columns_reproduce_the_pmf() {
        let w = [0.5, 0.0, 3.0, 1.0, 0.0, 7.5, 0.25];
        let t = AliasTable::new(&w).unwrap();
        let total: f64 = w.iter().map(|&x| f64::from(x)).sum();
        for (i, p) in realised_pmf(&t).into_iter().enumerate() {
            assert!(
                p.is_finite() && (p - f64::from(w[i]) / total).abs() < 1e-12,
                "index {i}"
            );
        }
    }

    #[test]
    fn zero_weights_are_never_returned() {
        let t = AliasTable::new(&[0.0, 1.0, 0.0, 0.0, 2.0, 0.0]).unwrap();
        let mut u = 0.0_f32;
        while u < 1.0 {
            let i = t.sample(u);
            assert!(i == 1 || i == 4, "u = {u} gave {i}");
            u += 1.0 / 4096.0;
        }
        for u in [0.0, ONE_MINUS_EPSILON, f32::NAN.max(0.0)] {
            assert!(matches!(t.sample(u), 1 | 4));
            assert!(matches!(t.sample_split(Vec2::new(u, u)), 1 | 4));
        }
    }

    /// `sample_reusing` chooses as `sample` does, and the reused values of a fine stratified
    /// `u` are spread evenly over `[0, 1)` for every index: counted in 16 bins, each bin of
    /// index `j` holds `count_j / 16` values give or take the pieces' edges (one per piece).
    #[test]
    fn reused_values_are_uniform_per_index() {
        let w = [0.5, 0.0, 3.0, 1.0, 7.5, 0.25];
        let t = AliasTable::new(&w).unwrap();
        let n = 1 << 16;
        let mut bins = vec![[0u32; 16]; w.len()];
        for k in 0..n {
            let u = (k as f32 + 0.5) / n as f32;
            let (j, pmf, rest) = t.sample_reusing(u);
            assert_eq!((j, pmf), t.sample_with_pmf(u), "u = {u}");
            assert!(
                rest.is_finite() && (0.0..1.0).contains(&rest),
                "u = {u}: {rest}"
            );
            bins[j][(rest * 16.0) as usize] += 1;
        }
        for (j, b) in bins.iter().enumerate() {
            let count: u32 = b.iter().sum();
            let expected = f64::from(count) / 16.0;
            for &c in b {
                // Each of the (at most n = 6) pieces of j's share can put one value more or
                // less in a bin.
                assert!((f64::from(c) - expected).abs() <= 7.0, "index {j}: {b:?}");
            }
        }
        for u in [0.0, ONE_MINUS_EPSILON, f32::NAN] {
            let (j, _, rest) = t.sample_reusing(u);
            assert!(j != 1 && (0.0..1.0).contains(&rest), "u = {u}: {j} {rest}");
        }
    }
}
