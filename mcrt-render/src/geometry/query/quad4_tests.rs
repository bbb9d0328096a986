//! Unit tests of the quad packet test against the two-triangle watertight test.

use super::*;
use crate::geometry::query::scalar::{TriRay, TriSoa};
use rand_core::{RngCore, SeedableRng};

/// Uniform in [-1, 1), on a grid of 2⁻²⁰ so that sums of a few points are exact.
fn uniform(rng: &mut rand_pcg::Pcg32) -> f32 {
    (rng.next_u32() >> 12) as f32 / (1u32 << 20) as f32 * 2.0 - 1.0
}

fn point(rng: &mut rand_pcg::Pcg32) -> Vec3 {
    Vec3::new(uniform(rng), uniform(rng), uniform(rng))
}

/// The two triangles of a parallelogram, in the order [`Quad::from_pair`] expects.
fn halves(corner: Vec3, e1: Vec3, e2: Vec3) -> [[Vec3; 3]; 2] {
    let (a, c) = (corner + e1, corner + e2);
    [[corner, a, c], [a, a + e2, c]]
}

/// Nearest hit of the two-triangle test: (triangle, t, b1, b2).
fn two_triangles(o: Vec3, d: Vec3, t: &[[Vec3; 3]; 2], t_max: f32) -> Option<(u32, f32, f32, f32)> {
    let ray = TriRay::new(o, d);
    let mut best = None;
    for (k, tri) in t.iter().enumerate() {
        if let Some((t, b1, b2)) = ray.hit(&TriSoa::new(*tri), t_max) {
            if best.is_none_or(|(_, bt, _, _)| t < bt) {
                best = Some((k as u32, t, b1, b2));
            }
        }
    }
    best
}

/// Exact parameters (f64) of the ray's crossing with the parallelogram's plane.
fn exact_uv(o: Vec3, d: Vec3, corner: Vec3, e1: Vec3, e2: Vec3) -> (f64, f64) {
    let [o, d, c, e1, e2] = [o, d, corner, e1, e2].map(|p| p.as_dvec3());
    let n = e1.cross(e2);
    let t = n.dot(c - o) / n.dot(d);
    let r = o + t * d - c;
    let (a, b) = (
        e2.cross(n) / n.length_squared(),
        n.cross(e1) / n.length_squared(),
    );
    (a.dot(r), b.dot(r))
}

#[test]
fn random_rays_agree_with_the_two_triangle_test() {
    let mut rng = rand_pcg::Pcg32::seed_from_u64(5);
    let (mut hits, mut near_edge, mut n) = (0, 0, 0);
    for round in 0..20_000 {
        let corner = point(&mut rng);
        let (e1, e2) = (point(&mut rng), point(&mut rng));
        let tris = halves(corner, e1, e2);
        let Some(q) = Quad::from_pair(tris[0], tris[1]) else {
            continue;
        };
        // Aim at a point of the plane in [-0.2, 1.2]², from a random origin.
        let (s, r) = (uniform(&mut rng) * 0.7 + 0.5, uniform(&mut rng) * 0.7 + 0.5);
        let o = point(&mut rng) * 3.0;
        let d = corner + s * e1 + r * e2 - o;
        let t_max = [0.99, 1.01, f32::INFINITY][round % 3];
        let want = two_triangles(o, d, &tris, t_max);
        let got = QuadRay4::new(o, d).closest(&QuadPacket::new(&[q]), t_max);
        assert_eq!(
            QuadRay4::new(o, d).any(&QuadPacket::new(&[q]), t_max),
            got.is_some()
        );
        n += 1;
        let (u, v) = exact_uv(o, d, corner, e1, e2);
        let edge = [u, 1.0 - u, v, 1.0 - v]
            .into_iter()
            .map(f64::abs)
            .fold(f64::INFINITY, f64::min);
        let cos = q.e1.cross(q.e2).normalize().dot(d.normalize()).abs();
        match (want, got) {
            (Some((k, tt, b1, b2)), Some(h)) => {
                hits += 1;
                assert!(h.t.is_finite() && h.u.is_finite() && h.v.is_finite());
                // Same distance up to rounding (worse at grazing angles).
                let tol = 2e-6 / cos.max(1e-3);
                assert!(
                    (h.t - tt).abs() <= tol * tt,
                    "round {round}: {} vs {tt}",
                    h.t
                );
                let (kq, c1, c2) = Quad::barycentrics(&q.maps(), h.u, h.v);
                let on_diagonal = (u + v - 1.0).abs() < 1e-4;
                assert!(
                    kq == k || on_diagonal,
                    "round {round}: triangle {kq} vs {k}"
                );
                let at = |k: u32, b1: f32, b2: f32| {
                    let t = tris[k as usize];
                    (1.0 - b1 - b2) * t[0] + b1 * t[1] + b2 * t[2]
                };
                let scale = 1.0 + o.length() + d.length() * tt;
                let gap = at(kq, c1, c2).distance(at(k, b1, b2));
                assert!(gap <= 1e-5 * scale / cos.max(1e-2), "round {round}: {gap}");
            }
            (None, None) => {}
            // Hit or miss may differ only within the slack band at the border.
            _ => {
                assert!(edge <= 2.0 * SLACK as f64, "round {round}: {u} {v}");
                near_edge += 1;
            }
        }
    }
    assert!(
        hits > n / 3 && near_edge < n / 100,
        "{hits} hits, {near_edge} near edges of {n}"
    );
}

