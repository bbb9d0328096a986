//! Issue 26 ("hostile inputs"): degenerate but valid triangle soups (copies of one
//! triangle, on shared or on separate vertices; overlapping shifted copies in one plane; a
//! fan of triangles on one edge; zero-area triangles) build with the BVH, the grid and the
//! kd-tree in bounded memory, and answer rays as brute force does.
//!
//! The bound is on the structure, not on time: [`Geometry::accel_heap_bytes`] at most
//! [`BYTES_PER_PRIM`] per triangle plus [`BYTES_FIXED`] (before the fix the grid took 64 KiB
//! per copy of one triangle, and pairing and the grid took time quadratic in the copies).

use mcrt::glam::Vec3;
use mcrt_render::description::ShapeDesc;
use mcrt_render::geometry::{AccelKind, Geometry, Ray};

#[path = "common/degenerate.rs"]
mod degenerate;

/// Triangles per soup.
const N: usize = 20_000;
/// Heap bytes allowed per primitive in an acceleration structure...
const BYTES_PER_PRIM: usize = 512;
/// ... plus these.
const BYTES_FIXED: usize = 1 << 20;

const KINDS: [AccelKind; 4] = [
    AccelKind::Bvh,
    AccelKind::Bvh8,
    AccelKind::Grid,
    AccelKind::KdTree,
];

fn down(x: f32, y: f32) -> Ray {
    Ray {
        origin: Vec3::new(x, y, 1.0),
        dir: -Vec3::Z,
    }
}

/// Rays from a fixed xorshift sequence: from above the soups towards points of the square
/// [−0.6, 0.6]² at z ∈ [−0.3, 0.3].
fn rays(n: usize) -> Vec<Ray> {
    let mut s = 0x2545_f491_4f6c_dd1d_u64;
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 40) as f32 / (1u64 << 24) as f32 - 0.5
    };
    (0..n)
        .map(|_| {
            let origin = Vec3::new(2.0 * next(), 2.0 * next(), 1.5);
            let target = Vec3::new(1.2 * next(), 1.2 * next(), 0.6 * next());
            Ray {
                origin,
                dir: (target - origin).normalize(),
            }
        })
        .collect()
}

fn build(shape: &ShapeDesc, kind: AccelKind) -> Geometry {
    Geometry::new(std::slice::from_ref(shape), None, kind).expect("a valid mesh builds")
}

#[test]
fn degenerate_soups_build_bounded_and_answer_as_brute_force() {
    let rays = rays(300);
    for (name, shape) in degenerate::all(N) {
        let brute = build(&shape, AccelKind::BruteForce);
        let expect: Vec<Option<f32>> = rays
            .iter()
            .map(|r| brute.intersect(r, f32::INFINITY).map(|h| h.t))
            .collect();
        for kind in KINDS {
            let g = build(&shape, kind);
            assert_eq!(g.primitive_count(), brute.primitive_count());
            let bytes = g.accel_heap_bytes();
            println!("{name} {kind:?}: {bytes} heap bytes");
            assert!(
                bytes <= BYTES_PER_PRIM * g.primitive_count() + BYTES_FIXED,
                "{name} {kind:?}: {bytes} bytes"
            );
            for (ray, want) in rays.iter().zip(&expect) {
                let got = g.intersect(ray, f32::INFINITY).map(|h| h.t);
                let same = match (got, want) {
                    (Some(a), Some(b)) => (a - b).abs() <= 1e-4 * b,
                    (a, b) => a == *b,
                };
                assert!(
                    same,
                    "{name} {kind:?} {ray:?}: {got:?}, brute force {want:?}"
                );
                assert_eq!(g.occluded(ray, f32::INFINITY), want.is_some());
            }
        }
    }
}

/// A ray through the repeated triangle hits it at t = 1 (z = 0 from z = 1), one beside it
/// misses; through the fan's edge-on triangles and the lifted triangle above the zero-area
/// ones, likewise.
#[test]
fn rays_through_and_beside_hit_and_miss() {
    // (soup, ray through: its t, ray beside)
    let cases = [
        (
            degenerate::identical(N),
            down(0.0, 0.0),
            1.0,
            down(0.6, 0.4),
        ),
        (
            degenerate::stacked(N),
            down(0.1, -0.2),
            1.0,
            down(-0.3, 0.4),
        ),
        (degenerate::shifted(N), down(0.1, 0.0), 1.0, down(0.9, 0.4)),
        (
            degenerate::zero_area(N),
            down(0.0, 0.0),
            0.5,
            down(0.7, 0.7),
        ),
    ];
    for kind in KINDS {
        for (k, (shape, through, t, beside)) in cases.iter().enumerate() {
            let g = build(shape, kind);
            let hit = g.intersect(through, f32::INFINITY);
            assert!(
                hit.is_some_and(|h| (h.t - t).abs() < 1e-5),
                "case {k} {kind:?}: {hit:?}"
            );
            assert!(
                g.intersect(beside, f32::INFINITY).is_none(),
                "case {k} {kind:?}"
            );
            assert!(!g.occluded(beside, f32::INFINITY), "case {k} {kind:?}");
        }
        // The fan: its triangle at angle 0 lies in z = 0, x ≥ 0; from below, along +z at
        // x = 0.1, the first triangle met is that one (the others rise above it).
        let g = build(&degenerate::fan(N), kind);
        let up = Ray {
            origin: Vec3::new(0.1, 0.0, -1.0),
            dir: Vec3::Z,
        };
        let hit = g.intersect(&up, f32::INFINITY);
        assert!(
            hit.is_some_and(|h| (h.t - 1.0).abs() < 1e-5),
            "fan {kind:?}: {hit:?}"
        );
        // Beside the fan: past the end of its edge (|y| ≤ ½ on every triangle).
        let beside = Ray {
            origin: Vec3::new(0.1, 0.6, -1.0),
            dir: Vec3::Z,
        };
        assert!(
            g.intersect(&beside, f32::INFINITY).is_none(),
            "fan {kind:?}"
        );
    }
}
