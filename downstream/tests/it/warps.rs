//! Warps as a user calls them, through the crate-root re-exports: each sample's density
//! agrees with `pdf`, the inverse gives `u` back, `pdf · J = 1`, and the density integrates to
//! 1 over its domain. Then a latitude–longitude sky: directions drawn through
//! `PiecewiseConstant2D` and `LatLong`, their density per steradian against the lookup at
//! the inverse, its integral over the sphere, and an importance-sampled estimate of the sky's
//! power against the exact texel sum.
//!
//! Tolerances: `invert(sample(u)) = u` within 2·10⁻⁴ (directions near a pole lose a few
//! digits of `u`; a wrong inverse is off by far more), `sample_with_pdf` against `pdf` within
//! 10⁻⁵ relative (the same `f32` formula, evaluated once more), `|∫ pdf − 1| ≤ 10⁻³` (mcrt's
//! quadrature, as the workspace suite), `pdf · J = 1` within mcrt's default 10⁻². Every
//! compared value is checked finite first.

#![forbid(unsafe_code)]

use mcrt::glam::{Vec2, Vec3};
use mcrt::stats::{
    check_integral, check_warp_inverse, check_warp_jacobian, Directions, JacobianCheck, Rectangle,
};
use mcrt::{
    CosineHemisphere, Exponential, Frame, Ggx, HenyeyGreenstein, IndependentSampler,
    InvertibleWarp, LatLong, PowerCosineHemisphere, SampleSource, Sampler, Tent, UniformCone,
    UniformDisk, UniformDiskConcentric, UniformHemisphere, UniformSphere, UniformTriangle,
    VonMisesFisher, Warp, Warp1D,
};
use mcrt_downstream::Sky;

/// A `n × n` grid of cell centres in `[0, 1)²`.
fn grid(n: usize) -> impl Iterator<Item = Vec2> {
    (0..n * n).map(move |k| {
        Vec2::new(
            ((k % n) as f32 + 0.5) / n as f32,
            ((k / n) as f32 + 0.5) / n as f32,
        )
    })
}

/// `sample_with_pdf` against `sample` and `pdf`, on a grid: the same point, a finite
/// positive density, the same density.
fn check_sample_with_pdf<W>(name: &str, warp: &W, close: impl Fn(W::Point, W::Point) -> bool)
where
    W: Warp,
    W::Point: std::fmt::Debug,
{
    for u in grid(32) {
        let (p, pdf) = warp.sample_with_pdf(u);
        let again = warp.pdf(p);
        assert!(
            close(p, warp.sample(u)),
            "{name}: sample_with_pdf({u}) moved the point"
        );
        assert!(pdf.is_finite() && pdf > 0.0, "{name}: pdf {pdf} at {u}");
        assert!(
            again.is_finite() && (again - pdf).abs() <= 1e-5 * pdf,
            "{name}: {pdf} from sample_with_pdf, {again} from pdf at {p:?}"
        );
    }
}

/// The checks of a warp to directions: unit length, the density, the inverse, the Jacobian,
/// the integral over the sphere.
fn check_directions<W: InvertibleWarp<Point = Vec3> + Sync>(name: &str, warp: &W) {
    for u in grid(32) {
        let w = warp.sample(u);
        let len = w.length();
        assert!(
            len.is_finite() && (len - 1.0).abs() <= 1e-5,
            "{name}: |{w}| = {len}"
        );
    }
    check_sample_with_pdf(name, warp, |a, b| a == b);
    let inverse = check_warp_inverse(warp, 64, 2e-4);
    assert!(inverse.passed(), "{name}: {}", inverse.report());
    let jacobian = check_warp_jacobian(warp, JacobianCheck::default());
    assert!(jacobian.passed(), "{name}: {}", jacobian.report());
    let integral = check_integral(
        &Directions::sphere().resolution(64, 128),
        |w| warp.pdf(w),
        1e-3,
    );
    assert!(integral.passed(), "{name}: {}", integral.report());
}

/// The same for a warp to the plane, with the domain of its integral.
fn check_plane<W: InvertibleWarp<Point = Vec2> + Sync>(name: &str, warp: &W, domain: Rectangle) {
    check_sample_with_pdf(name, warp, |a, b| a == b);
    let inverse = check_warp_inverse(warp, 64, 2e-4);
    assert!(inverse.passed(), "{name}: {}", inverse.report());
    let jacobian = check_warp_jacobian(warp, JacobianCheck::default());
    assert!(jacobian.passed(), "{name}: {}", jacobian.report());
    let integral = check_integral(&domain, |p| warp.pdf(p), 1e-3);
    assert!(integral.passed(), "{name}: {}", integral.report());
}

