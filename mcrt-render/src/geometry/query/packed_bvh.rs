//! Ray queries through the 4-wide or the 8-wide BVH ([`LeafTree`]: both have the same
//! leaves) with each leaf's primitives packed: its quads
//! (triangle pairs forming a parallelogram, [`QuadPacket`]) into one 4-wide quad test, its
//! other triangles into one [`TriPacket`]. Spheres and disks in a leaf are stored after them
//! and tested one by one.
//!
//! The BVH is built over *units* ([`Unit`]): a quad or a single primitive. Stored
//! primitives ("slots", what [`HitRecord::slot`] counts) list each leaf's quads first, two
//! triangles per quad (the one with `u + v ≤ 1` first), then its triangles, then the rest.

use super::super::data::Prim;
use super::pairing::{Quad, Unit, WeightMaps};
use super::quad4::{QuadPacket, QuadRay4};
use super::tri4::{TriPacket, TriRay4};
use super::{HitRecord, Ray, Stored};
use crate::accel::{Bvh4, Bvh8, LeafQueries};
use std::ops::Range;

/// A BVH whose leaves hold ranges of stored primitives, walked per leaf
/// ([`LeafQueries::closest_leaf`], [`LeafQueries::any_leaf`]): [`Bvh4`] and [`Bvh8`] (the
/// rest are their inherent methods of the same names).
pub(crate) trait LeafTree: LeafQueries {
    /// `order[i]`: the input index of the unit stored at position `i`.
    fn order(&self) -> &[u32];
    /// Number of leaves.
    fn leaf_count(&self) -> usize;
    /// The stored units of leaf `k`.
    fn leaf(&self, k: usize) -> Range<u32>;
    /// Heap bytes held.
    fn heap_bytes(&self) -> usize;
}

macro_rules! leaf_tree {
    ($t:ty) => {
        impl LeafTree for $t {
            fn order(&self) -> &[u32] {
                <$t>::order(self)
            }
            fn leaf_count(&self) -> usize {
                <$t>::leaf_count(self)
            }
            fn leaf(&self, k: usize) -> Range<u32> {
                <$t>::leaf(self, k)
            }
            fn heap_bytes(&self) -> usize {
                <$t>::heap_bytes(self)
            }
        }
    };
}
leaf_tree!(Bvh4);
leaf_tree!(Bvh8);

/// A BVH leaf as the geometry stores it.
#[derive(Debug, Clone)]
pub(super) struct Leaf {
    /// First slot: quad `l` of the leaf is slots `first + 2l` and `first + 2l + 1`; its
    /// triangles follow the quads, then its spheres and disks, up to `end`.
    pub(super) first: u32,
    pub(super) end: u32,
    /// Index of the quad packet and of the triangle packet (when there are any).
    pub(super) quad: u32,
    pub(super) tri: u32,
    pub(super) quads: u8,
    pub(super) tris: u8,
}

impl Leaf {
    /// The slot of the leaf's first triangle outside a quad (its triangle packet's lane 0).
    #[inline(always)]
    pub(super) fn first_tri(&self) -> u32 {
        self.first + 2 * u32::from(self.quads)
    }

    /// The slot of the leaf's first sphere or disk.
    #[inline(always)]
    pub(super) fn first_other(&self) -> u32 {
        self.first_tri() + u32::from(self.tris)
    }
}

/// Where a quad packet's `N` lanes live: the first slot of each lane's pair and how its
/// parameters map to barycentrics ([`Quad::barycentrics`]).
#[derive(Debug, Clone, Copy)]
pub(super) struct QuadSlots<const N: usize> {
    slot: [u32; N],
    maps: [WeightMaps; N],
}

impl<const N: usize> QuadSlots<N> {
    fn new() -> Self {
        Self {
            slot: [0; N],
            maps: [WeightMaps::default(); N],
        }
    }

    /// The triangle slot and barycentrics of a hit at parameters `(u, v)` in lane `lane`.
    #[inline(always)]
    pub(super) fn record(&self, lane: u32, u: f32, v: f32) -> HitRecord {
        let lane = lane as usize % N;
        let (k, b1, b2) = Quad::barycentrics(&self.maps[lane], u, v);
        HitRecord {
            slot: self.slot[lane] + k,
            b1,
            b2,
        }
    }
}

