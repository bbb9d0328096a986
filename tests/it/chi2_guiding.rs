//! The directional quadtrees of path guiding (`mcrt::sampling::guiding`) against their own
//! densities under the chi-square harness, at the suite's settings: an untrained tree (the
//! uniform sphere), trees trained on a broad lobe, a sharp lobe at the pole of the map (where
//! the equal-area square is most distorted), two lobes, and a lobe with a dark half (cells
//! with zero density). Each run also checks that the pdf integrates to 1. The equal-area map
//! itself passes chi-square, the Jacobian identity (`pdf · 4π` = 1/`|∂ω/∂u|`) and the inverse
//! round trip. The guided path tracer's direction sampling (one-sample mixture of a trained
//! guide and a Lambertian BSDF on a tilted frame) against its mixture density, with its
//! weights `f·cos/pdf`. Eight chi-square runs against the suite's budget.

use crate::common;

use common::third_value;
use common::{chi2, sphere};
use mcrt::glam::{Vec2, Vec3};
use mcrt::integrator::{Bsdf, BsdfFlags, BsdfSample, GuidedPathTracer};
use mcrt::sampling::guiding::{square_to_sphere, DQuadTree, EqualAreaSphere, SdTree};
use mcrt::sampling::sampler::SampleSource;
use mcrt::sampling::warp::{CosineHemisphere, Warp};
use mcrt::sampling::Frame;
use mcrt::stats::{check_warp_inverse, check_warp_jacobian};

/// A tree trained for `iterations` rounds (refine, then record on a 128² lattice of the
/// square) on the radiance `f`.
fn trained(iterations: u32, f: impl Fn(Vec3) -> f32) -> DQuadTree {
    let mut t = DQuadTree::new();
    for _ in 0..iterations {
        let mut next = t.refined(0.01, 20);
        let n = 128u32;
        for i in 0..n * n {
            let u = Vec2::new(
                ((i % n) as f32 + 0.5) / n as f32,
                ((i / n) as f32 + 0.5) / n as f32,
            );
            let d = square_to_sphere(u);
            next.record(d, f64::from(f(d)));
        }
        t = next;
    }
    t
}

fn lobe(axis: Vec3, k: i32) -> impl Fn(Vec3) -> f32 {
    let axis = axis.normalize();
    move |d| d.dot(axis).max(0.0).powi(k)
}

fn run(name: &str, t: &DQuadTree) {
    let o = chi2(sphere(), name).run_warp(t);
    assert!(o.passed(), "{}", o.report());
}

#[test]
fn untrained_tree_is_uniform() {
    run("guiding untrained", &DQuadTree::new());
    // The SD-tree's distribution before any training, anywhere.
    let s = SdTree::new(Vec3::splat(-1.0), Vec3::ONE);
    assert_eq!(s.distribution(Vec3::new(0.3, 0.1, -0.2)), &DQuadTree::new());
}

#[test]
fn broad_lobe() {
    let t = trained(3, lobe(Vec3::new(1.0, 0.5, 0.2), 4));
    assert!(t.depth() >= 4);
    run("guiding broad lobe", &t);
}

#[test]
fn sharp_lobe_at_the_pole() {
    let t = trained(4, lobe(Vec3::new(0.05, 0.0, 1.0), 200));
    assert!(t.depth() >= 6, "depth {}", t.depth());
    run("guiding sharp lobe at the pole", &t);
}

#[test]
fn two_lobes() {
    let a = lobe(Vec3::new(-1.0, 1.0, 0.0), 30);
    let b = lobe(Vec3::new(0.2, -0.3, -1.0), 10);
    let t = trained(3, move |d| a(d) + 0.5 * b(d));
    run("guiding two lobes", &t);
}

#[test]
fn dark_half_has_zero_density() {
    // Radiance only from y > 0: cells of y < 0 hold no energy, and their density is 0.
    let t = trained(3, |d| if d.y > 0.0 { 1.0 + d.x } else { 0.0 });
    assert_eq!(t.pdf(Vec3::new(0.0, -1.0, 0.0)), 0.0);
    run("guiding dark half", &t);
}

