//! Property tests of the basic warps (disk, triangle, hemisphere, sphere, cone, power cosine,
//! θ/sin θ): finiteness, support, pdf > 0 at samples, pdf consistency, inverse round trips and
//! the Jacobian identity pdf(sample(u)) · J(u) = 1, for u drawn freely and pinned to the edges
//! {0, 0.5, 1 − 2⁻²⁴}, at parameters that include the extremes.
//!
//! Tolerances (measured in `tests/it/warp_accuracy_basic.rs`; run it with `--nocapture` to print
//! the tables):
//! - interior round trip `invert(sample(u)) ≈ u` for u ∈ [10⁻³, 1 − 10⁻³]²: `4e-6` absolute
//!   (u₂ compared on the circle where it is an azimuth), i.e. 64 ulps of 1. f32 resolves u to
//!   6·10⁻⁸; the inverses add a few roundings (√, atan2, ln/exp), amplified where the
//!   forward map is steep (√u₁ near 0). Measured on a 257² grid: ≤ 3.6·10⁻⁷ for every warp
//!   and parameter (the printed table).
//! - edge round trip `sample(invert(p)) ≈ p`: the xy part within `1e-5 · (scale + |p_xy|)`
//!   and z within `1e-5 · scale + 2⁻²²`, where `scale` is the support's size (sin θ_max of a
//!   cone, 1/√(n + 1) for a power-cosine lobe, 1 otherwise), so tiny cones are held to
//!   relative accuracy; both plus the distance the sample moves when u moves by 2 ulps
//!   (`resolution`), which is what f32 allows where the map is steep (the rim of the cosine
//!   map: one ulp of u moves z by ~2·10⁻⁴).
//! - Jacobian: central differences in f64 of the f32 map with h = 10⁻³, u ∈ [0.01, 0.99]²
//!   (truncation error of √u₁ is h²/(8u₁²) ≤ 1.3·10⁻³ there), skipping 4h around the
//!   concentric map's diagonals; `|pdf · J − 1| ≤ 10⁻²`. For directions J is the triple
//!   product `|det(∂ω/∂u₁, ∂ω/∂u₂, ω)|`, which equals `|∂ω/∂u₁ × ∂ω/∂u₂|` for an exact map
//!   onto the sphere but ignores the rounding noise of z near the pole (z of a 10⁻⁴ rad cone
//!   is always 1.0 in f32).

use crate::warp_basic_support;

use crate::props;
use mcrt::glam::{DVec3, Vec2, Vec3};
use mcrt::sampling::warp::{
    triangle_area, triangle_area_pdf, triangle_point, CosineHemisphere, InvertibleWarp,
    PowerCosineHemisphere, ThetaOverSinHemisphere, UniformCone, UniformDisk, UniformDiskConcentric,
    UniformHemisphere, UniformSphere, UniformTriangle, Warp,
};
use mcrt::sampling::ONE_MINUS_EPSILON as ONE_MINUS;
use props::{config, u_any};
use proptest::prelude::*;
use std::f64::consts::PI;
use warp_basic_support::*;

const EDGE_TOL: f64 = 1e-5;

fn u_jacobian() -> impl Strategy<Value = Vec2> {
    (JAC_MARGIN..1.0 - JAC_MARGIN, JAC_MARGIN..1.0 - JAC_MARGIN).prop_map(|(a, b)| Vec2::new(a, b))
}

/// What the test knows of a warp independently of its code.
struct Spec<P> {
    name: String,
    /// Geometric support test (including unit length for directions).
    inside: Box<dyn Fn(DVec3) -> bool>,
    /// Points on a boundary of measure zero, where the pdf may be 0.
    boundary: Box<dyn Fn(DVec3) -> bool>,
    /// Whether u₂ is an azimuth (compared on the circle).
    periodic_u2: bool,
    /// Size of the support, for relative tolerances.
    scale: f64,
    /// Whether the map is the concentric one (kinks on the diagonals of u).
    concentric: bool,
    _p: std::marker::PhantomData<P>,
}

fn spec<P>(name: impl Into<String>, inside: impl Fn(DVec3) -> bool + 'static) -> Spec<P> {
    Spec {
        name: name.into(),
        inside: Box::new(inside),
        boundary: Box::new(|_| false),
        periodic_u2: true,
        scale: 1.0,
        concentric: false,
        _p: std::marker::PhantomData,
    }
}

fn unit(p: DVec3) -> bool {
    (p.length() - 1.0).abs() <= 1e-5
}

