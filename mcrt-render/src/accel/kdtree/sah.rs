//! Events and the SAH sweep of the kd-tree build (Wald & Havran 2006; the SAH of MacDonald
//! & Booth 1990).
//!
//! Each axis has one list of events, sorted by position once at the root (ends before starts
//! at one position). A node sweeps its three lists: at a plane `p`, `N_L` counts the boxes
//! that start before `p` and `N_R` those that end after it, so a box ending at `p` is left
//! only and one starting at `p` right only, and the plane costs
//! `λ · (K_T + K_I · (A_L N_L + A_R N_R) / A)`. Boxes are not clipped to the voxels:
//! clipping a box (not the primitive) would only move the events lying outside a voxel onto
//! its faces, where they are no candidates, and leave the counts at every plane inside it
//! unchanged, so the SAH is the same.

use super::{EMPTY_BONUS, INTERSECTION_COST, TRAVERSAL_COST};
use crate::accel::aabb::Aabb;
use glam::Vec3;

/// One event: the position and `prim << 1 | START` (an end has the low bit clear).
#[derive(Debug, Clone, Copy)]
pub(super) struct Event {
    pub(super) pos: f32,
    key: u32,
}

const START: u32 = 1;

impl Event {
    #[inline]
    pub(super) fn prim(self) -> usize {
        (self.key >> 1) as usize
    }

    #[inline]
    pub(super) fn is_start(self) -> bool {
        self.key & START != 0
    }
}

/// A split plane and its cost, with the primitive counts on each side.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Split {
    pub(super) axis: usize,
    pub(super) pos: f32,
    pub(super) cost: f64,
    pub(super) left: usize,
    pub(super) right: usize,
}

/// The padded box of a primitive, or `None` if it is empty or holds a NaN; infinite
/// coordinates are clamped to the largest finite float.
pub(super) fn usable(b: &Aabb) -> Option<Aabb> {
    if b.min.is_nan() || b.max.is_nan() || b.is_empty() {
        return None;
    }
    let big = Vec3::splat(f32::MAX);
    let clamp = |v: Vec3| v.clamp(-big, big);
    let p = Aabb {
        min: clamp(b.min),
        max: clamp(b.max),
    }
    .padded();
    Some(Aabb {
        // The padding cannot make min and max meet: a relative 2⁻²⁰ exceeds an ulp.
        min: clamp(p.min) + Vec3::ZERO, // + 0 turns −0 into +0, so == and the sort agree
        max: clamp(p.max) + Vec3::ZERO,
    })
}

/// The start and end events of the usable boxes along `axis`, sorted by position, ends
/// first at one position (then by primitive, so the order is fixed).
pub(super) fn sorted_events(boxes: &[Option<Aabb>], axis: usize) -> Vec<Event> {
    let mut ev = Vec::with_capacity(2 * boxes.len());
    for (i, b) in boxes.iter().enumerate() {
        if let Some(b) = b {
            let key = (i as u32) << 1;
            ev.push(Event {
                pos: b.min[axis],
                key: key | START,
            });
            ev.push(Event {
                pos: b.max[axis],
                key,
            });
        }
    }
    ev.sort_unstable_by(|a, b| {
        a.pos
            .total_cmp(&b.pos)
            .then((a.key & START).cmp(&(b.key & START)))
            .then(a.key.cmp(&b.key))
    });
    ev
}

/// The SAH cost of the planes across one axis of a voxel: precomputed factors.
struct SahAxis {
    /// `u·v` and `u + v` of the voxel's two other edge lengths.
    uv: f64,
    u_plus_v: f64,
    lo: f64,
    hi: f64,
    /// `K_I / A(V)`.
    scale: f64,
}

impl SahAxis {
    fn new(voxel: &Aabb, area: f64, axis: usize) -> Self {
        let e = voxel.extent().as_dvec3();
        let (u, v) = (e[(axis + 1) % 3], e[(axis + 2) % 3]);
        Self {
            uv: u * v,
            u_plus_v: u + v,
            lo: f64::from(voxel.min[axis]),
            hi: f64::from(voxel.max[axis]),
            scale: INTERSECTION_COST / area,
        }
    }

