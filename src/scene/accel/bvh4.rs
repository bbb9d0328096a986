//! A 4-wide BVH: the binary SAH hierarchy collapsed so that every node holds up to four
//! children whose boxes are tested at once in SIMD lanes (as in Wald, Benthin & Boulos 2008,
//! "Getting Rid of Packets: Efficient SIMD Single-Ray Traversal using Multi-branching BVHs",
//! IEEE Symposium on Interactive Ray Tracing). Collapsing repeatedly opens the interior child
//! of largest surface area until four children are gathered.
//!
//! Traversal descends into the nearest child the ray enters and pushes the others, farthest
//! first, with their entry distances;
//! a popped entry farther than the nearest hit so far is skipped. The stack is a fixed array
//! on the call stack when the tree is shallow enough (it always is for sane scenes: each
//! level pushes at most three entries), else a per-thread buffer reused across queries; no
//! allocation per ray either way.

use super::aabb::{Aabb, RayBoxTest};
use super::bvh::Bvh;
use glam::{Vec3, Vec4};
use std::cell::RefCell;

/// Entries of the on-stack traversal stack; trees needing more use the per-thread buffer.
const ARRAY_STACK: usize = 16;

/// Marks a stack entry or child as a leaf: `LEAF | first << 3 | count`.
const LEAF: u32 = 1 << 31;
/// An empty child slot (its box is empty, so it is never entered).
const EMPTY: u32 = u32::MAX;

/// `1 + 2γ₃` (see [`RayBoxTest`]).
const SLAB_GROW: f32 = 1.0 + 2.0 * (3.0 * f32::EPSILON * 0.5) / (1.0 - 3.0 * f32::EPSILON * 0.5);

/// Four child boxes by coordinate (lane = child), and the children: a node index, or a leaf
/// `LEAF | first << 3 | count`, or [`EMPTY`].
#[derive(Debug, Clone, Copy)]
struct Node4 {
    lo: [Vec4; 3],
    hi: [Vec4; 3],
    child: [u32; 4],
}

/// The 4-wide BVH.
#[derive(Debug, Clone)]
pub struct Bvh4 {
    nodes: Vec<Node4>,
    /// The root: a node index or a leaf code (a scene of at most four primitives).
    root: u32,
    root_box: Aabb,
    order: Vec<u32>,
    /// Levels of 4-wide nodes on the longest root-to-leaf path.
    depth: usize,
}

thread_local! {
    static STACK: RefCell<Vec<(u32, f32)>> = RefCell::new(Vec::with_capacity(256));
}

impl Bvh4 {
    /// Builds the binary SAH BVH over the bounds and collapses it.
    pub fn build(bounds: &[Aabb]) -> Self {
        let bvh = Bvh::build(bounds);
        let mut out = Self {
            nodes: Vec::with_capacity(bvh.node_count() / 2 + 1),
            root: EMPTY,
            root_box: bvh.bounds(),
            order: bvh.order().to_vec(),
            depth: 0,
        };
        if !bounds.is_empty() {
            out.root = out.collapse(&bvh, 0);
            out.depth = out.node_depth(out.root);
        }
        out
    }

    /// `order[i]` is the input index of the primitive to store at position `i`.
    pub fn order(&self) -> &[u32] {
        &self.order
    }

    /// Number of 4-wide nodes.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Levels of 4-wide nodes below and including `code` (0 for a leaf).
    fn node_depth(&self, code: u32) -> usize {
        if code & LEAF != 0 || code == EMPTY {
            return 0;
        }
        let n = &self.nodes[code as usize];
        1 + n
            .child
            .iter()
            .map(|&c| self.node_depth(c))
            .max()
            .unwrap_or(0)
    }

    /// The code of binary node `b`: a leaf code, or the index of its 4-wide node.
    fn collapse(&mut self, bvh: &Bvh, b: usize) -> u32 {
        if let Some((first, count)) = bvh.leaf(b) {
            debug_assert!(first < 1 << 28 && count <= 7, "leaf code overflow");
            return LEAF | first << 3 | count;
        }
        let mut kids = bvh.children(b).to_vec();
        while kids.len() < 4 {
            let open = kids
                .iter()
                .enumerate()
                .filter(|(_, &k)| bvh.leaf(k).is_none())
                .max_by(|a, b| bvh.area(*a.1).total_cmp(&bvh.area(*b.1)))
                .map(|(i, _)| i);
            let Some(i) = open else { break };
            let k = kids.swap_remove(i);
            kids.extend(bvh.children(k));
        }
        let me = self.nodes.len();
        self.nodes.push(Node4 {
            lo: [Vec4::splat(f32::INFINITY); 3],
            hi: [Vec4::splat(f32::NEG_INFINITY); 3],
            child: [EMPTY; 4],
        });
        for (lane, &k) in kids.iter().enumerate() {
            let code = self.collapse(bvh, k);
            let (lo, hi) = bvh.node_box(k);
            let n = &mut self.nodes[me];
            for a in 0..3 {
                n.lo[a][lane] = lo[a];
                n.hi[a][lane] = hi[a];
            }
            n.child[lane] = code;
        }
        me as u32
    }

