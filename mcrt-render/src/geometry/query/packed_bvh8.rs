//! Ray queries through the 8-wide BVH (its leaves the binary tree's, or binary subtrees of
//! up to eight units merged: [`MERGE_UNITS`]), each leaf's quads packed into one 8-lane quad test
//! ([`QuadPacket8`]) and its other triangles into one [`TriPacket8`]; spheres and disks
//! follow, tested one by one. Slots are laid out as [`super::packed_bvh`] lays them out.
//!
//! A query is dispatched once (`Simd8::dispatch`): the walk and the leaf tests then run
//! on the same lanes, AVX2 where the processor has it (the leaf visitor inlined into the
//! walk), else two 4-lane halves. The lanes compute what the 4-wide packets compute, so a
//! primitive's hit has the same bits as with [`super::packed_bvh::PackedBvh`]; which of two
//! primitives at exactly the same distance wins may differ (here the lower lane of a leaf).

use super::super::data::Prim;
use super::packed_bvh::{Leaf, LeafHit, PackedLeaves};
use super::pairing::Unit;
use super::quad8::{QuadPacket8, QuadRay8};
use super::tri8::{TriPacket8, TriRay8};
use super::{HitRecord, Ray, Stored};
use crate::accel::{Bvh8, Lanes8, WithLanes8};

/// Binary subtrees of at most this many units are merged into one leaf (at most 8: one
/// packet's lanes). 0: the leaves are the binary tree's, as the 4-wide tree's, so every
/// ray meets the same primitives in the same order and renders are byte-identical to
/// `Bvh`'s. Merging to 8 saves a further 4–9 % of the instructions on the 130k-triangle
/// sphere and the 100k soup but changes which of two primitives at the same distance wins
/// (a few pixels of a 4-spp render differ); `docs/geometry.md`, "The 8-wide BVH".
pub(super) const MERGE_UNITS: u32 = 0;

/// The 8-wide BVH and its 8-lane packed leaves.
pub(crate) type PackedBvh8 = PackedLeaves<Bvh8, QuadPacket8, TriPacket8, 8>;

impl PackedBvh8 {
    /// Builds the tree over the units' boxes and packs its leaves; returns the slots' input
    /// primitive indices and the packed BVH. `prims` is in input order.
    pub(super) fn build(
        boxes: &[crate::accel::Aabb],
        units: &[Unit],
        prims: &[Prim],
    ) -> (Vec<u32>, Self) {
        let bvh = Bvh8::build_merging(boxes, MERGE_UNITS);
        Self::pack_with(bvh, units, prims, QuadPacket8::new, TriPacket8::new)
    }

    /// This BVH with its walk and leaf tests run on `simd` (tests compare both paths).
    #[cfg(test)]
    pub(super) fn with_simd(mut self, simd: crate::accel::Simd8) -> Self {
        self.bvh = self.bvh.with_simd(simd);
        self
    }

    /// The nearest hit with `0 < t < t_max`.
    #[inline(always)]
    pub(super) fn closest(
        &self,
        stored: Stored,
        ray: &Ray,
        t_max: f32,
    ) -> Option<(f32, HitRecord)> {
        let (t, found) = self.bvh.simd().dispatch(Query::<true> {
            p: self,
            stored,
            ray,
            t_max,
        });
        Some((t, self.record(found?)))
    }

    /// True when anything is hit with `0 < t < t_max`.
    #[inline(always)]
    pub(super) fn any(&self, stored: Stored, ray: &Ray, t_max: f32) -> bool {
        self.bvh.simd().dispatch(Query::<false> {
            p: self,
            stored,
            ray,
            t_max,
        })
    }

    /// The nearest hit among a leaf's spheres and disks (out of line: rare in meshes).
    #[inline(never)]
    fn closest_others(
        stored: Stored,
        leaf: &Leaf,
        ray: &Ray,
        bound: &mut f32,
        found: &mut Option<LeafHit>,
    ) {
        for i in leaf.first_other()..leaf.end {
            if let Some((t, b1, b2)) = stored.hit(ray, None, i, *bound) {
                *bound = t;
                *found = Some(LeafHit::Prim(HitRecord { slot: i, b1, b2 }));
            }
        }
    }

    /// True when one of a leaf's spheres and disks is hit (out of line).
    #[inline(never)]
    fn any_others(stored: Stored, leaf: &Leaf, ray: &Ray, t_max: f32) -> bool {
        (leaf.first_other()..leaf.end).any(|i| stored.hit(ray, None, i, t_max).is_some())
    }
}

/// A query to run on some lanes: the closest hit (`CLOSEST`: the bound reached and what lies
/// there) or any hit.
struct Query<'a, const CLOSEST: bool> {
    p: &'a PackedBvh8,
    stored: Stored<'a>,
    ray: &'a Ray,
    t_max: f32,
}