#[test]
fn direction_warps_have_their_pdfs_and_inverses() {
    check_directions("cosine hemisphere", &CosineHemisphere);
    check_directions("uniform hemisphere", &UniformHemisphere);
    check_directions("uniform sphere", &UniformSphere);
    check_directions("cone 60°", &UniformCone::new(0.5).expect("a valid cone"));
    check_directions(
        "power cosine n = 10",
        &PowerCosineHemisphere::new(10.0).expect("a valid exponent"),
    );
    check_directions("GGX α = 0.5", &Ggx::new(0.5).expect("a valid roughness"));
    check_directions(
        "Henyey-Greenstein g = 0.3",
        &HenyeyGreenstein::new(0.3).expect("a valid g"),
    );
    check_directions(
        "von Mises-Fisher κ = 5",
        &VonMisesFisher::new(5.0).expect("a valid κ"),
    );
}

#[test]
fn planar_warps_have_their_pdfs_and_inverses() {
    let square = Rectangle::new(Vec2::splat(-1.0), Vec2::splat(1.0), 64, 64);
    check_plane("uniform disk", &UniformDisk, square.clone());
    check_plane("concentric disk", &UniformDiskConcentric, square);
    // Barycentric coordinates, density 2 on the reference triangle.
    check_plane(
        "uniform triangle",
        &UniformTriangle,
        Rectangle::unit_square(64),
    );
}

#[test]
fn one_dimensional_warps_have_their_pdfs_and_inverses() {
    let tent = Tent::new(2.0).expect("a valid radius");
    let exponential = Exponential::new(1.5).expect("a valid rate");
    let warps: [(&str, &dyn Warp1D, f32, f32); 2] = [
        ("tent r = 2", &tent, -2.0, 2.0),
        // Beyond x = 20 the density is below 10⁻¹³.
        ("exponential λ = 1.5", &exponential, 0.0, 20.0),
    ];
    for (name, warp, lo, hi) in warps {
        for k in 0..1000 {
            let u = (k as f32 + 0.5) / 1000.0;
            let (x, pdf) = warp.sample_with_pdf(u);
            assert!(
                x.is_finite() && (lo..=hi).contains(&x),
                "{name}: {u} -> {x}"
            );
            assert!(pdf.is_finite() && pdf > 0.0, "{name}: pdf {pdf} at {x}");
            let again = warp.pdf(x);
            assert!(
                again.is_finite() && (again - pdf).abs() <= 1e-5 * pdf,
                "{name}: {again}"
            );
            let back = warp.invert(x);
            assert!(
                back.is_finite() && (back - u).abs() <= 2e-4,
                "{name}: {u} -> {back}"
            );
        }
        // Midpoint rule over the support.
        let n = 200_000;
        let h = f64::from(hi - lo) / n as f64;
        let integral: f64 = (0..n)
            .map(|k| f64::from(warp.pdf(lo + ((k as f64 + 0.5) * h) as f32)) * h)
            .sum();
        assert!(
            integral.is_finite() && (integral - 1.0).abs() <= 1e-3,
            "{name}: ∫ pdf = {integral}"
        );
    }
}

/// The sky of these tests: 64 × 32 texels, the sun at u = 0.3.
fn sky() -> Sky {
    Sky::procedural(64, 32, 0.3).expect("a valid sky")
}

/// Directions drawn from the sky's table: unit, with a finite positive density per
/// steradian equal to the one looked up at the direction's inverse (away from the poles and
/// the seam, where neighbouring texels may be picked), proportional to the texel's radiance
/// per unit solid angle, and turned about a frame as a renderer would.
#[test]
fn sky_directions_have_consistent_solid_angle_pdfs() {
    let sky = sky();
    let [w, h] = sky.size();
    let mean_weight = sky.summed_area_table().integral(Vec2::ZERO, Vec2::ONE);
    assert!(
        mean_weight.is_finite() && mean_weight > 0.0,
        "{mean_weight}"
    );
    let frame = Frame::from_normal(Vec3::new(0.0, 0.6, 0.8));
    for u in grid(256) {
        let (dir, pdf) = sky.sample(u);
        let len = dir.length();
        assert!(
            len.is_finite() && (len - 1.0).abs() <= 1e-5,
            "|{dir}| = {len}"
        );
        assert!(pdf.is_finite() && pdf > 0.0, "pdf {pdf} at {u}");

        let (uv, pdf_uv) = sky.table().sample_with_pdf(u);
        assert_eq!(LatLong.sample(uv), dir, "at {u}");
        let sin_theta = LatLong::sin_theta(dir);
        let on_edge = sin_theta < 1e-3 || uv.x < 1e-4 || uv.x > 1.0 - 1e-4;
        let looked_up = sky.pdf(dir);
        assert!(
            looked_up.is_finite() && looked_up > 0.0,
            "{dir}: {looked_up}"
        );
        assert!(
            on_edge || (looked_up - pdf).abs() <= 1e-4 * pdf,
            "{dir}: sampled {pdf}, looked up {looked_up}"
        );

        // The table's density is the texel's weight (radiance × sin θ at its centre) over
        // the mean weight, and per steradian that is the radiance over the power, up to
        // sin θ / sin θ_centre.
        let [i, j] = sky.texel(uv);
        let theta_c = std::f32::consts::PI * (j as f32 + 0.5) / h as f32;
        let weight = sky.texel_radiance([i, j]) * theta_c.sin();
        let expected_uv = f64::from(weight) / mean_weight;
        assert!(
            (f64::from(pdf_uv) - expected_uv).abs() <= 1e-4 * expected_uv,
            "texel ({i}, {j}) of {w} × {h}: {pdf_uv} vs {expected_uv}"
        );

        // In a shading frame the density per steradian is unchanged (a rotation).
        let local = frame.to_local(dir);
        let back = frame.to_world(local);
        assert!((back - dir).length() <= 1e-5, "{dir} -> {local} -> {back}");
    }
}

