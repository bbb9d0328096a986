//! Tests of the 8-wide BVH: its leaves, both lane paths, and agreement with the 4-wide tree.

use super::super::lanes8::Simd8;
use super::super::{Bvh4, LeafQueries};
use super::*;
use glam::Vec3;
use rand_core::{RngCore, SeedableRng};

/// The tree on the detected lanes and on the portable ones.
fn both(b: &[Aabb]) -> [Bvh8; 2] {
    let bvh = Bvh8::build(b);
    [bvh.clone(), bvh.with_simd(Simd8::Portable)]
}

#[test]
fn identical_boxes_still_build() {
    let b = vec![Aabb::from_points(&[Vec3::ZERO, Vec3::ONE]); 300];
    for bvh in both(&b) {
        let mut hits = 0;
        bvh.any(Vec3::new(0.5, 0.5, -1.0), Vec3::Z, f32::INFINITY, |_, _| {
            hits += 1;
            false
        });
        assert_eq!(hits, 300);
    }
}

#[test]
fn empty_bvh_finds_nothing() {
    for bvh in both(&[]) {
        assert!(!bvh.any(Vec3::ZERO, Vec3::Z, 1.0, |_, _| true));
        assert_eq!(bvh.closest(Vec3::ZERO, Vec3::Z, 1.0, |_, t| Some(t)), None);
    }
}

#[test]
fn small_scenes_and_leaf_roots() {
    for n in [1usize, 3, 4, 5, 8, 9, 17, 200, 3000] {
        let b: Vec<Aabb> = (0..n)
            .map(|i| {
                let p = Vec3::new(i as f32 * 2.0, 0.0, 0.0);
                Aabb::from_points(&[p, p + Vec3::ONE])
            })
            .collect();
        for bvh in both(&b) {
            let mut seen = vec![false; n];
            bvh.any(Vec3::new(-1.0, 0.5, 0.5), Vec3::X, f32::INFINITY, |i, _| {
                seen[i as usize] = true;
                false
            });
            assert!(seen.iter().all(|&s| s), "n = {n}");
            let t = bvh.closest(
                Vec3::new(-1.0, 0.5, 0.5),
                Vec3::X,
                f32::INFINITY,
                |i, tm| {
                    let t = 1.0 + b[bvh.order()[i as usize] as usize].min.x;
                    (t < tm).then_some(t)
                },
            );
            assert_eq!(t, Some(1.0), "n = {n}");
        }
    }
}

/// The leaves are the 4-wide tree's (the same ranges of the same order), and a random ray
/// finds the same nearest box and the same occlusion through both trees, on both lane paths.
#[test]
fn agrees_with_the_four_wide_tree_on_random_boxes() {
    let mut rng = rand_pcg::Pcg32::seed_from_u64(27);
    let mut f = move || (rng.next_u32() >> 8) as f32 / (1u32 << 24) as f32 * 2.0 - 1.0;
    let b: Vec<Aabb> = (0..5000)
        .map(|_| {
            let p = Vec3::new(f(), f(), f()) * 10.0;
            let e = Vec3::new(f(), f(), f()).abs() * 0.3;
            Aabb::from_points(&[p, p + e])
        })
        .collect();
    let four = Bvh4::build(&b);
    let eight = both(&b);
    assert!(
        eight[0].depth < four.depth,
        "{} {}",
        eight[0].depth,
        four.depth
    );
    assert_eq!(four.order(), eight[0].order());
    let mut r4: Vec<_> = (0..four.leaf_count()).map(|k| four.leaf(k)).collect();
    let mut r8: Vec<_> = (0..eight[0].leaf_count())
        .map(|k| eight[0].leaf(k))
        .collect();
    r4.sort_by_key(|r| r.start);
    r8.sort_by_key(|r| r.start);
    assert_eq!(r4, r8);
    // "Hit" a box at its slab entry distance (computed in f64, so both trees agree).
    let hit = |order: &[u32], i: u32, o: Vec3, d: Vec3, tm: f32| {
        let bx = b[order[i as usize] as usize];
        let (mut t0, mut t1) = (0f64, f64::from(tm));
        for a in 0..3 {
            let inv = 1.0 / f64::from(d[a]);
            let u = (f64::from(bx.min[a]) - f64::from(o[a])) * inv;
            let v = (f64::from(bx.max[a]) - f64::from(o[a])) * inv;
            t0 = t0.max(u.min(v));
            t1 = t1.min(u.max(v));
        }
        (t0 <= t1 && t0 > 0.0 && (t0 as f32) < tm).then_some(t0 as f32)
    };
    let mut hits = 0;
    for _ in 0..4000 {
        let o = Vec3::new(f(), f(), f()) * 12.0;
        let d = Vec3::new(f(), f(), f()).normalize_or(Vec3::Z);
        let t_max = if f() > 0.0 { f32::INFINITY } else { 3.0 };
        let want = four.closest(o, d, t_max, |i, tm| hit(four.order(), i, o, d, tm));
        let occluded = four.any(o, d, t_max, |i, tm| {
            hit(four.order(), i, o, d, tm).is_some()
        });
        for bvh in &eight {
            let got = bvh.closest(o, d, t_max, |i, tm| hit(bvh.order(), i, o, d, tm));
            if let Some(t) = got {
                assert!(t.is_finite());
            }
            assert_eq!(got, want);
            let any = bvh.any(o, d, t_max, |i, tm| hit(bvh.order(), i, o, d, tm).is_some());
            assert_eq!(any, occluded);
        }
        hits += usize::from(want.is_some());
    }
    assert!(hits > 300, "{hits}");
}

