//! What each connection strategy contributed to an image: the render log's table of
//! shares per path length and strategy.

use glam::Vec3;

/// Sums of the weighted contributions of each strategy `(s, t)` (as mean RGB), to report
/// what share of the image each path length and strategy made.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct StrategyStats {
    /// `sums[s + t][s]`: summed contribution of strategy `(s, t)` (per channel mean).
    sums: Vec<Vec<f64>>,
}

impl StrategyStats {
    /// Adds a weighted contribution of strategy `(s, t)`.
    pub fn add(&mut self, s: usize, t: usize, v: Vec3) {
        let n = s + t;
        if self.sums.len() <= n {
            self.sums.resize(n + 1, Vec::new());
        }
        let row = &mut self.sums[n];
        if row.len() <= s {
            row.resize(s + 1, 0.0);
        }
        let m = (v.x as f64 + v.y as f64 + v.z as f64) / 3.0;
        if m.is_finite() {
            row[s] += m;
        }
    }

    /// Adds another set of sums.
    pub fn merge(&mut self, other: &StrategyStats) {
        for (n, row) in other.sums.iter().enumerate() {
            for (s, &v) in row.iter().enumerate() {
                if v != 0.0 {
                    self.add_raw(n, s, v);
                }
            }
        }
    }

    fn add_raw(&mut self, n: usize, s: usize, v: f64) {
        if self.sums.len() <= n {
            self.sums.resize(n + 1, Vec::new());
        }
        let row = &mut self.sums[n];
        if row.len() <= s {
            row.resize(s + 1, 0.0);
        }
        row[s] += v;
    }

    /// Every strategy with a nonzero sum: `(s, t, share of the total)`, by path length
    /// then `s`.
    pub fn shares(&self) -> Vec<(usize, usize, f64)> {
        let total: f64 = self.sums.iter().flatten().sum();
        let mut out = Vec::new();
        if total.is_nan() || total <= 0.0 {
            return out;
        }
        for (n, row) in self.sums.iter().enumerate() {
            for (s, &v) in row.iter().enumerate() {
                if v != 0.0 {
                    out.push((s, n - s, v / total));
                }
            }
        }
        out
    }

    /// The summed contribution (channel mean) per path length in segments
    /// (`s + t − 1`): `totals[k]` for `k` segments (`totals[0]` is 0).
    pub fn length_totals(&self) -> Vec<f64> {
        (0..self.sums.len())
            .map(|n| {
                if n == 0 {
                    0.0
                } else {
                    self.sums[n].iter().sum()
                }
            })
            .skip(1)
            .collect()
    }

    /// Share of the total per path length in segments (`s + t − 1`), from 1 up; lengths
    /// that contributed nothing are left out.
    pub fn length_shares(&self) -> Vec<(usize, f64)> {
        let totals = self.length_totals();
        let total: f64 = totals.iter().sum();
        if total.is_nan() || total <= 0.0 {
            return Vec::new();
        }
        totals
            .iter()
            .enumerate()
            .filter(|(_, &v)| v != 0.0)
            .map(|(k, &v)| (k, v / total))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shares_sum_to_one() {
        let mut a = StrategyStats::default();
        a.add(0, 2, Vec3::splat(1.0));
        a.add(1, 2, Vec3::splat(2.0));
        let mut b = StrategyStats::default();
        b.add(2, 1, Vec3::splat(1.0));
        a.merge(&b);
        let s = a.shares();
        assert_eq!(s.len(), 3);
        let total: f64 = s.iter().map(|x| x.2).sum();
        assert!(total.is_finite() && (total - 1.0).abs() < 1e-12);
        assert_eq!(a.length_shares(), vec![(1, 0.25), (2, 0.75)]);
    }
}
