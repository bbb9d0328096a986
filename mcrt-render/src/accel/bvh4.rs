//! A 4-wide BVH: the binary SAH hierarchy collapsed so that every node holds up to four
//! children whose boxes are tested at once in SIMD lanes (as in Wald, Benthin & Boulos 2008,
//! "Getting Rid of Packets: Efficient SIMD Single-Ray Traversal using Multi-branching BVHs",
//! IEEE Symposium on Interactive Ray Tracing). Collapsing repeatedly opens the interior child
//! of largest surface area until four children are gathered.
//!
//! Leaves are numbered; a child code is a node index, `LEAF | leaf index` or [`EMPTY`], and
//! [`WideBvh::leaf`] gives a leaf's range of stored primitives. Queries either call back per
//! primitive ([`Bvh4::closest`], [`Bvh4::any`]) or per leaf ([`Bvh4::closest_leaf`],
//! [`Bvh4::any_leaf`], which `Geometry` uses to test a leaf's quads and triangles as SIMD
//! packets).
//! Traversal is in `traverse.rs`.

use super::aabb::Aabb;
use super::wide_bvh::WideBvh;
use glam::Vec4;

pub(super) use super::wide_bvh::{EMPTY, LEAF};

/// Four child boxes by coordinate (lane = child), and the children: a node index, or a leaf
/// `LEAF | leaf index`, or [`EMPTY`].
#[derive(Debug, Clone, Copy)]
pub(crate) struct Node4 {
    pub(super) lo: [Vec4; 3],
    pub(super) hi: [Vec4; 3],
    pub(super) child: [u32; 4],
    /// Bit `i` set when child `i` is not [`EMPTY`].
    pub(super) valid: u32,
}

super::wide_bvh::wide_node!(
    Node4,
    4,
    Vec4::splat(f32::INFINITY),
    Vec4::splat(f32::NEG_INFINITY)
);

/// The 4-wide BVH.
pub(crate) type Bvh4 = WideBvh<Node4>;

impl Bvh4 {
    /// Builds the binary SAH BVH over the bounds and collapses it.
    pub(crate) fn build(bounds: &[Aabb]) -> Self {
        Self::build_with(bounds, 0, ())
    }
}

super::leaf_queries::leaf_queries!(Bvh4);

#[cfg(test)]
mod tests {
    use super::super::LeafQueries;
    use super::*;
    use glam::Vec3;

    #[test]
    fn identical_boxes_still_build() {
        let b = vec![Aabb::from_points(&[Vec3::ZERO, Vec3::ONE]); 300];
        let bvh = Bvh4::build(&b);
        let mut hits = 0;
        bvh.any(Vec3::new(0.5, 0.5, -1.0), Vec3::Z, f32::INFINITY, |_, _| {
            hits += 1;
            false
        });
        assert_eq!(hits, 300);
    }

    #[test]
    fn leaves_partition_the_stored_order_and_leaf_walks_reach_them() {
        for n in [0usize, 1, 4, 5, 37, 500] {
            let b: Vec<Aabb> = (0..n)
                .map(|i| {
                    let p = Vec3::new((i % 7) as f32, (i / 7 % 5) as f32, (i / 35) as f32);
                    Aabb::from_points(&[p, p + Vec3::splat(0.5)])
                })
                .collect();
            let bvh = Bvh4::build(&b);
            let mut ranges: Vec<_> = (0..bvh.leaf_count()).map(|k| bvh.leaf(k)).collect();
            ranges.sort_by_key(|r| r.start);
            let mut next = 0;
            for r in ranges {
                assert!(
                    r.start == next && r.end > r.start && r.len() <= 4,
                    "n {n} {r:?}"
                );
                next = r.end;
            }
            assert_eq!(next as usize, n);
            assert!(bvh.leaf(bvh.leaf_count()).is_empty());
            // A ray along +x through the first row: every leaf on it is visited once.
            let o = Vec3::new(-1.0, 0.25, 0.25);
            let mut seen = vec![0; bvh.leaf_count()];
            bvh.any_leaf(o, Vec3::X, f32::INFINITY, |k, _| {
                seen[k as usize] += 1;
                false
            });
            let on_row = |k: usize| {
                bvh.leaf(k).any(|i| {
                    let bx = b[bvh.order()[i as usize] as usize];
                    bx.min.y <= 0.25 && bx.min.z <= 0.25
                })
            };
            for (k, &s) in seen.iter().enumerate() {
                assert!(s <= 1 && (s == 1 || !on_row(k)), "n {n} leaf {k} seen {s}");
            }
            // The closest walk shrinks the bound to the first box's face.
            let bound = bvh.closest_leaf(o, Vec3::X, f32::INFINITY, |k, t| {
                for i in bvh.leaf(k as usize) {
                    let hit = b[bvh.order()[i as usize] as usize].min.x + 1.0;
                    if on_row(k as usize) && hit < *t {
                        *t = hit;
                    }
                }
            });
            assert_eq!(bound, if n == 0 { f32::INFINITY } else { 1.0 }, "n {n}");
        }
    }

    #[test]
    fn empty_bvh_finds_nothing() {
        let bvh = Bvh4::build(&[]);
        assert!(!bvh.any(Vec3::ZERO, Vec3::Z, 1.0, |_, _| true));
    }

    #[test]
    fn small_scenes_and_leaf_roots() {
        for n in [1usize, 3, 4, 5, 17, 200] {
            let b: Vec<Aabb> = (0..n)
                .map(|i| {
                    let p = Vec3::new(i as f32 * 2.0, 0.0, 0.0);
                    Aabb::from_points(&[p, p + Vec3::ONE])
                })
                .collect();
            let bvh = Bvh4::build(&b);
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
                    let t = 1.0 + 2.0 * b[bvh.order()[i as usize] as usize].min.x / 2.0;
                    (t < tm).then_some(t)
                },
            );
            assert_eq!(t, Some(1.0));
        }
        assert!(!Bvh4::build(&[]).any(Vec3::ZERO, Vec3::X, 1.0, |_, _| true));
    }
}
