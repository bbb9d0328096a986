//! Property tests of the toolbox warps of issue 15 (linear, bilinear, tent, exponential,
//! normal, Box–Muller, logistic, smoothstep, Henyey–Greenstein, von Mises–Fisher, the
//! low-distortion triangle): finiteness, support, pdf > 0 at samples, `sample_with_pdf`
//! consistency and the inverse round trip, for u drawn freely and pinned to the edges
//! {0, 0.5, 1 − 2⁻²⁴}, at parameters that include the extremes each constructor accepts; and
//! pdf and invert of arbitrary finite points never NaN.
//!
//! Round-trip tolerance in u: `4·10⁻⁶` (64 ulps of 1, as `warp_properties_basic`) plus what the
//! `f32` rounding of the sample allows: for the 1D warps, twice the span of u that the two f32
//! neighbours of x cover (`invert(x⁺) − invert(x⁻)`), since a smoothstep on
//! `[1, 1 + 10⁻⁶]` or a normal of σ = 1 about 10³⁰ is quantised by f32 itself, not by the warp.

use crate::props;
use mcrt::glam::{Vec2, Vec3};
use mcrt::sampling::warp::*;
use mcrt::sampling::ONE_MINUS_EPSILON as ONE_MINUS;
use props::{config, coord, u_any};
use proptest::prelude::*;

const RT_TOL: f64 = 4e-6;

/// Every property of a 1D warp at one u; `support` is closed, `zero_ok(x)` tells where the
/// density may vanish (an end where it is 0).
fn check_1d<W: Warp1D>(
    name: &str,
    w: &W,
    support: (f32, f32),
    zero_ok: impl Fn(f32) -> bool,
    u: f32,
) -> Result<(), TestCaseError> {
    let x = w.sample(u);
    prop_assert!(x.is_finite(), "{name}: sample({u}) = {x}");
    prop_assert!(
        x >= support.0 && x <= support.1,
        "{name}: sample({u}) = {x} outside"
    );
    let pdf = w.pdf(x);
    prop_assert!(pdf.is_finite() && pdf >= 0.0, "{name}: pdf {pdf} at {x}");
    prop_assert!(
        pdf > 0.0 || zero_ok(x),
        "{name}: pdf 0 at sample {x} (u = {u})"
    );
    let (x2, pdf2) = w.sample_with_pdf(u);
    prop_assert!(x2 == x && pdf2.is_finite() && (pdf2 - pdf).abs() <= 1e-5 * pdf);
    let back = w.invert(x);
    prop_assert!(
        back.is_finite() && (0.0..1.0).contains(&back),
        "{name}: invert {back}"
    );
    // The u that the neighbouring f32 values of x cover: the resolution f32 allows at x.
    let cell = f64::from((w.invert(x.next_up()) - w.invert(x.next_down())).abs());
    let tol = RT_TOL + 2.0 * cell;
    let err = f64::from((back - u).abs());
    prop_assert!(
        err <= tol,
        "{name}: invert(sample({u})) = {back} (x = {x}, tol {tol})"
    );
    Ok(())
}

/// Every property of a warp onto the sphere at one u.
fn check_sphere<W: InvertibleWarp<Point = Vec3>>(
    name: &str,
    w: &W,
    u: Vec2,
) -> Result<(), TestCaseError> {
    let d = w.sample(u);
    prop_assert!(d.is_finite(), "{name}: sample({u}) = {d}");
    prop_assert!(
        (d.length() - 1.0).abs() <= 1e-5,
        "{name}: |sample({u})| = {}",
        d.length()
    );
    let pdf = w.pdf(d);
    prop_assert!(
        pdf.is_finite() && pdf > 0.0,
        "{name}: pdf {pdf} at {d} (u = {u})"
    );
    let (d2, pdf2) = w.sample_with_pdf(u);
    prop_assert!(d2 == d && pdf2.is_finite() && (pdf2 - pdf).abs() <= 1e-5 * pdf);
    let back = w.invert(d);
    prop_assert!(back.is_finite() && back.min_element() >= 0.0 && back.max_element() < 1.0);
    if u.min_element() >= 1e-3 && u.max_element() <= 1.0 - 1e-3 {
        let e1 = f64::from((back.x - u.x).abs());
        let d2 = f64::from((back.y - u.y).abs());
        let e2 = d2.min(1.0 - d2);
        prop_assert!(
            e1 <= 1e-4 && e2 <= RT_TOL,
            "{name}: invert(sample({u})) = {back}"
        );
    }
    Ok(())
}

