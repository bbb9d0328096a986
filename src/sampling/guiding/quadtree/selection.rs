//! The guide's learned selection probability: per candidate probability, the estimated second
//! moment of the one-sample estimator, summed over the selection records (after Müller 2019,
//! "Practical Path Guiding in Production"; derivation in docs/renderer.md, "The learned
//! selection probability").

use super::DQuadTree;

/// The candidates for the probability of sampling the guide that a tree judges
/// ([`DQuadTree::selection_probability`]). None above ½: the BSDF keeps at least half of the
/// samples, so a vertex's weight `f·|cos|/q` is at most twice BSDF sampling's wherever the
/// guide is poor; and the records judge a high `α` mostly by the rare BSDF-sampled directions
/// where the guide is poor, whose tail a leaf's few records miss (docs/renderer.md, "The
/// learned selection probability": the cap lowered the dark indirect room's error by 9 %).
pub(crate) const SELECTION_CANDIDATES: [f32; 6] = [0.0, 0.1, 0.2, 0.3, 0.4, 0.5];

/// The fewest selection records from which a tree gives a selection probability.
const MIN_SELECTION_RECORDS: u64 = 64;

impl DQuadTree {
    /// The probability with which the guided path tracer should sample this tree rather
    /// than the BSDF, learned from what it saw while the tree trained: the candidate of
    /// 0, 0.1, …, 0.5 with the least estimated second moment of the one-sample estimator
    /// `F/q_α`, `q_α = α·p_guide + (1 − α)·p_bsdf` (the smallest on ties). The estimate is
    /// `Σ F²/(q·q_α)` over the records, each sampled with the mixture `q` in use then
    /// (importance sampling of `∫F²/q_α`). `None` before 64 records, or where the tree
    /// did not learn ([`SdTree::learn_selection`](crate::sampling::guiding::SdTree::learn_selection)).
    ///
    /// The estimate judges the candidates with the density of the guide that sampled the
    /// records, older than this tree; the guide improves as it trains, so the choice errs
    /// towards the BSDF.
    pub fn selection_probability(&self) -> Option<f32> {
        self.derived().selection
    }

    /// The estimated second moments `(M_0, min_j M_j)` of the one-sample estimator with BSDF
    /// sampling alone and with the best candidate (sums over the selection records, see
    /// [`DQuadTree::selection_probability`]); `None` where that gives no probability.
    pub(crate) fn selection_moments(&self) -> Option<(f64, f64)> {
        self.best_candidate().map(|(m, _)| (self.selection[0], m))
    }

    pub(super) fn best_selection(&self) -> Option<f32> {
        self.best_candidate().map(|(_, a)| a)
    }

    /// The candidate of least estimated second moment, with that moment (the smallest
    /// candidate on ties); `None` before [`MIN_SELECTION_RECORDS`] records or where no
    /// moment is finite.
    fn best_candidate(&self) -> Option<(f64, f32)> {
        if self.selection_records < MIN_SELECTION_RECORDS {
            return None;
        }
        let mut best: Option<(f64, f32)> = None;
        for (m, a) in self.selection.iter().zip(SELECTION_CANDIDATES) {
            if m.is_finite() && best.is_none_or(|(b, _)| *m < b) {
                best = Some((*m, a));
            }
        }
        best
    }

    /// Adds one selection record: a direction sampled with the mixture density `pdf`, where
    /// the guide's density is `p_guide`, the BSDF's `p_bsdf` and the integrand
    /// `F = T·f·|cos θ|·L` is `integrand` (`T` the path throughput before the vertex). A
    /// candidate under which the direction has zero density while `F > 0` gets an infinite
    /// second moment. Records with a density that is not positive and finite, or an
    /// integrand that is negative or not finite, are ignored.
    pub(crate) fn record_selection(&mut self, integrand: f32, p_guide: f32, p_bsdf: f32, pdf: f32) {
        let ok = |x: f32| x >= 0.0 && x.is_finite();
        if !(pdf > 0.0 && pdf.is_finite() && ok(integrand) && ok(p_guide) && ok(p_bsdf)) {
            return;
        }
        self.derived.take();
        let f2 = f64::from(integrand) * f64::from(integrand);
        if p_bsdf > 0.0 {
            // Every candidate's density is positive (`1 − α ≥ 0.5`): the same sums without a
            // branch per candidate, which the compiler vectorises.
            let (pg, pb, pdf) = (f64::from(p_guide), f64::from(p_bsdf), f64::from(pdf));
            for (m, a) in self.selection.iter_mut().zip(SELECTION_CANDIDATES) {
                let q = f64::from(a) * pg + f64::from(1.0 - a) * pb;
                *m += f2 / (pdf * q);
            }
            self.selection_records += 1;
            return;
        }
        for (m, a) in self.selection.iter_mut().zip(SELECTION_CANDIDATES) {
            let q = f64::from(a) * f64::from(p_guide) + f64::from(1.0 - a) * f64::from(p_bsdf);
            if q > 0.0 {
                *m += f2 / (f64::from(pdf) * q);
            } else if f2 > 0.0 {
                *m = f64::INFINITY;
            }
        }
        self.selection_records += 1;
    }
}
