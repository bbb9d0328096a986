//! The result of a chi-square run and its human-readable report.

use super::chi2::CellCount;
use std::fmt::Write as _;
use std::path::PathBuf;

/// Why a chi-square run failed.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum Chi2Failure {
    /// The p-value fell below the (Šidák-corrected) level: the samples do not follow the pdf.
    Rejected,
    /// Samples fell in cells where the pdf integrates to zero.
    ZeroExpectedHit {
        /// The first such cell, described.
        cell: String,
        /// Samples in all such cells.
        count: u64,
    },
    /// Samples were outside the domain, not finite, or (for directions) not unit length.
    OutsideDomain {
        /// How many.
        count: u64,
    },
    /// A weighted sampler returned a NaN, infinite or negative weight.
    BadWeight {
        /// How many.
        count: u64,
    },
    /// The pdf does not integrate to 1 over the domain (to 1 or less for a sampler that may
    /// reject samples).
    NotNormalized {
        /// The integral found.
        integral: f64,
    },
}

/// The outcome of [`super::ChiSquareTest`]: statistic, degrees of freedom, p-value, the
/// verdict, and the worst cells.
#[derive(Clone, Debug)]
pub struct Chi2Outcome {
    /// The test's name (used for the image files).
    pub name: String,
    /// Samples drawn.
    pub samples: usize,
    /// Pearson's statistic over the pooled cells.
    pub statistic: f64,
    /// Degrees of freedom (pooled terms − 1). 0 means all expected mass sits in one
    /// (pooled) cell: nothing is left to compare, the p-value is 1, and the run passes when
    /// no other check fails.
    pub dof: usize,
    /// The upper-tail probability of the statistic.
    pub p_value: f64,
    /// The per-test level the p-value is compared with (Šidák-corrected).
    pub threshold: f64,
    /// The pdf's integral over the domain.
    pub integral: f64,
    /// Cells pooled because their expected count was below 5.
    pub pooled_cells: usize,
    /// Samples rejected by a weighted sampler (`None` or weight 0).
    pub rejected: u64,
    /// The terms with the largest contributions, largest first (cell described in words).
    pub worst: Vec<(String, CellCount)>,
    /// Everything that failed; empty when the run passed.
    pub failures: Vec<Chi2Failure>,
    /// Where the observed, expected and difference images were written (on failure).
    pub images: Vec<PathBuf>,
}

impl Chi2Outcome {
    /// Whether every check passed.
    pub fn passed(&self) -> bool {
        self.failures.is_empty()
    }

    /// Whether the chi-square statistic itself was rejected (ignoring the other checks).
    pub fn rejected_by_statistic(&self) -> bool {
        self.failures.contains(&Chi2Failure::Rejected)
    }

    /// A report a person can read: verdict, statistic, dof, p-value, threshold, failures,
    /// the worst cells with observed and expected counts, and the image paths.
    pub fn report(&self) -> String {
        let mut s = String::new();
        let verdict = if self.passed() { "PASSED" } else { "FAILED" };
        let _ = writeln!(s, "chi-square test `{}`: {verdict}", self.name);
        let _ = writeln!(
            s,
            "  samples {}, statistic {:.2}, dof {}, p-value {:.3e}, threshold {:.3e}",
            self.samples, self.statistic, self.dof, self.p_value, self.threshold
        );
        let _ = writeln!(
            s,
            "  pdf integral {:.6}, pooled cells {}, rejected samples {}",
            self.integral, self.pooled_cells, self.rejected
        );
        for f in &self.failures {
            let _ = writeln!(s, "  failure: {}", describe(f));
        }
        let _ = writeln!(s, "  worst cells (observed / expected, contribution):");
        for (what, c) in &self.worst {
            let _ = writeln!(
                s,
                "    {what}: {} / {:.1}  ({:.1})",
                c.observed,
                c.expected,
                c.contribution()
            );
        }
        for p in &self.images {
            let _ = writeln!(s, "  image: {}", p.display());
        }
        s
    }

    /// Panics with [`Chi2Outcome::report`] unless the run passed; returns `self` otherwise.
    ///
    /// # Panics
    /// When any check failed.
    #[track_caller]
    pub fn assert_passed(&self) -> &Self {
        assert!(self.passed(), "{}", self.report());
        self
    }
}

impl std::fmt::Display for Chi2Outcome {
    /// Writes [`Chi2Outcome::report`].
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.report())
    }
}

fn describe(f: &Chi2Failure) -> String {
    match f {
        Chi2Failure::Rejected => {
            "p-value below the threshold: samples do not follow the pdf".into()
        }
        Chi2Failure::ZeroExpectedHit { cell, count } => format!(
            "{count} samples where the pdf integrates to 0 (first: {cell}); if the pdf has a \
             spike narrower than a cell, zoom the domain or give exact masses"
        ),
        Chi2Failure::OutsideDomain { count } => {
            format!("{count} samples outside the domain, not finite, or not unit length")
        }
        Chi2Failure::BadWeight { count } => {
            format!("{count} samples with a NaN/infinite/negative weight")
        }
        Chi2Failure::NotNormalized { integral } => {
            format!("the pdf integrates to {integral:.6} over the domain, not 1")
        }
    }
}
