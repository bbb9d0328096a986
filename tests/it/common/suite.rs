//! Settings shared by the statistical suite of both crates (`tests/it/chi2_*.rs` here and
//! `mcrt-render/tests/it/chi2_*.rs`): one file, one Šidák budget. The renderer's
//! `tests/it/common/mod.rs` includes this file by path, so [`N_TESTS`] counts the chi-square
//! runs of the whole workspace.
//!
//! Every chi-square test of the suite uses the same family-wise level [`ALPHA`] over a fixed,
//! stated number of tests [`N_TESTS`] (Šidák correction), so a filtered run (`cargo test --release
//! -p mcrt --test it chi2_warps::ggx`) applies exactly the same per-test threshold as the full suite.
//! `N_TESTS` is an upper bound on the number of statistical tests in the suite: the
//! chi-square runs of both crates and the renderer's image comparisons (block z-tests and
//! replicate t-tests against a reference, each one test at [`per_test_alpha`]); counting
//! more tests than exist only makes each one slightly stricter.

use mcrt::stats::{ChiSquareTest, Directions, Domain, JacobianCheck};

/// Family-wise significance level of the whole suite.
pub const ALPHA: f64 = 0.01;

/// The number of chi-square runs the suite's level is corrected for.
pub const N_TESTS: u32 = 400;

/// The per-test significance level of the suite: Šidák over [`N_TESTS`] at [`ALPHA`]
/// (2.513·10⁻⁵). Every statistical test of the workspace that is counted in the budget runs
/// at this level: each chi-square run, and each image comparison of the renderer
/// (`mcrt-render/tests`: a render's block means against a reference, Šidák-corrected over
/// its own blocks and channels to this level).
pub fn per_test_alpha() -> f64 {
    1.0 - (1.0 - ALPHA).powf(1.0 / f64::from(N_TESTS))
}

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

/// A uniform value in [0, 1) from the bits of `u` (SplitMix64 finaliser): a third sample
/// value for samplers that take three (a BSDF's component choice) when the harness hands
/// out two; a fixed, deterministic function, uniform and independent of `u` for the
/// purpose of a test.
pub fn third_value(u: mcrt::glam::Vec2) -> f32 {
    let mut z = (u64::from(u.x.to_bits()) << 32 | u64::from(u.y.to_bits()))
        .wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^= z >> 31;
    (z >> 40) as f32 / (1u64 << 24) as f32
}

/// A BSDF's sampling at `wo` against its own density and value: the chi-square test of the
/// directions `sample` draws (channel-maximum weight deciding rejection) over `dirs`, then
/// the weight check `weight = f·|cos|/pdf` on every channel. `sample` is the BSDF's
/// `sample` with the caller's choice of component value (and, for materials with Dirac
/// parts, those parts left out).
pub fn check_bsdf_sampling<B: mcrt::integrator::Bsdf + Sync>(
    name: &str,
    b: &B,
    wo: mcrt::glam::Vec3,
    dirs: Directions,
    sample: impl Fn(mcrt::glam::Vec2) -> Option<mcrt::integrator::BsdfSample> + Sync,
) {
    let out = chi2(dirs, name).run_weighted(
        |u| sample(u).map(|s| (s.wi, s.weight.max_element())),
        |wi| b.pdf(wo, wi),
    );
    assert!(out.passed(), "{}", out.report());
    for c in 0..3 {
        let w = mcrt::stats::check_weights(
            |u| sample(u).map(|s| (s.wi, s.weight[c])),
            |wi| b.pdf(wo, wi),
            |wi| b.eval(wo, wi)[c],
            64,
            1e-3,
        );
        assert!(w.passed(), "{name} channel {c}: {}", w.report());
    }
}