fn disk_spec(name: &str, concentric: bool) -> Spec<Vec2> {
    let mut s = spec(name, |p: DVec3| p.length_squared() <= 1.0 + 1e-6);
    s.boundary = Box::new(|p| p.length_squared() >= 1.0 - 1e-6);
    s.periodic_u2 = !concentric;
    s.concentric = concentric;
    s
}

fn triangle_spec() -> Spec<Vec2> {
    let mut s = spec("triangle", |p: DVec3| {
        p.x >= 0.0 && p.y >= 0.0 && p.x + p.y <= 1.0 + 1e-6
    });
    s.boundary = Box::new(|p| p.x <= 1e-6 || p.y <= 1e-6 || p.x + p.y >= 1.0 - 1e-6);
    s.periodic_u2 = false;
    s
}

fn hemisphere_spec(name: &str) -> Spec<Vec3> {
    let mut s = spec(name, |p: DVec3| unit(p) && p.z >= 0.0);
    s.boundary = Box::new(|p| p.z <= 1e-6);
    s
}

fn cone_spec(theta_max: f32) -> Spec<Vec3> {
    let t = f64::from(theta_max);
    let mut s = spec(format!("cone {theta_max}"), move |p: DVec3| {
        unit(p) && angle_to_z(p) <= t * (1.0 + 1e-3)
    });
    s.scale = t.min(PI / 2.0).sin();
    s
}

fn power_spec(n: f32) -> Spec<Vec3> {
    let mut s = hemisphere_spec(&format!("power cosine {n}"));
    s.scale = (1.0 / (f64::from(n) + 1.0).sqrt()).min(1.0);
    s
}

/// Every property that needs one u.
fn check<W: InvertibleWarp>(w: &W, s: &Spec<W::Point>, u: Vec2) -> Result<(), TestCaseError>
where
    W::Point: Point,
{
    let name = &s.name;
    let p = w.sample(u);
    let d = p.d3();
    prop_assert!(d.is_finite(), "{name}: sample({u}) = {p:?} not finite");
    prop_assert!(
        (s.inside)(d),
        "{name}: sample({u}) = {p:?} outside the support"
    );
    let pdf = w.pdf(p);
    prop_assert!(pdf.is_finite() && pdf >= 0.0, "{name}: pdf {pdf} at {p:?}");
    prop_assert!(
        pdf > 0.0 || (s.boundary)(d),
        "{name}: pdf 0 at sample {p:?} (u = {u})"
    );
    let (p2, pdf2) = w.sample_with_pdf(u);
    prop_assert!(p2.d3() == d, "{name}: sample_with_pdf point differs at {u}");
    prop_assert!(pdf2.is_finite(), "{name}: sample_with_pdf pdf {pdf2}");
    let rel = (f64::from(pdf2) - f64::from(pdf)).abs() / f64::from(pdf).max(1e-30);
    prop_assert!(
        rel <= 1e-3 || pdf < 1e-30,
        "{name}: pdf {pdf} vs {pdf2} at {u}"
    );

    let back = w.invert(p);
    prop_assert!(back.is_finite() && back.min_element() >= 0.0 && back.max_element() < 1.0);
    if u.min_element() >= INTERIOR && u.max_element() <= 1.0 - INTERIOR {
        let e1 = f64::from((back.x - u.x).abs());
        let e2 = if s.periodic_u2 {
            circular_diff(back.y.into(), u.y.into())
        } else {
            f64::from((back.y - u.y).abs())
        };
        prop_assert!(
            e1 <= RT_TOL && e2 <= RT_TOL,
            "{name}: invert(sample({u})) = {back}"
        );
    }
    let again = w.sample(back).d3();
    let (dxy, dz) = ((again - d).truncate().length(), (again.z - d.z).abs());
    let res = resolution(w, u);
    let xy_tol = EDGE_TOL * (s.scale + d.truncate().length()) + res;
    let z_tol = EDGE_TOL * s.scale + 2f64.powi(-22) + res;
    prop_assert!(
        dxy <= xy_tol && dz <= z_tol,
        "{name}: sample(invert(p)) = {again} vs p = {d} (u = {u})"
    );
    Ok(())
}