impl WithLanes8 for Query<'_, true> {
    type Output = (f32, Option<LeafHit>);

    #[inline(always)]
    fn run<L: Lanes8>(self, l: L) -> Self::Output {
        let (p, stored, ray, mut t_max) = (self.p, self.stored, self.ray, self.t_max);
        let quad = QuadRay8::new(l, ray.origin, ray.dir);
        // The triangle test's per-ray set-up only where there are triangle packets.
        let tri = (!p.tris.is_empty()).then(|| TriRay8::new(l, ray.origin, ray.dir));
        let mut found = None;
        p.bvh.walk_on::<L, true>(
            l,
            ray.origin,
            ray.dir,
            &mut t_max,
            #[inline(always)]
            |k, bound| {
                let leaf = &p.leaves[k as usize];
                if leaf.quads > 0 {
                    if let Some(h) = quad.closest(&p.quads[leaf.quad as usize], *bound) {
                        *bound = h.t;
                        found = Some(LeafHit::Quad {
                            packet: leaf.quad,
                            lane: h.lane,
                            u: h.u,
                            v: h.v,
                        });
                    }
                }
                if let (true, Some(tri)) = (leaf.tris > 0, &tri) {
                    if let Some(h) = tri.closest(&p.tris[leaf.tri as usize], *bound) {
                        *bound = h.t;
                        found = Some(LeafHit::Prim(HitRecord {
                            slot: leaf.first_tri() + h.lane,
                            b1: h.b1,
                            b2: h.b2,
                        }));
                    }
                }
                if leaf.first_other() < leaf.end {
                    PackedBvh8::closest_others(stored, leaf, ray, bound, &mut found);
                }
                false
            },
        );
        (t_max, found)
    }
}

impl WithLanes8 for Query<'_, false> {
    type Output = bool;

    #[inline(always)]
    fn run<L: Lanes8>(self, l: L) -> bool {
        let (p, stored, ray, mut t_max) = (self.p, self.stored, self.ray, self.t_max);
        let quad = QuadRay8::new(l, ray.origin, ray.dir);
        // The triangle test's per-ray set-up only where there are triangle packets.
        let tri = (!p.tris.is_empty()).then(|| TriRay8::new(l, ray.origin, ray.dir));
        p.bvh.walk_on::<L, false>(
            l,
            ray.origin,
            ray.dir,
            &mut t_max,
            #[inline(always)]
            |k, bound| {
                let leaf = &p.leaves[k as usize];
                (leaf.quads > 0 && quad.any(&p.quads[leaf.quad as usize], *bound))
                    || (leaf.tris > 0
                        && tri
                            .as_ref()
                            .is_some_and(|r| r.any(&p.tris[leaf.tri as usize], *bound)))
                    || (leaf.first_other() < leaf.end
                        && PackedBvh8::any_others(stored, leaf, ray, *bound))
            },
        )
    }
}

#[cfg(test)]
mod tests {
    use super::super::super::{AccelKind, Geometry, Ray};
    use super::super::RayQuery;
    use crate::accel::Simd8;
    use crate::description::{ShapeDesc, ShapeKind};
    use glam::Vec3;
    use rand_core::{RngCore, SeedableRng};

    /// A triangle soup (leaves of up to eight triangles), a grid of parallelograms and a
    /// sphere: the portable lanes give the same hits and occlusion as the detected ones,
    /// and the same as the 4-wide BVH but for ties.
    #[test]
    fn portable_lanes_agree_with_detected_lanes() {
        let mut rng = rand_pcg::Pcg32::seed_from_u64(5);
        let mut f = move || (rng.next_u32() >> 8) as f32 / (1u32 << 24) as f32 * 2.0 - 1.0;
        let positions: Vec<Vec3> = (0..600).map(|_| Vec3::new(f(), f(), f())).collect();
        let indices = (0..200).map(|k| [3 * k, 3 * k + 1, 3 * k + 2]).collect();
        let soup = ShapeDesc::new(ShapeKind::Mesh {
            positions,
            normals: vec![],
            indices,
        });
        let mut grid = Vec::new();
        let mut quads = Vec::new();
        for i in 0..20u32 {
            for j in 0..20u32 {
                grid.push(Vec3::new(i as f32 * 0.1 - 1.0, j as f32 * 0.1 - 1.0, -1.2));
                if i < 19 && j < 19 {
                    let v = i * 20 + j;
                    quads.push([v, v + 20, v + 1]);
                    quads.push([v + 20, v + 21, v + 1]);
                }
            }
        }
        let plane = ShapeDesc::new(ShapeKind::Mesh {
            positions: grid,
            normals: vec![],
            indices: quads,
        });
        let ball = ShapeDesc::new(ShapeKind::Sphere {
            center: Vec3::new(0.2, 0.1, -0.3),
            radius: 0.3,
        });
        let shapes = [soup, plane, ball];
        let detected = Geometry::new(&shapes, None, AccelKind::Bvh8).unwrap();
        let four = Geometry::new(&shapes, None, AccelKind::Bvh).unwrap();
        let mut portable = detected.clone();
        match &mut portable.top.query {
            RayQuery::PackedBvh8(p) => *p = p.clone().with_simd(Simd8::Portable),
            _ => panic!("not the 8-wide BVH"),
        }
        let mut hits = 0;
        for _ in 0..4000 {
            let o = Vec3::new(f(), f(), f()) * 1.5;
            let ray = Ray {
                origin: o,
                dir: Vec3::new(f(), f(), f()).normalize_or(Vec3::Z),
            };
            let a = detected.intersect(&ray, f32::INFINITY);
            assert_eq!(a, portable.intersect(&ray, f32::INFINITY), "{ray:?}");
            let b = four.intersect(&ray, f32::INFINITY);
            match (&a, &b) {
                (Some(a), Some(b)) if a != b => {
                    assert!(a.t.is_finite() && b.t.is_finite());
                    assert!((a.t - b.t).abs() <= 1e-6 * b.t, "{a:?} vs {b:?}");
                }
                _ => assert_eq!(a, b, "{ray:?}"),
            }
            let t_max = f().abs() * 2.0;
            let occ = four.occluded(&ray, t_max);
            assert_eq!(detected.occluded(&ray, t_max), occ);
            assert_eq!(portable.occluded(&ray, t_max), occ);
            hits += usize::from(a.is_some());
        }
        assert!(hits > 1000, "{hits}");
    }
}