    /// Visits the primitives that may be hit in `(0, t_max)`, nearest subtrees first.
    /// `test(i, t_max)` intersects primitive `i` (in stored order) and returns the hit
    /// distance if it hits before `t_max`; the search then continues with that distance as
    /// the new bound. Returns the nearest distance found, if any.
    #[inline]
    pub fn closest(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_max: f32,
        mut test: impl FnMut(u32, f32) -> Option<f32>,
    ) -> Option<f32> {
        let mut best = None;
        let mut t_max = t_max;
        self.walk::<true>(origin, dir, &mut t_max, |i, bound| {
            if let Some(t) = test(i, *bound) {
                *bound = t;
                best = Some(t);
            }
            false
        });
        best
    }

    /// True when `test(i, t_max)` holds for some primitive `i`; stops at the first one.
    #[inline]
    pub fn any(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_max: f32,
        mut test: impl FnMut(u32, f32) -> bool,
    ) -> bool {
        let mut t_max = t_max;
        // Any hit will do: children are visited in node order, not sorted by distance.
        self.walk::<false>(origin, dir, &mut t_max, |i, t| test(i, *t))
    }

    #[inline(always)]
    fn walk<const ORDERED: bool>(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_max: &mut f32,
        visit: impl FnMut(u32, &mut f32) -> bool,
    ) -> bool {
        let rb = RayBoxTest::new(origin, dir);
        if self.root == EMPTY
            || !rb.hits(self.root_box.min.into(), self.root_box.max.into(), *t_max)
        {
            return false;
        }
        let o = [0, 1, 2].map(|a| Vec4::splat(rb.origin[a]));
        let inv = [0, 1, 2].map(|a| Vec4::splat(rb.inv_dir[a]));
        // Each level pushes at most three entries.
        if 3 * self.depth < ARRAY_STACK {
            let mut stack = ArrayStack {
                items: [(0, 0.0); ARRAY_STACK],
                len: 0,
            };
            self.traverse::<ORDERED>(&mut stack, o, inv, t_max, visit)
        } else {
            STACK.with_borrow_mut(|stack| {
                stack.clear();
                self.traverse::<ORDERED>(stack, o, inv, t_max, visit)
            })
        }
    }

    #[inline(always)]
    fn traverse<const ORDERED: bool>(
        &self,
        stack: &mut impl Stack,
        o: [Vec4; 3],
        inv: [Vec4; 3],
        t_max: &mut f32,
        mut visit: impl FnMut(u32, &mut f32) -> bool,
    ) -> bool {
        let mut code = self.root;
        loop {
            if code & LEAF != 0 {
                let first = (code & !LEAF) >> 3;
                for i in first..first + (code & 7) {
                    if visit(i, t_max) {
                        return true;
                    }
                }
            } else {
                let n = &self.nodes[code as usize];
                let mut near = Vec4::ZERO;
                let mut far = Vec4::splat(*t_max);
                for a in 0..3 {
                    let t0 = (n.lo[a] - o[a]) * inv[a];
                    let t1 = (n.hi[a] - o[a]) * inv[a];
                    near = near.max(t0.min(t1));
                    far = far.min(t0.max(t1) * SLAB_GROW);
                }
                let mask = near.cmple(far).bitmask();
                let next = if ORDERED {
                    descend(stack, n, mask, near)
                } else {
                    descend_unordered(stack, n, mask)
                };
                if let Some(next) = next {
                    code = next;
                    continue;
                }
            }
            // Pop the nearest pending child that may still hold a closer hit.
            loop {
                let Some((next, t_entry)) = stack.pop() else {
                    return false;
                };
                if t_entry <= *t_max {
                    code = next;
                    break;
                }
            }
        }
    }
}

