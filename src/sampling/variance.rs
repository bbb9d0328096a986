//! A streaming mean and variance estimator (Welford's method).

/// The running mean and variance of a stream of values, in one pass and `O(1)` memory, by
/// Welford's update; two estimators over disjoint streams [merge](Self::merge) by the
/// parallel formula of Chan, Golub and LeVeque.
///
/// Update for a value `x` (count `n` after it): `δ = x − mean`, `mean += δ/n`,
/// `M₂ += δ (x − mean)`; the sample variance is `M₂/(n − 1)`. Unlike `Σx² − (Σx)²/n`, this
/// does not cancel when the mean is large against the spread. Accumulated in `f64`. A NaN or
/// infinite value makes the results NaN or infinite (nothing panics).
///
/// Citation: B. P. Welford, 1962, "Note on a method for calculating corrected sums of squares
/// and products", Technometrics 4(3). Derivation: `docs/derivations.md`.
///
/// ```
/// use mcrt::sampling::VarianceEstimator;
///
/// let mut v = VarianceEstimator::new();
/// for x in [1e9 + 4.0, 1e9 + 7.0, 1e9 + 13.0, 1e9 + 16.0] {
///     v.add(x);
/// }
/// assert_eq!(v.mean(), 1e9 + 10.0);
/// assert_eq!(v.variance(), 30.0); // the naive formula returns garbage here in f32
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct VarianceEstimator {
    count: u64,
    mean: f64,
    m2: f64,
}

impl VarianceEstimator {
    /// An empty estimator.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds one value.
    pub fn add(&mut self, x: f64) {
        self.count += 1;
        let delta = x - self.mean;
        self.mean += delta / self.count as f64;
        self.m2 += delta * (x - self.mean);
    }

    /// Merges an estimator over a disjoint stream into this one.
    pub fn merge(&mut self, other: &Self) {
        if other.count == 0 {
            return;
        }
        if self.count == 0 {
            *self = *other;
            return;
        }
        let (n_a, n_b) = (self.count as f64, other.count as f64);
        let n = n_a + n_b;
        let delta = other.mean - self.mean;
        self.mean += delta * n_b / n;
        self.m2 += other.m2 + delta * delta * n_a * n_b / n;
        self.count += other.count;
    }

    /// The number of values added.
    #[must_use]
    pub fn count(&self) -> u64 {
        self.count
    }

    /// The mean (0 when empty).
    #[must_use]
    pub fn mean(&self) -> f64 {
        self.mean
    }

    /// The unbiased sample variance `M₂/(n − 1)` (0 for fewer than two values).
    #[must_use]
    pub fn variance(&self) -> f64 {
        if self.count > 1 {
            self.m2 / (self.count - 1) as f64
        } else {
            0.0
        }
    }

    /// The variance of the mean, `variance / n` (0 for fewer than two values).
    #[must_use]
    pub fn variance_of_mean(&self) -> f64 {
        if self.count > 1 {
            self.variance() / self.count as f64
        } else {
            0.0
        }
    }

    /// `variance / mean²`, the relative variance (0 when the mean is 0).
    #[must_use]
    pub fn relative_variance(&self) -> f64 {
        if self.mean == 0.0 {
            0.0
        } else {
            self.variance() / (self.mean * self.mean)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn merge_equals_sequential() {
        let xs: Vec<f64> = (0..100).map(|i| 1e8 + f64::from(i % 7) * 0.5).collect();
        let mut all = VarianceEstimator::new();
        xs.iter().for_each(|&x| all.add(x));
        let (mut a, mut b) = (VarianceEstimator::new(), VarianceEstimator::new());
        xs[..37].iter().for_each(|&x| a.add(x));
        xs[37..].iter().for_each(|&x| b.add(x));
        a.merge(&b);
        assert_eq!(a.count(), all.count());
        assert!((a.mean() - all.mean()).abs() < 1e-7);
        let (va, vall) = (a.variance(), all.variance());
        assert!(
            va.is_finite() && (va - vall).abs() < 1e-7 * vall,
            "{va} {vall}"
        );
        let mut empty = VarianceEstimator::new();
        empty.merge(&all);
        assert_eq!(empty, all);
        assert_eq!(VarianceEstimator::new().variance(), 0.0);
    }
}