    /// The cost of the plane at `pos` with `left` and `right` primitives on its sides;
    /// in f64, so huge scenes do not overflow.
    #[inline]
    fn cost(&self, pos: f32, left: u32, right: u32) -> f64 {
        let side_area = |w: f64| 2.0 * (self.uv + w * self.u_plus_v);
        let pos = f64::from(pos);
        let weighted = side_area(pos - self.lo) * f64::from(left)
            + side_area(self.hi - pos) * f64::from(right);
        let cost = TRAVERSAL_COST + self.scale * weighted;
        if left == 0 || right == 0 {
            EMPTY_BONUS * cost
        } else {
            cost
        }
    }
}

/// The cheapest plane strictly inside `voxel` over the three sweeps, if it is cheaper than
/// a leaf of `n` primitives (`K_I · n`).
pub(super) fn best_split(voxel: &Aabb, events: &[Vec<Event>; 3], n: usize) -> Option<Split> {
    let e = voxel.extent().as_dvec3();
    let area = 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
    if !(area > 0.0 && area.is_finite()) {
        return None;
    }
    let mut best = None;
    let mut best_cost = INTERSECTION_COST * n as f64; // a leaf's
    for (axis, list) in events.iter().enumerate() {
        let sah = SahAxis::new(voxel, area, axis);
        let (lo, hi) = (voxel.min[axis], voxel.max[axis]);
        let (mut left, mut right) = (0u32, n as u32);
        let mut i = 0;
        while i < list.len() {
            // The events at one position: its ends, then its starts.
            let pos = list[i].pos;
            let (mut ends, mut starts) = (0, 0);
            while i < list.len() && list[i].pos == pos {
                if list[i].is_start() {
                    starts += 1;
                } else {
                    ends += 1;
                }
                i += 1;
            }
            right -= ends;
            if pos > lo && pos < hi {
                let cost = sah.cost(pos, left, right);
                if cost < best_cost {
                    best_cost = cost;
                    best = Some(Split {
                        axis,
                        pos,
                        cost,
                        left: left as usize,
                        right: right as usize,
                    });
                }
            }
            left += starts;
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube(x: f32, size: f32) -> Aabb {
        Aabb::from_points(&[Vec3::new(x, 0.0, 0.0), Vec3::new(x + size, 1.0, 1.0)])
    }

    fn events(boxes: &[Aabb]) -> [Vec<Event>; 3] {
        let b: Vec<Option<Aabb>> = boxes.iter().map(usable).collect();
        [0, 1, 2].map(|axis| sorted_events(&b, axis))
    }

    fn voxel(boxes: &[Aabb]) -> Aabb {
        boxes
            .iter()
            .filter_map(usable)
            .fold(Aabb::EMPTY, |b, p| b.union(p))
    }

    /// One unit cube at x ∈ [0, 1] and three at x ∈ [9, 10]: in the voxel [0, 10] × [0, 1]²
    /// (area 42) the plane x = 9 costs 15 + 20 · (38 · 1 + 6 · 3) / 42 = 41.67, against
    /// 15 + 20 · (6 · 1 + 38 · 3) / 42 = 72.1 at x = 1 and a leaf's 80.
    #[test]
    fn sah_picks_the_plane_by_hand() {
        let boxes = [
            cube(0.0, 1.0),
            cube(9.0, 1.0),
            cube(9.0, 1.0),
            cube(9.0, 1.0),
        ];
        let s = best_split(&voxel(&boxes), &events(&boxes), 4).expect("a split pays");
        assert_eq!((s.axis, s.left, s.right), (0, 1, 3), "{s:?}");
        let want_pos = usable(&boxes[1]).unwrap().min.x;
        assert_eq!(s.pos, want_pos);
        let want_cost = 15.0 + 20.0 * (38.0 + 6.0 * 3.0) / 42.0;
        assert!(
            s.cost.is_finite() && (s.cost - want_cost).abs() < 1e-3,
            "{} vs {want_cost}",
            s.cost
        );
    }

    /// A leaf when no plane beats `K_I · N`: two boxes overlapping over most of their length.
    #[test]
    fn leaf_when_no_split_pays() {
        let boxes = [cube(0.0, 1.0), cube(0.05, 1.0)];
        assert_eq!(best_split(&voxel(&boxes), &events(&boxes), 2), None);
        // Identical boxes: no plane strictly inside the voxel at all.
        let same = [cube(0.0, 1.0); 5];
        assert_eq!(best_split(&voxel(&same), &events(&same), 5), None);
    }
}
