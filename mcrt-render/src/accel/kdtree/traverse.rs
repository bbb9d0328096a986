//! Front-to-back traversal of the [`KdTree`] with a stack of far children.
//!
//! The ray is clipped to the root voxel, giving `[t_near, t_far]`. At an interior node the
//! plane distance `t` decides: the near child (the side of the origin) alone when the plane
//! lies behind the origin or beyond `t_far`, the far child alone when it lies before
//! `t_near`, else the near child over `[t_near, t]` with the far one pushed over
//! `[t, t_far]`. The comparisons allow `t` a relative error of 2γ₃ (as the slab test of
//! [`RayBoxTest`] does), so a child the ray barely enters is visited rather than skipped.
//! A popped child entered beyond the current bound (the nearest hit so far, or the occlusion
//! distance) is dropped, which ends a closest-hit search once every child entered before its
//! hit has been seen.
//!
//! The stack is an array on the call stack, 24 entries for trees up to 24 levels deep and
//! [`MAX_DEPTH`] beyond (each level pushes at most one entry).

use super::{KdTree, MAX_DEPTH};
use crate::accel::aabb::RayBoxTest;
use glam::Vec3;

/// `1 + 2γ₃` with γₙ = nε/(1 − nε): the relative slack on a plane distance.
const GROW: f32 = 1.0 + 2.0 * (3.0 * f32::EPSILON * 0.5) / (1.0 - 3.0 * f32::EPSILON * 0.5);

/// Stack sizes: trees up to `SMALL` levels, and the rest.
const SMALL: usize = 24;
const LARGE: usize = MAX_DEPTH as usize;

/// A far child to visit later over `[t_near, t_far]`.
#[derive(Debug, Clone, Copy, Default)]
struct Entry {
    node: u32,
    t_near: f32,
    t_far: f32,
}

impl KdTree {
    /// Like [`crate::accel::Bvh4::closest`]: visits primitives along the ray, `test`
    /// returns a hit distance below its bound, and the nearest distance found is returned.
    /// A primitive listed in several leaves may be tested more than once.
    #[inline]
    pub fn closest(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_max: f32,
        mut test: impl FnMut(u32, f32) -> Option<f32>,
    ) -> Option<f32> {
        let mut best = None;
        let mut bound = t_max;
        self.walk(origin, dir, &mut bound, |items, bound| {
            for &i in items {
                if let Some(t) = test(i, *bound) {
                    *bound = t;
                    best = Some(t);
                }
            }
            false
        });
        best
    }

    /// Like [`crate::accel::Bvh4::any`]: true as soon as `test(i, t_max)` holds for a
    /// primitive.
    #[inline]
    pub fn any(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_max: f32,
        mut test: impl FnMut(u32, f32) -> bool,
    ) -> bool {
        let mut bound = t_max;
        self.walk(origin, dir, &mut bound, |items, bound| {
            items.iter().any(|&i| test(i, *bound))
        })
    }

    /// Calls `visit(leaf primitives, &mut bound)` on the non-empty leaves along the ray,
    /// nearest first; stops and returns true as soon as a visit does.
    #[inline(always)]
    fn walk(
        &self,
        origin: Vec3,
        dir: Vec3,
        bound: &mut f32,
        visit: impl FnMut(&[u32], &mut f32) -> bool,
    ) -> bool {
        if self.items.is_empty() {
            return false;
        }
        if self.depth as usize <= SMALL {
            self.walk_with::<SMALL>(origin, dir, bound, visit)
        } else {
            self.walk_with::<LARGE>(origin, dir, bound, visit)
        }
    }

