//! The harness's own tests, on closures only: correct samplers pass, broken ones are
//! rejected (power), and the outcome is deterministic and well defined in edge cases.

mod common;

use common::{chi2, hemisphere};
use mcrt::glam::{Vec2, Vec3};
use mcrt::stats::{
    check_integral, check_inverse, check_jacobian, check_weights, Chi2Failure, ChiSquareTest,
    Directions, Discrete, Interval, JacobianCheck, Rectangle,
};
use std::f32::consts::{FRAC_1_PI, PI, TAU};

fn square() -> Rectangle {
    Rectangle::new(Vec2::splat(-1.0), Vec2::splat(1.0), 48, 48)
}

fn polar(r: f32, phi: f32) -> Vec2 {
    Vec2::new(r * phi.cos(), r * phi.sin())
}

fn disk_sqrt(u: Vec2) -> Vec2 {
    polar(u.x.sqrt(), TAU * u.y)
}

fn disk_pdf(p: Vec2) -> f32 {
    if p.length_squared() <= 1.0 {
        FRAC_1_PI
    } else {
        0.0
    }
}

fn cosine_hemisphere(u: Vec2) -> Vec3 {
    let d = disk_sqrt(u);
    Vec3::new(d.x, d.y, (1.0 - u.x).max(0.0).sqrt())
}

fn cosine_pdf(w: Vec3) -> f32 {
    w.z.max(0.0) * FRAC_1_PI
}

fn uniform_hemisphere_pdf(w: Vec3) -> f32 {
    if w.z >= 0.0 {
        0.5 * FRAC_1_PI
    } else {
        0.0
    }
}

fn triangle_pdf(b: Vec2) -> f32 {
    if b.x >= 0.0 && b.y >= 0.0 && b.x + b.y <= 1.0 {
        2.0
    } else {
        0.0
    }
}

/// A uniform cone of half-angle `theta_max` about `axis`, computed so that narrow cones are
/// exact: `1 − cos θ` is sampled directly and sin θ derived from it.
struct Cone {
    axis: Vec3,
    t: Vec3,
    b: Vec3,
    one_minus_cos_max: f32,
}

impl Cone {
    fn new(axis: Vec3, theta_max: f32) -> Self {
        let axis = axis.normalize();
        let (t, b) = axis.any_orthonormal_pair();
        let s = (0.5 * theta_max).sin();
        Self {
            axis,
            t,
            b,
            one_minus_cos_max: 2.0 * s * s,
        }
    }
    fn sample(&self, u: Vec2) -> Vec3 {
        let omc = u.x * self.one_minus_cos_max;
        let sin = (omc * (2.0 - omc)).sqrt();
        let phi = TAU * u.y;
        self.t * (sin * phi.cos()) + self.b * (sin * phi.sin()) + self.axis * (1.0 - omc)
    }
    fn pdf(&self, w: Vec3) -> f32 {
        // 1 − cos θ from the tangential components, stable near the axis.
        let (x, y) = (w.dot(self.t), w.dot(self.b));
        let s2 = x * x + y * y;
        let omc = if w.dot(self.axis) > 0.0 {
            s2 / (1.0 + (1.0 - s2).max(0.0).sqrt())
        } else {
            2.0
        };
        if omc <= self.one_minus_cos_max {
            1.0 / (TAU * self.one_minus_cos_max)
        } else {
            0.0
        }
    }
}

// ---- correct samplers pass ----

#[test]
fn uniform_disk_by_sqrt_passes() {
    chi2(square(), "harness-disk")
        .run(disk_sqrt, disk_pdf)
        .assert_passed();
}

#[test]
fn cosine_hemisphere_passes() {
    chi2(hemisphere(), "harness-cosine")
        .run(cosine_hemisphere, cosine_pdf)
        .assert_passed();
}

