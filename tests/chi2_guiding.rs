//! The directional quadtrees of path guiding (`mcrt::sampling::guiding`) against their own
//! densities under the chi-square harness, at the suite's settings: an untrained tree (the
//! uniform sphere), trees trained on a broad lobe, a sharp lobe at the pole of the map (where
//! the equal-area square is most distorted), two lobes, and a lobe with a dark half (cells
//! with zero density). Each run also checks that the pdf integrates to 1. The equal-area map
//! itself passes chi-square, the Jacobian identity (`pdf · 4π` = 1/`|∂ω/∂u|`) and the inverse
//! round trip. Six chi-square runs against the suite's budget.

mod common;

use common::{chi2, sphere};
use mcrt::glam::{Vec2, Vec3};
use mcrt::sampling::guiding::{square_to_sphere, DQuadTree, EqualAreaSphere, SdTree};
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
