//! Single-ray traversal of the 8-wide BVH ([`Bvh8`]), as `traverse.rs` walks the 4-wide
//! one: the eight child boxes of a node are slab-tested at once; a closest-hit walk descends
//! into the nearest child entered and pushes the others, farthest first, with their entry
//! distances (popped entries beyond the nearest hit so far are skipped); an any-hit walk
//! pushes entered children in node order.
//!
//! The lanes ([`Lanes8`]) are chosen once per query: [`Simd8::dispatch`](super::lanes8::Simd8::dispatch) runs the whole walk,
//! the caller's leaf visits included, on AVX2 or on two 4-lane halves; a caller whose leaf
//! tests use the lanes too dispatches itself and walks with [`Bvh8::walk_on`].
//!
//! The stack is a fixed array on the call stack sized for the tree (each level pushes at
//! most seven entries), or a per-thread buffer for trees too deep for the largest array.

use super::aabb::{RayBoxTest, SLAB_GROW};
use super::bvh8::{Bvh8, Node8, EMPTY, LEAF};
use super::lanes8::{Lanes8, WithLanes8};
use super::stack::{entry, pop_within, with_stack, Stack};
use glam::Vec3;

/// Array stack sizes: tiny trees (up to 2 levels of 8-wide nodes), small ones (up to 4)
/// and the rest (up to 9).
const TINY: usize = 14;
const SMALL: usize = 28;
const LARGE: usize = 63;

impl Bvh8 {
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
        self.simd.dispatch(Walk::<_, ORDERED> {
            bvh: self,
            origin,
            dir,
            t_max,
            visit,
        })
    }
}

/// A walk to run on some lanes.
struct Walk<'a, F, const ORDERED: bool> {
    bvh: &'a Bvh8,
    origin: Vec3,
    dir: Vec3,
    t_max: &'a mut f32,
    visit: F,
}

impl<F: FnMut(u32, &mut f32) -> bool, const ORDERED: bool> WithLanes8 for Walk<'_, F, ORDERED> {
    type Output = bool;

    #[inline(always)]
    fn run<L: Lanes8>(self, l: L) -> bool {
        let Walk {
            bvh,
            origin,
            dir,
            t_max,
            visit,
        } = self;
        bvh.walk_on::<L, ORDERED>(l, origin, dir, t_max, visit)
    }
}

impl Bvh8 {
    /// [`Bvh8::walk`] on lanes `l` already chosen (for a caller whose leaf visits use them
    /// too, inside its own [`Simd8::dispatch`](super::lanes8::Simd8::dispatch)).
    #[inline(always)]
    pub(crate) fn walk_on<L: Lanes8, const ORDERED: bool>(
        &self,
        l: L,
        origin: Vec3,
        dir: Vec3,
        t_max: &mut f32,
        visit: impl FnMut(u32, &mut f32) -> bool,
    ) -> bool {
        if self.root == EMPTY {
            return false;
        }
        let ray = RayBoxTest::new(origin, dir);
        let (o, inv) = (ray.origin, ray.inv_dir);
        let ray = SlabRay {
            o: [l.splat(o.x), l.splat(o.y), l.splat(o.z)],
            inv: [l.splat(inv.x), l.splat(inv.y), l.splat(inv.z)],
            l,
        };
        let levels = 7 * self.depth;
        with_stack!(
            levels,
            [TINY, SMALL, LARGE],
            |stack| traverse::<L, ORDERED>(self, stack, &ray, t_max, visit)
        )
    }
}

#[inline(always)]
fn traverse<L: Lanes8, const ORDERED: bool>(
    bvh: &Bvh8,
    stack: &mut impl Stack,
    ray: &SlabRay<L>,
    t_max: &mut f32,
    mut visit: impl FnMut(u32, &mut f32) -> bool,
) -> bool {
    let mut code = bvh.root;
    loop {
        if code & LEAF != 0 {
            if visit(code & !LEAF, t_max) {
                return true;
            }
        } else {
            let n = &bvh.nodes[code as usize];
            let (mask, near) = ray.enter(n, *t_max);
            if mask != 0 {
                code = if ORDERED {
                    descend(stack, n, mask, ray.l.to_array(near))
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

/// The ray's origin and reciprocal direction, splatted.
struct SlabRay<L: Lanes8> {
    o: [L::V; 3],
    inv: [L::V; 3],
    l: L,
}

impl<L: Lanes8> SlabRay<L> {
    /// The children of `n` the ray enters within `[0, t_max]` (a bitmask of lanes) and
    /// their entry distances; the operations of the 4-wide test, lane by lane.
    #[inline(always)]
    fn enter(&self, n: &Node8, t_max: f32) -> (u32, L::V) {
        let l = self.l;
        let mut near = l.splat(0.0);
        let mut far = l.splat(t_max);
        let grow = l.splat(SLAB_GROW);
        for a in 0..3 {
            let t0 = l.mul(l.sub(l.load(&n.lo[a]), self.o[a]), self.inv[a]);
            let t1 = l.mul(l.sub(l.load(&n.hi[a]), self.o[a]), self.inv[a]);
            near = l.max(near, l.min(t0, t1));
            far = l.min(far, l.mul(l.max(t0, t1), grow));
        }
        (l.le_bits(near, far) & n.valid, near)
    }
}

/// Pushes all entered children (bits of `mask`, nonzero) but the first, in node order, and
/// returns that first one: for any-hit queries, where the order does not matter.
#[inline(always)]
fn descend_unordered(stack: &mut impl Stack, n: &Node8, mask: u32) -> u32 {
    let first = n.child[mask.trailing_zeros() as usize & 7];
    let mut rest = mask & (mask - 1);
    while rest != 0 {
        stack.push(entry(n.child[rest.trailing_zeros() as usize & 7], 0.0));
        rest &= rest - 1;
    }
    first
}

/// Pushes all entered children (bits of `mask`, nonzero) but the nearest, farthest first,
/// and returns the nearest. Of children entered at the same distance the higher lane is
/// taken first.
#[inline(always)]
fn descend(stack: &mut impl Stack, n: &Node8, mask: u32, d: [f32; 8]) -> u32 {
    let a = mask.trailing_zeros() as usize & 7;
    let rest = mask & (mask - 1);
    if rest == 0 {
        return n.child[a];
    }
    let b = rest.trailing_zeros() as usize & 7;
    if rest & (rest - 1) == 0 {
        let (first, second) = if d[b] <= d[a] { (b, a) } else { (a, b) };
        stack.push(entry(n.child[second], d[second]));
        return n.child[first];
    }
    // Three to eight: insertion sort, descending by entry distance.
    let mut hit = [(0usize, 0f32); 8];
    let mut k = 0;
    let mut m = mask;
    while m != 0 {
        let lane = m.trailing_zeros() as usize & 7;
        m &= m - 1;
        let e = (lane, d[lane]);
        let mut j = k;
        while j > 0 && hit[j - 1].1 < e.1 {
            hit[j] = hit[j - 1];
            j -= 1;
        }
        hit[j & 7] = e;
        k += 1;
    }
    for &(lane, t) in &hit[..k - 1] {
        stack.push(entry(n.child[lane], t));
    }
    n.child[hit[(k - 1) & 7].0]
}
