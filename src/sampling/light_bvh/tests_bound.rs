//! The importance bound is conservative: wherever a light can reach a point (a point of
//! its box, a normal of its cone, a direction inside its emission spread), its pmf there is
//! positive. Points are built at the edge of a light's emission (a corner of its box, a
//! normal on the rim of its cone, a direction just inside `θ_e`), where the bound is tight.

use glam::{DVec3, Vec3};
use rand_core::{RngCore, SeedableRng};
use rand_pcg::Pcg32;

use super::cone::{angle_between, cone_union};
use super::tests::{direction, random_lights, random_query, uni};
use super::{LightBounds, LightBvh};

/// The unit vector at angle `theta` from the unit `axis`, at azimuth `phi` about it.
fn at_angle(axis: DVec3, theta: f64, phi: f64) -> DVec3 {
    let t = axis.any_orthonormal_vector();
    let b = axis.cross(t);
    let d = axis * theta.cos() + (t * phi.cos() + b * phi.sin()) * theta.sin();
    d / d.length()
}

/// A point of the light's box (a corner half of the time) and a normal of its cone (on
/// the rim half of the time; either side when two-sided), in `f64`.
fn emitter(l: &LightBounds, rng: &mut Pcg32) -> (DVec3, DVec3) {
    let (lo, hi) = (l.min.as_dvec3(), l.max.as_dvec3());
    let t = if rng.next_u32().is_multiple_of(2) {
        DVec3::new(
            f64::from(rng.next_u32() % 2),
            f64::from(rng.next_u32() % 2),
            f64::from(rng.next_u32() % 2),
        )
    } else {
        DVec3::new(
            f64::from(uni(rng)),
            f64::from(uni(rng)),
            f64::from(uni(rng)),
        )
    };
    let x = lo + (hi - lo) * t;
    let axis = if l.cos_theta_o == -1.0 {
        DVec3::Z
    } else {
        l.axis.as_dvec3().normalize()
    };
    let theta_o = f64::from(l.cos_theta_o).acos();
    let theta = if rng.next_u32().is_multiple_of(2) {
        theta_o
    } else {
        theta_o * f64::from(uni(rng))
    };
    let mut m = at_angle(axis, theta, std::f64::consts::TAU * f64::from(uni(rng)));
    if l.two_sided && rng.next_u32().is_multiple_of(2) {
        m = -m;
    }
    (x, m)
}

/// Whether the emitter `(x, m)` of `l` sends light to `p` (with normal `n`, or none).
fn reaches(l: &LightBounds, x: DVec3, m: DVec3, p: Vec3, n: Vec3) -> bool {
    let v = p.as_dvec3() - x;
    let len = v.length();
    if len.is_nan() || len <= 0.0 {
        return false;
    }
    let d = v / len;
    let n = n.as_dvec3();
    m.dot(d) > f64::from(l.cos_theta_e) && (n == DVec3::ZERO || n.normalize().dot(d) != 0.0)
}

#[test]
fn lights_that_reach_a_point_have_positive_pmf() {
    let mut checked = 0;
    for (set, n_lights) in [(0u64, 1), (1, 2), (2, 17), (3, 17), (4, 200)] {
        let lights = random_lights(n_lights, 50 + set);
        let bvh = LightBvh::new(&lights).unwrap();
        let mut rng = Pcg32::seed_from_u64(60 + set);
        let mut zeros = 0;
        for _ in 0..400 {
            // At the edge of one light's emission.
            let target = rng.next_u32() as usize % n_lights;
            let l = &lights[target];
            let (x, m) = emitter(l, &mut rng);
            let theta_e = f64::from(l.cos_theta_e).acos();
            let delta = [1e-2, 1e-4, 1e-6][rng.next_u32() as usize % 3];
            if l.power > 0.0 && theta_e > delta {
                let d = at_angle(
                    m,
                    theta_e - delta,
                    std::f64::consts::TAU * f64::from(uni(&mut rng)),
                );
                let dist = 10f64.powf(f64::from(uni(&mut rng)) * 4.0 - 2.0);
                let p = (x + d * dist).as_vec3();
                let n = direction(&mut rng);
                if reaches(l, x, m, p, n) {
                    let pmf = bvh.pmf(p, n, target);
                    assert!(
                        pmf.is_finite() && pmf > 0.0,
                        "light {target} {l:?} reaches {p} but pmf = {pmf}"
                    );
                    checked += 1;
                }
            }
            // Anywhere, every light, several emitters.
            let (p, n) = random_query(&mut rng);
            for (i, l) in lights.iter().enumerate().filter(|(_, l)| l.power > 0.0) {
                let pmf = bvh.pmf(p, n, i);
                assert!(pmf.is_finite());
                if pmf == 0.0 {
                    zeros += 1;
                }
                for _ in 0..8 {
                    let (x, m) = emitter(l, &mut rng);
                    if reaches(l, x, m, p, n) {
                        assert!(
                            pmf > 0.0,
                            "light {i} {l:?} reaches {p} (n = {n}) but pmf = 0"
                        );
                        checked += 1;
                    }
                }
            }
        }
        // Not vacuous: lights facing away do get 0 (except for a lone full-sphere light).
        if n_lights >= 17 {
            assert!(zeros > 0, "set {set}: no light ever ruled out");
        }
    }
    assert!(checked > 10_000, "only {checked} checks");
}

