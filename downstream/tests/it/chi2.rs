//! mcrt's chi-square harness on samplers of this crate's own: the warp `Tent2D` (a custom
//! `mcrt::Warp`) and the sky's directions (`PiecewiseConstant2D` through `LatLong`, density
//! per steradian), at the workspace suite's settings.
//!
//! **The Šidák budget.** The suite's level is family-wise over `N_TESTS` chi-square runs
//! of the whole workspace (`tests/it/common/suite.rs`, included below, so this file uses the
//! same `ALPHA`, `N_TESTS`, seed and sample count as every other chi-square test). This file
//! makes 2 runs (`tent-2d` and `sky-latlong`) and counts them against that budget: with the
//! library's and the renderer's runs (about 242, `docs/testing.md`) the workspace stays
//! well below `N_TESTS = 400`. A change that adds runs here must keep the total within
//! `N_TESTS`, or raise it.

#![forbid(unsafe_code)]

#[path = "../../../tests/it/common/suite.rs"]
#[allow(dead_code)] // the suite's BSDF helpers
mod suite;

use mcrt::glam::Vec2;
use mcrt::stats::{check_warp_inverse, check_warp_jacobian, Rectangle};
use mcrt_downstream::{Sky, Tent2D};
use std::path::PathBuf;

/// Failure images go to Cargo's temporary directory for tests, not into the source tree.
fn failures() -> Option<PathBuf> {
    Some(PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("chi2-failures"))
}

/// Chi-square run 1 of 2: `Tent2D` over `[−1, 1]²` in 48 × 48 cells (the suite's cells for
/// planar warps), with its Jacobian and inverse.
#[test]
fn tent_2d_passes_the_chi_square_test() {
    let domain = Rectangle::new(Vec2::splat(-1.0), Vec2::splat(1.0), 48, 48);
    let outcome = suite::chi2(domain, "tent-2d")
        .output_dir(failures())
        .run_warp(&Tent2D);
    assert!(
        outcome.p_value.is_finite() && outcome.passed(),
        "{}",
        outcome.report()
    );
    let jacobian = check_warp_jacobian(&Tent2D, suite::jacobian());
    assert!(jacobian.passed(), "{}", jacobian.report());
    let inverse = check_warp_inverse(&Tent2D, 64, 1e-5);
    assert!(inverse.passed(), "{}", inverse.report());
}

/// Chi-square run 2 of 2: directions from the sky's table over the sphere at the suite's
/// resolution, against the density per steradian a renderer's MIS would use.
#[test]
fn sky_directions_pass_the_chi_square_test() {
    let sky = Sky::procedural(64, 32, 0.3).expect("a valid sky");
    let outcome = suite::chi2(suite::sphere(), "sky-latlong")
        .output_dir(failures())
        .run(|u| sky.sample(u).0, |w| sky.pdf(w));
    assert!(
        outcome.p_value.is_finite() && outcome.passed(),
        "{}",
        outcome.report()
    );
}
