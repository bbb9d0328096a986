//! The build of [`super::bvh::Bvh`]: binned SAH splits (`bvh.rs` describes them), done so
//! that a node costs one pass over its primitives to bin them and one to partition them.
//!
//! - The primitives' boxes are moved along with their indices as the build partitions them,
//!   so that every pass reads memory in order instead of looking boxes up by index.
//! - All three axes are binned in the same pass.
//! - The partition pass gathers each side's bounds and centroid bounds, which the children
//!   take as given instead of folding over their primitives again.
//! - Subtrees of at least [`PARALLEL_MIN`] primitives are built in parallel (`rayon::join`),
//!   each into its own node list, appended in depth-first order. Splits depend only on the
//!   primitives, so the tree is the same for any number of threads.
//!
//! Min and max are exact, so gathering bounds in another order gives the same boxes and the
//! same tree as folding them per node.

use super::aabb::Aabb;
use super::bvh_node::{Node, BINS, MAX_LEAF, MEDIAN_DEPTH};
use glam::Vec3A;

/// Subtrees over at least this many primitives are built in parallel.
pub(super) const PARALLEL_MIN: usize = 1 << 14;

/// A box in SIMD lanes: the build's copy of an [`Aabb`], whose operations it repeats lane
/// by lane (so with the same results).
#[derive(Debug, Clone, Copy)]
struct Bx {
    min: Vec3A,
    max: Vec3A,
}

impl Bx {
    const EMPTY: Self = Self {
        min: Vec3A::splat(f32::INFINITY),
        max: Vec3A::splat(f32::NEG_INFINITY),
    };

    #[inline(always)]
    fn union(self, o: Self) -> Self {
        Self {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
        }
    }