#[test]
fn a_light_facing_away_gets_zero() {
    let lights = [
        LightBounds::planar(
            Vec3::new(-1.0, -1.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::Z,
            false,
            1.0,
        ),
        LightBounds::point(Vec3::new(0.0, 0.0, -5.0), 1.0),
    ];
    let bvh = LightBvh::new(&lights).unwrap();
    let below = Vec3::new(0.0, 0.0, -3.0);
    assert_eq!(bvh.pmf(below, Vec3::ZERO, 0), 0.0);
    assert_eq!(bvh.pmf(below, Vec3::ZERO, 1), 1.0);
    // Just above the plane of the panel, beside it: reachable at grazing angles.
    let beside = Vec3::new(5.0, 0.0, 1e-3);
    assert!(bvh.pmf(beside, Vec3::ZERO, 0) > 0.0);
    // Two-sided: reachable from below.
    let two = [
        LightBounds {
            two_sided: true,
            ..lights[0]
        },
        lights[1],
    ];
    let bvh = LightBvh::new(&two).unwrap();
    assert!(bvh.pmf(below, Vec3::ZERO, 0) > 0.0);
}

#[test]
fn merged_cones_contain_both() {
    let mut rng = Pcg32::seed_from_u64(70);
    for _ in 0..20_000 {
        let cone = |rng: &mut Pcg32| {
            let c = match rng.next_u32() % 4 {
                0 => 1.0,
                1 => f64::from(uni(rng)).mul_add(2e-3, 1.0 - 2e-3),
                _ => f64::from(uni(rng)) * 2.0 - 1.0,
            };
            (direction(rng).as_dvec3().normalize(), c)
        };
        let (a, b) = (cone(&mut rng), cone(&mut rng));
        let (w, c) = cone_union(a, b);
        let theta = c.acos();
        assert!(w.is_finite() && c.is_finite());
        for (axis, cos) in [a, b] {
            // The farthest direction of the cone from w is at angle(w, axis) + θ.
            let far = angle_between(w, axis) + cos.acos();
            assert!(
                c == -1.0 || far <= theta,
                "{a:?} ∪ {b:?} = ({w}, {c}): {far} > {theta}"
            );
        }
    }
}

#[test]
fn a_point_behind_the_plane_of_a_panel_gets_zero() {
    // A downward lamp 5 mm below a ceiling at y = 1, and a point lamp.
    let h = 0.035;
    let lights = [
        LightBounds::planar(
            Vec3::new(-h, 0.995, -h),
            Vec3::new(h, 0.995, h),
            Vec3::NEG_Y,
            false,
            1.0,
        ),
        LightBounds::point(Vec3::new(0.0, 0.0, 0.0), 1.0),
    ];
    let bvh = LightBvh::new(&lights).unwrap();
    // On the ceiling beside the lamp, inside its bounding sphere's cone: behind its plane.
    for x in [0.02f32, 0.05, 0.1, 0.5] {
        assert_eq!(
            bvh.pmf(Vec3::new(x, 1.0, 0.0), Vec3::NEG_Y, 0),
            0.0,
            "x = {x}"
        );
    }
    // Just in front of its plane, beside it: reached at grazing angles.
    for x in [0.05f32, 0.5] {
        assert!(bvh.pmf(Vec3::new(x, 0.995 - 1e-4, 0.0), Vec3::NEG_Y, 0) > 0.0);
    }
}

#[test]
fn f32_lanes_never_rule_out_what_the_f64_bound_admits() {
    // Every node of the binary tree as one lane: where its f64 importance is positive, the
    // lane's f32 importance must be too (the margins of derivations Part V §7).
    let mut rng = Pcg32::seed_from_u64(80);
    let mut positive = 0;
    for (set, n_lights) in [(0u64, 17), (1, 200)] {
        let lights = random_lights(n_lights, 90 + set);
        let nodes = super::binary_nodes(&lights);
        for _ in 0..300 {
            let (p, n) = random_query(&mut rng);
            let n64 = n.as_dvec3();
            let n64 = (n64.length() > 0.0).then(|| n64.normalize());
            let n32 = (n.length() > 0.0).then(|| n.normalize());
            for node in &nodes {
                let lane = super::wide::Wide::single(node);
                let i64 = node.importance(p.as_dvec3(), n64);
                let i32 = lane
                    .importances(&super::wide::Query::new(p, p.abs().element_sum(), n32))
                    .to_array()[0];
                assert!(i32.is_finite() && i32 >= 0.0);
                if i64 > 0.0 {
                    assert!(i32 > 0.0, "f64 {i64} > 0 but f32 0 at {p}, n = {n}");
                    positive += 1;
                }
            }
        }
    }
    assert!(positive > 10_000, "only {positive} positive importances");
}