/// Every property of a warp onto the plane at one u; `inside(p)` is the support,
/// `zero_ok(p)` where the density may vanish.
fn check_plane<W: InvertibleWarp<Point = Vec2>>(
    name: &str,
    w: &W,
    inside: impl Fn(Vec2) -> bool,
    zero_ok: impl Fn(Vec2) -> bool,
    u: Vec2,
    periodic_u2: bool,
) -> Result<(), TestCaseError> {
    let p = w.sample(u);
    prop_assert!(p.is_finite() && inside(p), "{name}: sample({u}) = {p}");
    let pdf = w.pdf(p);
    prop_assert!(
        pdf.is_finite() && pdf >= 0.0 && (pdf > 0.0 || zero_ok(p)),
        "{name}: pdf {pdf} at {p}"
    );
    let back = w.invert(p);
    prop_assert!(back.is_finite() && back.min_element() >= 0.0 && back.max_element() < 1.0);
    if u.min_element() >= 1e-3 && u.max_element() <= 1.0 - 1e-3 {
        let e1 = f64::from((back.x - u.x).abs());
        let mut e2 = f64::from((back.y - u.y).abs());
        if periodic_u2 {
            e2 = e2.min(1.0 - e2);
        }
        prop_assert!(
            e1 <= 1e-5 && e2 <= 1e-5,
            "{name}: invert(sample({u})) = {back}"
        );
    }
    Ok(())
}

fn linears() -> Vec<Linear> {
    [
        (0.0, 1.0),
        (1.0, 0.0),
        (1.0, 1.0),
        (0.0, f32::MAX),
        (1e-45, 1.0),
        (f32::MAX, f32::MIN_POSITIVE),
    ]
    .iter()
    .map(|&(a, b)| Linear::new(a, b).expect("valid"))
    .collect()
}