#[test]
fn equal_area_map() {
    run_map();
}

fn run_map() {
    let o = chi2(sphere(), "guiding equal-area map").run_warp(&EqualAreaSphere);
    assert!(o.passed(), "{}", o.report());
    let j = check_warp_jacobian(&EqualAreaSphere, common::jacobian());
    assert!(j.passed(), "{}", j.report());
    let i = check_warp_inverse(&EqualAreaSphere, 64, 1e-4);
    assert!(i.passed(), "{}", i.report());
}

/// A Lambertian BSDF of albedo 0.8, cosine-weighted sampling.
struct Lambert;

impl Bsdf for Lambert {
    fn flags(&self) -> BsdfFlags {
        BsdfFlags {
            smooth: true,
            ..BsdfFlags::default()
        }
    }
    fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Vec3::ZERO;
        }
        Vec3::splat(0.8 * wi.z / std::f32::consts::PI)
    }
    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        CosineHemisphere.pdf(wi)
    }
    fn sample(&self, wo: Vec3, _u1: f32, u2: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let (wi, pdf) = CosineHemisphere.sample_with_pdf(u2);
        BsdfSample::from_value(wi, self.eval(wo, wi), pdf, 1.0)
    }
    fn samples_component(&self) -> bool {
        false
    }
}

/// The values one `u` of the harness stands for: the choice (a hash of `u`), then `u`.
struct Values([f32; 3], usize);

impl SampleSource for Values {
    fn next_1d(&mut self) -> f32 {
        let v = self.0[self.1.min(2)];
        self.1 += 1;
        v
    }
}

fn values(u: Vec2) -> Values {
    Values([third_value(u), u.x, u.y], 0)
}

#[test]
fn guided_mixture_with_a_lambertian_bsdf() {
    let n = Vec3::new(0.3, 0.2, 1.0).normalize();
    let frame = Frame::from_normal(n);
    let wo = frame.to_local(Vec3::new(0.0, 0.6, 0.8).normalize());
    // A guide toward a lobe partly below the surface, with a floor (no zero cells).
    let guide = {
        let l = lobe(Vec3::new(1.0, 0.0, -0.2), 20);
        trained(3, move |d| l(d) + 0.01)
    };
    for (name, alpha, guide) in [
        ("guided mixture, trained", 0.5, guide),
        ("guided mixture, untrained", 0.3, DQuadTree::new()),
    ] {
        let gpt = GuidedPathTracer {
            guide_probability: alpha,
            ..GuidedPathTracer::default()
        };
        let sample = |u: Vec2| {
            gpt.sample_direction(&Lambert, &frame, wo, &guide, &mut values(u))
                .map(|s| (s.wi, 1.0))
        };
        let pdf = |wi: Vec3| gpt.pdf(&Lambert, &frame, wo, &guide, wi);
        let o = chi2(sphere(), name).run_weighted(sample, pdf);
        assert!(o.passed(), "{}", o.report());
        // The weights: f·cos/pdf with the mixture density, both branches.
        let m = 64u32;
        for i in 0..m * m {
            let u = Vec2::new(
                ((i % m) as f32 + 0.5) / m as f32,
                ((i / m) as f32 + 0.5) / m as f32,
            );
            let s = gpt
                .sample_direction(&Lambert, &frame, wo, &guide, &mut values(u))
                .expect("a sample");
            assert!(s.weight.is_finite() && s.pdf.is_finite() && !s.delta);
            // Equal up to the rounding of the frame's round trip in the BSDF's density.
            assert!(
                (s.pdf - pdf(s.wi)).abs() <= 1e-5 * s.pdf,
                "{name}: {}",
                s.pdf
            );
            let f = Lambert.eval(wo, frame.to_local(s.wi)).x;
            assert!(
                (s.weight.x * s.pdf - f).abs() <= 1e-5 * f.max(1e-3),
                "{name}: {} vs {f}",
                s.weight.x * s.pdf
            );
        }
    }
}
