//! Settings shared by the statistical suite (`tests/chi2_*.rs`).
//!
//! Every chi-square test of the suite uses the same family-wise level [`ALPHA`] over a fixed,
//! stated number of tests [`N_TESTS`] (Šidák correction), so a filtered run (`cargo test --release
//! --test chi2_warps ggx`) applies exactly the same per-test threshold as the full suite.
//! `N_TESTS` is an upper bound on the number of chi-square runs in the suite; counting more
//! runs than exist only makes each run slightly stricter.
#![allow(dead_code)] // each test file uses a different subset

pub mod replicates;
pub mod samplers;

use mcrt::stats::{ChiSquareTest, Directions, Domain, JacobianCheck};

/// Family-wise significance level of the whole suite.
pub const ALPHA: f64 = 0.01;

/// The number of chi-square runs the suite's level is corrected for.
pub const N_TESTS: u32 = 400;

/// The suite's seed.
pub const SEED: u64 = 0x6d63_7274; // "mcrt"

/// Samples per chi-square run.
pub const SAMPLES: usize = 1_000_000;

/// Tolerance of `|∫ pdf − 1|`.
pub const INTEGRAL_TOL: f64 = 1e-3;

/// A chi-square test at the suite's settings.
pub fn chi2<D: Domain>(domain: D, name: &str) -> ChiSquareTest<D> {
    ChiSquareTest::new(domain)
        .samples(SAMPLES)
        .seed(SEED)
        .significance(ALPHA, N_TESTS)
        .integral_tolerance(INTEGRAL_TOL)
        .name(name)
}

/// The hemisphere at the suite's resolution (64 rings refined near the pole × 128 sectors).
pub fn hemisphere() -> Directions {
    Directions::hemisphere().resolution(64, 128)
}

/// The sphere at the suite's resolution.
pub fn sphere() -> Directions {
    Directions::sphere().resolution(64, 128)
}

/// Jacobian-check settings of the suite.
pub fn jacobian() -> JacobianCheck {
    JacobianCheck::default()
}
