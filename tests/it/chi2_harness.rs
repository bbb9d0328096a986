//! The harness's own tests, on closures only: correct samplers pass and broken ones are
//! rejected (power). Edge cases and other inputs are in `chi2_harness_edges.rs`.

use crate::common;

use common::samplers::*;
use common::{chi2, hemisphere};
use mcrt::glam::{Vec2, Vec3};
use mcrt::stats::{check_integral, Chi2Failure, Directions, Interval, Rectangle};
use std::f32::consts::TAU;

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
        !c.passed() && c.worst_error.is_finite() && c.worst_error > 5e-3,
        "{}",
        c.report()
    );
    check_integral(&square(), disk_pdf, common::INTEGRAL_TOL).assert_passed();
}