/// A BVH (`B`: 4-wide or 8-wide) and its packed leaves: quad packets `Q` and triangle
/// packets `T` of `N` lanes each ([`PackedBvh`]: 4, [`super::packed_bvh8::PackedBvh8`]: 8).
#[derive(Debug, Clone)]
pub(crate) struct PackedLeaves<B, Q, T, const N: usize> {
    pub(super) bvh: B,
    /// By leaf number.
    pub(super) leaves: Vec<Leaf>,
    pub(super) quads: Vec<Q>,
    pub(super) quad_slots: Vec<QuadSlots<N>>,
    pub(super) tris: Vec<T>,
}

/// A BVH (4-wide or 8-wide) with 4-lane packets.
pub(crate) type PackedBvh<B = Bvh4> = PackedLeaves<B, QuadPacket, TriPacket, 4>;

impl<B: LeafTree, Q, T, const N: usize> PackedLeaves<B, Q, T, N> {
    /// Orders the units of each leaf of `bvh` (built over `units`; `prims` in input order)
    /// quads first, then triangles, then the rest, and makes each leaf's packets from its
    /// quads and triangles (when it has any) with `quad_packet` and `tri_packet`; returns
    /// the slots' input primitive indices and the packed BVH.
    pub(super) fn pack_with(
        bvh: B,
        units: &[Unit],
        prims: &[Prim],
        quad_packet: impl Fn(&[Quad]) -> Q,
        tri_packet: impl Fn(&[[glam::Vec3; 3]]) -> T,
    ) -> (Vec<u32>, Self) {
        let kind = |u: &Unit| match u {
            Unit::Pair { .. } => 0,
            Unit::One(i) if matches!(prims[*i as usize], Prim::Tri(_)) => 1,
            Unit::One(_) => 2,
        };
        let mut order = bvh.order().to_vec();
        let mut ranges: Vec<_> = (0..bvh.leaf_count()).map(|k| (bvh.leaf(k), k)).collect();
        ranges.sort_unstable_by_key(|(r, _)| r.start); // the starts differ
        let mut slots = Vec::with_capacity(prims.len());
        let mut quad_slots = Vec::new();
        let (mut quad_packets, mut tri_packets) = (Vec::new(), Vec::new());
        let mut leaves = vec![None; ranges.len()];
        // Each leaf's quads and triangles, cleared per leaf (allocated once).
        let (mut quads, mut tris) = (Vec::with_capacity(N), Vec::with_capacity(N));
        for (r, k) in ranges {
            let leaf_units = &mut order[r.start as usize..r.end as usize];
            leaf_units.sort_by_key(|&u| kind(&units[u as usize])); // stable
            let first = slots.len() as u32;
            let mut q_slots = QuadSlots::new();
            quads.clear();
            tris.clear();
            for &u in leaf_units.iter() {
                match units[u as usize] {
                    Unit::Pair {
                        first,
                        second,
                        quad,
                    } => {
                        q_slots.slot[quads.len() % N] = slots.len() as u32;
                        q_slots.maps[quads.len() % N] = quad.maps();
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
                quads.len() + tris.len() <= N,
                "BVH leaves hold at most {N} units"
            );
            leaves[k] = Some(Leaf {
                first,
                end: slots.len() as u32,
                quad: quad_packets.len() as u32,
                tri: tri_packets.len() as u32,
                quads: quads.len() as u8,
                tris: tris.len() as u8,
            });
            if !quads.is_empty() {
                quad_packets.push(quad_packet(&quads));
                quad_slots.push(q_slots);
            }
            if !tris.is_empty() {
                tri_packets.push(tri_packet(&tris));
            }
        }
        let packed = Self {
            bvh,
            leaves: leaves.into_iter().flatten().collect(),
            quads: quad_packets,
            quad_slots,
            tris: tri_packets,
        };
        (slots, packed)
    }

    /// Heap bytes held (the BVH and the packed leaves).
    pub(super) fn heap_bytes(&self) -> usize {
        use crate::accel::vec_bytes;
        self.bvh.heap_bytes()
            + vec_bytes(&self.leaves)
            + vec_bytes(&self.quads)
            + vec_bytes(&self.quad_slots)
            + vec_bytes(&self.tris)
    }

    /// The triangle slot and barycentrics of what a closest-hit search found.
    #[inline(always)]
    pub(super) fn record(&self, found: LeafHit) -> HitRecord {
        match found {
            LeafHit::Prim(r) => r,
            LeafHit::Quad { packet, lane, u, v } => {
                self.quad_slots[packet as usize].record(lane, u, v)
            }
        }
    }
}

/// What a closest-hit search found in a leaf: a primitive, or a quad lane and its
/// parameters (mapped to a triangle and barycentrics once the search is over).
#[derive(Clone, Copy)]
pub(super) enum LeafHit {
    Prim(HitRecord),
    Quad {
        packet: u32,
        lane: u32,
        u: f32,
        v: f32,
    },
}

impl<B: LeafTree> PackedBvh<B> {
    /// Packs the leaves of `bvh` (built over `units`); returns the slots' input primitive
    /// indices and the packed BVH. `prims` is in input order.
    pub(super) fn pack(bvh: B, units: &[Unit], prims: &[Prim]) -> (Vec<u32>, Self) {
        Self::pack_with(bvh, units, prims, QuadPacket::new, TriPacket::new)
    }

    /// The nearest hit with `0 < t < t_max`.
    #[inline(always)]
    pub(super) fn closest(
        &self,
        stored: Stored,
        ray: &Ray,
        t_max: f32,
    ) -> Option<(f32, HitRecord)> {
        let quad = QuadRay4::new(ray.origin, ray.dir);
        // The triangle test's per-ray set-up only where there are triangle packets.
        let tri = (!self.tris.is_empty()).then(|| TriRay4::new(ray.origin, ray.dir));
        let mut found = None;
        // The visitor is inlined into the walk: called, it cost as much again as the quad
        // test (the walk's ray spilled around each call), about 60 instructions per leaf.
        let t = self.bvh.closest_leaf(
            ray.origin,
            ray.dir,
            t_max,
            #[inline(always)]
            |k, bound| {
                let leaf = &self.leaves[k as usize];
                if leaf.quads > 0 {
                    if let Some(h) = quad.closest(&self.quads[leaf.quad as usize], *bound) {
                        *bound = h.t;
                        found = Some(LeafHit::Quad {
                            packet: leaf.quad,
                            lane: h.lane,
                            u: h.u,
                            v: h.v,
                        });
                    }
                }
                if leaf.first_tri() < leaf.end {
                    self.closest_past_quads(stored, leaf, ray, tri.as_ref(), bound, &mut found);
                }
            },
        );
        Some((t, self.record(found?)))
    }

    /// The nearest hit among a leaf's triangles, spheres and disks (out of line, so that
    /// leaves of quads alone stay cheap).
    #[inline(never)]
    fn closest_past_quads(
        &self,
        stored: Stored,
        leaf: &Leaf,
        ray: &Ray,
        tri: Option<&TriRay4>,
        bound: &mut f32,
        found: &mut Option<LeafHit>,
    ) {
        if let (true, Some(tri)) = (leaf.tris > 0, tri) {
            if let Some(h) = tri.closest(&self.tris[leaf.tri as usize], *bound) {
                *bound = h.t;
                *found = Some(LeafHit::Prim(HitRecord {
                    slot: leaf.first_tri() + h.lane,
                    b1: h.b1,
                    b2: h.b2,
                }));
            }
        }
        for i in leaf.first_other()..leaf.end {
            if let Some((t, b1, b2)) = stored.hit(ray, None, i, *bound) {
                *bound = t;
                *found = Some(LeafHit::Prim(HitRecord { slot: i, b1, b2 }));
            }
        }
    }

    /// True when a leaf's triangle packet is hit with `0 < t < t_max`, out of line (so the
    /// any-hit visitor stays small where quads are tested inline).
    #[inline(never)]
    fn any_tri_packet_out_of_line(&self, leaf: &Leaf, tri: Option<&TriRay4>, t_max: f32) -> bool {
        self.any_tri_packet(leaf, tri, t_max)
    }

    /// True when a leaf's triangle packet is hit with `0 < t < t_max`.
    #[inline(always)]
    fn any_tri_packet(&self, leaf: &Leaf, tri: Option<&TriRay4>, t_max: f32) -> bool {
        tri.is_some_and(|r| r.any(&self.tris[leaf.tri as usize], t_max))
    }

    /// True when one of a leaf's spheres, disks or cylinders is hit with `0 < t < t_max`
    /// (out of line, so that leaves of quads and triangles alone stay cheap).
    #[inline(never)]
    fn any_other(&self, stored: Stored, leaf: &Leaf, ray: &Ray, t_max: f32) -> bool {
        (leaf.first_other()..leaf.end).any(|i| stored.hit(ray, None, i, t_max).is_some())
    }

    /// True when anything is hit with `0 < t < t_max`.
    #[inline(always)]
    pub(super) fn any(&self, stored: Stored, ray: &Ray, t_max: f32) -> bool {
        if self.quads.is_empty() {
            self.any_in_leaves::<false>(stored, ray, t_max)
        } else {
            self.any_in_leaves::<true>(stored, ray, t_max)
        }
    }

    /// [`PackedBvh::any`] for a scene with (`QUADS`) or without quad packets (then the
    /// triangle packet test is inline).
    #[inline(always)]
    fn any_in_leaves<const QUADS: bool>(&self, stored: Stored, ray: &Ray, t_max: f32) -> bool {
        let quad = QUADS.then(|| QuadRay4::new(ray.origin, ray.dir));
        let tri = (!self.tris.is_empty()).then(|| TriRay4::new(ray.origin, ray.dir));
        // Inlined into the walk, as in `closest`.
        self.bvh.any_leaf(
            ray.origin,
            ray.dir,
            t_max,
            #[inline(always)]
            |k, bound| {
                let leaf = &self.leaves[k as usize];
                let tris = || {
                    if QUADS {
                        self.any_tri_packet_out_of_line(leaf, tri.as_ref(), bound)
                    } else {
                        self.any_tri_packet(leaf, tri.as_ref(), bound)
                    }
                };
                (leaf.quads > 0
                    && quad
                        .as_ref()
                        .is_some_and(|q| q.any(&self.quads[leaf.quad as usize], bound)))
                    || (leaf.tris > 0 && tris())
                    || (leaf.first_other() < leaf.end && self.any_other(stored, leaf, ray, bound))
            },
        )
    }
}

#[cfg(test)]
mod tests {
    use super::super::super::{AccelKind, Geometry, Ray};
    use super::super::RayQuery;
    use super::PackedBvh;
    use mcrt::integrator::SurfacePoint;

    fn packed(g: &Geometry) -> &PackedBvh {
        match &g.top.query {
            RayQuery::PackedBvh(p) => p,
            _ => panic!("not the packed BVH"),
        }
    }
    use crate::description::{ShapeDesc, ShapeKind};
    use glam::Vec3;
    use rand_core::{RngCore, SeedableRng};

    fn uniform(rng: &mut rand_pcg::Pcg32) -> f32 {
        (rng.next_u32() >> 8) as f32 / (1u32 << 24) as f32 * 2.0 - 1.0
    }

    fn random_ray(rng: &mut rand_pcg::Pcg32, spread: f32) -> Ray {
        let mut v = || Vec3::new(uniform(rng), uniform(rng), uniform(rng));
        Ray {
            origin: v() * spread,
            dir: v().normalize_or(Vec3::Z),
        }
    }

    /// On the Cornell box every wall and box face becomes a quad, and hits through the
    /// quads land on the same triangle at the same point (barycentrics mapped back) as the
    /// brute-force triangle tests find, away from the diagonals and borders.
    #[test]
    fn cornell_box_quads_map_back_to_the_same_triangles() {
        let shapes = crate::cornell_box::cornell_box().shapes;
        let bvh = Geometry::new(&shapes, None, AccelKind::Bvh).unwrap();
        let brute = Geometry::new(&shapes, None, AccelKind::BruteForce).unwrap();
        let quads: usize = packed(&bvh)
            .leaves
            .iter()
            .map(|l| usize::from(l.quads))
            .sum();
        assert_eq!((quads, packed(&bvh).tris.len()), (18, 0));
        assert_eq!(bvh.primitive_count(), brute.primitive_count());
        let mut rng = rand_pcg::Pcg32::seed_from_u64(3);
        let (mut same, mut n) = (0, 0);
        for _ in 0..20_000 {
            let ray = random_ray(&mut rng, 0.95);
            let w = |h: &SurfacePoint| {
                let w = [1.0 - h.uv.x - h.uv.y, h.uv.x, h.uv.y];
                w.into_iter().fold(f32::INFINITY, f32::min)
            };
            let (a, b) = match (
                bvh.intersect(&ray, f32::INFINITY),
                brute.intersect(&ray, f32::INFINITY),
            ) {
                (Some(a), Some(b)) => (a, b),
                (None, None) => continue, // out through the open front
                // In the slack band of a quad's border (the ray then leaves by the front).
                (Some(a), None) if w(&a) < 1e-4 => continue,
                (a, b) => panic!("{a:?} vs {b:?} for {ray:?}"),
            };
            assert!(a.t.is_finite() && a.p.is_finite() && a.uv.is_finite());
            n += 1;
            assert!(w(&a) >= 0.0, "barycentrics outside the triangle: {a:?}");
            let tie = a.shape != b.shape && (a.t - b.t).abs() <= 1e-5 * b.t;
            if w(&b) < 1e-4 || tie || (w(&a) < 1e-4 && a.t < b.t) {
                continue; // near an edge or a diagonal, or coplanar faces (box on the floor)
            }
            assert_eq!((a.shape, a.prim), (b.shape, b.prim), "{ray:?}");
            assert!(a.p.distance(b.p) < 1e-5, "{a:?} vs {b:?}");
            assert!((a.uv - b.uv).abs().max_element() < 1e-4, "{a:?} vs {b:?}");
            assert_eq!((a.ng, a.frame.n), (b.ng, b.frame.n));
            same += 1;
        }
        assert!(same > n * 9 / 10, "{same} of {n}");
    }

    /// Meshes without parallelograms keep triangle packets, and their hits stay bit for
    /// bit those of the one-triangle test.
    #[test]
    fn scenes_without_quads_are_unchanged() {
        let mut rng = rand_pcg::Pcg32::seed_from_u64(4);
        let positions: Vec<Vec3> = (0..300)
            .map(|_| Vec3::new(uniform(&mut rng), uniform(&mut rng), uniform(&mut rng)))
            .collect();
        let indices = (0..100).map(|k| [3 * k, 3 * k + 1, 3 * k + 2]).collect();
        let soup = ShapeDesc::new(ShapeKind::Mesh {
            positions,
            normals: vec![],
            indices,
        });
        let ball = ShapeDesc::new(ShapeKind::Sphere {
            center: Vec3::new(0.2, 0.1, -0.3),
            radius: 0.3,
        });
        let shapes = [soup, ball];
        let bvh = Geometry::new(&shapes, None, AccelKind::Bvh).unwrap();
        let brute = Geometry::new(&shapes, None, AccelKind::BruteForce).unwrap();
        assert!(packed(&bvh).quads.is_empty() && !packed(&bvh).tris.is_empty());
        let mut hits = 0;
        for _ in 0..5000 {
            let ray = random_ray(&mut rng, 2.0);
            let (a, b) = (
                bvh.intersect(&ray, f32::INFINITY),
                brute.intersect(&ray, f32::INFINITY),
            );
            if let (Some(a), Some(b)) = (a, b) {
                assert!(a.t.is_finite());
                if a.t == b.t && (a.shape, a.prim) != (b.shape, b.prim) {
                    continue; // a tie between two primitives
                }
            }
            assert_eq!(a, b, "{ray:?}");
            assert_eq!(bvh.occluded(&ray, 1.0), brute.occluded(&ray, 1.0));
            hits += usize::from(a.is_some());
        }
        assert!(hits > 500, "{hits}");
    }
}
