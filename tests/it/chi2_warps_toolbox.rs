//! The sampling toolbox of issue 15 (1D densities, bilinear, Box–Muller, Henyey–Greenstein,
//! von Mises–Fisher, the low-distortion triangle), at several parameters including the
//! extremes, against their own pdfs: chi-square (which includes `|∫ pdf − 1| ≤ 10⁻³`), the
//! Jacobian identity, and the inverse round trip. Settings in `tests/it/common/mod.rs`; the runs
//! are counted in `docs/testing.md`.

use crate::common;

use common::{chi2, sphere};
use mcrt::glam::{Vec2, Vec3};
use mcrt::sampling::warp::*;
use mcrt::stats::{
    check_inverse, check_jacobian, check_warp_inverse, check_warp_jacobian, Directions, Domain,
    Interval, JacobianCheck, Rectangle, StatPoint,
};

/// Samples per chi-square run of this file: the toolbox's densities are smooth and tested
/// on 100–2500 cells, where 2·10⁵ samples resolve a 2 % error in any cell.
const SAMPLES: usize = 200_000;

/// Collects the reports of failed checks, so that one test shows every failing parameter.
#[derive(Default)]
struct Failures(Vec<String>);

impl Failures {
    fn push(&mut self, name: &str, passed: bool, report: String) {
        if !passed {
            self.0.push(format!("{name}: {report}"));
        }
    }

    fn finish(self) {
        assert!(
            self.0.is_empty(),
            "{} check(s) failed:\n{}",
            self.0.len(),
            self.0.join("\n")
        );
    }
}

fn jac(step: f64) -> JacobianCheck {
    JacobianCheck {
        step,
        ..common::jacobian()
    }
}

/// Settings for a lobe of angular width `width` on the sphere: below 0.05 rad the `f32`
/// rounding of the directions' z over a step of 2⁻⁹ approaches the tolerance, so the step is
/// 2⁻⁷ (as for the spherical polygons in `chi2_warps`), and up to a quarter of the lattice may
/// be skipped as points where `J(h)` and `J(2h)` disagree: the heavy tail of Henyey–Greenstein
/// at `|g| = 0.999` makes the map steep for `u₁ > 0.9` (1 − cos θ grows from 5·10⁻⁵ to 2), and
/// the von Mises–Fisher map is logarithmic in `1 − u₁`.
fn lobe_jac(width: f64) -> JacobianCheck {
    if width < 0.05 {
        JacobianCheck {
            max_skipped: 0.25,
            ..jac(1.0 / 128.0)
        }
    } else {
        common::jacobian()
    }
}

/// Chi-square over `domain`, the Jacobian `|dx/du| · pdf = 1` and the round trip
/// `invert(sample(u)) = u` (to `inv_tol`) of a 1D warp.
fn check_1d<W: Warp1D + Sync>(f: &mut Failures, name: &str, w: &W, domain: Interval, inv_tol: f64) {
    let o = chi2(domain, name)
        .samples(SAMPLES)
        .run(|u| w.sample(u.x), |x| w.pdf(x));
    f.push(name, o.passed(), o.report());
    let j = check_jacobian(
        |u| w.sample(u.x),
        |x| w.pdf(x),
        jac(common::jacobian().step),
    );
    f.push(name, j.passed(), j.report());
    let i = check_inverse(
        |u| w.sample(u.x),
        |x| Vec2::new(w.invert(x), 0.5),
        1,
        256,
        inv_tol,
    );
    f.push(name, i.passed(), i.report());
}

/// The same for a warp from the square.
fn check_2d<W, D>(
    f: &mut Failures,
    name: &str,
    w: &W,
    domain: D,
    settings: JacobianCheck,
    inv_tol: f64,
) where
    W: InvertibleWarp + Sync,
    W::Point: StatPoint,
    D: Domain<Point = W::Point>,
{
    let o = chi2(domain, name).samples(SAMPLES).run_warp(w);
    f.push(name, o.passed(), o.report());
    let j = check_warp_jacobian(w, settings);
    f.push(name, j.passed(), j.report());
    let i = check_warp_inverse(w, 64, inv_tol);
    f.push(name, i.passed(), i.report());
}

#[test]
fn linear_and_bilinear() {
    let mut f = Failures::default();
    for (a, b) in [(0.0, 1.0), (1.0, 0.0), (1.0, 1.0), (1e-30, 1e30)] {
        let w = Linear::new(a, b).expect("valid");
        check_1d(
            &mut f,
            &format!("Linear-{a:e}-{b:e}"),
            &w,
            Interval::new(0.0, 1.0, 100),
            1e-4,
        );
    }
    for corners in [
        [1.0, 2.0, 3.0, 4.0],
        [0.0, 0.0, 0.0, 1.0],
        [1e-20, 1.0, 1.0, 1e-20],
    ] {
        let w = Bilinear::new(corners).expect("valid");
        let name = format!("Bilinear-{corners:?}");
        check_2d(
            &mut f,
            &name,
            &w,
            Rectangle::unit_square(32),
            common::jacobian(),
            1e-4,
        );
    }
    f.finish();
}

