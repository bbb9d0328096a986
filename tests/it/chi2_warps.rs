//! Every warp of `mcrt::sampling::warp`, at several parameters including the extremes of the
//! sampling issue, against its own pdf: chi-square, integral = 1, the Jacobian identity, and
//! the inverse round trip where one exists. Settings in `tests/it/common/mod.rs` and
//! `docs/testing.md`.

use crate::common;

use common::{chi2, hemisphere, sphere};
use mcrt::glam::{Vec2, Vec3};
use mcrt::sampling::warp::*;
use mcrt::stats::{
    check_warp_inverse, check_warp_jacobian, Directions, Domain, JacobianCheck, Rectangle,
    StatPoint,
};

/// Collects the reports of failed checks, so that one test shows every failing parameter.
#[derive(Default)]
struct Failures(Vec<String>);

impl Failures {
    fn finish(self) {
        assert!(
            self.0.is_empty(),
            "{} check(s) failed:\n{}",
            self.0.len(),
            self.0.join("\n")
        );
    }
}

/// Chi-square (which includes the check that the pdf integrates to 1 over the domain within
/// `INTEGRAL_TOL`), and the Jacobian identity.
fn check<W, D>(f: &mut Failures, name: &str, warp: &W, domain: D, jac: Option<JacobianCheck>)
where
    W: Warp + Sync,
    W::Point: StatPoint,
    D: Domain<Point = W::Point>,
{
    check_n(f, name, warp, domain, jac, common::SAMPLES);
}

/// [`check`] with `samples` samples (for warps too slow for the default count).
fn check_n<W, D>(
    f: &mut Failures,
    name: &str,
    warp: &W,
    domain: D,
    jac: Option<JacobianCheck>,
    samples: usize,
) where
    W: Warp + Sync,
    W::Point: StatPoint,
    D: Domain<Point = W::Point>,
{
    let o = chi2(domain, name).samples(samples).run_warp(warp);
    if !o.passed() {
        f.0.push(o.report());
    }
    if let Some(settings) = jac {
        let j = check_warp_jacobian(warp, settings);
        if !j.passed() {
            f.0.push(format!("{name}: {}", j.report()));
        }
    }
}

fn check_inverse<W>(f: &mut Failures, name: &str, warp: &W, tol: f64)
where
    W: InvertibleWarp + Sync,
    W::Point: StatPoint,
{
    let c = check_warp_inverse(warp, 64, tol);
    if !c.passed() {
        f.0.push(format!("{name}: {}", c.report()));
    }
}

/// A cap about +z wide enough for a lobe of angular width `width`, rings not refined (the
/// cap is already zoomed); the whole hemisphere when the lobe is wide.
fn lobe_domain(width: f32) -> Directions {
    let theta = 8.0 * width;
    if theta >= 1.2 {
        hemisphere()
    } else {
        Directions::cap(Vec3::Z, theta)
            .resolution(61, 64)
            .refinement(1.5)
    }
}

fn square() -> Rectangle {
    Rectangle::new(Vec2::splat(-1.0), Vec2::splat(1.0), 48, 48)
}

fn jac() -> Option<JacobianCheck> {
    Some(common::jacobian())
}

/// A wider difference step for maps onto small solid angles, where the `f32` rounding of
/// the sampled directions (≈ 6·10⁻⁸) over a step of 2⁻⁹ would exceed the tolerance.
fn jac_wide() -> Option<JacobianCheck> {
    Some(JacobianCheck {
        step: 1.0 / 128.0,
        ..common::jacobian()
    })
}

#[test]
fn disks() {
    let mut f = Failures::default();
    check(&mut f, "UniformDisk", &UniformDisk, square(), jac());
    check_inverse(&mut f, "UniformDisk", &UniformDisk, 1e-4);
    let c = UniformDiskConcentric;
    check(&mut f, "UniformDiskConcentric", &c, square(), jac());
    check_inverse(&mut f, "UniformDiskConcentric", &c, 1e-4);
    f.finish();
}