/// With merging, every leaf is a binary leaf or a subtree of at most eight boxes, the
/// leaves still partition the stored order (the binary tree's), and random rays find the
/// same nearest box and occlusion as through the 4-wide tree, on both lane paths.
#[test]
fn merged_leaves_partition_the_order_and_agree_with_the_four_wide_tree() {
    let mut rng = rand_pcg::Pcg32::seed_from_u64(28);
    let mut f = move || (rng.next_u32() >> 8) as f32 / (1u32 << 24) as f32 * 2.0 - 1.0;
    for n in [0usize, 1, 5, 8, 9, 40, 3000] {
        let b: Vec<Aabb> = (0..n)
            .map(|_| {
                let p = Vec3::new(f(), f(), f()) * 10.0;
                let e = Vec3::new(f(), f(), f()).abs() * 0.3;
                Aabb::from_points(&[p, p + e])
            })
            .collect();
        let four = Bvh4::build(&b);
        let merged = Bvh8::build_merging(&b, 8);
        assert_eq!(merged.order(), four.order());
        let mut ranges: Vec<_> = (0..merged.leaf_count()).map(|k| merged.leaf(k)).collect();
        ranges.sort_by_key(|r| r.start);
        let mut next = 0;
        for r in &ranges {
            assert!(
                r.start == next && r.end > r.start && r.len() <= 8,
                "n {n} {r:?}"
            );
            next = r.end;
        }
        assert_eq!(next as usize, n);
        if n >= 40 {
            assert!(merged.leaf_count() < four.leaf_count(), "n {n}");
        }
        let hit = |order: &[u32], i: u32, o: Vec3, d: Vec3, tm: f32| {
            let bx = b[order[i as usize] as usize];
            let (mut t0, mut t1) = (0f64, f64::from(tm));
            for a in 0..3 {
                let inv = 1.0 / f64::from(d[a]);
                let u = (f64::from(bx.min[a]) - f64::from(o[a])) * inv;
                let v = (f64::from(bx.max[a]) - f64::from(o[a])) * inv;
                t0 = t0.max(u.min(v));
                t1 = t1.min(u.max(v));
            }
            (t0 <= t1 && t0 > 0.0 && (t0 as f32) < tm).then_some(t0 as f32)
        };
        for bvh in [merged.clone(), merged.clone().with_simd(Simd8::Portable)] {
            for _ in 0..300 {
                let o = Vec3::new(f(), f(), f()) * 12.0;
                let d = Vec3::new(f(), f(), f()).normalize_or(Vec3::Z);
                let t_max = if f() > 0.0 { f32::INFINITY } else { 3.0 };
                let want = four.closest(o, d, t_max, |i, tm| hit(four.order(), i, o, d, tm));
                let got = bvh.closest(o, d, t_max, |i, tm| hit(bvh.order(), i, o, d, tm));
                assert_eq!(got, want, "n {n}");
                let occluded = four.any(o, d, t_max, |i, tm| {
                    hit(four.order(), i, o, d, tm).is_some()
                });
                let any = bvh.any(o, d, t_max, |i, tm| hit(bvh.order(), i, o, d, tm).is_some());
                assert_eq!(any, occluded, "n {n}");
            }
        }
    }
}
