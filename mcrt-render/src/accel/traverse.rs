//! Single-ray traversal of the 4-wide BVH ([`Bvh4`]).
//!
//! The four child boxes of a node are slab-tested at once. A closest-hit walk descends into
//! the nearest child it enters and pushes the others, farthest first, with their entry
//! distances; a popped entry beyond the nearest hit so far is skipped. The common cases of
//! one and two children entered take no sort. An any-hit walk pushes entered children in
//! node order. Leaves go to the caller's visitor as they are reached.
//!
//! The stack is a fixed array on the call stack sized for the tree (each level pushes at
//! most three entries), or a per-thread buffer for trees too deep for the largest array; no
//! allocation per ray either way. Entries pack the code and the entry distance's bits into
//! one `u64`, so zeroing a fresh array is a few vector stores.

use super::aabb::{RayBoxTest, SLAB_GROW};
use super::bvh4::{Bvh4, Node4, EMPTY, LEAF};
use super::stack::{entry, pop_within, with_stack, Stack};
use glam::{Vec3, Vec4};

/// Array stack sizes: tiny trees (up to 2 levels of 4-wide nodes), small ones (up to 5)
/// and the rest.
const TINY: usize = 8;
const SMALL: usize = 16;
const LARGE: usize = 48;

impl Bvh4 {
    /// Walks the tree for the ray, calling `visit(leaf, &mut t_max)` on each leaf reached;
    /// stops and returns true as soon as a visit does. `ORDERED`: nearest children first.
    #[inline(always)]
    pub(super) fn walk<const ORDERED: bool>(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_max: &mut f32,
        visit: impl FnMut(u32, &mut f32) -> bool,
    ) -> bool {
        if self.root == EMPTY {
            return false;
        }
        let rb = RayBoxTest::new(origin, dir);
        let ray = SlabRay {
            o: [0, 1, 2].map(|a| Vec4::splat(rb.origin[a])),
            inv: [0, 1, 2].map(|a| Vec4::splat(rb.inv_dir[a])),
        };
        let levels = 3 * self.depth;
        with_stack!(levels, [TINY, SMALL, LARGE], |stack| self
            .traverse::<ORDERED>(stack, &ray, t_max, visit))
    }

    #[inline(always)]
    fn traverse<const ORDERED: bool>(
        &self,
        stack: &mut impl Stack,
        ray: &SlabRay,
        t_max: &mut f32,
        mut visit: impl FnMut(u32, &mut f32) -> bool,
    ) -> bool {
        let mut code = self.root;
        loop {
            if code & LEAF != 0 {
                if visit(code & !LEAF, t_max) {
                    return true;
                }
            } else {
                let n = &self.nodes[code as usize];
                let (mask, near) = ray.enter(n, *t_max);
                if mask != 0 {
                    code = if ORDERED {
                        descend(stack, n, mask, near)
                    } else {
                        descend_unordered(stack, n, mask)
                    };
                    continue;
                }
            }
            // Pop the nearest pending child that may still hold a closer hit.
            let Some(next) = pop_within(stack, *t_max) else {
                return false;
            };
            code = next;
        }
    }
}

/// The ray's origin and reciprocal direction, splatted.
struct SlabRay {
    o: [Vec4; 3],
    inv: [Vec4; 3],
}

impl SlabRay {
    /// The children of `n` the ray enters within `[0, t_max]` (a bitmask of lanes) and
    /// their entry distances.
    #[inline(always)]
    fn enter(&self, n: &Node4, t_max: f32) -> (u32, Vec4) {
        let mut near = Vec4::ZERO;
        let mut far = Vec4::splat(t_max);
        for a in 0..3 {
            let t0 = (n.lo[a] - self.o[a]) * self.inv[a];
            let t1 = (n.hi[a] - self.o[a]) * self.inv[a];
            near = near.max(t0.min(t1));
            far = far.min(t0.max(t1) * SLAB_GROW);
        }
        (near.cmple(far).bitmask() & n.valid, near)
    }
}

/// Pushes all entered children (bits of `mask`, nonzero) but the first, in node order, and
/// returns that first one: for any-hit queries, where the order does not matter.
#[inline(always)]
fn descend_unordered(stack: &mut impl Stack, n: &Node4, mask: u32) -> u32 {
    let first = n.child[mask.trailing_zeros() as usize];
    let mut rest = mask & (mask - 1);
    while rest != 0 {
        stack.push(entry(n.child[rest.trailing_zeros() as usize], 0.0));
        rest &= rest - 1;
    }
    first
}

/// Pushes all entered children (bits of `mask`, nonzero) but the nearest, farthest first,
/// and returns the nearest. Of children entered at the same distance the higher lane is
/// taken first.
#[inline(always)]
fn descend(stack: &mut impl Stack, n: &Node4, mask: u32, near: Vec4) -> u32 {
    let a = mask.trailing_zeros() as usize;
    let rest = mask & (mask - 1);
    if rest == 0 {
        return n.child[a];
    }
    let d = near.to_array();
    let b = rest.trailing_zeros() as usize;
    if rest & (rest - 1) == 0 {
        let (first, second) = if d[b] <= d[a] { (b, a) } else { (a, b) };
        stack.push(entry(n.child[second], d[second]));
        return n.child[first];
    }
    // Three or four: insertion sort, descending by entry distance.
    let mut hit = [(0usize, 0f32); 4];
    let mut k = 0;
    let mut m = mask;
    while m != 0 {
        let lane = m.trailing_zeros() as usize;
        m &= m - 1;
        let e = (lane, d[lane]);
        let mut j = k;
        while j > 0 && hit[j - 1].1 < e.1 {
            hit[j] = hit[j - 1];
            j -= 1;
        }
        hit[j] = e;
        k += 1;
    }
    for &(lane, t) in &hit[..k - 1] {
        stack.push(entry(n.child[lane], t));
    }
    n.child[hit[k - 1].0]
}
