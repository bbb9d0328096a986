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
use super::pair::{Quad, Unit, WeightMaps};
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
    maps: [WeightMaps; 4],
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
                    q_slots.maps[quads.len()] = quad.maps();
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
            if leaf.tris > 0 || leaf.first + 2 * u32::from(leaf.quads) < leaf.end {
                self.closest_rest(leaf, ray, tri.as_ref(), bound, &mut found);
            }
        });
        let rec = match found? {
            Found::Prim(r) => r,
            Found::Quad { packet, lane, u, v } => {
                let s = &p.quad_slots[packet as usize];
                let lane = lane as usize & 3;
                let (k, b1, b2) = Quad::barycentrics(&s.maps[lane], u, v);
                HitRecord {
                    index: s.slot[lane] + k,
                    b1,
                    b2,
                }
            }
        };
        Some((t, rec))
    }

    /// The nearest hit among a leaf's triangles, spheres and disks (out of line, so that
    /// leaves of quads alone stay cheap).
    #[inline(never)]
    fn closest_rest(
        &self,
        leaf: &Leaf,
        ray: &Ray,
        tri: Option<&TriRay4>,
        bound: &mut f32,
        found: &mut Option<Found>,
    ) {
        self.closest_rest_inline(leaf, ray, tri, bound, found);
    }

    /// The body of [`Geometry::closest_rest`], inlined where a leaf holds no quads.
    #[inline(always)]
    fn closest_rest_inline(
        &self,
        leaf: &Leaf,
        ray: &Ray,
        tri: Option<&TriRay4>,
        bound: &mut f32,
        found: &mut Option<Found>,
    ) {
        let first = leaf.first + 2 * u32::from(leaf.quads);
        if let (true, Some(tri)) = (leaf.tris > 0, tri) {
            if let Some(h) = tri.closest(&self.packed.tris[leaf.tri as usize], *bound) {
                *bound = h.t;
                *found = Some(Found::Prim(HitRecord {
                    index: first + h.lane,
                    b1: h.b1,
                    b2: h.b2,
                }));
            }
        }
        for i in first + u32::from(leaf.tris)..leaf.end {
            if let Some((t, b1, b2)) = self.hit_other(ray, i, *bound) {
                *bound = t;
                *found = Some(Found::Prim(HitRecord { index: i, b1, b2 }));
            }
        }
    }

    /// True when a leaf's triangle packet is hit with `0 < t < t_max` (out of line: the
    /// any-hit visitor stays small).
    #[inline(never)]
    fn any_tris(&self, leaf: &Leaf, tri: Option<&TriRay4>, t_max: f32) -> bool {
        self.any_tris_inline(leaf, tri, t_max)
    }

    /// The body of [`Geometry::any_tris`], inlined where the scene has no quads.
    #[inline(always)]
    fn any_tris_inline(&self, leaf: &Leaf, tri: Option<&TriRay4>, t_max: f32) -> bool {
        tri.is_some_and(|r| r.any(&self.packed.tris[leaf.tri as usize], t_max))
    }

    /// True when anything is hit with `0 < t < t_max`, through the BVH's packed leaves.
    #[inline(always)]
    pub(super) fn occluded_packed(&self, bvh: &Bvh4, ray: &Ray, t_max: f32) -> bool {
        if self.packed.quads.is_empty() {
            self.occluded_leaves::<false>(bvh, ray, t_max)
        } else {
            self.occluded_leaves::<true>(bvh, ray, t_max)
        }
    }

    /// [`Geometry::occluded_packed`] for a scene with (`QUADS`) or without quad packets (then
    /// the triangle packet test is inline).
    #[inline(always)]
    fn occluded_leaves<const QUADS: bool>(&self, bvh: &Bvh4, ray: &Ray, t_max: f32) -> bool {
        let p = &self.packed;
        let quad = QUADS.then(|| QuadRay4::new(ray.origin, ray.dir));
        let tri = (!p.tris.is_empty()).then(|| TriRay4::new(ray.origin, ray.dir));
        bvh.any_leaf(ray.origin, ray.dir, t_max, |k, bound| {
            let leaf = &p.leaves[k as usize];
            let rest = leaf.first + 2 * u32::from(leaf.quads) + u32::from(leaf.tris);
            let tris = || {
                if QUADS {
                    self.any_tris(leaf, tri.as_ref(), bound)
                } else {
                    self.any_tris_inline(leaf, tri.as_ref(), bound)
                }
            };
            (leaf.quads > 0
                && quad
                    .as_ref()
                    .is_some_and(|q| q.any(&p.quads[leaf.quad as usize], bound)))
                || (leaf.tris > 0 && tris())
                || (rest..leaf.end).any(|i| self.hit_other(ray, i, bound).is_some())
        })
    }
}

#[cfg(test)]
mod tests {
    use super::super::{AccelKind, Geometry, Hit, Ray};
    use crate::scene::description::{ShapeDesc, ShapeKind};
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
        let shapes = crate::scene::cornell_box::cornell_box().shapes;
        let bvh = Geometry::new(&shapes, None, AccelKind::Bvh).unwrap();
        let brute = Geometry::new(&shapes, None, AccelKind::BruteForce).unwrap();
        let quads: usize = bvh.packed.leaves.iter().map(|l| usize::from(l.quads)).sum();
        assert_eq!((quads, bvh.packed.tris.len()), (18, 0));
        assert_eq!(bvh.primitive_count(), brute.primitive_count());
        let mut rng = rand_pcg::Pcg32::seed_from_u64(3);
        let (mut same, mut n) = (0, 0);
        for _ in 0..20_000 {
            let ray = random_ray(&mut rng, 0.95);
            let w = |h: &Hit| {
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
            assert_eq!((a.ng, a.ns), (b.ng, b.ns));
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
        assert!(bvh.packed.quads.is_empty() && !bvh.packed.tris.is_empty());
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