/// How far the sample moves when u moves by two f32 ulps (of 1) in either coordinate: the
/// resolution f32 allows at u. At the rim of the cosine map, for instance, one ulp of u moves
/// z by ~2·10⁻⁴, so no inverse can do better there.
fn resolution<W: Warp>(w: &W, u: Vec2) -> f64
where
    W::Point: Point,
{
    let p = w.sample(u).d3();
    let step = 2.0 / 16_777_216.0;
    let mut worst = 0.0f64;
    for (dx, dy) in [(step, 0.0), (-step, 0.0), (0.0, step), (0.0, -step)] {
        let v = (u + Vec2::new(dx, dy)).clamp(Vec2::ZERO, Vec2::splat(ONE_MINUS));
        worst = worst.max((w.sample(v).d3() - p).length());
    }
    worst
}

fn check_jacobian<W: Warp>(w: &W, s: &Spec<W::Point>, u: Vec2) -> Result<(), TestCaseError>
where
    W::Point: Point,
{
    if s.concentric && near_concentric_diagonal(u) {
        return Ok(());
    }
    let j = numerical_jacobian(w, u);
    let pdf = f64::from(w.pdf(w.sample(u)));
    let product = pdf * j;
    prop_assert!(
        product.is_finite() && (product - 1.0).abs() <= JAC_TOL,
        "{}: pdf {pdf} * J {j} = {product} at u = {u}",
        s.name
    );
    Ok(())
}

proptest! {
    #![proptest_config(config(2048))]

    #[test]
    fn planar_warps(u in u_any()) {
        check(&UniformDisk, &disk_spec("disk polar", false), u)?;
        check(&UniformDiskConcentric, &disk_spec("disk concentric", true), u)?;
        check(&UniformTriangle, &triangle_spec(), u)?;
    }

    #[test]
    fn hemispheres_and_sphere(u in u_any()) {
        check(&UniformHemisphere, &hemisphere_spec("uniform hemisphere"), u)?;
        let mut cosine = hemisphere_spec("cosine hemisphere");
        cosine.periodic_u2 = false;
        check(&CosineHemisphere, &cosine, u)?;
        check(&ThetaOverSinHemisphere, &hemisphere_spec("theta over sin"), u)?;
        check(&UniformSphere, &spec("sphere", unit), u)?;
    }

    #[test]
    fn cones(u in u_any()) {
        for theta in CONE_ANGLES {
            check(&UniformCone::from_angle(theta).unwrap(), &cone_spec(theta), u)?;
        }
    }

    #[test]
    fn power_cosines(u in u_any()) {
        for n in EXPONENTS {
            check(&PowerCosineHemisphere::new(n).unwrap(), &power_spec(n), u)?;
        }
    }

    #[test]
    fn jacobians(u in u_jacobian()) {
        check_jacobian(&UniformDisk, &disk_spec("disk polar", false), u)?;
        check_jacobian(&UniformDiskConcentric, &disk_spec("disk concentric", true), u)?;
        check_jacobian(&UniformTriangle, &triangle_spec(), u)?;
        check_jacobian(&UniformHemisphere, &hemisphere_spec("uniform hemisphere"), u)?;
        let mut cosine = hemisphere_spec("cosine hemisphere");
        cosine.concentric = true;
        check_jacobian(&CosineHemisphere, &cosine, u)?;
        check_jacobian(&ThetaOverSinHemisphere, &hemisphere_spec("theta over sin"), u)?;
        check_jacobian(&UniformSphere, &spec("sphere", unit), u)?;
        for theta in CONE_ANGLES {
            check_jacobian(&UniformCone::from_angle(theta).unwrap(), &cone_spec(theta), u)?;
        }
        for n in EXPONENTS {
            check_jacobian(&PowerCosineHemisphere::new(n).unwrap(), &power_spec(n), u)?;
        }
    }

    /// A cone of half-angle 10⁻⁴ rad: every sample within θ_max (1 + 10⁻³) of the axis, and
    /// its pdf 1/(2π(1 − cos θ_max)) within 10⁻³ relative, with 1 − cos θ_max = 2 sin²(θ/2)
    /// in f64 as the reference.
    #[test]
    fn tiny_cone_is_exact(u in u_any()) {
        let theta = 1e-4f32;
        let cone = UniformCone::from_angle(theta).unwrap();
        let t = f64::from(theta);
        let reference = 1.0 / (2.0 * PI * 2.0 * (t / 2.0).sin().powi(2));
        let w = cone.sample(u);
        let angle = angle_to_z(w.as_dvec3());
        prop_assert!(w.is_finite() && angle.is_finite() && angle <= t * (1.0 + 1e-3), "{angle}");
        let pdf = f64::from(cone.pdf(w));
        prop_assert!(pdf.is_finite() && ((pdf - reference) / reference).abs() <= 1e-3, "{pdf}");
    }
}

