//! Chi-square tests of `LightBvh::sample` against `LightBvh::pmf` over the lights (a
//! `Discrete` domain, one category per light) at the suite's settings: random sets of 17,
//! 1000 and 10⁴ lights of mixed kind, size, orientation and power (some of power 0), at
//! points on surfaces, in a medium (no normal), and inside a light's box; and panels on the
//! walls of a room (the half-space test and the cut), near and far. 8 runs.

use mcrt::glam::Vec3;
use mcrt::sampling::light_bvh::{LightBounds, LightBvh};
use mcrt::stats::Discrete;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

use crate::common;
use common::{chi2, SEED};

/// A random unit vector.
fn direction(rng: &mut Pcg64) -> Vec3 {
    let z: f32 = rng.random_range(-1.0..1.0);
    let phi: f32 = rng.random_range(0.0..std::f32::consts::TAU);
    let r = (1.0 - z * z).max(0.0).sqrt();
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// `n` lights in `[-10, 10]³`: points, spots, one- and two-sided panels, boxes with wide
/// cones; powers over four decades, one in sixteen 0.
fn lights(n: usize, seed: u64) -> Vec<LightBounds> {
    let mut rng = Pcg64::seed_from_u64(seed);
    (0..n)
        .map(|_| {
            let c = Vec3::new(
                rng.random_range(-10.0..10.0),
                rng.random_range(-10.0..10.0),
                rng.random_range(-10.0..10.0),
            );
            let power = if rng.random_range(0..16) == 0 {
                0.0
            } else {
                10f32.powf(rng.random_range(-2.0..2.0))
            };
            let size = Vec3::new(rng.random(), rng.random(), rng.random()) * 2.0;
            match rng.random_range(0..5) {
                0 => LightBounds::point(c, power),
                1 => LightBounds::spot(c, direction(&mut rng), 0.8, 0.5, power),
                2 => LightBounds::planar(c, c + size, direction(&mut rng), false, power),
                3 => LightBounds::planar(c, c + size, direction(&mut rng), true, power),
                _ => LightBounds {
                    min: c,
                    max: c + size,
                    axis: direction(&mut rng),
                    cos_theta_o: rng.random_range(-1.0..1.0),
                    cos_theta_e: rng.random_range(0.0..1.0),
                    two_sided: false,
                    power,
                },
            }
        })
        .collect()
}

/// `n` small panels on each of a room's ceiling (facing down) and two side walls (facing in),
/// powers over three decades.
fn room_lights(n: usize, seed: u64) -> Vec<LightBounds> {
    let mut rng = Pcg64::seed_from_u64(seed);
    let mut out = Vec::new();
    for wall in 0..3 {
        for _ in 0..n {
            let (a, b): (f32, f32) = (rng.random_range(-0.9..0.9), rng.random_range(-0.9..0.9));
            let power = 10f32.powf(rng.random_range(-1.5..1.5));
            let h = 0.035;
            let (c, normal, e) = match wall {
                0 => (Vec3::new(a, 0.995, b), Vec3::NEG_Y, Vec3::new(h, 0.0, h)),
                1 => (Vec3::new(-0.995, a, b), Vec3::X, Vec3::new(0.0, h, h)),
                _ => (Vec3::new(0.995, a, b), Vec3::NEG_X, Vec3::new(0.0, h, h)),
            };
            out.push(LightBounds::planar(c - e, c + e, normal, false, power));
        }
    }
    out
}

/// `sample` against `pmf` at `p` with normal `n` (`None` from `sample` is a rejection; the
/// pmf must then sum to less than 1 by that much).
fn check(bvh: &LightBvh, n_lights: usize, p: Vec3, n: Vec3, name: &str) {
    let total: f64 = (0..n_lights).map(|i| f64::from(bvh.pmf(p, n, i))).sum();
    assert!(
        total.is_finite() && (total - 1.0).abs() < 1e-5,
        "{name}: Σ pmf = {total}"
    );
    chi2(Discrete::new(n_lights), name)
        .run_weighted(
            |u| bvh.sample(p, n, u.x).map(|(i, _)| (i, 1.0)),
            |i| bvh.pmf(p, n, i),
        )
        .assert_passed();
}

#[test]
fn light_bvh_sample_matches_pmf() {
    let set17 = lights(17, SEED + 17);
    let bvh = LightBvh::new(&set17).unwrap();
    check(
        &bvh,
        17,
        Vec3::new(0.5, -2.0, 1.0),
        Vec3::new(0.0, 0.6, 0.8),
        "LightBvh-17-surface",
    );
    check(
        &bvh,
        17,
        Vec3::new(0.5, -2.0, 1.0),
        Vec3::ZERO,
        "LightBvh-17-medium",
    );
    // Inside the box of a light (its importance has no orientation bound there).
    let inside = 0.5 * (set17[2].min + set17[2].max);
    check(&bvh, 17, inside, Vec3::Y, "LightBvh-17-inside");

    let set1000 = lights(1000, SEED + 1000);
    let bvh = LightBvh::new(&set1000).unwrap();
    check(
        &bvh,
        1000,
        Vec3::new(3.0, 1.0, -4.0),
        Vec3::new(0.0, 0.0, 1.0),
        "LightBvh-1000-surface",
    );
    check(
        &bvh,
        1000,
        Vec3::new(-30.0, 5.0, 0.0),
        Vec3::ZERO,
        "LightBvh-1000-far",
    );

    // Panels on three walls of a room, each wall's facing one way: nodes below a wall are
    // cut (chosen among by power) from afar, and points behind a wall's plane rule it out.
    let room = room_lights(300, SEED + 300);
    let bvh = LightBvh::new(&room).unwrap();
    check(
        &bvh,
        room.len(),
        Vec3::new(0.2, -0.9, 0.3),
        Vec3::Y,
        "LightBvh-room-floor",
    );
    check(
        &bvh,
        room.len(),
        Vec3::new(0.0, 8.0, -9.0),
        Vec3::ZERO,
        "LightBvh-room-far",
    );

    let set10k = lights(10_000, SEED + 10_000);
    let bvh = LightBvh::new(&set10k).unwrap();
    check(
        &bvh,
        10_000,
        Vec3::new(1.0, 2.0, 3.0),
        Vec3::new(0.6, 0.0, 0.8),
        "LightBvh-10000-surface",
    );
}
