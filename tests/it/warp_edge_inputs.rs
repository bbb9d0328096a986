//! What every warp does with inputs outside its contract (see the "Inputs outside the unit
//! square" section of `mcrt::sampling::warp`): `u` negative, ≥ 1, NaN or infinite never
//! panics in `sample` or `sample_with_pdf`, and `pdf` of any point, NaN and infinite points included, is finite and ≥ 0 (0
//! for a non-finite point), so `pdf(sample(u))` is never NaN.

use mcrt::glam::{Vec2, Vec3};
use mcrt::sampling::warp::{
    Beckmann, BeckmannVisible, CosineHemisphere, Ggx, GgxVisible, PowerCosineHemisphere,
    SphericalRectangle, SphericalTriangle, ThetaOverSinHemisphere, UniformCone, UniformDisk,
    UniformDiskConcentric, UniformHemisphere, UniformSphere, UniformTriangle, Warp,
    SPHERICAL_MIN_SOLID_ANGLE,
};

const ODD: [f32; 7] = [
    f32::NAN,
    f32::INFINITY,
    f32::NEG_INFINITY,
    -0.5,
    1.0,
    1.5,
    -0.0,
];

fn u_values() -> Vec<Vec2> {
    let mut v = Vec::new();
    for a in ODD {
        v.push(Vec2::new(a, 0.5));
        v.push(Vec2::new(0.5, a));
        v.push(Vec2::splat(a));
    }
    v
}

/// The contract for one warp with points of type `P`.
fn check<W: Warp>(name: &str, w: &W, nonfinite: &[W::Point], is_finite: fn(W::Point) -> bool)
where
    W::Point: std::fmt::Debug,
{
    for u in u_values() {
        let p = w.sample(u);
        let pdf = w.pdf(p);
        assert!(
            pdf.is_finite() && pdf >= 0.0,
            "{name}: pdf {pdf} at sample({u}) = {p:?}"
        );
        if !is_finite(p) {
            assert_eq!(pdf, 0.0, "{name}: non-finite sample({u}) = {p:?}");
        }
        // Unspecified values, but no panic.
        let _ = w.sample_with_pdf(u);
    }
    for &p in nonfinite {
        assert_eq!(w.pdf(p), 0.0, "{name}: pdf at {p:?}");
    }
}

fn dirs() -> Vec<Vec3> {
    let mut v = Vec::new();
    for a in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        v.push(Vec3::new(a, 0.0, 1.0));
        v.push(Vec3::new(0.0, 0.0, a));
        v.push(Vec3::splat(a));
    }
    v
}

fn points() -> Vec<Vec2> {
    let mut v = Vec::new();
    for a in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        v.push(Vec2::new(a, 0.0));
        v.push(Vec2::new(0.0, a));
    }
    v
}

#[test]
fn planar_warps() {
    let (p, f) = (points(), |p: Vec2| p.is_finite());
    check("UniformDisk", &UniformDisk, &p, f);
    check("UniformDiskConcentric", &UniformDiskConcentric, &p, f);
    check("UniformTriangle", &UniformTriangle, &p, f);
}

#[test]
fn directional_warps() {
    let (d, f) = (dirs(), |p: Vec3| p.is_finite());
    check("UniformHemisphere", &UniformHemisphere, &d, f);
    check("CosineHemisphere", &CosineHemisphere, &d, f);
    check("UniformSphere", &UniformSphere, &d, f);
    check("ThetaOverSinHemisphere", &ThetaOverSinHemisphere, &d, f);
    for theta in [1e-4, 0.3, 3.0] {
        check(
            "UniformCone",
            &UniformCone::from_angle(theta).unwrap(),
            &d,
            f,
        );
    }
    for n in [0.0, 1.0, 1e6] {
        check(
            "PowerCosine",
            &PowerCosineHemisphere::new(n).unwrap(),
            &d,
            f,
        );
    }
    for alpha in [1e-4, 0.1, 1.0] {
        check("Beckmann", &Beckmann::new(alpha).unwrap(), &d, f);
        check("Ggx", &Ggx::new(alpha).unwrap(), &d, f);
        let wi = Vec3::new(0.6, 0.0, 0.8);
        check("GgxVisible", &GgxVisible::new(alpha, wi).unwrap(), &d, f);
        check(
            "BeckmannVisible",
            &BeckmannVisible::new(alpha, wi).unwrap(),
            &d,
            f,
        );
    }
    let tri = SphericalTriangle::new(
        Vec3::ZERO,
        Vec3::new(-1.0, -1.0, 2.0),
        Vec3::new(1.0, -1.0, 2.0),
        Vec3::new(0.0, 1.0, 2.0),
    )
    .unwrap();
    check("SphericalTriangle", &tri, &d, f);
    let rect = SphericalRectangle::new(
        Vec3::ZERO,
        Vec3::new(-1.0, -1.0, 1.0),
        2.0 * Vec3::X,
        2.0 * Vec3::Y,
    )
    .unwrap();
    check("SphericalRectangle", &rect, &d, f);
}

#[test]
fn ggx_pdf_of_a_nan_direction_is_zero() {
    // It was NaN (the other distributions returned 0).
    let g = Ggx::new(0.3).unwrap();
    for m in [
        Vec3::NAN,
        Vec3::new(f32::NAN, 0.0, 1.0),
        Vec3::new(0.0, f32::NAN, 0.5),
    ] {
        assert_eq!(g.pdf(m), 0.0, "{m}");
    }
}

#[test]
fn spherical_shapes_too_small_for_an_f32_density_are_refused_for_area_sampling() {
    // A triangle of 5·10⁻⁴¹ sr and a rectangle with 10⁻³⁰ edges: their densities per
    // steradian (~10⁴⁰ and ~10⁶⁰) do not fit f32, and they used to come out infinite.
    let tri = SphericalTriangle::new(
        Vec3::ZERO,
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(1e-20, 0.0, 1.0),
        Vec3::new(0.0, 1e-20, 1.0),
    );
    assert!(tri.is_err(), "{tri:?}");
    let rect = SphericalRectangle::new(Vec3::ZERO, Vec3::Z, 1e-30 * Vec3::X, 1e-30 * Vec3::Y);
    assert!(rect.is_err(), "{rect:?}");
    // Just above the bound: accepted, with finite densities at its samples.
    let side = (4.0 * SPHERICAL_MIN_SOLID_ANGLE).sqrt() as f32;
    let rect = SphericalRectangle::new(Vec3::ZERO, Vec3::Z, side * Vec3::X, side * Vec3::Y)
        .expect("a tiny but representable rectangle");
    let tri = SphericalTriangle::new(
        Vec3::ZERO,
        Vec3::Z,
        Vec3::new(2.0 * side, 0.0, 1.0),
        Vec3::new(0.0, 2.0 * side, 1.0),
    )
    .expect("a tiny but representable triangle");
    assert!(tri.is_area_sampled());
    for u in [
        Vec2::new(0.5, 0.5),
        Vec2::new(0.0, 0.0),
        Vec2::new(0.9, 0.1),
    ] {
        let (_, p) = rect.sample_with_pdf(u);
        assert!(p.is_finite() && p > 0.0, "rectangle {u}: {p}");
        let (_, p) = tri.sample_with_pdf(u);
        assert!(p.is_finite() && p > 0.0, "triangle {u}: {p}");
    }
}