    #[inline(always)]
    fn walk_with<const N: usize>(
        &self,
        origin: Vec3,
        dir: Vec3,
        bound: &mut f32,
        mut visit: impl FnMut(&[u32], &mut f32) -> bool,
    ) -> bool {
        let rb = RayBoxTest::new(origin, dir);
        let (lo, hi) = (self.bounds.min.into(), self.bounds.max.into());
        let Some((mut t_near, mut t_far)) = rb.clip(lo, hi, *bound) else {
            return false;
        };
        // Padded to four lanes so that indexing by `axis` (< 4) needs no bounds check.
        let o = rb.origin.extend(0.0).to_array();
        let inv = rb.inv_dir.extend(0.0).to_array();
        let mut stack = [Entry::default(); N];
        let mut top = 0;
        let mut node = 0usize;
        loop {
            let n = self.nodes[node];
            if !n.is_leaf() {
                let axis = n.axis();
                let split = n.split();
                // Never NaN: `inv` is finite and nonzero (see `RayBoxTest`).
                let t = (split - o[axis]) * inv[axis];
                let below_first = o[axis] < split || (o[axis] == split && inv[axis] < 0.0);
                let (below, above) = (node + 1, n.upper() as usize);
                let (near, far) = if below_first {
                    (below, above)
                } else {
                    (above, below)
                };
                if t <= 0.0 || t > t_far * GROW {
                    node = near;
                } else if t * GROW < t_near {
                    node = far;
                } else {
                    stack[top] = Entry {
                        node: far as u32,
                        t_near: t_near.max(t / GROW),
                        t_far,
                    };
                    top += 1;
                    node = near;
                    t_far = t_far.min(t * GROW);
                }
                continue;
            }
            if n.upper() > 0 && visit(self.leaf_items(n), bound) {
                return true;
            }
            loop {
                if top == 0 {
                    return false;
                }
                top -= 1;
                let e = stack[top];
                if e.t_near <= *bound {
                    node = e.node as usize;
                    t_near = e.t_near;
                    t_far = e.t_far.min(*bound);
                    break;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::accel::aabb::Aabb;

    fn unit_box(x: f32) -> Aabb {
        Aabb::from_points(&[Vec3::new(x, 0.0, 0.0), Vec3::new(x + 1.0, 1.0, 1.0)])
    }

    /// A long box crossing many split planes is reported at its own distance, and a nearer
    /// small box wins over it wherever the walk meets them.
    #[test]
    fn straddling_primitive_and_order() {
        let mut boxes: Vec<Aabb> = (0..16).map(|k| unit_box(2.0 * k as f32)).collect();
        // Box 16 spans them all, a little above them in y.
        boxes.push(Aabb::from_points(&[
            Vec3::new(0.0, 1.5, 0.0),
            Vec3::new(32.0, 2.0, 1.0),
        ]));
        let tree = KdTree::build(&boxes);
        assert!(tree.stats().references > boxes.len(), "{:?}", tree.stats());
        // "Intersect" box i where the ray enters it.
        let hit = |origin: Vec3, dir: Vec3| {
            let mut who = None;
            let t = tree.closest(origin, dir, f32::INFINITY, |i, bound| {
                let b = boxes[i as usize];
                let (t0, _) =
                    RayBoxTest::new(origin, dir).clip(b.min.into(), b.max.into(), bound)?;
                who = Some(i);
                Some(t0)
            });
            (t, who)
        };
        // Down the long box from the right, starting inside it: t = 0, box 16.
        let (t, who) = hit(Vec3::new(31.5, 1.75, 0.5), -Vec3::X);
        assert_eq!((t, who), (Some(0.0), Some(16)));
        // From above onto box 5 (x in [10, 11]) through the long box at y = 2.
        let (t, who) = hit(Vec3::new(10.5, 3.0, 0.5), -Vec3::Y);
        assert_eq!((t, who), (Some(1.0), Some(16)));
        // Along the row of small boxes from the left: box 0 at t = 1.
        let (t, who) = hit(Vec3::new(-1.0, 0.5, 0.5), Vec3::X);
        assert_eq!((t, who), (Some(1.0), Some(0)));
        // Occlusion stops at the first primitive; nothing within t_max = 0.5.
        assert!(tree.any(Vec3::new(-1.0, 0.5, 0.5), Vec3::X, 2.0, |_, _| true));
        assert!(!tree.any(Vec3::new(-1.0, 0.5, 0.5), Vec3::X, 0.5, |_, _| true));
    }

    /// A ray lying in a split plane (zero direction component, origin on the plane) still
    /// meets the boxes that touch the plane from either side.
    #[test]
    fn ray_inside_a_split_plane() {
        let boxes: Vec<Aabb> = (0..8).map(|k| unit_box(k as f32)).collect();
        let tree = KdTree::build(&boxes);
        for k in 1..8 {
            let mut seen = Vec::new();
            tree.any(
                Vec3::new(k as f32, 0.5, -1.0),
                Vec3::Z,
                f32::INFINITY,
                |i, _| {
                    seen.push(i);
                    false
                },
            );
            assert!(
                seen.contains(&(k - 1)) && seen.contains(&k),
                "plane x = {k}: {seen:?}"
            );
        }
    }
}
