//! The evaluation behind [`ChiSquareTest`](super::ChiSquareTest)'s `run*` methods: counting
//! samples, re-checking suspect cells, pooling, the statistic and the verdict.

use super::chi2::{p_value, pool, sidak, statistic, CellCount};
use super::domain::Domain;
use super::outcome::{Chi2Failure, Chi2Outcome};
use super::parallel::{chunk_rng, for_chunks, map_indexed, next_u, CHUNK};
use super::report;
use glam::Vec2;
use std::path::PathBuf;

/// Cells whose count is further than this many standard deviations from the quadrature's
/// expectation are re-integrated finely before the statistic is formed.
pub const RECHECK_SIGMAS: f64 = 4.0;

/// At most this many cells are re-integrated per run.
pub const RECHECK_MAX_CELLS: usize = 64;

/// The settings of a chi-square run (what the [`ChiSquareTest`](super::ChiSquareTest)
/// builder sets).
#[derive(Clone, Debug)]
pub(super) struct Settings {
    pub(super) samples: usize,
    pub(super) seed: u64,
    pub(super) alpha: f64,
    pub(super) test_count: u32,
    pub(super) integral_tolerance: f64,
    pub(super) threads: usize,
    pub(super) name: String,
    pub(super) output_dir: Option<PathBuf>,
}

/// One run: a domain and the settings.
pub(super) struct Run<'a, D: Domain> {
    pub(super) domain: &'a D,
    pub(super) settings: &'a Settings,
}

/// What one draw produced.
pub(super) enum Draw<P> {
    At(P),
    Rejected,
    BadWeight,
}

/// Sample counts of one run.
#[derive(Clone)]
struct Counts {
    cells: Vec<u64>,
    rejected: u64,
    outside: u64,
    bad_weights: u64,
}