proptest! {
    #![proptest_config(config(1024))]

    #[test]
    fn linear_tent_exponential(u in coord()) {
        for l in linears() {
            check_1d("linear", &l, (0.0, 1.0), |x| x == 0.0 || x == 1.0, u)?;
        }
        for r in [3e-39f32, 1.0, f32::MAX] {
            let t = Tent::new(r).expect("valid");
            check_1d(&format!("tent {r:e}"), &t, (-r, r), |x| x.abs() == r, u)?;
        }
        for rate in [5e-38f32, 1.0, f32::MAX] {
            let e = Exponential::new(rate).expect("valid");
            // The pdf underflows f32 where λx > 103 + ln λ: never for u ≤ 1 − 2⁻²⁴ (λx ≤ 16.7).
            check_1d(&format!("exponential {rate:e}"), &e, (0.0, f32::MAX), |_| false, u)?;
        }
        for (rate, min, max) in [
            (f32::MAX, 0.0f32, 1.0f32), (-1e4, 0.0, 1.0), (0.0, -1.0, 1.0), (1e-30, -1e30, 1e30),
            (1.0, -f32::MAX, f32::MAX),
        ] {
            let e = TruncatedExponential::new(rate, min, max).expect("valid");
            // Only the far end of a steep rate may underflow to 0.
            let steep = rate.abs() * (max - min) > 80.0;
            check_1d(&format!("truncated exponential {rate:e}"), &e, (min, max), |_| steep, u)?;
        }
    }

    #[test]
    fn normal_logistic_smoothstep(u in coord()) {
        for (mean, sigma) in [(0.0f32, 1.0f32), (0.0, 1e-38), (0.0, 1e36), (1e30, 1.0), (-7.0, 1e-6)] {
            let n = Normal::new(mean, sigma).expect("valid");
            // The density may underflow f32 in the far tail of a wide normal.
            let tiny = move |x: f32| {
                let z = (f64::from(x) - f64::from(mean)) / f64::from(sigma);
                (-0.5 * z * z).exp() / f64::from(sigma) < 1e-44
            };
            check_1d(&format!("normal {mean} {sigma:e}"), &n, (-f32::MAX, f32::MAX), tiny, u)?;
        }
        for (mean, scale) in [(0.0f32, 1.0f32), (0.0, 1e-37), (0.0, 1e35), (-1e30, 1.0)] {
            let l = Logistic::new(mean, scale).expect("valid");
            let tiny = move |x: f32| {
                let z = (f64::from(x) - f64::from(mean)) / f64::from(scale);
                (-z.abs()).exp() / f64::from(scale) < 1e-44
            };
            check_1d(&format!("logistic {mean} {scale:e}"), &l, (-f32::MAX, f32::MAX), tiny, u)?;
        }
        for (mean, scale, min, max) in [
            (0.0f32, 1.0f32, -1.0f32, 1.0f32), (0.0, 1.0, 600.0, 700.0), (0.0, 1.0, -700.0, -600.0),
            (0.0, 1e-30, -1.0, 1.0), (0.0, 1.0, 0.0, 1e-30), (5.0, 2.0, -f32::MAX, f32::MAX),
        ] {
            let t = TrimmedLogistic::new(mean, scale, min, max).expect("valid");
            // A logistic of scale 10⁻³⁰ trimmed to [−1, 1] underflows away from its mean.
            let tails = scale < 1e-20 || max - min > 1e30;
            check_1d(&format!("trimmed logistic {min} {max}"), &t, (min, max), |_| tails, u)?;
        }
        for (min, max) in [(0.0f32, 1.0f32), (-f32::MAX, f32::MAX), (1.0, 1.000_001), (-1e-38, 1e-38)] {
            let s = Smoothstep::new(min, max).expect("valid");
            // The density is 0 at min, and underflows f32 within ~10⁻²² of it.
            let near_min = move |x: f32| f64::from(x) - f64::from(min) <= 1e-20 * (f64::from(max) - f64::from(min));
            check_1d(&format!("smoothstep {min} {max}"), &s, (min, max), near_min, u)?;
        }
    }

    #[test]
    fn bilinear_and_box_muller(u in u_any()) {
        for corners in [[1.0f32, 1.0, 1.0, 1.0], [0.0, 0.0, 0.0, 1.0], [f32::MAX, 0.0, 0.0, 0.0], [1e-45, 1.0, 1.0, 1e-45]] {
            let b = Bilinear::new(corners).expect("valid");
            let unit = |p: Vec2| p.min_element() >= 0.0 && p.max_element() <= 1.0;
            let edge = |p: Vec2| p.min_element() <= 1e-6 || p.max_element() >= 1.0 - 1e-6;
            check_plane(&format!("bilinear {corners:?}"), &b, unit, edge, u, false)?;
        }
        for (mean, sigma) in [(Vec2::ZERO, 1.0f32), (Vec2::new(1e30, -1e30), 1.0), (Vec2::ZERO, 2.3e-20), (Vec2::ZERO, 3.5e18)] {
            let n = Normal2D::new(mean, sigma).expect("valid");
            let near = move |p: Vec2| (p - mean).as_dvec2().length() / f64::from(sigma) <= 5.8;
            // Points 10³⁰ from 0 with σ = 1 are quantised by f32 (the round trip is then
            // meaningless): check support and pdf only.
            if mean.length() > 1.0 {
                let p = n.sample(u);
                prop_assert!(p.is_finite() && n.pdf(p).is_finite());
                prop_assert!(n.invert(p).is_finite());
            } else {
                check_plane(&format!("box-muller {sigma:e}"), &n, near, |_| false, u, true)?;
            }
        }
    }

    /// Bilinear patches: twisted, collapsed to a triangle (p₁₁ = p₁₀: the area element is 0
    /// along that edge), tiny and huge. Samples finite, pdf finite and > 0 except where the
    /// area element vanishes, invert in [0, 1)² and round trips in the interior.
    #[test]
    fn bilinear_patches(u in u_any()) {
        let twisted = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(1.3, 0.9, 0.8)];
        let collapsed = [Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::X];
        let scaled = |k: f32| twisted.map(|c| c * k);
        for (name, corners) in [("twisted", twisted), ("collapsed", collapsed), ("tiny", scaled(1e-15)), ("huge", scaled(1e15))] {
            let q = BilinearPatch::new(corners).expect("valid patch");
            let (p, pdf) = q.sample_with_pdf(u);
            prop_assert!(p.is_finite() && pdf.is_finite() && pdf >= 0.0, "{name}: {p} {pdf}");
            let edge = u.min_element() == 0.0 || u.max_element() == ONE_MINUS;
            prop_assert!(pdf > 0.0 || name == "collapsed" || edge, "{name}: pdf 0 at {u}");
            let back = q.invert(p);
            prop_assert!(back.is_finite() && back.min_element() >= 0.0 && back.max_element() < 1.0);
            let again = q.pdf(p);
            prop_assert!(again.is_finite() && (again - pdf).abs() <= 1e-3 * pdf, "{name}: pdf {again} vs {pdf}");
            if u.min_element() >= 1e-3 && u.max_element() <= 1.0 - 1e-3 && name != "collapsed" {
                prop_assert!((back - u).abs().max_element() <= 1e-4, "{name}: {u} -> {back}");
            }
        }
    }

    #[test]
    fn low_distortion_triangle(u in u_any()) {
        let tri = |p: Vec2| p.min_element() >= 0.0 && p.x + p.y <= 1.0;
        check_plane("low-distortion triangle", &LowDistortionTriangle, tri, |_| false, u, false)?;
        let back = LowDistortionTriangle.invert(LowDistortionTriangle.sample(u));
        // Exact up to one rounding of u/2 and a sum: 2 ulps of 1.
        prop_assert!(back.is_finite() && (back - u).abs().max_element() <= 2.0 * f32::EPSILON);
    }

    #[test]
    fn henyey_greenstein_and_von_mises_fisher(u in u_any()) {
        for g in [-ONE_MINUS, -0.999_999, -0.9, 0.0, 1e-7, 0.5, 0.9999, ONE_MINUS] {
            let hg = HenyeyGreenstein::new(g).expect("valid");
            check_sphere(&format!("henyey-greenstein {g}"), &hg, u)?;
        }
        for kappa in [0.0f32, 1e-30, 1.0, 1e4, 1e10] {
            let v = VonMisesFisher::new(kappa).expect("valid");
            check_sphere(&format!("von mises-fisher {kappa:e}"), &v, u)?;
        }
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

proptest! {
    #![proptest_config(config(1024))]

    /// pdf and invert of arbitrary finite points: pdf finite and ≥ 0, invert in [0, 1).
    #[test]
    fn pdf_and_invert_never_nan(x in any_finite(), y in any_finite(), z in any_finite()) {
        let one_d: Vec<Box<dyn Warp1D>> = vec![
            Box::new(Linear::new(0.0, 1.0).expect("valid")),
            Box::new(Tent::new(1.0).expect("valid")),
            Box::new(Exponential::new(1.0).expect("valid")),
            Box::new(TruncatedExponential::new(-3.0, 0.0, 1.0).expect("valid")),
            Box::new(Normal::new(0.0, 1.0).expect("valid")),
            Box::new(Logistic::new(0.0, 1.0).expect("valid")),
            Box::new(TrimmedLogistic::new(0.0, 1.0, 2.0, 3.0).expect("valid")),
            Box::new(Smoothstep::new(0.0, 1.0).expect("valid")),
        ];
        for w in &one_d {
            let (pdf, u) = (w.pdf(x), w.invert(x));
            prop_assert!(pdf.is_finite() && pdf >= 0.0, "pdf {pdf} at {x}");
            prop_assert!(u.is_finite() && (0.0..1.0).contains(&u), "invert {u} at {x}");
        }
        let p = Vec2::new(x, y);
        let b = Bilinear::new([1.0, 2.0, 0.0, 3.0]).expect("valid");
        let t = LowDistortionTriangle;
        let (tp, tu) = (t.pdf(p), t.invert(p));
        prop_assert!(tp.is_finite() && tu.is_finite() && tu.min_element() >= 0.0 && tu.max_element() < 1.0);
        let n = Normal2D::new(Vec2::ZERO, 1.0).expect("valid");
        for (pdf, u) in [(b.pdf(p), b.invert(p)), (n.pdf(p), n.invert(p))] {
            prop_assert!(pdf.is_finite() && pdf >= 0.0 && u.is_finite() && u.min_element() >= 0.0 && u.max_element() < 1.0);
        }
        let v = Vec3::new(x, y, z);
        let hg = HenyeyGreenstein::new(0.9).expect("valid");
        let vmf = VonMisesFisher::new(100.0).expect("valid");
        for (pdf, u) in [(hg.pdf(v), hg.invert(v)), (vmf.pdf(v), vmf.invert(v))] {
            prop_assert!(pdf.is_finite() && pdf >= 0.0, "pdf {pdf} at {v}");
            prop_assert!(u.is_finite() && u.min_element() >= 0.0 && u.max_element() < 1.0, "{u} at {v}");
        }
    }
}
