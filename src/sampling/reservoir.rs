//! Weighted reservoir sampling: choose one item of a stream with probability proportional to
//! its weight, in one pass and `O(1)` memory.

/// A reservoir holding one item of a stream, chosen with probability proportional to its
/// weight.
///
/// After items with weights `w₁ … wₙ` have been offered with independent uniform numbers `u`,
/// item `i` is held with probability `wᵢ / Σw`. [`WeightedReservoir::add`] keeps the new item
/// when `u < w / W`, `W` the running sum including `w` (by induction, every earlier item
/// keeps probability `wⱼ/W`). Two reservoirs over disjoint streams [merge](Self::merge) into
/// one over their union. The uniform numbers come from the caller (a sampler or an RNG), as
/// everywhere in `mcrt::sampling`; the running sum is kept in `f64`.
///
/// Weights that are negative, NaN or infinite are ignored (the item is not offered), so user
/// data cannot poison the reservoir; a weight of 0 is offered but never chosen.
///
/// Citation: M. T. Chao, 1982, "A general purpose unequal probability sampling plan",
/// Biometrika 69(3). Derivation: `docs/derivations.md`.
///
/// ```
/// use mcrt::sampling::WeightedReservoir;
///
/// let mut r = WeightedReservoir::new();
/// for (item, (w, u)) in [(1.0, 0.3), (0.0, 0.0), (3.0, 0.5)].into_iter().enumerate() {
///     r.add(item, w, u);
/// }
/// assert_eq!(r.item(), Some(&2)); // 0.5 < 3/4: the third item replaced the first
/// assert!((r.probability() - 0.75).abs() < 1e-7);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct WeightedReservoir<T> {
    item: Option<T>,
    item_weight: f32,
    total: f64,
    offered: u64,
}

impl<T> Default for WeightedReservoir<T> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T> WeightedReservoir<T> {
    /// An empty reservoir.
    #[must_use]
    pub fn new() -> Self {
        Self {
            item: None,
            item_weight: 0.0,
            total: 0.0,
            offered: 0,
        }
    }

    /// Offers `item` with `weight ≥ 0`, using the fresh uniform `u ∈ [0,1)`; returns whether
    /// the reservoir now holds it. A weight that is negative, NaN or infinite is ignored.
    pub fn add(&mut self, item: T, weight: f32, u: f32) -> bool {
        if !(weight.is_finite() && weight >= 0.0) {
            return false;
        }
        self.offered += 1;
        self.total += f64::from(weight);
        let take = weight > 0.0 && f64::from(u) * self.total < f64::from(weight);
        if take {
            self.item = Some(item);
            self.item_weight = weight;
        }
        take
    }

    /// Merges `other` (a reservoir over a disjoint stream) into `self` with the fresh
    /// uniform `u`: `other`'s item is kept with probability `W_other / (W_self + W_other)`.
    /// Returns whether `self` now holds `other`'s item.
    pub fn merge(&mut self, other: Self, u: f32) -> bool {
        self.offered += other.offered;
        self.total += other.total;
        let take = other.total > 0.0 && f64::from(u) * self.total < other.total;
        if take {
            self.item = other.item;
            self.item_weight = other.item_weight;
        }
        take
    }

    /// The held item, if any item with a positive weight has been offered.
    #[must_use]
    pub fn item(&self) -> Option<&T> {
        self.item.as_ref()
    }

    /// The held item, consuming the reservoir.
    #[must_use]
    pub fn into_item(self) -> Option<T> {
        self.item
    }

    /// The weight the held item was offered with (0 when empty).
    #[must_use]
    pub fn item_weight(&self) -> f32 {
        self.item_weight
    }

    /// The sum of the weights offered, in `f64`.
    #[must_use]
    pub fn total_weight(&self) -> f64 {
        self.total
    }

    /// The number of items offered (ignored ones not counted).
    #[must_use]
    pub fn offered(&self) -> u64 {
        self.offered
    }

    /// The probability that the held item was chosen, `w / Σw` (0 when empty).
    #[must_use]
    pub fn probability(&self) -> f32 {
        if self.total > 0.0 {
            (f64::from(self.item_weight) / self.total) as f32
        } else {
            0.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ignores_bad_weights_and_never_takes_zero() {
        let mut r = WeightedReservoir::new();
        assert!(!r.add(0, f32::NAN, 0.0));
        assert!(!r.add(1, -1.0, 0.0));
        assert!(!r.add(2, f32::INFINITY, 0.0));
        assert!(!r.add(3, 0.0, 0.0));
        assert_eq!((r.item(), r.offered(), r.probability()), (None, 1, 0.0));
        assert!(r.add(4, 2.0, 0.999_999_9));
        assert_eq!(r.item(), Some(&4));
    }

    #[test]
    fn merge_keeps_the_proportions() {
        let mut a = WeightedReservoir::new();
        a.add('a', 1.0, 0.5);
        let mut b = WeightedReservoir::new();
        b.add('b', 3.0, 0.5);
        let mut c = a.clone();
        assert!(c.merge(b.clone(), 0.7)); // 0.7 < 3/4
        assert_eq!(c.item(), Some(&'b'));
        assert!(!a.merge(b, 0.8));
        assert_eq!(
            (a.item(), a.total_weight(), a.offered()),
            (Some(&'a'), 4.0, 2)
        );
    }
}
