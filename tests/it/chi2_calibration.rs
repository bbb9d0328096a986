//! Calibration of the harness: a correct sampler run over 1000 seeds at the uncorrected
//! level α = 0.01 must be rejected between 2 and 22 times (the 99.9 % band of
//! Binomial(1000, 0.01)). A slower test (a few seconds); the counts measured are in
//! `docs/testing.md`.

use mcrt::glam::{Vec2, Vec3};
use mcrt::stats::{ChiSquareTest, Directions, Domain, Rectangle};
use std::f32::consts::{FRAC_1_PI, TAU};

const SEEDS: u64 = 1000;
const SAMPLES: usize = 20_000;

/// Rejections among [`SEEDS`] runs at α = 0.01 (one test, no correction).
fn rejections<D: Domain + Clone>(
    domain: D,
    sample: impl Fn(Vec2) -> D::Point + Sync + Copy,
    pdf: impl Fn(D::Point) -> f32 + Sync,
) -> u64 {
    let base = ChiSquareTest::new(domain)
        .samples(SAMPLES)
        .significance(0.01, 1)
        .threads(1)
        .output_dir(None);
    let masses = base.expected_masses(pdf);
    let count = |seeds: std::ops::Range<u64>| {
        seeds
            .filter(|&s| {
                let o = base.clone().seed(s).run_with_masses(sample, |c| masses[c]);
                assert!(o.p_value.is_finite() && o.dof > 20, "{}", o.report());
                !o.passed()
            })
            .count() as u64
    };
    // Two fixed halves on two threads: the count does not depend on scheduling.
    std::thread::scope(|s| {
        let a = s.spawn(|| count(0..SEEDS / 2));
        let b = count(SEEDS / 2..SEEDS);
        a.join().expect("calibration thread") + b
    })
}

#[test]
fn cosine_hemisphere_is_rejected_at_the_nominal_rate() {
    let sample = |u: Vec2| {
        let (r, phi) = (u.x.sqrt(), TAU * u.y);
        Vec3::new(r * phi.cos(), r * phi.sin(), (1.0 - u.x).max(0.0).sqrt())
    };
    let pdf = |w: Vec3| w.z.max(0.0) * FRAC_1_PI;
    let n = rejections(Directions::hemisphere().resolution(16, 32), sample, pdf);
    println!("cosine hemisphere: {n} of {SEEDS} rejected at alpha = 0.01");
    assert!((2..=22).contains(&n), "{n} rejections out of {SEEDS}");
}

#[test]
fn uniform_disk_is_rejected_at_the_nominal_rate() {
    // The disk's rim crosses cells, and cells outside it have zero mass: pooling at work.
    let sample = |u: Vec2| {
        let (r, phi) = (u.x.sqrt(), TAU * u.y);
        Vec2::new(r * phi.cos(), r * phi.sin())
    };
    let pdf = |p: Vec2| {
        if p.length_squared() <= 1.0 {
            FRAC_1_PI
        } else {
            0.0
        }
    };
    let domain = Rectangle::new(Vec2::splat(-1.0), Vec2::splat(1.0), 24, 24);
    let n = rejections(domain, sample, pdf);
    println!("uniform disk: {n} of {SEEDS} rejected at alpha = 0.01");
    assert!((2..=22).contains(&n), "{n} rejections out of {SEEDS}");
}
