//! Ray queries through the 4-wide BVH with each leaf's primitives packed: its quads
//! (triangle pairs forming a parallelogram, [`QuadPacket`]) into one 4-wide quad test, its
//! other triangles into one [`TriPacket`]. Spheres and disks in a leaf are stored after them
//! and tested one by one.
//!
//! The BVH is built over *units* ([`Unit`]): a quad or a single primitive. Stored
//! primitives ("slots", what [`HitRecord::index`] counts) list each leaf's quads first, two
//! triangles per quad (the one with `u + v ≤ 1` first), then its triangles, then the rest.

use super::build::Prim;
use super::packet::{TriPacket, TriRay4};
use super::pair::{Quad, Unit};
use super::quad::{QuadPacket, QuadRay4};
use super::{Geometry, HitRecord, Ray};
use crate::scene::accel::Bvh4;

/// A BVH leaf as the geometry stores it.
#[derive(Debug, Clone)]
pub(super) struct Leaf {
    /// First slot: quad `l` of the leaf is slots `first + 2l` and `first + 2l + 1`; its
    /// triangles follow the quads, then its spheres and disks, up to `end`.
    first: u32,
    end: u32,
    /// Index of the quad packet and of the triangle packet (when there are any).
    quad: u32,
    tri: u32,
    quads: u8,
    tris: u8,
}

/// Where a quad packet's lanes live: the first slot of each lane's pair and how its
/// parameters map to barycentrics ([`Quad::barycentrics`]).
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct QuadSlots {
    slot: [u32; 4],
    roles: [[[u8; 2]; 2]; 4],
}

/// The packed leaves of a BVH.
#[derive(Debug, Clone, Default)]
pub(super) struct Packed {
    leaves: Vec<Leaf>,
    quads: Vec<QuadPacket>,
    quad_slots: Vec<QuadSlots>,
    tris: Vec<TriPacket>,
}

/// Packs the BVH's leaves (built over `units`); returns the slots' input primitive indices
/// and the packed leaves. `prims` is in input order.
pub(super) fn pack(bvh: &Bvh4, units: &[Unit], prims: &[Prim]) -> (Vec<u32>, Packed) {
    let kind = |u: &Unit| match u {
        Unit::Pair { .. } => 0,
        Unit::One(i) if matches!(prims[*i as usize], Prim::Tri(_)) => 1,
        Unit::One(_) => 2,
    };
    let mut order = bvh.order().to_vec();
    let mut ranges: Vec<_> = (0..bvh.leaf_count()).map(|k| (bvh.leaf(k), k)).collect();
    ranges.sort_by_key(|(r, _)| r.start);
    let mut slots = Vec::with_capacity(prims.len());
    let mut packed = Packed::default();
    let mut leaves = vec![None; ranges.len()];
    for (r, k) in ranges {
        let unit = &mut order[r.start as usize..r.end as usize];
        unit.sort_by_key(|&u| kind(&units[u as usize])); // stable
        let first = slots.len() as u32;
        let (mut quads, mut q_slots, mut tris) = (Vec::new(), QuadSlots::default(), Vec::new());
        for &u in unit.iter() {
            match units[u as usize] {
                Unit::Pair {
                    first,
                    second,
                    quad,
                } => {
                    q_slots.slot[quads.len()] = slots.len() as u32;
                    q_slots.roles[quads.len()] = quad.roles;
                    quads.push(quad);
                    slots.extend([first, second]);
                }
                Unit::One(i) => {
                    if let Prim::Tri(t) = &prims[i as usize] {
                        tris.push(t.vertices());
                    }
                    slots.push(i);
                }
            }
        }
        debug_assert!(
            quads.len() + tris.len() <= 4,
            "BVH leaves hold at most 4 units"
        );
        leaves[k] = Some(Leaf {
            first,
            end: slots.len() as u32,
            quad: packed.quads.len() as u32,
            tri: packed.tris.len() as u32,
            quads: quads.len() as u8,
            tris: tris.len() as u8,
        });
        if !quads.is_empty() {
            packed.quads.push(QuadPacket::new(&quads));
            packed.quad_slots.push(q_slots);
        }
        if !tris.is_empty() {
            packed.tris.push(TriPacket::new(&tris));
        }
    }
    packed.leaves = leaves.into_iter().flatten().collect();
    (slots, packed)
}

/// What a closest-hit search found: a primitive, or a quad lane and its parameters.
#[derive(Clone, Copy)]
enum Found {
    Prim(HitRecord),
    Quad {
        packet: u32,
        lane: u32,
        u: f32,
        v: f32,
    },
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
        let p = &self.packed;
        let quad = QuadRay4::new(ray.origin, ray.dir);
        // The triangle test's per-ray set-up only where there are triangle packets.
        let tri = (!p.tris.is_empty()).then(|| TriRay4::new(ray.origin, ray.dir));
        let mut found = None;
        let t = bvh.closest_leaf(ray.origin, ray.dir, t_max, |k, bound| {
            let leaf = &p.leaves[k as usize];
            if leaf.quads > 0 {
                if let Some(h) = quad.closest(&p.quads[leaf.quad as usize], *bound) {
                    *bound = h.t;
                    found = Some(Found::Quad {
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
                    found = Some(Found::Prim(HitRecord {
                        index: leaf.first + 2 * u32::from(leaf.quads) + h.lane,
                        b1: h.b1,
                        b2: h.b2,
                    }));
                }
            }
            let rest = leaf.first + 2 * u32::from(leaf.quads) + u32::from(leaf.tris);
            for i in rest..leaf.end {
                if let Some((t, b1, b2)) = self.hit_other(ray, i, *bound) {
                    *bound = t;
                    found = Some(Found::Prim(HitRecord { index: i, b1, b2 }));
                }
            }
        });
        let rec = match found? {
            Found::Prim(r) => r,
            Found::Quad { packet, lane, u, v } => {
                let s = &p.quad_slots[packet as usize];
                let (k, b1, b2) = Quad::barycentrics(s.roles[lane as usize], u, v);
                HitRecord {
                    index: s.slot[lane as usize] + k,
                    b1,
                    b2,
                }
            }
        };
        Some((t, rec))
    }

    /// True when anything is hit with `0 < t < t_max`, through the BVH's packed leaves.
    #[inline(always)]
    pub(super) fn occluded_packed(&self, bvh: &Bvh4, ray: &Ray, t_max: f32) -> bool {
        let p = &self.packed;
        let quad = QuadRay4::new(ray.origin, ray.dir);
        let tri = (!p.tris.is_empty()).then(|| TriRay4::new(ray.origin, ray.dir));
        bvh.any_leaf(ray.origin, ray.dir, t_max, |k, bound| {
            let leaf = &p.leaves[k as usize];
            let rest = leaf.first + 2 * u32::from(leaf.quads) + u32::from(leaf.tris);
            (leaf.quads > 0 && quad.any(&p.quads[leaf.quad as usize], bound))
                || (leaf.tris > 0 && tri.is_some_and(|r| r.any(&p.tris[leaf.tri as usize], bound)))
                || (rest..leaf.end).any(|i| self.hit_other(ray, i, bound).is_some())
        })
    }
}
