//! Accuracy of the basic warps at f32, measured on fixed grids and asserted: the interior
//! inverse round trip, the Jacobian identity, and the extremes (a 10⁻⁴ rad cone, exponent
//! 10⁶) against f64 references. `cargo test --release -p mcrt --test it warp_accuracy_basic::
//! -- --nocapture` prints the tables quoted in `docs/derivations.md`.

use crate::warp_basic_support;

use mcrt::glam::{Vec2, Vec3};
use mcrt::sampling::warp::{
    CosineHemisphere, InvertibleWarp, PowerCosineHemisphere, ThetaOverSinHemisphere, UniformCone,
    UniformDisk, UniformDiskConcentric, UniformHemisphere, UniformSphere, UniformTriangle, Warp,
};
use std::f64::consts::PI;
use warp_basic_support::*;

/// Largest interior round-trip error of one warp over a 257 × 257 grid of u in
/// [10⁻³, 1 − 10⁻³]².
fn max_round_trip_error<W: InvertibleWarp>(w: &W, periodic_u2: bool) -> f64 {
    let n = 257;
    let mut worst = 0.0f64;
    for i in 0..n {
        for j in 0..n {
            let f = |k: usize| INTERIOR + (1.0 - 2.0 * INTERIOR) * k as f32 / (n - 1) as f32;
            let u = Vec2::new(f(i), f(j));
            let back = w.invert(w.sample(u));
            assert!(back.is_finite());
            let e2 = if periodic_u2 {
                circular_diff(back.y.into(), u.y.into())
            } else {
                f64::from((back.y - u.y).abs())
            };
            worst = worst.max(f64::from((back.x - u.x).abs())).max(e2);
        }
    }
    worst
}

#[test]
fn round_trip_accuracy_is_within_tolerance() {
    let mut rows = vec![
        (
            "disk polar".to_string(),
            max_round_trip_error(&UniformDisk, true),
        ),
        (
            "disk concentric".into(),
            max_round_trip_error(&UniformDiskConcentric, false),
        ),
        (
            "triangle".into(),
            max_round_trip_error(&UniformTriangle, false),
        ),
        (
            "uniform hemisphere".into(),
            max_round_trip_error(&UniformHemisphere, true),
        ),
        (
            "cosine hemisphere".into(),
            max_round_trip_error(&CosineHemisphere, false),
        ),
        (
            "theta over sin".into(),
            max_round_trip_error(&ThetaOverSinHemisphere, true),
        ),
        ("sphere".into(), max_round_trip_error(&UniformSphere, true)),
    ];
    for theta in CONE_ANGLES {
        let cone = UniformCone::from_angle(theta).unwrap();
        rows.push((format!("cone {theta}"), max_round_trip_error(&cone, true)));
    }
    for n in EXPONENTS {
        let lobe = PowerCosineHemisphere::new(n).unwrap();
        rows.push((
            format!("power cosine {n}"),
            max_round_trip_error(&lobe, true),
        ));
    }
    for (name, err) in &rows {
        println!("round trip max |invert(sample(u)) - u|: {name:>20}: {err:.2e}");
        assert!(err.is_finite() && *err <= RT_TOL, "{name}: {err}");
    }
}

/// Accuracy at the extremes against f64 references, over a 257 × 257 grid of u in
/// [10⁻³, 1 − 10⁻³]²: the largest relative error of the sampled polar angle θ and of the pdf
/// at the sample. Printed with `--nocapture`; the figures are quoted in the derivations.
fn extreme_errors<W: Warp<Point = Vec3>>(
    w: &W,
    theta_ref: impl Fn(f64) -> f64,
    pdf_ref: impl Fn(f64) -> f64,
) -> (f64, f64) {
    let n = 257;
    let (mut worst_theta, mut worst_pdf) = (0.0f64, 0.0f64);
    for i in 0..n {
        let u1 = INTERIOR + (1.0 - 2.0 * INTERIOR) * i as f32 / (n - 1) as f32;
        for j in 0..n {
            let u2 = INTERIOR + (1.0 - 2.0 * INTERIOR) * j as f32 / (n - 1) as f32;
            let w_ = w.sample(Vec2::new(u1, u2));
            let theta = angle_to_z(w_.as_dvec3());
            let t_ref = theta_ref(f64::from(u1));
            let pdf = f64::from(w.pdf(w_));
            let p_ref = pdf_ref(t_ref);
            assert!(theta.is_finite() && pdf.is_finite());
            worst_theta = worst_theta.max(((theta - t_ref) / t_ref).abs());
            worst_pdf = worst_pdf.max(((pdf - p_ref) / p_ref).abs());
        }
    }
    (worst_theta, worst_pdf)
}