#[test]
fn tent_exponential_smoothstep() {
    let mut f = Failures::default();
    for r in [1e-20f32, 1.0, 1e20] {
        let w = Tent::new(r).expect("valid");
        check_1d(
            &mut f,
            &format!("Tent-{r:e}"),
            &w,
            Interval::new(-f64::from(r), f64::from(r), 100),
            1e-4,
        );
    }
    for rate in [1e-20f32, 1.0, 1e20] {
        let w = Exponential::new(rate).expect("valid");
        let top = 17.0 / f64::from(rate);
        check_1d(
            &mut f,
            &format!("Exponential-{rate:e}"),
            &w,
            Interval::new(0.0, top, 170),
            1e-4,
        );
    }
    // A steep rate on [0, 3], where f32 resolves the lobe at the peak end (near −1, its
    // 10⁻³ width would be only 8000 f32 steps).
    for (rate, min, max) in [
        (5.0f32, -1.0, 2.0),
        (-5.0, -1.0, 2.0),
        (1e-6, -1.0, 2.0),
        (1e3, 0.0, 3.0),
    ] {
        let w = TruncatedExponential::new(rate, min, max).expect("valid");
        let name = format!("TruncatedExponential-{rate:e}");
        let cells = if rate.abs() > 100.0 { 3000 } else { 150 };
        let domain = Interval::new(f64::from(min), f64::from(max), cells);
        check_1d(&mut f, &name, &w, domain, 1e-4);
    }
    let w = Smoothstep::new(-1.0, 3.0).expect("valid");
    check_1d(
        &mut f,
        "Smoothstep",
        &w,
        Interval::new(-1.0, 3.0, 100),
        1e-4,
    );
    f.finish();
}

#[test]
fn normal_and_logistic() {
    let mut f = Failures::default();
    // Extreme scales about 0: a scale far below the f32 spacing at the mean cannot be
    // resolved (the property tests hold those to f32's resolution instead).
    for (mean, sigma) in [(0.0f32, 1.0f32), (0.0, 1e-30), (-2.0, 1e30)] {
        let w = Normal::new(mean, sigma).expect("valid");
        let (m, s) = (f64::from(mean), f64::from(sigma));
        let domain = Interval::new(m - 15.0 * s, m + 6.0 * s, 210);
        check_1d(
            &mut f,
            &format!("Normal-{mean}-{sigma:e}"),
            &w,
            domain,
            1e-4,
        );
    }
    let n2 = Normal2D::new(Vec2::new(1.0, -2.0), 0.5).expect("valid");
    let box_domain = Rectangle::new(Vec2::new(-2.0, -5.0), Vec2::new(4.0, 1.0), 48, 48);
    check_2d(
        &mut f,
        "Normal2D",
        &n2,
        box_domain,
        common::jacobian(),
        1e-4,
    );
    for (mean, scale) in [(0.0f32, 1.0f32), (0.0, 1e-30), (3.0, 1e30)] {
        let w = Logistic::new(mean, scale).expect("valid");
        let (m, s) = (f64::from(mean), f64::from(scale));
        let domain = Interval::new(m - 104.0 * s, m + 17.0 * s, 242);
        check_1d(
            &mut f,
            &format!("Logistic-{mean}-{scale:e}"),
            &w,
            domain,
            1e-4,
        );
    }
    for (min, max) in [(-1.0f32, 1.0f32), (20.0, 30.0), (-30.0, -20.0)] {
        let w = TrimmedLogistic::new(0.0, 1.0, min, max).expect("valid");
        let domain = Interval::new(f64::from(min), f64::from(max), 100);
        check_1d(
            &mut f,
            &format!("TrimmedLogistic-{min}-{max}"),
            &w,
            domain,
            1e-4,
        );
    }
    f.finish();
}

/// A cap about `axis` wide enough for a lobe of angular width `width`; the sphere when wide.
fn lobe(axis: Vec3, width: f64) -> Directions {
    let theta = 8.0 * width;
    if theta >= 1.5 {
        sphere()
    } else {
        Directions::cap(axis, theta as f32)
            .resolution(61, 64)
            .refinement(1.5)
    }
}

#[test]
fn henyey_greenstein() {
    let mut f = Failures::default();
    for g in [-0.999f32, -0.5, 0.0, 0.3, 0.9, 0.999] {
        let w = HenyeyGreenstein::new(g).expect("valid");
        let axis = if g < 0.0 { -Vec3::Z } else { Vec3::Z };
        let width = 1.0 - f64::from(g.abs());
        let name = format!("HenyeyGreenstein-{g}");
        check_2d(&mut f, &name, &w, lobe(axis, width), lobe_jac(width), 1e-3);
    }
    f.finish();
}