impl<D: Domain> Run<'_, D> {
    fn count(&self, draw: &(dyn Fn(Vec2) -> Draw<D::Point> + Sync)) -> Counts {
        let cells = self.domain.cell_count();
        let init = || Counts {
            cells: vec![0; cells],
            rejected: 0,
            outside: 0,
            bad_weights: 0,
        };
        let n = self.settings.samples;
        let work = |c: usize, acc: &mut Counts| {
            let mut rng = chunk_rng(self.settings.seed, c);
            for _ in c * CHUNK..((c + 1) * CHUNK).min(n) {
                match draw(next_u(&mut rng)) {
                    Draw::At(p) => match self.domain.cell_of(p) {
                        Some(i) => acc.cells[i] += 1,
                        None => acc.outside += 1,
                    },
                    Draw::Rejected => acc.rejected += 1,
                    Draw::BadWeight => acc.bad_weights += 1,
                }
            }
        };
        let parts = for_chunks(n.div_ceil(CHUNK), self.settings.threads, &init, &work);
        let mut total = init();
        for p in parts {
            for (t, x) in total.cells.iter_mut().zip(&p.cells) {
                *t += x;
            }
            total.rejected += p.rejected;
            total.outside += p.outside;
            total.bad_weights += p.bad_weights;
        }
        total
    }

    pub(super) fn execute(
        &self,
        draw: &(dyn Fn(Vec2) -> Draw<D::Point> + Sync),
        mut masses: Vec<f64>,
        pdf: Option<&(dyn Fn(D::Point) -> f32 + Sync)>,
        may_reject: bool,
    ) -> Chi2Outcome {
        let counts = self.count(draw);
        if let Some(pdf) = pdf {
            self.refine_suspect_cells(&mut masses, &counts.cells, pdf);
        }
        let n = self.settings.samples as f64;
        let integral: f64 = masses.iter().sum();
        let mut observed = counts.cells.clone();
        let mut expected: Vec<f64> = masses.iter().map(|m| m * n).collect();
        if may_reject {
            observed.push(counts.rejected);
            expected.push(n * (1.0 - integral).max(0.0));
        }
        let pooled = pool(&observed, &expected);
        let (stat, dof) = statistic(&pooled.terms);
        let p = p_value(stat, dof);
        let threshold = sidak(self.settings.alpha, self.settings.test_count);
        let failures = self.failures(
            &counts,
            &pooled.zero_hits,
            p,
            threshold,
            integral,
            may_reject,
        );
        let mut outcome = Chi2Outcome {
            name: self.settings.name.clone(),
            samples: self.settings.samples,
            statistic: stat,
            dof,
            p_value: p,
            threshold,
            integral,
            pooled_cells: pooled.pooled_cells,
            rejected: counts.rejected,
            worst: self.worst(&pooled.terms, pooled.pooled_cells),
            failures,
            images: Vec::new(),
        };
        if let (false, Some(dir)) = (outcome.passed(), &self.settings.output_dir) {
            outcome.images = report::write_images(
                dir,
                &self.settings.name,
                self.domain.grid(),
                &observed,
                &expected,
            );
        }
        outcome
    }

    /// Re-integrates, with a fine forced subdivision, the cells whose count disagrees with
    /// the quadrature by more than [`RECHECK_SIGMAS`] standard deviations or that hold samples
    /// where the mass came out 0 (at most [`RECHECK_MAX_CELLS`], worst first). The quadrature
    /// can miss a support narrower than its node spacing (a sliver triangle); a finer
    /// integral of the same pdf is closer to the truth, so this can only remove a false
    /// rejection, never hide a wrong sampler.
    fn refine_suspect_cells(
        &self,
        masses: &mut [f64],
        observed: &[u64],
        pdf: &(dyn Fn(D::Point) -> f32 + Sync),
    ) {
        let n = self.settings.samples as f64;
        let score = |c: usize| {
            let (o, e) = (observed[c] as f64, masses[c] * n);
            if o > 0.0 && e <= 0.0 {
                f64::INFINITY
            } else {
                (o - e) * (o - e) / e.max(1.0)
            }
        };
        let limit = RECHECK_SIGMAS * RECHECK_SIGMAS;
        let mut cells: Vec<(usize, f64)> = (0..masses.len())
            .map(|c| (c, score(c)))
            .filter(|&(_, s)| s > limit)
            .collect();
        cells.sort_by(|a, b| b.1.total_cmp(&a.1).then(a.0.cmp(&b.0)));
        cells.truncate(RECHECK_MAX_CELLS);
        let pdf64 = |p: D::Point| f64::from(pdf(p));
        let refined = map_indexed(cells.len(), self.settings.threads, &|k| {
            self.domain.cell_mass_refined(cells[k].0, &pdf64)
        });
        for (&(c, _), m) in cells.iter().zip(refined) {
            masses[c] = m;
        }
    }

    fn failures(
        &self,
        counts: &Counts,
        zero_hits: &[(usize, u64)],
        p: f64,
        threshold: f64,
        integral: f64,
        may_reject: bool,
    ) -> Vec<Chi2Failure> {
        let mut f = Vec::new();
        if p.is_nan() || p < threshold {
            f.push(Chi2Failure::Rejected);
        }
        if let Some(&(cell, _)) = zero_hits.first() {
            let cell = if cell < self.domain.cell_count() {
                self.domain.describe_cell(cell)
            } else {
                "rejected samples".into()
            };
            let count = zero_hits.iter().map(|z| z.1).sum();
            f.push(Chi2Failure::ZeroExpectedHit { cell, count });
        }
        if counts.outside > 0 {
            f.push(Chi2Failure::OutsideDomain {
                count: counts.outside,
            });
        }
        if counts.bad_weights > 0 {
            f.push(Chi2Failure::BadWeight {
                count: counts.bad_weights,
            });
        }
        let excess = if may_reject {
            integral - 1.0
        } else {
            (integral - 1.0).abs()
        };
        if excess.is_nan() || excess > self.settings.integral_tolerance {
            f.push(Chi2Failure::NotNormalized { integral });
        }
        f
    }

    fn worst(&self, terms: &[CellCount], pooled_cells: usize) -> Vec<(String, CellCount)> {
        let mut idx: Vec<usize> = (0..terms.len()).collect();
        idx.sort_by(|&a, &b| terms[b].contribution().total_cmp(&terms[a].contribution()));
        idx.truncate(8);
        idx.into_iter()
            .map(|i| {
                let t = &terms[i];
                let what = match t.cell {
                    None => format!("pool of {pooled_cells} sparse cells"),
                    Some(c) if c >= self.domain.cell_count() => "rejected samples".into(),
                    Some(c) => self.domain.describe_cell(c),
                };
                (what, t.clone())
            })
            .collect()
    }
}