#[test]
fn triangle() {
    let mut f = Failures::default();
    let d = Rectangle::unit_square(48);
    check(
        &mut f,
        "UniformTriangle",
        &UniformTriangle,
        d.clone(),
        jac(),
    );
    check_inverse(&mut f, "UniformTriangle", &UniformTriangle, 1e-4);
    f.finish();
}

/// A sliver triangle in 3D (1 × 10⁻³), sampled through `triangle_point`, against
/// `triangle_area_pdf` on its support: uniform in area.
#[test]
fn sliver_triangle_in_3d() {
    let (a, b, c) = (Vec3::ZERO, Vec3::X, Vec3::new(0.5, 1e-3, 0.0));
    let area_pdf = triangle_area_pdf(a, b, c);
    assert!(
        area_pdf.is_finite() && (area_pdf - 2000.0).abs() < 0.5,
        "{area_pdf}"
    );
    let inside = |p: Vec2| {
        let (x, y) = (f64::from(p.x), f64::from(p.y));
        y >= 0.0 && y <= 2e-3 * x.min(1.0 - x) * (1.0 + 1e-6)
    };
    let sample = |u: Vec2| triangle_point(a, b, c, UniformTriangle.sample(u)).truncate();
    let domain = Rectangle::new(Vec2::ZERO, Vec2::new(1.0, 1e-3), 64, 16);
    chi2(domain, "UniformTriangle-sliver-3d")
        .run(sample, |p| if inside(p) { area_pdf } else { 0.0 })
        .assert_passed();
}

#[test]
fn hemispheres_and_sphere() {
    let mut f = Failures::default();
    check(
        &mut f,
        "UniformHemisphere",
        &UniformHemisphere,
        hemisphere(),
        jac(),
    );
    check_inverse(&mut f, "UniformHemisphere", &UniformHemisphere, 1e-4);
    check(
        &mut f,
        "CosineHemisphere",
        &CosineHemisphere,
        hemisphere(),
        jac(),
    );
    check_inverse(&mut f, "CosineHemisphere", &CosineHemisphere, 1e-4);
    check(&mut f, "UniformSphere", &UniformSphere, sphere(), jac());
    check_inverse(&mut f, "UniformSphere", &UniformSphere, 1e-4);
    let q = ThetaOverSinHemisphere;
    check(&mut f, "ThetaOverSinHemisphere", &q, hemisphere(), jac());
    check_inverse(&mut f, "ThetaOverSinHemisphere", &q, 1e-4);
    f.finish();
}

/// The latitude–longitude map of environment maps: density `1/(2π² sin θ)`, infinite (but
/// integrable) at the poles, which the sphere's rings refined toward +z and the quadrature
/// resolve.
#[test]
fn lat_long() {
    let mut f = Failures::default();
    check(&mut f, "LatLong", &LatLong, sphere(), jac());
    check_inverse(&mut f, "LatLong", &LatLong, 1e-4);
    f.finish();
}

#[test]
fn cones() {
    let mut f = Failures::default();
    for theta in [2.5f32, 1.0, 0.3, 1e-2, 1e-3, 1e-4] {
        let name = format!("UniformCone-{theta:e}");
        let cone = UniformCone::from_angle(theta).expect("valid cone");
        // A cap 1.5 × the cone, 61 rings: the cone's edge falls inside a ring.
        let domain = || {
            if theta > 2.0 {
                sphere()
            } else {
                Directions::cap(Vec3::Z, 1.5 * theta)
                    .resolution(61, 64)
                    .refinement(1.0)
            }
        };
        check(&mut f, &name, &cone, domain(), jac());
        check_inverse(&mut f, &name, &cone, 1e-3);
    }
    let by_cos = UniformCone::new(0.5).expect("valid cone");
    check(&mut f, "UniformCone-cos0.5", &by_cos, hemisphere(), jac());
    f.finish();
}