#[test]
fn von_mises_fisher() {
    let mut f = Failures::default();
    for kappa in [0.0f32, 1e-6, 1.0, 100.0, 1e4] {
        let w = VonMisesFisher::new(kappa).expect("valid");
        let width = 1.0 / f64::from(kappa).max(1e-3).sqrt();
        let name = format!("VonMisesFisher-{kappa:e}");
        check_2d(
            &mut f,
            &name,
            &w,
            lobe(Vec3::Z, width),
            lobe_jac(width),
            1e-3,
        );
    }
    f.finish();
}

#[test]
fn low_distortion_triangle() {
    let mut f = Failures::default();
    let d = Rectangle::unit_square(48);
    // The map is piecewise linear with a seam on the diagonal u₁ = u₂ (skipped by the
    // Jacobian check as a point where J(h) and J(2h) disagree).
    let t = LowDistortionTriangle;
    check_2d(
        &mut f,
        "LowDistortionTriangle",
        &t,
        d,
        common::jacobian(),
        1e-6,
    );
    f.finish();
}

/// Bilinear patches: a planar trapezoid (not a parallelogram, so sampled through the bilinear
/// corner weights) by chi-square in its plane; a twisted quad (one corner lifted) and a
/// parallelogram by the Jacobian identity with the area element `|∂p/∂u₁ × ∂p/∂u₂|` (which,
/// the map being one-to-one from the square, also proves `∫ pdf dA = 1`); all by the round trip.
#[test]
fn bilinear_patches() {
    let mut f = Failures::default();
    let trapezoid = [
        Vec3::ZERO,
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.5, 1.0, 0.0),
        Vec3::new(1.2, 1.0, 0.0),
    ];
    let q = BilinearPatch::new(trapezoid).expect("valid patch");
    let domain = Rectangle::new(Vec2::ZERO, Vec2::new(2.0, 1.0), 64, 32);
    let o = chi2(domain, "BilinearPatch-trapezoid")
        .samples(SAMPLES)
        .run(|u| q.sample(u).truncate(), |p| q.pdf(p.extend(0.0)));
    f.push("BilinearPatch-trapezoid", o.passed(), o.report());
    let twisted = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(1.3, 0.9, 0.8)];
    let parallelogram = [
        Vec3::ZERO,
        Vec3::new(1.0, 0.0, 0.5),
        Vec3::Y,
        Vec3::new(1.0, 1.0, 0.5),
    ];
    for (name, corners) in [
        ("BilinearPatch-trapezoid", trapezoid),
        ("BilinearPatch-twisted", twisted),
        ("BilinearPatch-parallelogram", parallelogram),
    ] {
        let q = BilinearPatch::new(corners).expect("valid patch");
        let j = check_warp_jacobian(&q, common::jacobian());
        f.push(name, j.passed(), j.report());
        let i = check_warp_inverse(&q, 64, 1e-4);
        f.push(name, i.passed(), i.report());
    }
    f.finish();
}

/// A cap about the mean direction of `points` seen from `origin`, 1.3 × the widest angle (as
/// `chi2_warps` tests the uniform spherical triangles).
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

/// Cosine-weighted spherical triangles: a normal facing the triangle, one nearly edge-on to it
/// (two corner cosines near 0, floored at 1 %), on the near and far (area fallback) cases;
/// the Jacobian with step 2⁻⁷ as for the uniform spherical triangles.
#[test]
fn cosine_spherical_triangles() {
    let mut f = Failures::default();
    let o = Vec3::new(0.1, -0.2, 0.0);
    let near = [
        Vec3::new(-1.0, -1.0, 0.5),
        Vec3::new(1.5, -1.0, 0.5),
        Vec3::new(0.0, 1.0, 0.8),
    ];
    let far = [
        Vec3::new(3.0, 0.0, 10.0),
        Vec3::new(3.1, 0.0, 10.0),
        Vec3::new(3.0, 0.1, 10.0),
    ];
    for (tag, tri, normal) in [
        ("near-facing", near, Vec3::Z),
        ("near-grazing", near, Vec3::new(1.0, 0.3, 0.05)),
        ("far", far, Vec3::new(0.2, 0.1, 1.0)),
    ] {
        let name = format!("CosineSphericalTriangle-{tag}");
        let [a, b, c] = tri;
        let t = CosineSphericalTriangle::new(o, a, b, c, normal).expect("valid triangle");
        check_2d(
            &mut f,
            &name,
            &t,
            cap_around(o, &tri),
            jac(1.0 / 128.0),
            1e-3,
        );
    }
    f.finish();
}