/// The six faces of a rotated, scaled and translated cube (as in the Cornell box) as
/// quads, in two packets.
fn cube_quads() -> Vec<Quad> {
    let m = glam::Affine3A::from_cols_array(&[
        0.28491, 0.0, -0.0939491, 0.0, 0.61, 0.0, 0.0939491, 0.0, 0.28491, -0.33, -0.4, -0.28,
    ]);
    let (pos, idx) = crate::geometry::build::cube();
    let world = |t: [u32; 3]| t.map(|v| m.transform_point3(pos[v as usize]));
    idx.chunks(2)
        .map(|face| Quad::from_pair(world(face[0]), world(face[1])).unwrap())
        .collect()
}

#[test]
fn rays_at_shared_cube_edges_and_corners_never_leak() {
    let quads = cube_quads();
    let packets = [QuadPacket::new(&quads[..4]), QuadPacket::new(&quads[4..])];
    let corners: Vec<Vec3> = quads.iter().flat_map(Quad::corners).collect();
    let mut rng = rand_pcg::Pcg32::seed_from_u64(9);
    let mut tried = 0;
    for i in 0..corners.len() {
        for j in 0..corners.len() {
            // Points on edges (and corners) shared by faces: ends of one face's edge.
            let (p, q) = (corners[i], corners[j]);
            if p.distance(q) > 1.3 {
                continue;
            }
            for k in 0..20 {
                let aim = p + (q - p) * (k as f32 / 19.0);
                for dist in [0.5f32, 3.0, 20.0, 60.0] {
                    let o = aim + point(&mut rng).normalize_or(Vec3::X) * dist;
                    let r = QuadRay4::new(o, aim - o);
                    let hit = packets
                        .iter()
                        .any(|p| r.closest(p, f32::INFINITY).is_some());
                    assert!(hit, "ray from {o} to {aim} leaked");
                    assert!(packets.iter().any(|p| r.any(p, f32::INFINITY)));
                    tried += 1;
                }
            }
        }
    }
    assert!(tried > 10_000, "{tried}");
}

#[test]
fn nearest_lane_wins_ties_go_low_and_bounds_are_strict() {
    let at = |z: f32| {
        let c = Vec3::new(-1.0, -1.0, z);
        Quad::from_pair([c, c + Vec3::X * 2.0, c + Vec3::Y * 2.0], {
            let a = c + Vec3::X * 2.0;
            [a, a + Vec3::Y * 2.0, c + Vec3::Y * 2.0]
        })
        .unwrap()
    };
    let r = QuadRay4::new(Vec3::new(0.25, 0.5, 5.0), -Vec3::Z);
    let p = QuadPacket::new(&[at(0.0), at(2.0), at(1.0), at(2.0)]);
    let h = r.closest(&p, f32::INFINITY).unwrap();
    assert!(h.t.is_finite() && h.u.is_finite() && h.v.is_finite());
    assert_eq!((h.lane, h.t), (1, 3.0));
    assert!((h.u - 0.625).abs() < 1e-6 && (h.v - 0.75).abs() < 1e-6);
    assert!(r.closest(&p, 3.0).is_none() && !r.any(&p, 3.0));
    assert!(r.any(&p, 3.0001));
    for n in 1..=3 {
        let q = QuadPacket::new(&[at(0.0), at(9.0), at(9.0)][..n]);
        assert_eq!(r.closest(&q, 9.0).map(|h| (h.lane, h.t)), Some((0, 5.0)));
    }
    // Behind the origin, parallel to the plane, inside the plane, an empty packet.
    assert!(r.closest(&QuadPacket::new(&[at(6.0)]), 99.0).is_none());
    let flat = QuadRay4::new(Vec3::new(0.0, 0.0, 1.0), Vec3::X);
    assert!(flat.closest(&p, 99.0).is_none());
    let inside = QuadRay4::new(Vec3::new(-5.0, 0.0, 0.0), Vec3::X);
    assert!(!inside.any(&QuadPacket::new(&[at(0.0)]), 99.0));
    assert!(!r.any(&QuadPacket::new(&[]), 99.0));
    // Outside the border by more than the slack: a miss.
    let out = QuadRay4::new(Vec3::new(1.0 + 4.0 * 2.0 * SLACK, 0.0, 1.0), -Vec3::Z);
    assert!(!out.any(&QuadPacket::new(&[at(0.0)]), 9.0));
    let edge = QuadRay4::new(Vec3::new(1.0, 1.0, 1.0), -Vec3::Z);
    assert!(edge.any(&QuadPacket::new(&[at(0.0)]), 9.0));
}
