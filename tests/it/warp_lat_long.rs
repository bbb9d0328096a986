//! Property tests of the latitude–longitude map `LatLong` (environment-map coordinates):
//! round trips both ways, `(u, v)` always in `[0,1)²` (poles, the seam, ±0 components,
//! NaN, infinite and zero vectors), densities finite and positive on the whole sphere
//! (poles included), and a piecewise-constant table looked up at `invert(dir)` never 0 where
//! the table is positive. Fixed proptest seed.
//!
//! Tolerances: the interior round trip `invert(sample(uv)) ≈ uv` within `4·10⁻⁶` (64 ulps of 1,
//! as `warp_properties_basic`; `u` compared on the circle) for `v ∈ [10⁻³, 1 − 10⁻³]`, where
//! `u` is defined; `sample(invert(ω)) ≈ ω` within `2·10⁻⁶` for every unit `ω` (poles too:
//! there `u` is arbitrary but the direction is the pole).

use crate::props;
use mcrt::glam::{Vec2, Vec3};
use mcrt::sampling::distribution::PiecewiseConstant2D;
use mcrt::sampling::warp::{InvertibleWarp, LatLong, Warp};
use mcrt::sampling::ONE_MINUS_EPSILON;
use props::config;
use proptest::prelude::*;

/// One coordinate of a direction: free, or an edge value (±0, ±1).
fn component() -> impl Strategy<Value = f32> {
    prop_oneof![
        1 => Just(0.0f32),
        1 => Just(-0.0f32),
        1 => Just(1.0f32),
        1 => Just(-1.0f32),
        1 => Just(1e-30f32),
        1 => Just(-1e-30f32),
        6 => -1.0f32..1.0,
    ]
}

/// Unit directions, the poles and the seam (`x = ±0`, `z < 0`) included.
fn direction() -> impl Strategy<Value = Vec3> {
    (component(), component(), component())
        .prop_filter("not the zero vector", |(x, y, z)| {
            x * x + y * y + z * z > 1e-6
        })
        .prop_map(|(x, y, z)| Vec3::new(x, y, z).normalize())
}

/// Any `f32`, non-finite values included.
fn any_f32() -> impl Strategy<Value = f32> {
    prop_oneof![
        1 => Just(f32::NAN),
        1 => Just(f32::INFINITY),
        1 => Just(f32::NEG_INFINITY),
        1 => Just(0.0f32),
        1 => Just(-0.0f32),
        4 => proptest::num::f32::NORMAL | proptest::num::f32::SUBNORMAL | proptest::num::f32::ZERO,
    ]
}

/// The distance of two azimuth coordinates on the circle of circumference 1.
fn circle_distance(a: f32, b: f32) -> f32 {
    let d = (a - b).abs();
    d.min(1.0 - d)
}