/// A traversal stack of (child code, entry distance).
trait Stack {
    fn push(&mut self, e: (u32, f32));
    fn pop(&mut self) -> Option<(u32, f32)>;
}

impl Stack for Vec<(u32, f32)> {
    #[inline(always)]
    fn push(&mut self, e: (u32, f32)) {
        Vec::push(self, e);
    }
    #[inline(always)]
    fn pop(&mut self) -> Option<(u32, f32)> {
        Vec::pop(self)
    }
}

/// A fixed-capacity stack on the call stack (capacity checked against the tree depth
/// before use).
struct ArrayStack {
    items: [(u32, f32); ARRAY_STACK],
    len: usize,
}

impl Stack for ArrayStack {
    #[inline(always)]
    fn push(&mut self, e: (u32, f32)) {
        debug_assert!(self.len < ARRAY_STACK);
        if let Some(slot) = self.items.get_mut(self.len) {
            *slot = e;
            self.len += 1;
        }
    }
    #[inline(always)]
    fn pop(&mut self) -> Option<(u32, f32)> {
        self.len = self.len.checked_sub(1)?;
        Some(self.items[self.len])
    }
}

/// Pushes all entered children (bits of `mask`) but the first, in node order, and returns
/// that first one: for any-hit queries, where the order does not matter.
#[inline(always)]
fn descend_unordered(stack: &mut impl Stack, n: &Node4, mask: u32) -> Option<u32> {
    let mut first = None;
    for lane in 0..4 {
        let c = n.child[lane];
        if mask & (1 << lane) != 0 && c != EMPTY {
            match first {
                None => first = Some(c),
                Some(_) => stack.push((c, 0.0)),
            }
        }
    }
    first
}

/// Sorts the entered children (bits of `mask`) by entry distance, pushes all but the
/// nearest (farthest first) and returns the nearest.
#[inline(always)]
fn descend(stack: &mut impl Stack, n: &Node4, mask: u32, near: Vec4) -> Option<u32> {
    let mut hit = [(0u32, 0f32); 4];
    let mut k = 0;
    for lane in 0..4 {
        if mask & (1 << lane) != 0 && n.child[lane] != EMPTY {
            // Insertion sort, descending by entry distance.
            let entry = (n.child[lane], near[lane]);
            let mut j = k;
            while j > 0 && hit[j - 1].1 < entry.1 {
                hit[j] = hit[j - 1];
                j -= 1;
            }
            hit[j] = entry;
            k += 1;
        }
    }
    if k == 0 {
        return None;
    }
    for &e in &hit[..k - 1] {
        stack.push(e);
    }
    Some(hit[k - 1].0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identical_boxes_still_build() {
        let b = vec![Aabb::from_points(&[Vec3::ZERO, Vec3::ONE]); 300];
        let bvh = Bvh4::build(&b);
        let mut hits = 0;
        bvh.any(Vec3::new(0.5, 0.5, -1.0), Vec3::Z, f32::INFINITY, |_, _| {
            hits += 1;
            false
        });
        assert_eq!(hits, 300);
    }

    #[test]
    fn empty_bvh_finds_nothing() {
        let bvh = Bvh4::build(&[]);
        assert!(!bvh.any(Vec3::ZERO, Vec3::Z, 1.0, |_, _| true));
    }

    #[test]
    fn small_scenes_and_leaf_roots() {
        for n in [1usize, 3, 4, 5, 17, 200] {
            let b: Vec<Aabb> = (0..n)
                .map(|i| {
                    let p = Vec3::new(i as f32 * 2.0, 0.0, 0.0);
                    Aabb::from_points(&[p, p + Vec3::ONE])
                })
                .collect();
            let bvh = Bvh4::build(&b);
            let mut seen = vec![false; n];
            bvh.any(Vec3::new(-1.0, 0.5, 0.5), Vec3::X, f32::INFINITY, |i, _| {
                seen[i as usize] = true;
                false
            });
            assert!(seen.iter().all(|&s| s), "n = {n}");
            let t = bvh.closest(
                Vec3::new(-1.0, 0.5, 0.5),
                Vec3::X,
                f32::INFINITY,
                |i, tm| {
                    let t = 1.0 + 2.0 * b[bvh.order()[i as usize] as usize].min.x / 2.0;
                    (t < tm).then_some(t)
                },
            );
            assert_eq!(t, Some(1.0));
        }
        assert!(!Bvh4::build(&[]).any(Vec3::ZERO, Vec3::X, 1.0, |_, _| true));
    }
}
