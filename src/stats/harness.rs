//! [`ChiSquareTest`]: the builder that draws samples, integrates the pdf per cell and
//! compares the two.

use super::chi2::{p_value, pool, sidak, statistic, CellCount};
use super::domain::Domain;
use super::outcome::{Chi2Failure, Chi2Outcome};
use super::parallel::{chunk_rng, default_threads, for_chunks, map_indexed, next_u, CHUNK};
use super::report;
use crate::sampling::warp::Warp;
use glam::Vec2;
use std::path::PathBuf;

/// Cells whose count is further than this many standard deviations from the quadrature's
/// expectation are re-integrated finely before the statistic is formed.
pub const RECHECK_SIGMAS: f64 = 4.0;

/// At most this many cells are re-integrated per run.
pub const RECHECK_MAX_CELLS: usize = 256;

/// What one draw produced.
pub(crate) enum Draw<P> {
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

/// A chi-square goodness-of-fit test of a sampler against its pdf over a [`Domain`].
///
/// Draws `samples` points from `u ∈ [0,1)²` (PCG64, fixed seed, fixed chunks of 2¹⁵
/// samples with one RNG stream each, so the counts do not depend on the thread count),
/// integrates the pdf over each cell (adaptive Gauss–Legendre in `f64`), pools cells whose
/// expected count is below 5, and compares Pearson's statistic with χ². The run fails when
/// the p-value is below the Šidák-corrected level for `test_count` tests, when a sample
/// lands where the pdf integrates to 0 or outside the domain, or when the pdf does not
/// integrate to 1 within the tolerance (default 10⁻³). Before the statistic is formed, cells
/// whose count is more than 4σ from the quadrature's expectation are re-integrated with a
/// finer forced subdivision (see [`RECHECK_SIGMAS`]). On failure the observed, expected
/// and difference histograms are written as PNG images (see [`ChiSquareTest::output_dir`]).
///
/// ```
/// use mcrt::glam::{Vec2, Vec3};
/// use mcrt::stats::{ChiSquareTest, Directions};
/// use std::f32::consts::PI;
///
/// // Cosine-weighted hemisphere by Malley's method, against its pdf cos θ / π.
/// let sample = |u: Vec2| {
///     let (r, phi) = (u.x.sqrt(), 2.0 * PI * u.y);
///     Vec3::new(r * phi.cos(), r * phi.sin(), (1.0 - u.x).max(0.0).sqrt())
/// };
/// let pdf = |w: Vec3| w.z.max(0.0) / PI;
/// let outcome = ChiSquareTest::new(Directions::hemisphere().resolution(16, 32))
///     .samples(100_000)
///     .run(sample, pdf);
/// outcome.assert_passed();
/// assert!(outcome.p_value > 1e-3);
/// ```
#[derive(Clone, Debug)]
pub struct ChiSquareTest<D: Domain> {
    domain: D,
    samples: usize,
    seed: u64,
    alpha: f64,
    test_count: u32,
    integral_tolerance: f64,
    threads: usize,
    name: String,
    output_dir: Option<PathBuf>,
}

impl<D: Domain> ChiSquareTest<D> {
    /// A test over `domain`: 10⁶ samples, seed 0, α = 0.01 for a single test, integral
    /// tolerance 10⁻³, all available threads, images into `target/chi2-failures` (or the
    /// directory in the `MCRT_CHI2_OUTPUT` environment variable).
    pub fn new(domain: D) -> Self {
        let output_dir = std::env::var_os("MCRT_CHI2_OUTPUT")
            .map_or_else(|| PathBuf::from("target/chi2-failures"), PathBuf::from);
        Self {
            domain,
            samples: 1_000_000,
            seed: 0,
            alpha: 0.01,
            test_count: 1,
            integral_tolerance: 1e-3,
            threads: default_threads(),
            name: "chi2".into(),
            output_dir: Some(output_dir),
        }
    }

    /// Sets the number of samples drawn.
    #[must_use]
    pub fn samples(mut self, n: usize) -> Self {
        self.samples = n.max(1);
        self
    }

    /// Sets the seed (the same seed gives the same counts on any thread count).
    #[must_use]
    pub fn seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }

    /// Sets the family-wise level `alpha` for a suite of `test_count` tests: each run is
    /// rejected when its p-value is below `1 − (1 − alpha)^(1/test_count)` ([`sidak`]).
    /// Keep `test_count` fixed for a suite, so a filtered run uses the same threshold.
    #[must_use]
    pub fn significance(mut self, alpha: f64, test_count: u32) -> Self {
        self.alpha = if alpha > 0.0 && alpha < 1.0 {
            alpha
        } else {
            0.01
        };
        self.test_count = test_count.max(1);
        self
    }

    /// Sets the tolerance of `|∫ pdf − 1|` over the domain.
    #[must_use]
    pub fn integral_tolerance(mut self, tol: f64) -> Self {
        self.integral_tolerance = tol.abs();
        self
    }

    /// Sets the number of worker threads (results do not depend on it).
    #[must_use]
    pub fn threads(mut self, n: usize) -> Self {
        self.threads = n.max(1);
        self
    }