    #[inline(always)]
    fn grow(self, p: Vec3A) -> Self {
        Self {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    /// As [`Aabb::center`].
    #[inline(always)]
    fn center(&self) -> Vec3A {
        0.5 * (self.min + self.max)
    }

    /// As [`Aabb::surface_area`].
    #[inline(always)]
    fn surface_area(&self) -> f32 {
        let e = (self.max - self.min).max(Vec3A::ZERO);
        2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
    }

    fn aabb(&self) -> Aabb {
        Aabb {
            min: self.min.into(),
            max: self.max.into(),
        }
    }
}

impl From<Aabb> for Bx {
    fn from(b: Aabb) -> Self {
        Self {
            min: b.min.into(),
            max: b.max.into(),
        }
    }
}

/// Primitives `start ..` of the build: their boxes and input indices (moved together), and
/// the union of the boxes and of their centres.
struct Span<'a> {
    boxes: &'a mut [Bx],
    ids: &'a mut [u32],
    start: usize,
    bounds: Bx,
    cent: Bx,
}

/// How a node is split: the axis, the number of primitives on the left, and each side's
/// bounds and centroid bounds.
struct Split {
    axis: usize,
    mid: usize,
    left: (Bx, Bx),
    right: (Bx, Bx),
}

/// Builds the nodes (depth-first, as [`Node`] describes them) and the order of the
/// primitives over nonempty `bounds`.
pub(super) fn build(bounds: &[Aabb], parallel_min: usize) -> (Vec<Node>, Vec<u32>) {
    let mut boxes: Vec<Bx> = bounds.iter().map(|&b| Bx::from(b)).collect();
    let mut ids: Vec<u32> = (0..bounds.len() as u32).collect();
    let (b, c) = gather(&boxes);
    let span = Span {
        boxes: &mut boxes,
        ids: &mut ids,
        start: 0,
        bounds: b,
        cent: c,
    };
    let nodes = subtree_par(bounds, span, 0, parallel_min.max(2));
    (nodes, ids)
}

/// The union of the boxes and of their centres.
fn gather(boxes: &[Bx]) -> (Bx, Bx) {
    boxes.iter().fold((Bx::EMPTY, Bx::EMPTY), |(b, c), x| {
        (b.union(*x), c.grow(x.center()))
    })
}

/// The subtree over `span` as its own node list (root first, offsets from it), its halves
/// built in parallel when it is large.
fn subtree_par(input: &[Aabb], span: Span, depth: u32, parallel_min: usize) -> Vec<Node> {
    let n = span.ids.len();
    if n < parallel_min {
        let mut nodes = Vec::with_capacity(2 * n);
        subtree(input, span, depth, &mut nodes);
        return nodes;
    }
    let node = leaf_node(&span);
    let Some((split, left, right)) = split(input, span, depth) else {
        return vec![node];
    };
    let (l, r) = rayon::join(
        || subtree_par(input, left, depth + 1, parallel_min),
        || subtree_par(input, right, depth + 1, parallel_min),
    );
    let second = 1 + l.len();
    let mut nodes = Vec::with_capacity(second + r.len());
    nodes.push(Node {
        offset: second as u32,
        count: 0,
        axis: split.axis as u16,
        ..node
    });
    append(&mut nodes, l);
    append(&mut nodes, r);
    nodes
}

/// Appends a subtree's own node list, moving its interior nodes' child offsets along.
fn append(nodes: &mut Vec<Node>, part: Vec<Node>) {
    let shift = nodes.len() as u32;
    nodes.extend(part.into_iter().map(|mut m| {
        if m.count == 0 {
            m.offset += shift;
        }
        m
    }));
}

/// Appends the subtree over `span` to `nodes` (offsets index `nodes`); returns its root.
fn subtree(input: &[Aabb], span: Span, depth: u32, nodes: &mut Vec<Node>) -> usize {
    let me = nodes.len();
    nodes.push(leaf_node(&span));
    let Some((split, left, right)) = split(input, span, depth) else {
        return me;
    };
    subtree(input, left, depth + 1, nodes);
    let second = subtree(input, right, depth + 1, nodes);
    let node = &mut nodes[me];
    node.offset = second as u32;
    node.count = 0;
    node.axis = split.axis as u16;
    me
}

/// The node over `span` as a leaf (its padded bounds and primitive range).
fn leaf_node(span: &Span) -> Node {
    let padded = span.bounds.aabb().padded();
    Node {
        min: padded.min.into(),
        max: padded.max.into(),
        offset: span.start as u32,
        count: span.ids.len() as u16,
        axis: 0,
    }
}

/// Splits `span` (reordering its primitives) into its two children, or `None` when it
/// stays a leaf: one primitive, or at most [`MAX_LEAF`] with no cheaper split. Beyond
/// [`MEDIAN_DEPTH`], or when no SAH split separates the centroids, the median is taken.
fn split<'a>(input: &[Aabb], span: Span<'a>, depth: u32) -> Option<(Split, Span<'a>, Span<'a>)> {
    let n = span.ids.len();
    if n == 1 {
        return None;
    }
    let Span {
        boxes,
        ids,
        start,
        bounds,
        cent,
    } = span;
    let sah = if depth >= MEDIAN_DEPTH {
        None
    } else {
        sah_split(boxes, ids, &bounds, &cent)
    };
    let s = match sah {
        Some(s) => s,
        None if n <= MAX_LEAF => return None,
        None => median_split(input, boxes, ids, &cent),
    };
    let (lb, rb) = boxes.split_at_mut(s.mid);
    let (li, ri) = ids.split_at_mut(s.mid);
    let left = Span {
        boxes: lb,
        ids: li,
        start,
        bounds: s.left.0,
        cent: s.left.1,
    };
    let right = Span {
        boxes: rb,
        ids: ri,
        start: start + s.mid,
        bounds: s.right.0,
        cent: s.right.1,
    };
    Some((s, left, right))
}

/// The bin of centre `c` along each axis: `lo` the centroid bounds' lower corner, `scale`
/// bins per unit length. As `((c − lo) · scale) as usize` capped at `BINS − 1`, clamped in
/// floating point first (the same bins: NaN and negatives give 0 either way).
#[inline(always)]
pub(super) fn bins_of(c: Vec3A, lo: Vec3A, scale: Vec3A) -> [usize; 3] {
    let x = ((c - lo) * scale)
        .max(Vec3A::ZERO)
        .min(Vec3A::splat((BINS - 1) as f32));
    x.as_uvec3().to_array().map(|k| k as usize)
}