#[test]
fn narrow_cone_off_the_pole_passes() {
    let cone = Cone::new(Vec3::new(0.6, -0.3, 0.74), 1e-3);
    // 31 rings: the cone's edge (θ = 10⁻³, where f32 rounding of the direction puts a few
    // samples on either side) falls inside a ring, not on a ring boundary.
    let domain = Directions::cap(cone.axis, 2e-3)
        .resolution(31, 64)
        .refinement(1.0);
    chi2(domain, "harness-cone-cap")
        .run(|u| cone.sample(u), |w| cone.pdf(w))
        .assert_passed();
    // The same cone about +z on the whole hemisphere: the refined rings still resolve it.
    let cone = Cone::new(Vec3::Z, 1e-3);
    let o = chi2(
        hemisphere().resolution(128, 64).refinement(3.0),
        "harness-cone-hemisphere",
    )
    .run(|u| cone.sample(u), |w| cone.pdf(w));
    o.assert_passed();
    assert!(o.dof >= 20, "the cone covers too few cells: {}", o.report());
}

#[test]
fn linear_density_on_an_interval_passes() {
    // p(x) = 2x on [0, 1], sampled by x = √u.
    chi2(Interval::new(0.0, 1.0, 200), "harness-linear")
        .run(
            |u| u.x.sqrt(),
            |x| {
                if (0.0..=1.0).contains(&x) {
                    2.0 * x
                } else {
                    0.0
                }
            },
        )
        .assert_passed();
}

// ---- power: broken samplers are rejected ----

#[test]
fn obvious_but_wrong_disk_is_rejected() {
    let o = chi2(square(), "power-disk-r-u1")
        .output_dir(None)
        .run(|u| polar(u.x, TAU * u.y), disk_pdf);
    assert!(o.rejected_by_statistic(), "{}", o.report());
    assert!(o.p_value < 1e-100, "{}", o.report());
}

#[test]
fn cosine_sampler_with_uniform_pdf_is_rejected() {
    let o = chi2(hemisphere(), "power-cosine-vs-uniform")
        .output_dir(None)
        .run(cosine_hemisphere, uniform_hemisphere_pdf);
    assert!(o.rejected_by_statistic(), "{}", o.report());
}

#[test]
fn wrong_triangle_sampler_is_rejected() {
    // b₁ = u₁, b₂ = u₂(1 − u₁) covers the triangle but crowds the b₁ → 1 corner.
    let wrong = |u: Vec2| Vec2::new(u.x, u.y * (1.0 - u.x));
    let o = chi2(Rectangle::unit_square(48), "power-triangle")
        .output_dir(None)
        .run(wrong, triangle_pdf);
    assert!(o.rejected_by_statistic(), "{}", o.report());
    // The seeds' correct map passes.
    let right = |u: Vec2| {
        let s = u.x.sqrt();
        Vec2::new(1.0 - s, u.y * s)
    };
    chi2(Rectangle::unit_square(48), "harness-triangle")
        .run(right, triangle_pdf)
        .assert_passed();
}

#[test]
fn pdf_off_by_one_percent_is_caught_by_the_integral() {
    let scaled = |p: Vec2| 1.01 * disk_pdf(p);
    let o = chi2(square(), "power-scale")
        .output_dir(None)
        .run(disk_sqrt, scaled);
    assert!(!o.passed(), "{}", o.report());
    assert!(
        matches!(o.failures.as_slice(), [.., Chi2Failure::NotNormalized { integral }] if (integral - 1.01).abs() < 1e-4),
        "{}",
        o.report()
    );
    let c = check_integral(&square(), scaled, common::INTEGRAL_TOL);
    assert!(
        !c.passed && c.worst_error.is_finite() && c.worst_error > 5e-3,
        "{}",
        c.report()
    );
    check_integral(&square(), disk_pdf, common::INTEGRAL_TOL).assert_passed();
}

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
    assert!(!c.passed, "{}", c.report());
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
    for needle in [
        "FAILED",
        "statistic",
        "dof",
        "p-value",
        "worst cells",
        "observed-png",
        "expected.png",
    ] {
        let needle = needle.replace("-png", ".png");
        assert!(report.contains(&needle), "missing {needle}: {report}");
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
    assert!(!c.passed && c.worst_error.is_finite(), "{}", c.report());
    let c = check_jacobian(
        |u: Vec2| polar(u.x, TAU * u.y),
        disk_pdf,
        JacobianCheck::default(),
    );
    assert!(!c.passed, "{}", c.report());
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
    assert!(!c.passed && c.worst_error.is_finite(), "{}", c.report());
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
    let _ = PI;
}
