//! The harness's own tests, on closures only: outcomes in edge cases, weighted samplers,
//! exact masses, the failure report, and the companion checks.

use crate::common;

use common::samplers::*;
use common::{chi2, hemisphere};
use mcrt::glam::{Vec2, Vec3};
use mcrt::stats::{
    check_inverse, check_jacobian, check_weights, Chi2Failure, ChiSquareTest, Directions, Discrete,
    Interval, JacobianCheck,
};
use std::f32::consts::{FRAC_1_PI, TAU};

// ---- outcomes in edge cases ----

#[test]
fn sample_where_the_pdf_is_zero_fails_outright() {
    // Correct on the disk, but one sample in 10⁴ lands in a corner where the pdf is 0.
    let leaky = |u: Vec2| {
        if u.x < 1e-4 {
            Vec2::new(0.95, 0.95)
        } else {
            disk_sqrt(u)
        }
    };
    let o = chi2(square(), "edge-zero-cell")
        .output_dir(None)
        .run(leaky, disk_pdf);
    assert!(
        o.failures
            .iter()
            .any(|f| matches!(f, Chi2Failure::ZeroExpectedHit { count, .. } if *count > 50)),
        "{}",
        o.report()
    );
}

#[test]
fn samples_outside_the_domain_or_nan_fail() {
    let bad = |u: Vec2| if u.x < 1e-3 { Vec2::NAN } else { disk_sqrt(u) };
    let o = chi2(square(), "edge-nan")
        .output_dir(None)
        .run(bad, disk_pdf);
    assert!(
        o.failures
            .iter()
            .any(|f| matches!(f, Chi2Failure::OutsideDomain { .. })),
        "{}",
        o.report()
    );
}

#[test]
fn no_degree_of_freedom_passes_with_p_one_unless_a_zero_cell_is_hit() {
    let pmf = |i: usize| if i == 1 { 1.0 } else { 0.0 };
    let o = chi2(Discrete::new(3), "edge-dof0").run(|_| 1, |i| pmf(i) as f32);
    o.assert_passed();
    assert_eq!((o.dof, o.p_value), (0, 1.0));
    let o = chi2(Discrete::new(3), "edge-dof0-hit")
        .output_dir(None)
        .run(|u| if u.x < 0.01 { 2 } else { 1 }, |i| pmf(i) as f32);
    assert!(!o.passed() && o.dof == 0, "{}", o.report());
}

#[test]
fn results_do_not_depend_on_the_thread_count() {
    let run = |threads| {
        let o = chi2(hemisphere(), "determinism")
            .samples(300_000)
            .threads(threads)
            .run(cosine_hemisphere, cosine_pdf);
        (o.statistic, o.dof, o.p_value)
    };
    let one = run(1);
    assert!(one.0.is_finite());
    assert_eq!(one, run(2));
    assert_eq!(one, run(5));
    let other_seed = chi2(hemisphere(), "determinism")
        .samples(300_000)
        .seed(99)
        .run(cosine_hemisphere, cosine_pdf);
    assert_ne!(one.0, other_seed.statistic);
}

// ---- other inputs ----

#[test]
fn weighted_sampler_with_rejection() {
    // Uniform sphere directions; the lower half is rejected. The pdf of returned directions
    // per attempt is 1/(4π) on the upper hemisphere, integrating to 1/2.
    let sphere = |u: Vec2| {
        let z = 1.0 - 2.0 * u.x;
        let r = (1.0 - z * z).max(0.0).sqrt();
        Vec3::new(r * (TAU * u.y).cos(), r * (TAU * u.y).sin(), z)
    };
    let sampler = |u: Vec2| {
        let w = sphere(u);
        (w.z > 0.0).then_some((w, 2.0 * w.z))
    };
    let pdf = |w: Vec3| if w.z > 0.0 { 0.25 * FRAC_1_PI } else { 0.0 };
    let o = chi2(hemisphere(), "weighted").run_weighted(sampler, pdf);
    o.assert_passed();
    assert!(
        (o.integral - 0.5).abs() < 1e-4 && o.rejected > 400_000,
        "{}",
        o.report()
    );
    // Claiming a 60 % acceptance rate is caught by the rejected-samples cell.
    let o = chi2(hemisphere(), "weighted-wrong")
        .output_dir(None)
        .run_weighted(sampler, |w| 1.2 * pdf(w));
    assert!(o.rejected_by_statistic(), "{}", o.report());
    // Weights: f·cos = cos θ / (2π) here, so weight = f·cos / pdf = 2 cos θ.
    let value = |w: Vec3| w.z.max(0.0) * 0.5 * FRAC_1_PI;
    check_weights(sampler, pdf, value, 64, 1e-5).assert_passed();
    let c = check_weights(sampler, pdf, |w| 1.1 * value(w), 64, 1e-5);
    assert!(!c.passed(), "{}", c.report());
    let nan = chi2(hemisphere(), "weighted-nan")
        .output_dir(None)
        .run_weighted(|u| sampler(u).map(|(w, _)| (w, f32::NAN)), pdf);
    assert!(nan
        .failures
        .iter()
        .any(|f| matches!(f, Chi2Failure::BadWeight { .. })));
}