#[test]
fn power_cosine() {
    let mut f = Failures::default();
    for n in [0.0f32, 1.0, 10.0, 1e3, 1e6] {
        let name = format!("PowerCosineHemisphere-{n:e}");
        let w = PowerCosineHemisphere::new(n).expect("valid exponent");
        let domain = || lobe_domain(1.0 / (n + 1.0).sqrt());
        check(&mut f, &name, &w, domain(), jac());
        check_inverse(&mut f, &name, &w, 1e-3);
    }
    f.finish();
}

const ALPHAS: [f32; 6] = [1.0, 0.5, 0.1, 1e-2, 1e-3, 1e-4];

#[test]
fn microfacet_normals() {
    let mut f = Failures::default();
    for alpha in ALPHAS {
        let b = Beckmann::new(alpha).expect("valid alpha");
        let g = Ggx::new(alpha).expect("valid alpha");
        let (nb, ng) = (format!("Beckmann-{alpha:e}"), format!("Ggx-{alpha:e}"));
        check(&mut f, &nb, &b, lobe_domain(alpha), jac());
        check_inverse(&mut f, &nb, &b, 1e-3);
        check(&mut f, &ng, &g, lobe_domain(alpha), jac());
        check_inverse(&mut f, &ng, &g, 1e-3);
    }
    f.finish();
}

fn incident(theta_deg: f32) -> Vec3 {
    let (s, c) = theta_deg.to_radians().sin_cos();
    let phi = 0.7f32;
    Vec3::new(s * phi.cos(), s * phi.sin(), c)
}

#[test]
fn ggx_visible_normals() {
    let mut f = Failures::default();
    for alpha in [1.0f32, 0.3, 1e-2, 1e-4] {
        for theta in [0.0f32, 45.0, 80.0, 89.9] {
            let g = GgxVisible::new(alpha, incident(theta)).expect("valid");
            let name = format!("GgxVisible-{alpha:e}-{theta}deg");
            check(&mut f, &name, &g, lobe_domain(alpha), jac());
        }
    }
    f.finish();
}

#[test]
fn beckmann_visible_normals() {
    let mut f = Failures::default();
    for alpha in [1.0f32, 0.3, 1e-2, 1e-4] {
        for theta in [0.0f32, 45.0, 80.0, 89.9] {
            let b = BeckmannVisible::new(alpha, incident(theta)).expect("valid");
            let name = format!("BeckmannVisible-{alpha:e}-{theta}deg");
            // Beckmann visible normals cost about 3 µs per sample: a quarter of the samples.
            let samples = common::SAMPLES / 4;
            check_n(&mut f, &name, &b, lobe_domain(alpha), jac(), samples);
        }
    }
    f.finish();
}

/// A cap about the mean direction of `points` seen from `origin`, 1.3 × the widest angle.
fn cap_around(origin: Vec3, points: &[Vec3]) -> Directions {
    let dirs: Vec<Vec3> = points.iter().map(|&p| (p - origin).normalize()).collect();
    let axis = dirs.iter().copied().sum::<Vec3>().normalize();
    let widest = dirs
        .iter()
        .map(|d| d.dot(axis).clamp(-1.0, 1.0).acos())
        .fold(0.0, f32::max);
    Directions::cap(axis, (1.3 * widest).min(std::f32::consts::PI))
        .resolution(61, 64)
        .refinement(1.0)
}

#[test]
fn spherical_triangles() {
    let mut f = Failures::default();
    let o = Vec3::new(0.1, -0.2, 0.0);
    let cases = [
        (
            "near",
            [
                Vec3::new(-1.0, -1.0, 0.5),
                Vec3::new(1.5, -1.0, 0.5),
                Vec3::new(0.0, 1.0, 0.8),
            ],
        ),
        (
            "far",
            [
                Vec3::new(3.0, 0.0, 10.0),
                Vec3::new(3.1, 0.0, 10.0),
                Vec3::new(3.0, 0.1, 10.0),
            ],
        ),
        (
            "sliver",
            [
                Vec3::new(-1.0, 0.0, 2.0),
                Vec3::new(1.0, 0.0, 2.0),
                Vec3::new(0.0, 0.02, 2.0),
            ],
        ),
    ];
    for (tag, [a, b, c]) in cases {
        spherical_triangle(&mut f, tag, o, [a, b, c]);
    }
    f.finish();
}

