//! [`ChiSquareTest`]: the builder that draws samples, integrates the pdf per cell and
//! compares the two.

use super::domain::Domain;
use super::evaluate::{Draw, Run, Settings};
use super::outcome::Chi2Outcome;
use super::parallel::{default_threads, map_indexed};
use crate::sampling::warp::Warp;
use glam::Vec2;
use std::path::PathBuf;

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
/// finer forced subdivision (see [`RECHECK_SIGMAS`](super::RECHECK_SIGMAS)). On failure the observed, expected
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
    settings: Settings,
}

impl<D: Domain> ChiSquareTest<D> {
    /// A test over `domain`: 10⁶ samples, seed 0, α = 0.01 for a single test, integral
    /// tolerance 10⁻³, all available threads, images into `target/chi2-failures` (or the
    /// directory in the `MCRT_CHI2_OUTPUT` environment variable).
    pub fn new(domain: D) -> Self {
        let output_dir = std::env::var_os("MCRT_CHI2_OUTPUT")
            .map_or_else(|| PathBuf::from("target/chi2-failures"), PathBuf::from);
        let settings = Settings {
            samples: 1_000_000,
            seed: 0,
            alpha: 0.01,
            test_count: 1,
            integral_tolerance: 1e-3,
            threads: default_threads(),
            name: "chi2".into(),
            output_dir: Some(output_dir),
        };
        Self { domain, settings }
    }

    /// Sets the number of samples drawn.
    #[must_use]
    pub fn samples(mut self, n: usize) -> Self {
        self.settings.samples = n.max(1);
        self
    }

    /// Sets the seed (the same seed gives the same counts on any thread count).
    #[must_use]
    pub fn seed(mut self, seed: u64) -> Self {
        self.settings.seed = seed;
        self
    }

    /// Sets the family-wise level `alpha` for a suite of `test_count` tests: each run is
    /// rejected when its p-value is below `1 − (1 − alpha)^(1/test_count)` ([`sidak`](super::sidak)).
    /// Keep `test_count` fixed for a suite, so a filtered run uses the same threshold.
    /// An `alpha` outside `(0, 1)` falls back to 0.01.
    #[must_use]
    pub fn significance(mut self, alpha: f64, test_count: u32) -> Self {
        self.settings.alpha = if alpha > 0.0 && alpha < 1.0 {
            alpha
        } else {
            0.01
        };
        self.settings.test_count = test_count.max(1);
        self
    }

    /// Sets the tolerance of `|∫ pdf − 1|` over the domain.
    #[must_use]
    pub fn integral_tolerance(mut self, tol: f64) -> Self {
        self.settings.integral_tolerance = tol.abs();
        self
    }

    /// Sets the number of worker threads (results do not depend on it).
    #[must_use]
    pub fn threads(mut self, n: usize) -> Self {
        self.settings.threads = n.max(1);
        self
    }

    /// Names the test (the image files are `<name>-observed.ppm` etc., `.png` with the
    /// feature `report-png`).
    #[must_use]
    pub fn name(mut self, name: &str) -> Self {
        self.settings.name = name.into();
        self
    }

    /// Sets the directory for failure images; `None` writes none.
    #[must_use]
    pub fn output_dir(mut self, dir: Option<PathBuf>) -> Self {
        self.settings.output_dir = dir;
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
        self.run_of()
            .execute(&|u| Draw::At(sample(u)), masses, Some(&pdf), false)
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
        self.run_of().execute(&draw, masses, Some(&pdf), true)
    }

    /// Tests a sampler against exact cell masses (a tabulated density): `mass(cell)` is the
    /// probability of each cell of the domain.
    pub fn run_with_masses(
        &self,
        sample: impl Fn(Vec2) -> D::Point + Sync,
        mass: impl Fn(usize) -> f64 + Sync,
    ) -> Chi2Outcome {
        let masses = map_indexed(self.domain.cell_count(), self.settings.threads, &mass);
        self.run_of()
            .execute(&|u| Draw::At(sample(u)), masses, None, false)
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
        self.run_of()
            .execute(&|u| Draw::At(sample(u)), m, None, false)
    }

    /// The probability mass of every cell under `pdf` (what [`ChiSquareTest::run`]
    /// integrates), to reuse with [`ChiSquareTest::run_with_masses`] over many seeds.
    pub fn expected_masses(&self, pdf: impl Fn(D::Point) -> f32 + Sync) -> Vec<f64> {
        self.masses(&pdf)
    }

    fn run_of(&self) -> Run<'_, D> {
        Run {
            domain: &self.domain,
            settings: &self.settings,
        }
    }

    fn masses(&self, pdf: &(impl Fn(D::Point) -> f32 + Sync)) -> Vec<f64> {
        let pdf64 = |p: D::Point| f64::from(pdf(p));
        map_indexed(self.domain.cell_count(), self.settings.threads, &|c| {
            self.domain.cell_mass(c, &pdf64)
        })
    }
}
