//! Tests of the BVH build: the tree is the one a plain per-node build gives (kept here as
//! the reference: one fold per node for its bounds, one for its centroid bounds, one
//! binning pass per axis), for any number of threads, and it is a valid hierarchy.

use super::aabb::Aabb;
use super::bvh::Bvh;
use super::bvh_node::{Node, BINS, MAX_LEAF, MEDIAN_DEPTH};
use glam::{Vec3, Vec3A};
use rand_core::{RngCore, SeedableRng};
use rand_pcg::Pcg64;

/// The reference build (the crate's build before it was made single-pass and parallel).
struct Builder<'a> {
    bounds: &'a [Aabb],
    centroids: Vec<Vec3>,
    index: Vec<u32>,
    nodes: Vec<Node>,
}

fn reference(bounds: &[Aabb]) -> (Vec<Node>, Vec<u32>) {
    let mut b = Builder {
        bounds,
        centroids: bounds.iter().map(Aabb::center).collect(),
        index: (0..bounds.len() as u32).collect(),
        nodes: Vec::new(),
    };
    b.build(0, bounds.len(), 0);
    (b.nodes, b.index)
}

impl Builder<'_> {
    /// Builds the subtree over `index[start..end]` and returns its node index.
    fn build(&mut self, start: usize, end: usize, depth: u32) -> usize {
        let me = self.nodes.len();
        let ids = &self.index[start..end];
        let bounds = ids
            .iter()
            .fold(Aabb::EMPTY, |b, &i| b.union(self.bounds[i as usize]));
        let padded = bounds.padded();
        self.nodes.push(Node {
            min: padded.min.into(),
            max: padded.max.into(),
            offset: start as u32,
            count: (end - start) as u16,
            axis: 0,
        });
        let n = end - start;
        if n == 1 {
            return me;
        }
        let split = if depth >= MEDIAN_DEPTH {
            None
        } else {
            self.sah_split(start, end, &bounds)
        };
        let (axis, mid) = match split {
            Some(s) => s,
            None if n <= MAX_LEAF => return me,
            None => self.median_split(start, end),
        };
        self.build(start, mid, depth + 1);
        let second = self.build(mid, end, depth + 1);
        let node = &mut self.nodes[me];
        node.offset = second as u32;
        node.count = 0;
        node.axis = axis as u16;
        me
    }

    /// The best binned SAH split as (axis, partition point), or `None` if a leaf is at least
    /// as cheap (only allowed for small nodes) or the centroids cannot be separated.
    fn sah_split(&mut self, start: usize, end: usize, bounds: &Aabb) -> Option<(usize, usize)> {
        let ids = &self.index[start..end];
        let cb = ids
            .iter()
            .fold(Aabb::EMPTY, |b, &i| b.grow(self.centroids[i as usize]));
        let ext = cb.extent();
        let n = end - start;
        let mut best: Option<(f32, usize, usize)> = None; // (cost, axis, bin)
        for axis in 0..3 {
            if ext[axis] <= 0.0 {
                continue;
            }
            let scale = BINS as f32 / ext[axis];
            let bin_of = |c: Vec3| (((c[axis] - cb.min[axis]) * scale) as usize).min(BINS - 1);
            let mut cnt = [0usize; BINS];
            let mut bb = [Aabb::EMPTY; BINS];
            for &i in ids {
                let k = bin_of(self.centroids[i as usize]);
                cnt[k] += 1;
                bb[k] = bb[k].union(self.bounds[i as usize]);
            }
            // Sweep from the right, then from the left.
            let mut right_area = [0.0f32; BINS];
            let (mut acc, mut c) = (Aabb::EMPTY, 0usize);
            let mut right_cnt = [0usize; BINS];
            for k in (1..BINS).rev() {
                acc = acc.union(bb[k]);
                c += cnt[k];
                right_area[k] = acc.surface_area();
                right_cnt[k] = c;
            }
            let (mut acc, mut c) = (Aabb::EMPTY, 0usize);
            for k in 0..BINS - 1 {
                acc = acc.union(bb[k]);
                c += cnt[k];
                let (nr, nl) = (right_cnt[k + 1], c);
                if nl == 0 || nr == 0 {
                    continue;
                }
                let cost = acc.surface_area() * nl as f32 + right_area[k + 1] * nr as f32;
                if best.is_none_or(|(b, _, _)| cost < b) {
                    best = Some((cost, axis, k));
                }
            }
        }
        let (cost, axis, bin) = best?;
        let area = bounds.surface_area();
        let split_cost = 1.0 + if area > 0.0 { cost / area } else { n as f32 };
        if n <= MAX_LEAF && n as f32 <= split_cost {
            return None;
        }
        let scale = BINS as f32 / ext[axis];
        let (lo, cents) = (cb.min[axis], &self.centroids);
        let slice = &mut self.index[start..end];
        let mid = partition(slice, |&i| {
            let k = (((cents[i as usize][axis] - lo) * scale) as usize).min(BINS - 1);
            k <= bin
        });
        (mid > 0 && mid < n).then_some((axis, start + mid))
    }

    /// Splits at the median centroid along the widest centroid axis.
    fn median_split(&mut self, start: usize, end: usize) -> (usize, usize) {
        let cents = &self.centroids;
        let cb = self.index[start..end]
            .iter()
            .fold(Aabb::EMPTY, |b, &i| b.grow(cents[i as usize]));
        let axis = cb.extent().max_position();
        let mid = (end - start) / 2;
        self.index[start..end].select_nth_unstable_by(mid, |&a, &b| {
            cents[a as usize][axis].total_cmp(&cents[b as usize][axis])
        });
        (axis, start + mid)
    }
}