proptest! {
    #![proptest_config(config(4096))]

    #[test]
    fn interior_round_trip(u in 0.0f32..1.0, t in 0.0f32..1.0) {
        let v = 1e-3 + t * (1.0 - 2e-3);
        let back = LatLong.invert(LatLong.sample(Vec2::new(u, v)));
        let (du, dv) = (circle_distance(back.x, u), (back.y - v).abs());
        prop_assert!(du.is_finite() && du <= 4e-6, "u {u} -> {}", back.x);
        prop_assert!(dv.is_finite() && dv <= 4e-6, "v {v} -> {}", back.y);
    }

    #[test]
    fn direction_round_trip(w in direction()) {
        let back = LatLong.sample(LatLong.invert(w));
        let err = (back - w).length();
        prop_assert!(err.is_finite() && err <= 2e-6, "{w} -> {back}: {err}");
    }

    #[test]
    fn inverse_stays_in_the_square(x in any_f32(), y in any_f32(), z in any_f32()) {
        let uv = LatLong.invert(Vec3::new(x, y, z));
        for c in [uv.x, uv.y] {
            prop_assert!((0.0..=ONE_MINUS_EPSILON).contains(&c), "({x}, {y}, {z}) -> {uv}");
            prop_assert!(c.is_sign_positive(), "({x}, {y}, {z}) -> {uv}: −0");
        }
        let pdf = LatLong.pdf(Vec3::new(x, y, z));
        prop_assert!(pdf.is_finite() && pdf >= 0.0, "pdf {pdf}");
    }

    /// On the sphere the map's density and a positive table's density per steradian are
    /// finite and positive, the poles included.
    #[test]
    fn densities_are_positive_everywhere(w in direction()) {
        let pdf = LatLong.pdf(w);
        prop_assert!(pdf.is_finite() && pdf > 0.0, "{w}: {pdf}");
        let table = PiecewiseConstant2D::new(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0], 2, 3).unwrap();
        let pdf_uv = table.pdf(LatLong.invert(w));
        let pdf = LatLong::solid_angle_pdf(pdf_uv, LatLong::sin_theta(w));
        prop_assert!(pdf_uv > 0.0 && pdf.is_finite() && pdf > 0.0, "{w}: {pdf_uv} {pdf}");
    }

    /// Sampling a table through the map: the density is positive, also for `u` pinned to the
    /// edges, and `sample_with_pdf` and the lookup at the inverse agree away from the poles
    /// and the seam (where `u` is undefined or wraps, so the two may pick neighbouring
    /// columns: a set of no solid angle).
    #[test]
    fn table_sample_and_lookup_agree(
        ux in prop_oneof![Just(0.0f32), Just(ONE_MINUS_EPSILON), 0.0f32..1.0],
        uy in prop_oneof![Just(0.0f32), Just(ONE_MINUS_EPSILON), 0.0f32..1.0],
    ) {
        let table = PiecewiseConstant2D::new(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0], 3, 2).unwrap();
        let (uv, pdf_uv) = table.sample_with_pdf(Vec2::new(ux, uy));
        let dir = LatLong.sample(uv);
        let sin_theta = LatLong::sin_theta(dir);
        let sampled = LatLong::solid_angle_pdf(pdf_uv, sin_theta);
        let looked_up = LatLong::solid_angle_pdf(table.pdf(LatLong.invert(dir)), sin_theta);
        prop_assert!(sampled.is_finite() && sampled > 0.0, "{uv}: {sampled}");
        let on_edge = sin_theta < 1e-4 || uv.x < 1e-6 || uv.x > 1.0 - 1e-6;
        prop_assert!(looked_up.is_finite() && looked_up > 0.0, "{uv}: {looked_up}");
        prop_assert!(
            on_edge || (looked_up - sampled).abs() <= 1e-5 * sampled,
            "{uv}: {sampled} vs {looked_up}"
        );
    }
}

#[test]
fn poles_and_seam() {
    for (x, z) in [(0.0, 0.0), (-0.0, 0.0), (0.0, -0.0), (-0.0, -0.0)] {
        let north = LatLong.invert(Vec3::new(x, 1.0, z));
        let south = LatLong.invert(Vec3::new(x, -1.0, z));
        assert_eq!(north.y, 0.0, "({x}, {z})");
        assert_eq!(south.y, ONE_MINUS_EPSILON, "({x}, {z})");
        for u in [north.x, south.x] {
            assert!(u == 0.0 || u == 0.5, "({x}, {z}): u = {u}");
        }
    }
    // Just either side of the seam (−z, φ = 0 ≡ 2π): u near 0 or just below 1, never 1.
    for x in [1e-30f32, -1e-30, 1e-7, -1e-7, 0.0, -0.0] {
        let uv = LatLong.invert(Vec3::new(x, 0.0, -1.0));
        assert!(
            uv.x < 1.0 && (uv.x < 1e-7 || uv.x > 1.0 - 1e-7),
            "x = {x}: {uv}"
        );
    }
    assert_eq!(LatLong.invert(Vec3::new(-1e-30, 0.0, -1.0)).x, 0.0);
    // The map's density at a pole: finite, positive, the floor ε = f32::EPSILON.
    let at_pole = LatLong.pdf(Vec3::Y);
    let floor = 1.0 / (2.0 * std::f32::consts::PI.powi(2) * f32::EPSILON);
    assert!(at_pole.is_finite() && (at_pole - floor).abs() <= 1e-6 * floor);
    // Non-finite and zero inputs: no panic, a point of the square, a zero density.
    for w in [
        Vec3::NAN,
        Vec3::INFINITY,
        Vec3::ZERO,
        Vec3::new(f32::NAN, 1.0, 0.0),
    ] {
        let uv = LatLong.invert(w);
        assert!(
            (0.0..1.0).contains(&uv.x) && (0.0..1.0).contains(&uv.y),
            "{w}: {uv}"
        );
    }
    assert_eq!(LatLong.pdf(Vec3::NAN), 0.0);
    assert_eq!(LatLong::solid_angle_pdf(f32::NAN, 0.5), 0.0);
    assert_eq!(LatLong::solid_angle_pdf(-1.0, 0.5), 0.0);
}