/// `∫ pdf dω = 1` over the sphere: the density per steradian carries LatLong's Jacobian
/// `2π² sin θ`. The midpoint rule in `(θ, φ)` on a 512 × 1024 grid (16 × 16 points per
/// texel, so no point falls on a texel's edge): `pdf · sin θ` is constant in each texel, so
/// the sum is exact up to rounding (tolerance 10⁻⁴); a density off by `sin θ` or by `2π²`
/// fails by far more. (mcrt's own quadrature checks the same integral in `tests/it/chi2.rs`.)
#[test]
fn sky_pdf_integrates_to_one_over_the_sphere() {
    use std::f64::consts::{PI, TAU};
    let sky = sky();
    let (rows, cols) = (512, 1024);
    let (d_theta, d_phi) = (PI / rows as f64, TAU / cols as f64);
    let mut integral = 0.0f64;
    for j in 0..rows {
        let theta = (j as f64 + 0.5) * d_theta;
        for i in 0..cols {
            let phi = (i as f64 + 0.5) * d_phi;
            // LatLong's axes: +y up, φ = 0 toward −z, φ = π/2 toward +x.
            let dir = Vec3::new(
                (theta.sin() * phi.sin()) as f32,
                theta.cos() as f32,
                (-theta.sin() * phi.cos()) as f32,
            );
            let pdf = sky.pdf(dir);
            assert!(pdf.is_finite() && pdf > 0.0, "{dir}: {pdf}");
            integral += f64::from(pdf) * theta.sin() * d_theta * d_phi;
        }
    }
    assert!(
        integral.is_finite() && (integral - 1.0).abs() <= 1e-4,
        "∫ pdf dω = {integral}"
    );
}

/// Importance sampling the sky estimates its power `∫ L dω` (the exact texel sum), and the
/// fraction of directions above the horizon matches the table's mass there (from the
/// summed-area table). 2¹⁸ i.i.d. samples from an `IndependentSampler` with a fixed seed
/// (not a midpoint grid: the integrand jumps at texel edges, so a deterministic grid's error
/// is not bounded by the standard error); the tolerance is four standard errors plus 10⁻⁵
/// relative for `f32` rounding.
#[test]
fn sky_importance_sampling_estimates_its_power() {
    let sky = sky();
    let exact = sky.power();
    assert!(exact.is_finite() && exact > 0.0, "{exact}");
    const N: u32 = 1 << 18;
    let mut sampler = IndependentSampler::new(N, 2026).expect("a valid sampler");
    let (mut sum, mut sum_sq, mut above, mut n) = (0.0f64, 0.0f64, 0u32, 0u32);
    for i in 0..N {
        sampler.start_pixel_sample([0, 0], i);
        let u = sampler.next_2d();
        let (dir, pdf) = sky.sample(u);
        assert!(pdf.is_finite() && pdf > 0.0, "{u}: {pdf}");
        let f = f64::from(sky.radiance(dir)) / f64::from(pdf);
        sum += f;
        sum_sq += f * f;
        above += u32::from(dir.y > 0.0);
        n += 1;
    }
    let n = f64::from(n);
    let mean = sum / n;
    let se = ((sum_sq / n - mean * mean).max(0.0) / (n - 1.0)).sqrt();
    assert!(mean.is_finite() && se.is_finite(), "{mean} ± {se}");
    assert!(
        (mean - exact).abs() <= 4.0 * se + 1e-5 * exact,
        "{mean} ± {se} against {exact}"
    );

    // The upper half of the image (v < ½) is the sky above the horizon.
    let sat = sky.summed_area_table();
    let mass = sat.integral(Vec2::ZERO, Vec2::new(1.0, 0.5)) / sat.integral(Vec2::ZERO, Vec2::ONE);
    let fraction = f64::from(above) / n;
    let se = (mass * (1.0 - mass) / n).sqrt();
    assert!(mass.is_finite() && mass > 0.0 && mass < 1.0, "{mass}");
    assert!(
        (fraction - mass).abs() <= 4.0 * se + 1e-6,
        "{fraction} above the horizon, table mass {mass} (± {se})"
    );
}