/// Moves the elements satisfying `pred` to the front; returns how many there are.
fn partition(s: &mut [u32], pred: impl Fn(&u32) -> bool) -> usize {
    let mut k = 0;
    for i in 0..s.len() {
        if pred(&s[i]) {
            s.swap(i, k);
            k += 1;
        }
    }
    k
}

fn uniform(rng: &mut Pcg64) -> f32 {
    (rng.next_u32() >> 8) as f32 / (1u32 << 24) as f32
}

/// `n` random boxes (a triangle soup's bounds): corners uniform in a unit cube scaled by
/// `spread`, sizes up to `size`; every seventh box repeats an earlier one, so that equal
/// centroids occur.
fn soup(seed: u64, n: usize, spread: f32, size: f32) -> Vec<Aabb> {
    let mut rng = Pcg64::seed_from_u64(seed);
    let mut out: Vec<Aabb> = Vec::with_capacity(n);
    for i in 0..n {
        if i % 7 == 6 {
            let j = rng.next_u32() as usize % i;
            out.push(out[j]);
            continue;
        }
        let p = spread * Vec3::new(uniform(&mut rng), uniform(&mut rng), uniform(&mut rng));
        let s = size * Vec3::new(uniform(&mut rng), uniform(&mut rng), uniform(&mut rng));
        out.push(Aabb::from_points(&[p, p + s]));
    }
    out
}

fn same_nodes(a: &[Node], b: &[Node]) -> bool {
    a.len() == b.len()
        && a.iter().zip(b).all(|(x, y)| {
            x.min == y.min
                && x.max == y.max
                && x.offset == y.offset
                && x.count == y.count
                && x.axis == y.axis
        })
}

