//! The ray queries of the wide BVHs ([`super::Bvh4`], [`super::Bvh8`]), written once over
//! what each tree provides: its leaves' ranges of stored primitives and a walk over the
//! leaves a ray may meet (`traverse.rs`, `traverse8.rs`).

use glam::Vec3;

/// A wide BVH's leaves and its walk; the queries come with it.
pub(crate) trait LeafQueries {
    /// `(first, count)`: leaf `k` holds the stored primitives `first .. first + count`.
    fn leaf_range(&self, k: u32) -> (u32, u32);

    /// Walks the leaves the ray `origin + t·dir` may meet within `(0, *t_max)`, nearest
    /// subtrees first when `ORDERED`; `visit(k, t_max)` may lower the bound and returns true
    /// to stop. Returns whether a visit stopped the walk.
    fn walk_leaves<const ORDERED: bool>(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_max: &mut f32,
        visit: impl FnMut(u32, &mut f32) -> bool,
    ) -> bool;

    /// Visits the primitives that may be hit in `(0, t_max)`, nearest subtrees first.
    /// `test(i, t_max)` intersects primitive `i` (in stored order) and returns the hit
    /// distance if it hits before `t_max`; the search then continues with that distance as
    /// the new bound. Returns the nearest distance found, if any.
    #[inline]
    fn closest(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_max: f32,
        mut test: impl FnMut(u32, f32) -> Option<f32>,
    ) -> Option<f32> {
        let mut best = None;
        self.closest_leaf(origin, dir, t_max, |k, bound| {
            let (first, n) = self.leaf_range(k);
            for i in first..first + n {
                if let Some(t) = test(i, *bound) {
                    *bound = t;
                    best = Some(t);
                }
            }
        });
        best
    }

    /// Visits the leaves that may hold a hit in `(0, t_max)`, nearest subtrees first:
    /// `visit(k, bound)` intersects the primitives of leaf `k` and lowers `bound` to the
    /// distance of any hit nearer than it; leaves entered beyond the bound are skipped.
    /// Returns the final bound.
    #[inline(always)]
    fn closest_leaf(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_max: f32,
        mut visit: impl FnMut(u32, &mut f32),
    ) -> f32 {
        let mut t_max = t_max;
        self.walk_leaves::<true>(
            origin,
            dir,
            &mut t_max,
            #[inline(always)]
            |k, bound| {
                visit(k, bound);
                false
            },
        );
        t_max
    }

    /// True when `visit(k, t_max)` holds for some leaf `k` the ray may meet within
    /// `(0, t_max)`; stops at the first one. Leaves are visited in no particular order.
    #[inline(always)]
    fn any_leaf(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_max: f32,
        mut visit: impl FnMut(u32, f32) -> bool,
    ) -> bool {
        let mut t_max = t_max;
        self.walk_leaves::<false>(
            origin,
            dir,
            &mut t_max,
            #[inline(always)]
            |k, t| visit(k, *t),
        )
    }

    /// True when `test(i, t_max)` holds for some primitive `i`; stops at the first one (any
    /// hit will do: children are visited in node order, not sorted by distance).
    #[inline]
    fn any(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_max: f32,
        mut test: impl FnMut(u32, f32) -> bool,
    ) -> bool {
        self.any_leaf(origin, dir, t_max, |k, t| {
            let (first, n) = self.leaf_range(k);
            (first..first + n).any(|i| test(i, t))
        })
    }
}

/// [`LeafQueries`] for a tree with a `leaves: Vec<(u32, u32)>` field and an inherent
/// `walk::<ORDERED>` of the trait's signature.
macro_rules! leaf_queries {
    ($t:ty) => {
        impl crate::accel::leaf_queries::LeafQueries for $t {
            #[inline(always)]
            fn leaf_range(&self, k: u32) -> (u32, u32) {
                self.leaves[k as usize]
            }

            #[inline(always)]
            fn walk_leaves<const ORDERED: bool>(
                &self,
                origin: glam::Vec3,
                dir: glam::Vec3,
                t_max: &mut f32,
                visit: impl FnMut(u32, &mut f32) -> bool,
            ) -> bool {
                self.walk::<ORDERED>(origin, dir, t_max, visit)
            }
        }
    };
}
pub(crate) use leaf_queries;