fn spherical_triangle(f: &mut Failures, tag: &str, o: Vec3, [a, b, c]: [Vec3; 3]) {
    let name = format!("SphericalTriangle-{tag}");
    let t = SphericalTriangle::new(o, a, b, c).expect("valid triangle");
    check(f, &name, &t, cap_around(o, &[a, b, c]), jac_wide());
    check_inverse(f, &name, &t, 1e-3);
}

/// A triangle of 5·10⁻⁷ sr, sampled by the area fallback. Kept apart: it fails while the
/// pdf's hit test accepts a fixed angular band of 10⁻⁶ rad around the triangle, which adds
/// 0.7 % to the support of a triangle 10⁻³ rad across (see `docs/testing.md`).
#[test]
fn spherical_triangle_tiny() {
    let mut f = Failures::default();
    let o = Vec3::new(0.1, -0.2, 0.0);
    let tri = [
        Vec3::new(0.0, 0.0, 50.0),
        Vec3::new(0.05, 0.0, 50.0),
        Vec3::new(0.0, 0.05, 50.0),
    ];
    spherical_triangle(&mut f, "tiny", o, tri);
    f.finish();
}

#[test]
fn spherical_rectangles() {
    let mut f = Failures::default();
    let o = Vec3::new(0.2, 0.1, 0.0);
    let cases = [
        (
            "near",
            Vec3::new(-1.0, -1.0, 1.0),
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.0, 2.0, 0.0),
        ),
        (
            "tilted",
            Vec3::new(1.0, -0.5, 0.2),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(0.3, 0.0, 1.0),
        ),
        (
            "far",
            Vec3::new(0.0, 0.0, 30.0),
            Vec3::new(0.2, 0.0, 0.0),
            Vec3::new(0.0, 0.1, 0.0),
        ),
        (
            "sliver",
            Vec3::new(-1.0, 0.0, 2.0),
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.0, 0.01, 0.0),
        ),
    ];
    for (tag, corner, ex, ey) in cases {
        let name = format!("SphericalRectangle-{tag}");
        let r = SphericalRectangle::new(o, corner, ex, ey).expect("valid rectangle");
        let pts = [corner, corner + ex, corner + ex + ey, corner + ey];
        check(&mut f, &name, &r, cap_around(o, &pts), jac_wide());
        check_inverse(&mut f, &name, &r, 1e-3);
    }
    f.finish();
}

/// The suite's default hemisphere cells (rings refined toward the pole) resolve a GGX lobe
/// of α = 0.01 without a zoomed cap.
#[test]
fn narrow_lobe_on_the_default_hemisphere() {
    let g = Ggx::new(0.01).expect("valid alpha");
    let o = chi2(hemisphere(), "Ggx-0.01-hemisphere").run_warp(&g);
    o.assert_passed();
    assert!(
        o.dof >= 100,
        "the lobe covers too few cells: {}",
        o.report()
    );
}

/// A Phong-like lobe about a reflected direction 60° off the pole (exponent 10³), tested in
/// a cap about that direction.
#[test]
fn reflected_lobe_off_the_pole() {
    let lobe = PowerCosineHemisphere::new(1000.0).expect("valid exponent");
    let r = Vec3::new(60f32.to_radians().sin(), 0.0, 60f32.to_radians().cos());
    let (t, b) = r.any_orthonormal_pair();
    let to_world = |w: Vec3| t * w.x + b * w.y + r * w.z;
    let to_local = |w: Vec3| Vec3::new(w.dot(t), w.dot(b), w.dot(r));
    let domain = Directions::cap(r, 8.0 / 1001f32.sqrt())
        .resolution(61, 64)
        .refinement(1.5);
    let o = chi2(domain, "PowerCosine-reflected")
        .run(|u| to_world(lobe.sample(u)), |w| lobe.pdf(to_local(w)));
    o.assert_passed();
    assert!(o.dof >= 100, "{}", o.report());
}