#[test]
fn exact_masses_for_tabulated_densities() {
    // A piecewise-constant density with a zero bin, sampled by inverting its CDF.
    let values = [1.0f64, 0.0, 3.0, 0.5, 2.5];
    let total: f64 = values.iter().sum();
    let cdf: Vec<f64> = values
        .iter()
        .scan(0.0, |s, v| {
            *s += v / total;
            Some(*s)
        })
        .collect();
    let sample = |u: Vec2| {
        let x = f64::from(u.x);
        let i = cdf.iter().position(|&c| x < c).unwrap_or(values.len() - 1);
        let lo = if i == 0 { 0.0 } else { cdf[i - 1] };
        ((i as f64 + (x - lo) / (cdf[i] - lo)) / values.len() as f64) as f32
    };
    let bins = 4 * values.len(); // four cells per table bin
    let mass = |c: usize| values[c / 4] / total / 4.0;
    chi2(Interval::new(0.0, 1.0, bins), "masses")
        .run_with_masses(sample, mass)
        .assert_passed();
    // A table of 10⁶ categories with one nonzero entry, as sparse masses: no degree of
    // freedom, and every sample must be that category.
    let o = chi2(Discrete::new(1_000_000), "masses-sparse")
        .run_with_sparse_masses(|_| 123_456, &[(123_456, 1.0)]);
    o.assert_passed();
    assert_eq!(o.dof, 0);
}

#[test]
fn failure_report_and_images() {
    let dir = std::env::temp_dir().join("mcrt-chi2-harness-test");
    let o = chi2(square(), "report-demo")
        .samples(100_000)
        .output_dir(Some(dir.clone()))
        .run(|u| polar(u.x, TAU * u.y), disk_pdf);
    let report = o.report();
    let ext = if cfg!(feature = "report-png") {
        "png"
    } else {
        "ppm"
    };
    let (observed, expected) = (format!("observed.{ext}"), format!("expected.{ext}"));
    for needle in [
        "FAILED",
        "statistic",
        "dof",
        "p-value",
        "worst cells",
        &observed,
        &expected,
    ] {
        assert!(report.contains(needle), "missing {needle}: {report}");
    }
    assert_eq!(o.images.len(), 3);
    for p in &o.images {
        assert!(
            p.starts_with(&dir) && std::fs::metadata(p).map(|m| m.len() > 100).unwrap_or(false)
        );
    }
    assert!(o.worst[0].1.contribution() > 100.0, "{report}");
}

#[test]
#[should_panic(expected = "p-value below the threshold")]
fn assert_passed_panics_with_the_report() {
    chi2(square(), "report-panic")
        .samples(100_000)
        .output_dir(None)
        .run(|u| polar(u.x, TAU * u.y), disk_pdf)
        .assert_passed();
}

// ---- companion checks on closures ----

#[test]
fn jacobian_check_accepts_right_and_rejects_wrong_pdfs() {
    check_jacobian(disk_sqrt, disk_pdf, JacobianCheck::default()).assert_passed();
    check_jacobian(cosine_hemisphere, cosine_pdf, JacobianCheck::default()).assert_passed();
    let c = check_jacobian(disk_sqrt, |p| 1.05 * disk_pdf(p), JacobianCheck::default());
    assert!(!c.passed() && c.worst_error.is_finite(), "{}", c.report());
    let c = check_jacobian(
        |u: Vec2| polar(u.x, TAU * u.y),
        disk_pdf,
        JacobianCheck::default(),
    );
    assert!(!c.passed(), "{}", c.report());
    // 1D: x = √u has density 2x.
    check_jacobian(
        |u: Vec2| u.x.sqrt(),
        |x: f32| 2.0 * x,
        JacobianCheck::default(),
    )
    .assert_passed();
}

#[test]
fn inverse_check() {
    let invert = |p: Vec2| {
        let phi = p.y.atan2(p.x);
        Vec2::new(
            p.length_squared(),
            if phi < 0.0 {
                phi / TAU + 1.0
            } else {
                phi / TAU
            },
        )
    };
    check_inverse(disk_sqrt, invert, 2, 64, 1e-5).assert_passed();
    let c = check_inverse(disk_sqrt, |p| invert(p) * 1.001, 2, 64, 1e-5);
    assert!(!c.passed() && c.worst_error.is_finite(), "{}", c.report());
}

#[test]
fn default_settings_are_usable_directly() {
    // The builder's defaults (10⁶ samples, one test at α = 0.01) on the sphere.
    let sphere = |u: Vec2| {
        let z = 1.0 - 2.0 * u.x;
        let r = (1.0 - z * z).max(0.0).sqrt();
        Vec3::new(r * (TAU * u.y).cos(), r * (TAU * u.y).sin(), z)
    };
    ChiSquareTest::new(Directions::sphere())
        .name("defaults-sphere")
        .run(sphere, |_| 0.25 * FRAC_1_PI)
        .assert_passed();
}

#[test]
fn samples_below_the_hemisphere_fail_outright() {
    // Cosine-weighted, but one sample in 10⁴ mirrored below the horizon: it lands in the
    // complement cell, where the pdf integrates to 0.
    let leaky = |u: Vec2| {
        let w = cosine_hemisphere(u);
        if u.y < 1e-4 {
            Vec3::new(w.x, w.y, -w.z)
        } else {
            w
        }
    };
    let o = chi2(hemisphere(), "edge-below-horizon")
        .output_dir(None)
        .run(leaky, cosine_pdf);
    assert!(
        o.failures.iter().any(|f| matches!(f, Chi2Failure::ZeroExpectedHit { cell, .. } if cell.contains("complement"))),
        "{}",
        o.report()
    );
}