    /// Names the test (the image files are `<name>-observed.png` etc.).
    #[must_use]
    pub fn name(mut self, name: &str) -> Self {
        self.name = name.into();
        self
    }

    /// Sets the directory for failure images; `None` writes none.
    #[must_use]
    pub fn output_dir(mut self, dir: Option<PathBuf>) -> Self {
        self.output_dir = dir;
        self
    }

    /// The domain.
    pub fn domain(&self) -> &D {
        &self.domain
    }

    /// Tests a [`Warp`] against its own pdf.
    pub fn run_warp<W>(&self, warp: &W) -> Chi2Outcome
    where
        W: Warp<Point = D::Point> + Sync,
    {
        self.run(|u| warp.sample(u), |p| warp.pdf(p))
    }

    /// Tests a sampling closure against a pdf closure (in the domain's measure).
    pub fn run(
        &self,
        sample: impl Fn(Vec2) -> D::Point + Sync,
        pdf: impl Fn(D::Point) -> f32 + Sync,
    ) -> Chi2Outcome {
        let masses = self.masses(&pdf);
        self.execute(&|u| Draw::At(sample(u)), masses, Some(&pdf), false)
    }

    /// Tests a BSDF-like sampler returning `Some((point, weight))`, or `None` (or weight 0)
    /// when it rejects the sample, against `pdf`, the density of returned points per
    /// attempt. The pdf may then integrate to less than 1; the rejected samples form one
    /// more cell with expected mass `1 − ∫ pdf`. A NaN, infinite or negative weight fails.
    /// Check the weights themselves with [`super::check_weights`].
    pub fn run_weighted(
        &self,
        sample: impl Fn(Vec2) -> Option<(D::Point, f32)> + Sync,
        pdf: impl Fn(D::Point) -> f32 + Sync,
    ) -> Chi2Outcome {
        let masses = self.masses(&pdf);
        let draw = |u| match sample(u) {
            Some((_, w)) if !(w.is_finite() && w >= 0.0) => Draw::BadWeight,
            Some((p, w)) if w > 0.0 => Draw::At(p),
            _ => Draw::Rejected,
        };
        self.execute(&draw, masses, Some(&pdf), true)
    }

    /// Tests a sampler against exact cell masses (a tabulated density): `mass(cell)` is the
    /// probability of each cell of the domain.
    pub fn run_with_masses(
        &self,
        sample: impl Fn(Vec2) -> D::Point + Sync,
        mass: impl Fn(usize) -> f64 + Sync,
    ) -> Chi2Outcome {
        let masses = map_indexed(self.domain.cell_count(), self.threads, &mass);
        self.execute(&|u| Draw::At(sample(u)), masses, None, false)
    }

    /// Like [`ChiSquareTest::run_with_masses`] with the masses as `(cell, mass)` pairs;
    /// cells not listed have mass 0 (pairs for the same cell add up).
    pub fn run_with_sparse_masses(
        &self,
        sample: impl Fn(Vec2) -> D::Point + Sync,
        masses: &[(usize, f64)],
    ) -> Chi2Outcome {
        let mut m = vec![0.0; self.domain.cell_count()];
        for &(c, v) in masses {
            if let Some(slot) = m.get_mut(c) {
                *slot += v;
            }
        }
        self.execute(&|u| Draw::At(sample(u)), m, None, false)
    }

    /// The probability mass of every cell under `pdf` (what [`ChiSquareTest::run`]
    /// integrates), to reuse with [`ChiSquareTest::run_with_masses`] over many seeds.
    pub fn expected_masses(&self, pdf: impl Fn(D::Point) -> f32 + Sync) -> Vec<f64> {
        self.masses(&pdf)
    }

    fn masses(&self, pdf: &(impl Fn(D::Point) -> f32 + Sync)) -> Vec<f64> {
        let pdf64 = |p: D::Point| f64::from(pdf(p));
        map_indexed(self.domain.cell_count(), self.threads, &|c| {
            self.domain.cell_mass(c, &pdf64)
        })
    }

    fn count(&self, draw: &(dyn Fn(Vec2) -> Draw<D::Point> + Sync)) -> Counts {
        let cells = self.domain.cell_count();
        let init = || Counts {
            cells: vec![0; cells],
            rejected: 0,
            outside: 0,
            bad_weights: 0,
        };
        let n = self.samples;
        let work = |c: usize, acc: &mut Counts| {
            let mut rng = chunk_rng(self.seed, c);
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
        let parts = for_chunks(n.div_ceil(CHUNK), self.threads, &init, &work);
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

    fn execute(
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
        let n = self.samples as f64;
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
        let threshold = sidak(self.alpha, self.test_count);
        let failures = self.failures(
            &counts,
            &pooled.zero_hits,
            p,
            threshold,
            integral,
            may_reject,
        );
        let mut outcome = Chi2Outcome {
            name: self.name.clone(),
            samples: self.samples,
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
        if let (false, Some(dir)) = (outcome.passed(), &self.output_dir) {
            outcome.images =
                report::write_images(dir, &self.name, self.domain.grid(), &observed, &expected);
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
        let n = self.samples as f64;
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
        let refined = map_indexed(cells.len(), self.threads, &|k| {
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
        if excess.is_nan() || excess > self.integral_tolerance {
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