/// Any finite f32, with a bias towards 0, ±1 and huge magnitudes.
fn any_finite() -> impl Strategy<Value = f32> {
    prop_oneof![
        1 => Just(0.0f32),
        1 => Just(1.0f32),
        1 => Just(-1.0f32),
        1 => Just(f32::MAX),
        1 => Just(-f32::MAX),
        2 => -1e30f32..1e30,
        4 => -2.0f32..2.0,
        2 => -1e-20f32..1e-20,
    ]
}

fn any_vec3() -> impl Strategy<Value = Vec3> {
    (any_finite(), any_finite(), any_finite()).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// pdf and invert of arbitrary finite points (not unit, not in the support): pdf finite and
/// ≥ 0, invert in [0, 1)².
fn check_any_point<W: InvertibleWarp>(w: &W, p: W::Point) -> Result<(), TestCaseError>
where
    W::Point: Point,
{
    let pdf = w.pdf(p);
    prop_assert!(pdf.is_finite() && pdf >= 0.0, "pdf {pdf} at {p:?}");
    let u = w.invert(p);
    prop_assert!(
        u.is_finite() && u.min_element() >= 0.0 && u.max_element() < 1.0,
        "{u} at {p:?}"
    );
    Ok(())
}

proptest! {
    #![proptest_config(config(2048))]

    #[test]
    fn pdf_and_invert_never_nan(v in any_vec3()) {
        let p2 = v.truncate();
        check_any_point(&UniformDisk, p2)?;
        check_any_point(&UniformDiskConcentric, p2)?;
        check_any_point(&UniformTriangle, p2)?;
        check_any_point(&UniformHemisphere, v)?;
        check_any_point(&CosineHemisphere, v)?;
        check_any_point(&UniformSphere, v)?;
        check_any_point(&ThetaOverSinHemisphere, v)?;
        for theta in CONE_ANGLES {
            check_any_point(&UniformCone::from_angle(theta).unwrap(), v)?;
        }
        for n in EXPONENTS {
            check_any_point(&PowerCosineHemisphere::new(n).unwrap(), v)?;
        }
    }

    /// Triangles in 3D, slivers and degenerate ones included: the sampled point is finite and
    /// on the triangle (within its bounding box), and the area pdf is finite and ≥ 0, > 0
    /// exactly when the area (in f64) is positive and its inverse fits f32.
    #[test]
    fn triangles_in_3d(a in any_vec3(), b in any_vec3(), c in any_vec3(), u in u_any()) {
        // Keep the corners where their differences cannot overflow.
        let clamp = |v: Vec3| v.clamp(Vec3::splat(-1e18), Vec3::splat(1e18));
        let (a, b, c) = (clamp(a), clamp(b), clamp(c));
        let bary = UniformTriangle.sample(u);
        let p = triangle_point(a, b, c, bary);
        prop_assert!(p.is_finite());
        let (lo, hi) = (a.min(b).min(c), a.max(b).max(c));
        let slack = (hi - lo) * 1e-5 + Vec3::splat(1e-30);
        prop_assert!(p.cmpge(lo - slack).all() && p.cmple(hi + slack).all(), "{p} outside");
        let pdf = triangle_area_pdf(a, b, c);
        let area = f64::from(triangle_area(a, b, c));
        prop_assert!(pdf.is_finite() && pdf >= 0.0 && area.is_finite() && area >= 0.0);
        if pdf > 0.0 {
            let rel = (f64::from(pdf) * area - 1.0).abs();
            prop_assert!(rel <= 1e-5, "pdf {pdf} area {area}");
        }
    }

    /// A sliver: the third corner 10⁻²⁰ off the base line.
    #[test]
    fn sliver_triangles(t in 0.0f32..1.0, u in u_any()) {
        let (a, b) = (Vec3::ZERO, Vec3::new(1.0, 0.0, 0.0));
        let c = Vec3::new(t, 1e-20, 0.0);
        let p = triangle_point(a, b, c, UniformTriangle.sample(u));
        let pdf = triangle_area_pdf(a, b, c);
        prop_assert!(p.is_finite() && pdf.is_finite() && pdf > 0.0);
        prop_assert!(((f64::from(pdf) - 2e20) / 2e20).abs() <= 1e-6, "{pdf}");
    }
}