#[test]
fn extremes_are_accurate_to_f32() {
    let theta_max = 1e-4f32;
    let omc = 2.0 * (f64::from(theta_max) / 2.0).sin().powi(2);
    let cone = UniformCone::from_angle(theta_max).unwrap();
    // 1 − cos θ = u₁ (1 − cos θ_max)  ⇒  θ = 2 asin(√(u₁ (1 − cos θ_max)/2)).
    let (ct, cp) = extreme_errors(
        &cone,
        |u1| 2.0 * (u1 * omc / 2.0).sqrt().asin(),
        |_| 1.0 / (2.0 * PI * omc),
    );
    println!("cone 1e-4 rad: max rel. error of theta {ct:.2e}, of pdf {cp:.2e}");
    assert!(ct <= 1e-6 && cp <= 1e-6, "{ct} {cp}");

    let n = 1e6f64;
    let lobe = PowerCosineHemisphere::new(n as f32).unwrap();
    // cos θ = u₁^{1/(n+1)}  ⇒  1 − cos θ = −expm1(ln u₁/(n + 1)).
    let (pt, pp) = extreme_errors(
        &lobe,
        |u1| 2.0 * ((-(u1.ln() / (n + 1.0)).exp_m1()) / 2.0).sqrt().asin(),
        |theta: f64| (n + 1.0) / (2.0 * PI) * theta.cos().powf(n),
    );
    println!("power cosine 1e6: max rel. error of theta {pt:.2e}, of pdf {pp:.2e}");
    assert!(pt <= 1e-6 && pp <= 1e-5, "{pt} {pp}");
}

#[test]
fn cone_from_cosine_matches_from_angle() {
    let a = UniformCone::new(0.5).unwrap();
    let b = UniformCone::from_angle(std::f32::consts::FRAC_PI_3).unwrap();
    let (x, y) = (a.one_minus_cos_theta_max(), b.one_minus_cos_theta_max());
    assert!(x.is_finite() && y.is_finite() && (x - y).abs() <= 1e-7);
    assert!((a.solid_angle() - std::f32::consts::PI).abs() <= 1e-6);
}

/// Largest |pdf(sample(u)) · J(u) − 1| over a 101 × 101 grid of u in [0.01, 0.99]² (skipping
/// the concentric diagonals as `check_jacobian` does).
fn max_jacobian_error<W: Warp>(w: &W, concentric: bool) -> f64
where
    W::Point: Point,
{
    let n = 101;
    let mut worst = 0.0f64;
    for i in 0..n {
        for j in 0..n {
            let f = |k: usize| JAC_MARGIN + (1.0 - 2.0 * JAC_MARGIN) * k as f32 / (n - 1) as f32;
            let u = Vec2::new(f(i), f(j));
            if concentric && near_concentric_diagonal(u) {
                continue;
            }
            let product = f64::from(w.pdf(w.sample(u))) * numerical_jacobian(w, u);
            assert!(product.is_finite());
            worst = worst.max((product - 1.0).abs());
        }
    }
    worst
}

#[test]
fn jacobian_identity_on_a_grid() {
    let mut rows = vec![
        (
            "disk polar".to_string(),
            max_jacobian_error(&UniformDisk, false),
        ),
        (
            "disk concentric".into(),
            max_jacobian_error(&UniformDiskConcentric, true),
        ),
        (
            "triangle".into(),
            max_jacobian_error(&UniformTriangle, false),
        ),
        (
            "uniform hemisphere".into(),
            max_jacobian_error(&UniformHemisphere, false),
        ),
        (
            "cosine hemisphere".into(),
            max_jacobian_error(&CosineHemisphere, true),
        ),
        (
            "theta over sin".into(),
            max_jacobian_error(&ThetaOverSinHemisphere, false),
        ),
        ("sphere".into(), max_jacobian_error(&UniformSphere, false)),
    ];
    for theta in CONE_ANGLES {
        let cone = UniformCone::from_angle(theta).unwrap();
        rows.push((format!("cone {theta}"), max_jacobian_error(&cone, false)));
    }
    for n in EXPONENTS {
        let lobe = PowerCosineHemisphere::new(n).unwrap();
        rows.push((
            format!("power cosine {n}"),
            max_jacobian_error(&lobe, false),
        ));
    }
    for (name, err) in &rows {
        println!("max |pdf * J - 1|: {name:>20}: {err:.2e}");
        assert!(err.is_finite() && *err <= JAC_TOL, "{name}: {err}");
    }
}
