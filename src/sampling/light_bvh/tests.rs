//! Unit tests of the light BVH: the pmf sums to 1, `sample` returns `pmf` bit for bit,
//! the depth bound, input validation, empty and zero-power inputs.

use glam::Vec3;
use rand_core::{RngCore, SeedableRng};
use rand_pcg::Pcg32;

use super::build::max_depth;
use super::{LightBounds, LightBvh, LightBvhError};

/// A value in `[0, 1)`.
pub(super) fn uni(rng: &mut Pcg32) -> f32 {
    (rng.next_u32() >> 8) as f32 / (1u32 << 24) as f32
}

/// A value in `[lo, hi)`.
pub(super) fn range(rng: &mut Pcg32, lo: f32, hi: f32) -> f32 {
    lo + (hi - lo) * uni(rng)
}

/// A uniformly distributed unit vector.
pub(super) fn direction(rng: &mut Pcg32) -> Vec3 {
    let z = range(rng, -1.0, 1.0);
    let phi = range(rng, 0.0, std::f32::consts::TAU);
    let r = (1.0 - z * z).max(0.0).sqrt();
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// A point in the cube `[-s, s]³`.
pub(super) fn point(rng: &mut Pcg32, s: f32) -> Vec3 {
    Vec3::new(range(rng, -s, s), range(rng, -s, s), range(rng, -s, s))
}

/// A light of a random kind (point, spot, planar one- or two-sided, a box with a wide
/// cone), size (0 to 2) and power (spanning 10⁴, 1 in 16 zero).
pub(super) fn random_light(rng: &mut Pcg32) -> LightBounds {
    let c = point(rng, 10.0);
    let power = if rng.next_u32().is_multiple_of(16) {
        0.0
    } else {
        10f32.powf(range(rng, -2.0, 2.0))
    };
    let size = Vec3::new(uni(rng), uni(rng), uni(rng)) * range(rng, 0.0, 2.0);
    match rng.next_u32() % 5 {
        0 => LightBounds::point(c, power),
        1 => {
            let start = range(rng, -0.5, 1.0);
            LightBounds::spot(c, direction(rng), start, range(rng, -1.0, start), power)
        }
        2 => LightBounds::planar(c, c + size, direction(rng), false, power),
        3 => LightBounds::planar(c, c + size, direction(rng), true, power),
        _ => LightBounds {
            min: c,
            max: c + size,
            axis: direction(rng),
            cos_theta_o: range(rng, -1.0, 1.0),
            cos_theta_e: range(rng, -0.2, 1.0),
            two_sided: rng.next_u32().is_multiple_of(2),
            power,
        },
    }
}

pub(super) fn random_lights(n: usize, seed: u64) -> Vec<LightBounds> {
    let mut rng = Pcg32::seed_from_u64(seed);
    (0..n).map(|_| random_light(&mut rng)).collect()
}

/// A shading point: inside or near the lights' region, with a random normal or none.
pub(super) fn random_query(rng: &mut Pcg32) -> (Vec3, Vec3) {
    let p = point(rng, 14.0);
    let n = if rng.next_u32().is_multiple_of(4) {
        Vec3::ZERO
    } else {
        direction(rng)
    };
    (p, n)
}

#[test]
fn pmf_sums_to_one_and_sample_agrees_bit_for_bit() {
    for (n, seed) in [(1, 1), (2, 2), (17, 3), (1000, 4)] {
        let mut lights = random_lights(n, seed);
        lights[0].power = 1.0;
        let bvh = LightBvh::new(&lights).unwrap();
        let mut rng = Pcg32::seed_from_u64(100 + seed);
        let mut nonempty = 0;
        for _ in 0..60 {
            let (p, nrm) = random_query(&mut rng);
            let pmf: Vec<f32> = (0..n).map(|i| bvh.pmf(p, nrm, i)).collect();
            assert!(pmf.iter().all(|x| x.is_finite() && (0.0..=1.0).contains(x)));
            for (i, l) in lights.iter().enumerate() {
                if l.power == 0.0 {
                    assert_eq!(pmf[i], 0.0);
                }
            }
            let total: f64 = pmf.iter().map(|&x| f64::from(x)).sum();
            assert!(total.is_finite());
            if total == 0.0 {
                // Nothing reaches p: nothing is sampled.
                assert_eq!(bvh.sample(p, nrm, 0.5), None);
                continue;
            }
            nonempty += 1;
            assert!((total - 1.0).abs() < 1e-5, "n = {n}: Σ pmf = {total}");
            for k in 0..50 {
                let u = if k == 0 { 0.0 } else { uni(&mut rng) };
                let (i, prob) = bvh.sample(p, nrm, u).expect("Σ pmf = 1");
                assert!(prob.is_finite() && prob > 0.0);
                assert_eq!(prob.to_bits(), pmf[i].to_bits(), "light {i} at u = {u}");
            }
            let (i, prob) = bvh
                .sample(p, nrm, crate::sampling::ONE_MINUS_EPSILON)
                .unwrap();
            assert_eq!(prob.to_bits(), pmf[i].to_bits());
        }
        let least = if n < 17 { 10 } else { 50 };
        assert!(
            nonempty >= least,
            "n = {n}: only {nonempty} points see a light"
        );
    }
}

#[test]
fn depth_is_logarithmic() {
    let n = 10_000;
    let bvh = LightBvh::new(&random_lights(n, 5)).unwrap();
    // 2⌈log₂ n⌉ + 8 = 36 for 10⁴ lights.
    assert_eq!(max_depth(n), 36);
    assert!(bvh.depth() <= max_depth(n), "depth {}", bvh.depth());
    // Four children per node: at least ⌈log₄ 10⁴⌉ = 7 levels, and not many more.
    assert!((7..=14).contains(&bvh.depth()), "depth {}", bvh.depth());
    // Adversarial for a cost-driven split: powers and positions growing geometrically (the
    // SAOH would peel off one light per level), and every light at the same point.
    let chain: Vec<_> = (0..10_000)
        .map(|i| {
            LightBounds::point(
                Vec3::new(1.001f32.powi(i), 0.0, 0.0),
                1.01f32.powi(i % 8000),
            )
        })
        .collect();
    let same = vec![LightBounds::point(Vec3::ONE, 1.0); 10_000];
    for lights in [chain, same] {
        let bvh = LightBvh::new(&lights).unwrap();
        assert!(
            bvh.depth() <= max_depth(lights.len()),
            "depth {}",
            bvh.depth()
        );
        let (p, n) = (Vec3::new(3.0, 1.0, 0.0), Vec3::Y);
        let total: f64 = (0..lights.len()).map(|i| f64::from(bvh.pmf(p, n, i))).sum();
        assert!((total - 1.0).abs() < 1e-4, "Σ pmf = {total}");
    }
}

#[test]
fn empty_and_zero_power_inputs_sample_nothing() {
    let bvh = LightBvh::new(&[]).unwrap();
    assert!(bvh.is_empty());
    assert_eq!(bvh.sample(Vec3::ZERO, Vec3::Z, 0.5), None);
    assert_eq!(bvh.pmf(Vec3::ZERO, Vec3::Z, 0), 0.0);
    let zero = vec![LightBounds::point(Vec3::ONE, 0.0); 3];
    let bvh = LightBvh::new(&zero).unwrap();
    assert_eq!(bvh.len(), 3);
    assert_eq!(bvh.sample(Vec3::ZERO, Vec3::Z, 0.5), None);
    assert_eq!(bvh.pmf(Vec3::ZERO, Vec3::Z, 1), 0.0);
    // One light of power 0 among others is never chosen.
    let mut lights = random_lights(17, 6);
    lights[4].power = 0.0;
    let bvh = LightBvh::new(&lights).unwrap();
    let mut rng = Pcg32::seed_from_u64(7);
    for _ in 0..2000 {
        let (p, n) = random_query(&mut rng);
        assert_ne!(bvh.sample(p, n, uni(&mut rng)).map(|s| s.0), Some(4));
        assert_eq!(bvh.pmf(p, n, 4), 0.0);
    }
    assert_eq!(bvh.pmf(Vec3::ZERO, Vec3::Z, 17), 0.0);
}

#[test]
fn bad_input_is_an_error_not_a_panic() {
    let good = LightBounds::planar(Vec3::ZERO, Vec3::ONE, Vec3::Z, false, 1.0);
    let cases: [(&str, LightBounds); 10] = [
        (
            "min",
            LightBounds {
                min: Vec3::new(f32::NAN, 0.0, 0.0),
                ..good
            },
        ),
        (
            "max",
            LightBounds {
                max: Vec3::new(0.0, f32::INFINITY, 0.0),
                ..good
            },
        ),
        (
            "max",
            LightBounds {
                max: Vec3::new(-1.0, 1.0, 1.0),
                ..good
            },
        ),
        (
            "axis",
            LightBounds {
                axis: Vec3::ZERO,
                ..good
            },
        ),
        (
            "axis",
            LightBounds {
                axis: Vec3::new(f32::NAN, 0.0, 1.0),
                ..good
            },
        ),
        (
            "cos_theta_o",
            LightBounds {
                cos_theta_o: 1.5,
                ..good
            },
        ),
        (
            "cos_theta_e",
            LightBounds {
                cos_theta_e: f32::NAN,
                ..good
            },
        ),
        (
            "power",
            LightBounds {
                power: -1.0,
                ..good
            },
        ),
        (
            "power",
            LightBounds {
                power: f32::INFINITY,
                ..good
            },
        ),
        (
            "power",
            LightBounds {
                power: f32::NAN,
                ..good
            },
        ),
    ];
    for (field, bad) in cases {
        match LightBvh::new(&[good, good, bad]) {
            Err(LightBvhError::InvalidLight {
                index: 2, field: f, ..
            }) => assert_eq!(f, field),
            other => panic!("{field}: {other:?}"),
        }
    }
    // A zero axis is fine for a full sphere.
    let point = LightBounds {
        axis: Vec3::ZERO,
        ..LightBounds::point(Vec3::ONE, 1.0)
    };
    assert!(LightBvh::new(&[point]).is_ok());
}

#[test]
fn odd_queries_give_no_nan() {
    let bvh = LightBvh::new(&random_lights(17, 8)).unwrap();
    let odd = [
        (Vec3::new(f32::NAN, 0.0, 0.0), Vec3::Z),
        (Vec3::ZERO, Vec3::new(f32::NAN, 0.0, 0.0)),
        (Vec3::splat(f32::MAX), Vec3::Z),
        (Vec3::splat(-3e38), Vec3::splat(1e-30)),
        (Vec3::ZERO, Vec3::splat(f32::INFINITY)),
    ];
    for (p, n) in odd {
        for u in [f32::NAN, -1.0, 0.0, 0.5, 1.0, 2.0] {
            if let Some((i, prob)) = bvh.sample(p, n, u) {
                assert!(prob.is_finite() && prob > 0.0 && prob <= 1.0);
                assert_eq!(prob.to_bits(), bvh.pmf(p, n, i).to_bits());
            }
        }
    }
    assert_eq!(
        bvh.sample(Vec3::new(f32::NAN, 0.0, 0.0), Vec3::Z, 0.5),
        None
    );
    // A point exactly on a point light.
    let bvh = LightBvh::new(&[
        LightBounds::point(Vec3::ONE, 1.0),
        LightBounds::point(Vec3::ZERO, 1.0),
    ])
    .unwrap();
    let (i, prob) = bvh.sample(Vec3::ONE, Vec3::Z, 0.5).unwrap();
    assert!(prob.is_finite() && prob > 0.0);
    assert_eq!(prob, bvh.pmf(Vec3::ONE, Vec3::Z, i));
}

#[test]
fn nearer_and_brighter_lights_are_more_likely() {
    let lights = [
        LightBounds::point(Vec3::new(1.0, 0.0, 0.0), 1.0),
        LightBounds::point(Vec3::new(10.0, 0.0, 0.0), 1.0),
        LightBounds::point(Vec3::new(-10.0, 0.0, 0.0), 100.0),
    ];
    let bvh = LightBvh::new(&lights).unwrap();
    let pmf: Vec<f32> = (0..3).map(|i| bvh.pmf(Vec3::ZERO, Vec3::ZERO, i)).collect();
    // Power over squared distance: 1, 0.01, 1.
    assert!(pmf[0] > 10.0 * pmf[1] && pmf[2] > 10.0 * pmf[1], "{pmf:?}");
}

/// `n` small square panels on each of a room's ceiling (`y = 0.995`, facing down) and two
/// walls (`x = ±0.995`, facing in), powers over three decades: the lights of one wall face
/// one way, so the tree's nodes below a wall are cut from afar.
pub(super) fn room_lights(n: usize, seed: u64) -> Vec<LightBounds> {
    let mut rng = Pcg32::seed_from_u64(seed);
    let mut lights = Vec::new();
    for wall in 0..3 {
        for _ in 0..n {
            let (a, b) = (range(&mut rng, -0.9, 0.9), range(&mut rng, -0.9, 0.9));
            let h = 0.035;
            let power = 10f32.powf(range(&mut rng, -1.5, 1.5));
            let (c, normal, e) = match wall {
                0 => (Vec3::new(a, 0.995, b), Vec3::NEG_Y, Vec3::new(h, 0.0, h)),
                1 => (Vec3::new(-0.995, a, b), Vec3::X, Vec3::new(0.0, h, h)),
                _ => (Vec3::new(0.995, a, b), Vec3::NEG_X, Vec3::new(0.0, h, h)),
            };
            lights.push(LightBounds::planar(c - e, c + e, normal, false, power));
        }
    }
    lights
}

#[test]
fn cut_nodes_keep_sample_and_pmf_in_agreement() {
    let lights = room_lights(150, 8);
    let bvh = LightBvh::new(&lights).unwrap();
    let mut rng = Pcg32::seed_from_u64(9);
    let mut cut = 0;
    for k in 0..80 {
        // Inside the room, and far outside it (where whole walls are cut).
        let s = if k % 4 == 0 { 20.0 } else { 0.99 };
        let p = point(&mut rng, s);
        let nrm = direction(&mut rng);
        let pmf: Vec<f32> = (0..lights.len()).map(|i| bvh.pmf(p, nrm, i)).collect();
        let total: f64 = pmf.iter().map(|&x| f64::from(x)).sum();
        assert!(total.is_finite());
        if total == 0.0 {
            assert_eq!(bvh.sample(p, nrm, 0.5), None);
            continue;
        }
        assert!((total - 1.0).abs() < 1e-5, "Σ pmf = {total} at {p}");
        if bvh.cuts_at(p) {
            cut += 1;
        }
        for j in 0..50 {
            let u = if j == 0 { 0.0 } else { uni(&mut rng) };
            let (i, prob) = bvh.sample(p, nrm, u).expect("Σ pmf = 1");
            assert!(prob.is_finite() && prob > 0.0);
            assert_eq!(
                prob.to_bits(),
                pmf[i].to_bits(),
                "light {i} at {p}, u = {u}"
            );
        }
    }
    assert!(cut >= 20, "only {cut} points pass a cut");
}