/// Checks the tree: every primitive in exactly one leaf, leaves small, every node's box
/// holding its children's or its primitives' boxes.
fn check_valid(bvh: &Bvh, bounds: &[Aabb]) {
    let mut seen = vec![0u32; bounds.len()];
    let mut stack = vec![0usize];
    let inside = |(lo, hi): (Vec3A, Vec3A), b: &Aabb| {
        lo.cmple(b.min.into()).all() && hi.cmpge(b.max.into()).all()
    };
    while let Some(k) = stack.pop() {
        if let Some((first, count)) = bvh.leaf(k) {
            assert!(
                count as usize <= MAX_LEAF || bounds.len() <= 1,
                "leaf {k}: {count}"
            );
            for &i in &bvh.order()[first as usize..(first + count) as usize] {
                seen[i as usize] += 1;
                assert!(inside(bvh.node_box(k), &bounds[i as usize]), "node {k}");
            }
        } else {
            for c in bvh.children(k) {
                assert!(c > k && c < bvh.node_count(), "node {k} child {c}");
                let (lo, hi) = bvh.node_box(c);
                let child = Aabb {
                    min: lo.into(),
                    max: hi.into(),
                };
                // Children's padded boxes lie in the parent's padded box up to the padding.
                let pad = Vec3A::splat(1e-4);
                let (plo, phi) = bvh.node_box(k);
                assert!(inside((plo - pad, phi + pad), &child), "node {k} child {c}");
                stack.push(c);
            }
        }
    }
    assert!(
        seen.iter().all(|&s| s == 1),
        "primitives not each in one leaf"
    );
}

#[test]
fn build_matches_the_reference_for_any_parallel_split() {
    // Seeds fixed; soups of points (zero-size boxes), small and large boxes, and one flat
    // in z (an inactive axis).
    for (seed, n, spread, size) in [
        (1u64, 1usize, 1.0f32, 0.1f32),
        (2, 2, 1.0, 0.0),
        (3, 5, 1.0, 0.5),
        (4, 300, 1.0, 0.0),
        (5, 3000, 10.0, 0.3),
        (6, 20_000, 100.0, 2.0),
    ] {
        let mut b = soup(seed, n, spread, size);
        if seed == 5 {
            b.iter_mut().for_each(|x| (x.min.z, x.max.z) = (0.0, 0.0));
        }
        let (nodes, order) = reference(&b);
        for parallel_min in [2usize, 100, usize::MAX] {
            let bvh = Bvh::build_with(&b, parallel_min);
            assert!(
                same_nodes(bvh.nodes_for_tests(), &nodes) && bvh.order() == order.as_slice(),
                "seed {seed} n {n} parallel_min {parallel_min}"
            );
            check_valid(&bvh, &b);
        }
    }
}

#[test]
fn degenerate_and_deep_inputs_match_the_reference() {
    // Identical boxes (no SAH split separates them: the median split) and a geometric
    // series of sizes (a deep tree).
    let same = vec![Aabb::from_points(&[Vec3::ZERO, Vec3::ONE]); 1000];
    let geometric: Vec<Aabb> = (0..200)
        .map(|i| {
            let p = Vec3::splat(0.5f32.powi(i / 4) * (1.0 + (i % 4) as f32 * 0.1));
            Aabb::from_points(&[p, p * 1.01])
        })
        .collect();
    for b in [same, geometric] {
        let (nodes, order) = reference(&b);
        for parallel_min in [2usize, usize::MAX] {
            let bvh = Bvh::build_with(&b, parallel_min);
            assert!(same_nodes(bvh.nodes_for_tests(), &nodes));
            assert_eq!(bvh.order(), order.as_slice());
            check_valid(&bvh, &b);
        }
    }
}

#[test]
fn bins_match_the_saturating_conversion() {
    // Random centres, bin edges (whole numbers and their neighbours), values past the last
    // bin, below the first, infinite and NaN: the bin is `(x as usize).min(BINS - 1)`.
    let mut rng = Pcg64::seed_from_u64(11);
    let mut xs: Vec<f32> = (0..10_000)
        .map(|_| 20.0 * uniform(&mut rng) - 2.0)
        .collect();
    for k in 0..=BINS as u32 + 1 {
        let f = k as f32;
        xs.extend([f, f.next_down(), f.next_up()]);
    }
    xs.extend([
        -0.0,
        -1e30,
        1e30,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
        1e-45,
    ]);
    for x in xs {
        let want = (x as usize).min(BINS - 1);
        let got = super::bvh_build::bins_of(Vec3A::splat(x), Vec3A::ZERO, Vec3A::ONE);
        assert_eq!(got, [want; 3], "x = {x}");
    }
}