/// The best binned SAH split, with the primitives partitioned, or `None` if a leaf is at
/// least as cheap (only allowed for small nodes) or the centroids cannot be separated.
fn sah_split(boxes: &mut [Bx], ids: &mut [u32], bounds: &Bx, cb: &Bx) -> Option<Split> {
    let ext = (cb.max - cb.min).max(Vec3A::ZERO);
    let n = boxes.len();
    let active = [0, 1, 2].map(|a| ext[a] > 0.0);
    let scale =
        Vec3A::from_array([0, 1, 2].map(|a| if active[a] { BINS as f32 / ext[a] } else { 0.0 }));
    let mut cnt = [[0usize; BINS]; 3];
    let mut bb = [[Bx::EMPTY; BINS]; 3];
    for b in boxes.iter() {
        let k = bins_of(b.center(), cb.min, scale);
        for a in 0..3 {
            cnt[a][k[a]] += 1;
            bb[a][k[a]] = bb[a][k[a]].union(*b);
        }
    }
    let mut best: Option<(f32, usize, usize)> = None; // (cost, axis, bin)
    for axis in (0..3).filter(|&a| active[a]) {
        sweep(&cnt[axis], &bb[axis], axis, &mut best);
    }
    let (cost, axis, bin) = best?;
    let area = bounds.surface_area();
    let split_cost = 1.0 + if area > 0.0 { cost / area } else { n as f32 };
    if n <= MAX_LEAF && n as f32 <= split_cost {
        return None;
    }
    let s = partition(boxes, ids, axis, |c| bins_of(c, cb.min, scale)[axis] <= bin);
    (s.mid > 0 && s.mid < n).then_some(s)
}

/// The SAH sweep over one axis's bins: lowers `best` (cost, axis, bin) to a cheaper split
/// between bin `k` and `k + 1` (the first of equal costs wins). An empty bin `k` repeats
/// bin `k − 1`'s split exactly (the same boxes and counts on both sides), so it is skipped.
fn sweep(
    cnt: &[usize; BINS],
    bb: &[Bx; BINS],
    axis: usize,
    best: &mut Option<(f32, usize, usize)>,
) {
    // From the right, then from the left.
    let mut right_area = [0.0f32; BINS];
    let mut right_cnt = [0usize; BINS];
    let (mut acc, mut c) = (Bx::EMPTY, 0usize);
    for k in (1..BINS).rev() {
        if cnt[k] > 0 || k == BINS - 1 {
            acc = acc.union(bb[k]);
            c += cnt[k];
            right_area[k] = acc.surface_area();
        } else {
            right_area[k] = right_area[k + 1];
        }
        right_cnt[k] = c;
    }
    let (mut acc, mut c) = (Bx::EMPTY, 0usize);
    for k in 0..BINS - 1 {
        if cnt[k] == 0 {
            continue;
        }
        acc = acc.union(bb[k]);
        c += cnt[k];
        let (nr, nl) = (right_cnt[k + 1], c);
        if nr == 0 {
            continue;
        }
        let cost = acc.surface_area() * nl as f32 + right_area[k + 1] * nr as f32;
        if best.is_none_or(|(b, _, _)| cost < b) {
            *best = Some((cost, axis, k));
        }
    }
}

/// Moves the primitives whose centre satisfies `left` to the front, keeping the others in
/// the order a swap-to-front pass leaves them; gathers both sides' bounds.
fn partition(
    boxes: &mut [Bx],
    ids: &mut [u32],
    axis: usize,
    left: impl Fn(Vec3A) -> bool,
) -> Split {
    let (mut l, mut r) = ((Bx::EMPTY, Bx::EMPTY), (Bx::EMPTY, Bx::EMPTY));
    let mut k = 0;
    for i in 0..boxes.len() {
        let b = boxes[i];
        let c = b.center();
        if left(c) {
            l = (l.0.union(b), l.1.grow(c));
            boxes.swap(i, k);
            ids.swap(i, k);
            k += 1;
        } else {
            r = (r.0.union(b), r.1.grow(c));
        }
    }
    Split {
        axis,
        mid: k,
        left: l,
        right: r,
    }
}

/// Splits at the median centroid along the widest centroid axis (the order of
/// `select_nth_unstable` on the indices; the boxes follow from `input`).
fn median_split(input: &[Aabb], boxes: &mut [Bx], ids: &mut [u32], cb: &Bx) -> Split {
    let axis = cb.aabb().extent().max_position();
    let mid = ids.len() / 2;
    let key = |i: u32| input[i as usize].center()[axis];
    ids.select_nth_unstable_by(mid, |&a, &b| key(a).total_cmp(&key(b)));
    for (b, &i) in boxes.iter_mut().zip(ids.iter()) {
        *b = Bx::from(input[i as usize]);
    }
    let (l, r) = (gather(&boxes[..mid]), gather(&boxes[mid..]));
    Split {
        axis,
        mid,
        left: l,
        right: r,
    }
}
