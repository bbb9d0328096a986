//! Ray queries through the 4-wide BVH with each leaf's triangles packed into one
//! [`TriPacket`]: a leaf costs one 4-wide triangle test instead of up to four scalar ones.
//! Spheres and disks in a leaf are stored after its triangles and tested one by one.

use super::build::Prim;
use super::packet::{TriPacket, TriRay4};
use super::{Geometry, HitRecord, Ray};
use crate::scene::accel::Bvh4;

/// A BVH leaf as the geometry stores it: its triangles packed, then its other primitives.
#[derive(Debug, Clone)]
pub(super) struct Leaf {
    /// The leaf's triangles (stored positions `first .. first + tris`), lane `l` = position
    /// `first + l`.
    packet: TriPacket,
    first: u32,
    tris: u32,
    /// One past the last primitive; `first + tris .. end` are spheres and disks.
    end: u32,
}

/// Reorders the BVH's storage `order` so that every leaf lists its triangles first, and
/// packs the leaves. `prims` is in input order.
pub(super) fn pack(bvh: &Bvh4, prims: &[Prim], order: &mut [u32]) -> Vec<Leaf> {
    let is_tri = |i: &u32| matches!(prims[*i as usize], Prim::Tri(_));
    (0..bvh.leaf_count())
        .map(|k| {
            let r = bvh.leaf(k);
            let slot = &mut order[r.start as usize..r.end as usize];
            // Stable: triangles first, then the rest, each in BVH order.
            let (mut tri, rest): (Vec<u32>, Vec<u32>) = slot.iter().copied().partition(is_tri);
            let tris = tri.len();
            tri.extend(rest);
            slot.copy_from_slice(&tri);
            let verts: Vec<_> = slot[..tris.min(4)]
                .iter()
                .filter_map(|&i| match &prims[i as usize] {
                    Prim::Tri(t) => Some(t.vertices()),
                    _ => None,
                })
                .collect();
            debug_assert!(tris <= 4, "BVH leaves hold at most 4 primitives");
            Leaf {
                packet: TriPacket::new(&verts),
                first: r.start,
                tris: tris.min(4) as u32,
                end: r.end,
            }
        })
        .collect()
}

impl Geometry {
    /// The nearest hit through the BVH's packed leaves.
    #[inline(always)]
    pub(super) fn closest_packed(
        &self,
        bvh: &Bvh4,
        ray: &Ray,
        t_max: f32,
    ) -> Option<(f32, HitRecord)> {
        let tri = TriRay4::new(ray.origin, ray.dir);
        let mut rec = None;
        let t = bvh.closest_leaf(ray.origin, ray.dir, t_max, |k, bound| {
            let leaf = &self.leaves[k as usize];
            if leaf.tris > 0 {
                if let Some(h) = tri.closest(&leaf.packet, *bound) {
                    *bound = h.t;
                    rec = Some(HitRecord {
                        index: leaf.first + h.lane,
                        b1: h.b1,
                        b2: h.b2,
                    });
                }
            }
            for i in leaf.first + leaf.tris..leaf.end {
                if let Some((t, b1, b2)) = self.hit_other(ray, i, *bound) {
                    *bound = t;
                    rec = Some(HitRecord { index: i, b1, b2 });
                }
            }
        });
        rec.map(|r| (t, r))
    }

    /// True when anything is hit with `0 < t < t_max`, through the BVH's packed leaves.
    #[inline(always)]
    pub(super) fn occluded_packed(&self, bvh: &Bvh4, ray: &Ray, t_max: f32) -> bool {
        let tri = TriRay4::new(ray.origin, ray.dir);
        bvh.any_leaf(ray.origin, ray.dir, t_max, |k, bound| {
            let leaf = &self.leaves[k as usize];
            (leaf.tris > 0 && tri.any(&leaf.packet, bound))
                || (leaf.first + leaf.tris..leaf.end)
                    .any(|i| self.hit_other(ray, i, bound).is_some())
        })
    }
}
