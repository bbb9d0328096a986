//! Choosing a light by power (stand-in for the alias table of `sampling::distribution`
//! until it lands: a CDF searched by bisection, same interface).

/// A discrete distribution over lights with `O(log n)` sampling.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Picker {
    cdf: Vec<f32>,
    pmf: Vec<f32>,
}

impl Picker {
    /// From non-negative weights; all-zero or non-finite weights fall back to uniform.
    pub(crate) fn new(weights: &[f32]) -> Self {
        let n = weights.len().max(1);
        let total: f64 = weights.iter().map(|&w| w.max(0.0) as f64).sum();
        let uniform = !(total > 0.0 && total.is_finite());
        let pmf: Vec<f32> = weights
            .iter()
            .map(|&w| {
                if uniform {
                    1.0 / n as f32
                } else {
                    (w.max(0.0) as f64 / total) as f32
                }
            })
            .collect();
        let mut acc = 0.0f64;
        let cdf = pmf
            .iter()
            .map(|&p| {
                acc += p as f64;
                acc as f32
            })
            .collect();
        Self { cdf, pmf }
    }

    /// Chooses an index for `u ∈ [0,1)` and returns it with `u` rescaled to `[0,1)` within
    /// the chosen bin (so it can be reused).
    #[inline]
    pub(crate) fn sample(&self, u: f32) -> Option<(usize, f32)> {
        if self.pmf.is_empty() {
            return None;
        }
        let mut i = self
            .cdf
            .partition_point(|&c| c <= u)
            .min(self.pmf.len() - 1);
        while self.pmf[i] == 0.0 && i > 0 {
            i -= 1;
        }
        let lo = if i == 0 { 0.0 } else { self.cdf[i - 1] };
        let r = ((u - lo) / self.pmf[i]).clamp(0.0, 1.0 - f32::EPSILON / 2.0);
        Some((i, r))
    }

    /// Probability of index `i`.
    #[inline]
    pub(crate) fn pmf(&self, i: usize) -> f32 {
        self.pmf.get(i).copied().unwrap_or(0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn picks_by_weight_and_never_a_zero() {
        let p = Picker::new(&[1.0, 0.0, 3.0]);
        assert_eq!(p.sample(0.0).map(|x| x.0), Some(0));
        assert_eq!(p.sample(0.2499).map(|x| x.0), Some(0));
        assert_eq!(p.sample(0.25).map(|x| x.0), Some(2));
        assert_eq!(p.sample(1.0 - 1e-7).map(|x| x.0), Some(2));
        assert_eq!(p.pmf(1), 0.0);
        let (_, r) = p.sample(0.625).expect("some");
        assert!(r.is_finite() && (r - 0.5).abs() < 1e-5);
    }
}
