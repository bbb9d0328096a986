//! Resampled importance sampling: draw `M` candidates from a source density, keep one in
//! proportion to a target function over the source density, and weight it so that the
//! estimator stays unbiased.

/// A resampler over candidates drawn from a source density `p`, keeping one with
/// probability in proportion to `w = p̂(y)/p(y)`, `p̂ ≥ 0` an unnormalised target (for
/// instance the unshadowed contribution of a light sample).
///
/// After `M` candidates (each distributed as `p`; they may depend on each other, e.g.
/// stratified, as long as each one alone has density `p`), the kept `y` with its
/// *contribution weight* `W = Σw / (M · p̂(y))` gives the estimate `f(y) · W` of `∫ f`,
/// unbiased wherever `p̂ > 0` on the support of `f` (and `p > 0` there). A candidate draw that
/// produced nothing still counts in `M` ([`Resampler::add_empty`]).
///
/// One uniform number `u` chooses, given at construction and rescaled after each decision
/// (`u/q` when the candidate of share `q = w/Σw` is taken, `(u − q)/(1 − q)` when not), so
/// that it stays uniform and independent of the decisions so far; it must be independent
/// of the candidates. Sums and `u` are kept in `f64`.
///
/// Citation: Talbot, Cline & Egbert 2005, "Importance Resampling for Global Illumination",
/// Proc. EGSR. Derivation and the unbiasedness argument: `docs/derivations.md`, Part V §8.
///
/// ```
/// use mcrt::sampling::Resampler;
///
/// // Two candidates drawn uniformly on [0, 1) (p = 1), target p̂(x) = x.
/// let mut r = Resampler::new(0.5);
/// r.add(0.25f32, 0.25, 1.0);
/// r.add(0.75f32, 0.75, 1.0);
/// let (x, w) = r.finish().unwrap();
/// assert_eq!(x, 0.75); // the first is taken (share 1), then the second (0.5 < 3/4)
/// assert!((w - (1.0 / (2.0 * 0.75))).abs() < 1e-6); // Σw/(M p̂) = 1/(2 · 0.75)
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Resampler<T> {
    item: Option<T>,
    item_target: f32,
    total: f64,
    count: u32,
    u: f64,
}

impl<T> Resampler<T> {
    /// An empty resampler choosing with the uniform `u ∈ [0, 1)` (NaN counts as 0).
    #[must_use]
    pub fn new(u: f32) -> Self {
        Self {
            item: None,
            item_target: 0.0,
            total: 0.0,
            count: 0,
            u: f64::from(crate::sampling::unit::clamp_unit(u)),
        }
    }

    /// Offers a candidate `item` drawn with density `source_pdf`, with target value
    /// `target`. A target that is not finite and positive, or a density that is not, gives
    /// the candidate weight 0 (it counts in `M` and is never kept).
    pub fn add(&mut self, item: T, target: f32, source_pdf: f32) {
        self.count += 1;
        let ok = |x: f32| x.is_finite() && x > 0.0;
        if !(ok(target) && ok(source_pdf)) {
            return;
        }
        let w = f64::from(target) / f64::from(source_pdf);
        if !w.is_finite() {
            return;
        }
        self.total += w;
        let q = w / self.total;
        if self.u < q {
            self.u /= q;
            self.item = Some(item);
            self.item_target = target;
        } else {
            self.u = (self.u - q) / (1.0 - q);
        }
        self.u = self.u.clamp(0.0, 1.0 - f64::EPSILON / 2.0);
    }

    /// Counts a candidate draw that produced no sample (weight 0).
    pub fn add_empty(&mut self) {
        self.count += 1;
    }

    /// The number of candidates offered (`M`).
    #[must_use]
    pub fn count(&self) -> u32 {
        self.count
    }

    /// The kept candidate and its contribution weight `W = Σw / (M · p̂(y))`, or `None`
    /// when no candidate had a positive weight.
    #[must_use]
    pub fn finish(self) -> Option<(T, f32)> {
        let item = self.item?;
        let w = self.total / (f64::from(self.count) * f64::from(self.item_target));
        Some((item, w as f32))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_candidates_count_but_are_never_kept() {
        let mut r = Resampler::new(0.0);
        r.add(0, f32::NAN, 1.0);
        r.add(1, 1.0, 0.0);
        r.add(2, -1.0, 1.0);
        r.add(3, f32::INFINITY, 1.0);
        r.add_empty();
        assert_eq!(r.count(), 5);
        assert_eq!(r.clone().finish(), None);
        r.add(4, 2.0, 4.0);
        let (item, w) = r.finish().unwrap();
        assert!(w.is_finite());
        // Σw = 0.5, M = 6, p̂ = 2.
        assert_eq!((item, w), (4, 0.5 / 12.0));
    }

    #[test]
    fn one_candidate_is_plain_importance_sampling() {
        let mut r = Resampler::new(0.7);
        r.add('a', 3.0, 0.5);
        let (item, w) = r.finish().unwrap();
        assert!(w.is_finite());
        assert_eq!((item, w), ('a', 2.0)); // W = 1/p
    }

    #[test]
    fn keeps_each_candidate_in_proportion() {
        // Weights 1, 2, 3, 4 over 4000 evenly spread u: candidate k kept for a share k/10.
        let n = 4000;
        let mut kept = [0u32; 4];
        for i in 0..n {
            let mut r = Resampler::new((i as f32 + 0.5) / n as f32);
            for k in 0..4 {
                r.add(k, (k + 1) as f32, 1.0);
            }
            kept[r.finish().unwrap().0] += 1;
        }
        for (k, &c) in kept.iter().enumerate() {
            let expected = n as f64 * (k + 1) as f64 / 10.0;
            assert!(
                (f64::from(c) - expected).abs() <= 2.0,
                "{k}: {c} vs {expected}"
            );
        }
    }
}
