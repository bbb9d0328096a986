//! Pearson's statistic with pooling of sparse cells, its p-value, and the Šidák-corrected
//! significance level.

use statrs::distribution::{ChiSquared, ContinuousCDF};

/// Cells whose expected count is below this are pooled.
pub const MIN_EXPECTED: f64 = 5.0;

/// The per-test level `1 − (1 − α)^(1/N)` that keeps the family-wise level of `N`
/// independent tests at `α` (Šidák 1967).
///
/// ```
/// let a = mcrt::stats::sidak(0.01, 1);
/// assert!((a - 0.01).abs() < 1e-15);
/// let a = mcrt::stats::sidak(0.01, 400); // 2.513e-5, a little above Bonferroni's 0.01/400
/// assert!(a > 0.01 / 400.0 && a < 0.0101 / 400.0);
/// ```
pub fn sidak(alpha: f64, test_count: u32) -> f64 {
    let n = f64::from(test_count.max(1));
    -((-alpha).ln_1p() / n).exp_m1()
}

/// One term of the statistic: a cell, or the pool of sparse cells.
#[derive(Clone, Debug, PartialEq)]
pub struct CellCount {
    /// The cell index, or `None` for the pool of cells with expected count below 5.
    pub cell: Option<usize>,
    /// Samples counted.
    pub observed: u64,
    /// Samples expected.
    pub expected: f64,
}

impl CellCount {
    /// This term's share `(O − E)² / E` of the statistic.
    pub fn contribution(&self) -> f64 {
        let d = self.observed as f64 - self.expected;
        d * d / self.expected
    }
}

/// The pooled terms and the cells hit despite zero expectation.
#[derive(Debug, Default)]
pub(crate) struct Pooled {
    pub terms: Vec<CellCount>,
    pub zero_hits: Vec<(usize, u64)>,
    pub pooled_cells: usize,
}

/// Pools cells with expected < [`MIN_EXPECTED`] into one term (kept as a term when it
/// reaches 5, else merged into the sparsest other term; it is the only term when nothing
/// else is left). Cells with expected ≤ 0 are left out; samples in them are reported.
pub(crate) fn pool(observed: &[u64], expected: &[f64]) -> Pooled {
    let mut out = Pooled::default();
    let mut order: Vec<usize> = Vec::with_capacity(expected.len());
    for (i, (&o, &e)) in observed.iter().zip(expected).enumerate() {
        if e > 0.0 {
            order.push(i);
        } else if o > 0 {
            out.zero_hits.push((i, o));
        }
    }
    order.sort_by(|&a, &b| expected[a].total_cmp(&expected[b]).then(a.cmp(&b)));
    let mut pool = CellCount {
        cell: None,
        observed: 0,
        expected: 0.0,
    };
    for &i in &order {
        if expected[i] < MIN_EXPECTED {
            pool.observed += observed[i];
            pool.expected += expected[i];
            out.pooled_cells += 1;
        } else {
            out.terms.push(CellCount {
                cell: Some(i),
                observed: observed[i],
                expected: expected[i],
            });
        }
    }
    if out.pooled_cells > 0 {
        match out.terms.first_mut() {
            Some(first) if pool.expected < MIN_EXPECTED => {
                first.cell = None;
                first.observed += pool.observed;
                first.expected += pool.expected;
            }
            _ => out.terms.insert(0, pool),
        }
    }
    out
}

/// Pearson's statistic and degrees of freedom (terms − 1) of pooled terms.
pub(crate) fn statistic(terms: &[CellCount]) -> (f64, usize) {
    let s = terms.iter().map(CellCount::contribution).sum();
    (s, terms.len().saturating_sub(1))
}

/// The upper-tail probability of `statistic` under χ²(dof); 1 when `dof == 0`.
pub fn p_value(statistic: f64, dof: usize) -> f64 {
    if dof == 0 {
        return 1.0;
    }
    match ChiSquared::new(dof as f64) {
        Ok(d) if statistic.is_finite() => d.sf(statistic),
        _ => 0.0,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sparse_cells_are_pooled() {
        let p = pool(&[3, 1, 100, 0, 2], &[2.0, 2.5, 99.0, 0.0, 1.0]);
        assert!(p.zero_hits.is_empty());
        // 2 + 2.5 + 1 = 5.5 ≥ 5: the pool stays a term.
        assert_eq!(p.terms.len(), 2);
        assert_eq!(p.terms[0].cell, None);
        assert_eq!(p.terms[0].observed, 6);
        let p = pool(&[3, 100, 7], &[2.0, 99.0, 0.0]);
        assert_eq!(p.zero_hits, vec![(2, 7)]);
        assert_eq!(
            p.terms.len(),
            1,
            "a pool below 5 merges into the sparsest cell"
        );
        assert_eq!(p.terms[0].observed, 103);
    }

    #[test]
    fn everything_sparse_is_one_term_with_no_degree_of_freedom() {
        let p = pool(&[1, 2, 0], &[1.0, 2.0, 1.5]);
        assert_eq!(p.terms.len(), 1);
        assert_eq!(p.pooled_cells, 3);
        let (stat, dof) = statistic(&p.terms);
        assert!(stat.is_finite());
        assert_eq!(dof, 0);
        assert_eq!(p_value(stat, dof), 1.0);
    }

    #[test]
    fn p_values_match_known_quantiles() {
        // The 0.95 quantile of χ²(10) is 18.307.
        let p = p_value(18.307, 10);
        assert!(p.is_finite() && (p - 0.05).abs() < 1e-4, "{p}");
        assert_eq!(p_value(123.0, 0), 1.0);
        assert_eq!(p_value(f64::NAN, 3), 0.0);
    }
}
