//! Finding pairs of mesh triangles that form a planar parallelogram, so that the BVH can
//! store them as one quad primitive ([`super::quad4::QuadPacket`]).
//!
//! Two triangles of one mesh pair up when they share an edge (the same two vertex
//! positions, bit for bit) and the fourth vertex lies within 10⁻⁶ of the shorter
//! parallelogram edge of `a + c − b` (`b` the first triangle's vertex off the shared edge
//! `a c`). That also makes them coplanar. Pairing is greedy in triangle order, so it is
//! deterministic; triangles left over stay triangles.
//!
//! An edge shared by more than [`MAX_SHARING`] triangles (a non-manifold fan, or a stack of
//! copies of one triangle) pairs none of them across it: each triangle then tries at most
//! `3 MAX_SHARING` partners, so pairing stays O(N log N) for any triangle soup instead of
//! quadratic in the number of triangles on one edge.

use super::super::data::{MeshData, Prim, PrimsView, ShapeData};
use glam::Vec3;
use rayon::prelude::*;

/// Relative tolerance on the fourth vertex, in units of the shorter parallelogram edge.
const TOLERANCE: f64 = 1e-6;
/// Most triangles on one edge (the same two positions) that are still paired across it.
pub(crate) const MAX_SHARING: usize = 16;
/// Smallest accepted `|e1 × e2| / (|e1| |e2|)` (sine of the corner angle): slivers stay
/// triangles.
const MIN_SINE: f64 = 1e-4;

/// A parallelogram `corner + u e1 + v e2`, `(u, v) ∈ [0, 1]²`, made of two triangles: the
/// first covers `u + v ≤ 1` (its vertices are `corner`, `corner + e1`, `corner + e2`), the
/// second the rest (its vertices are `corner + e1`, `corner + e2` and the fourth corner).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Quad {
    pub(crate) corner: Vec3,
    pub(crate) e1: Vec3,
    pub(crate) e2: Vec3,
    /// `roles[k][j]`: which weight of [`Quad::maps`]' list belongs to vertex
    /// `j + 1` of triangle `k` (0 = the corner of that half, 1 = `corner + e1`,
    /// 2 = `corner + e2`).
    pub(crate) roles: [[u8; 2]; 2],
}

impl Quad {
    /// The parallelogram formed by triangles `t1` and `t2` (vertices in their stored order),
    /// if they form one (see the module docs).
    pub(crate) fn from_pair(t1: [Vec3; 3], t2: [Vec3; 3]) -> Option<Self> {
        // The one vertex of each triangle that is not on the other.
        let only = |t: [Vec3; 3], other: [Vec3; 3]| {
            let mut off = (0..3).filter(|&i| !other.contains(&t[i]));
            match (off.next(), off.next()) {
                (Some(k), None) => Some(k),
                _ => None,
            }
        };
        let (k, l) = (only(t1, t2)?, only(t2, t1)?);
        let (b, d) = (t1[k], t2[l]);
        let (a, c) = (t1[(k + 1) % 3], t1[(k + 2) % 3]);
        if a == c {
            return None;
        }
        let [a64, b64, c64, d64] = [a, b, c, d].map(|p| p.as_dvec3());
        let (e1, e2) = (a64 - b64, c64 - b64);
        let (l1, l2) = (e1.length(), e2.length());
        let gap = (d64 - (a64 + c64 - b64)).length();
        let sine = e1.cross(e2).length() / (l1 * l2);
        if !(gap <= TOLERANCE * l1.min(l2) && sine >= MIN_SINE) {
            return None;
        }
        let role = |p: Vec3, corner: Vec3| -> u8 {
            if p == a {
                1
            } else if p == c {
                2
            } else {
                debug_assert_eq!(p, corner);
                0
            }
        };
        Some(Self {
            corner: b,
            e1: a - b,
            e2: c - b,
            roles: [
                [role(t1[1], b), role(t1[2], b)],
                [role(t2[1], d), role(t2[2], d)],
            ],
        })
    }

    /// The barycentric weights of vertices 1 and 2 of each triangle as affine functions of
    /// the parameters: `maps()[k][j] = [α, β, γ]`, weight `α + β u + γ v`.
    pub(crate) fn maps(&self) -> WeightMaps {
        // Per role: (1 − u − v, u, v) on the first triangle, (u + v − 1, 1 − v, 1 − u) on
        // the second.
        const ROLE: [[[f32; 3]; 3]; 2] = [
            [[1.0, -1.0, -1.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            [[-1.0, 1.0, 1.0], [1.0, 0.0, -1.0], [1.0, -1.0, 0.0]],
        ];
        [0, 1].map(|k| self.roles[k].map(|r| ROLE[k][usize::from(r)]))
    }

    /// Which triangle (0 or 1) holds parameters `(u, v)` and the barycentric weights of its
    /// vertices 1 and 2 there ([`Quad::maps`]). `u`, `v` are clamped into `[0, 1]` first,
    /// so the weights lie in the triangle.
    #[inline]
    pub(crate) fn barycentrics(maps: &WeightMaps, u: f32, v: f32) -> (u32, f32, f32) {
        let (u, v) = (u.clamp(0.0, 1.0), v.clamp(0.0, 1.0));
        let k = usize::from(u + v > 1.0);
        let w = |c: [f32; 3]| (c[0] + c[1] * u + c[2] * v).max(0.0);
        (k as u32, w(maps[k][0]), w(maps[k][1]))
    }

    /// The four corners.
    #[cfg(test)]
    pub(crate) fn corners(&self) -> [Vec3; 4] {
        let c = self.corner;
        [c, c + self.e1, c + self.e2, c + self.e1 + self.e2]
    }
}

/// Weights of a quad's triangles' vertices 1 and 2 as affine maps of `(u, v)`.
pub(crate) type WeightMaps = [[[f32; 3]; 2]; 2];

/// A primitive as the BVH sees it: one input primitive, or two triangles as a quad.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Unit {
    One(u32),
    /// Input primitives `first` (the triangle with `u + v ≤ 1`) and `second`.
    Pair {
        first: u32,
        second: u32,
        quad: Quad,
    },
}

/// Pairs up the triangles of every mesh in `built`; every primitive appears in exactly one
/// unit, in input order of the unit's first primitive.
pub(crate) fn units(built: &PrimsView) -> Vec<Unit> {
    let n = built.prims.len();
    let mut partner: Vec<Option<(u32, Quad)>> = vec![None; n];
    let mut taken = vec![false; n];
    let mut start = 0;
    while start < n {
        let shape = built.ids[start].shape;
        let end = (start..n)
            .find(|&i| built.ids[i].shape != shape)
            .unwrap_or(n);
        if let ShapeData::Mesh(mesh) = &built.shapes[shape as usize] {
            pair_range(built.prims, mesh, start..end, &mut partner, &mut taken);
        }
        start = end;
    }
    (0..n)
        .filter_map(|i| match partner[i] {
            Some((j, quad)) => Some(Unit::Pair {
                first: i as u32,
                second: j,
                quad,
            }),
            None if taken[i] => None,
            None => Some(Unit::One(i as u32)),
        })
        .collect()
}

/// Greedy pairing of the triangles `range` of one mesh (`mesh`, whose triangle `t` is
/// primitive `range.start + t`) through a sorted list of their edges: the triangles that
/// share an edge (the same two vertex positions, bit for bit) are neighbours in the list, in
/// input order. An edge is keyed by its two vertices' numbers after vertices at the same
/// position are given one number ([`same_position`]), 8 bytes instead of the positions'
/// 24. Sorting one flat list allocates once (a map of edge to triangles would allocate per
/// edge); each triangle finds its edges' places in the list, and where each edge's run of
/// entries begins, by index, not by search.
fn pair_range(
    prims: &[Prim],
    mesh: &MeshData,
    range: std::ops::Range<usize>,
    partner: &mut [Option<(u32, Quad)>],
    taken: &mut [bool],
) {
    debug_assert_eq!(range.len(), mesh.indices.len());
    let tri = |i: usize| match &prims[i] {
        Prim::Tri(t) => Some(t.vertices()),
        _ => None,
    };
    let same = same_position(&mesh.positions);
    let edge = |a: u32, b: u32| {
        let (a, b) = (same[a as usize], same[b as usize]);
        (u64::from(a.min(b)) << 32) | u64::from(a.max(b))
    };
    // (edge, 3 (i − start) + k for triangle i's edge k), sorted; `at[3 (i − start) + k]` is
    // where that entry landed.
    let start = range.start;
    let mut edges: Vec<(u64, u32)> = mesh
        .indices
        .par_iter()
        .enumerate()
        .flat_map_iter(|(t, v)| {
            (0..3).map(move |k| (edge(v[k], v[(k + 1) % 3]), (3 * t + k) as u32))
        })
        .collect();
    // The entries differ (each names its triangle and edge), so any sort gives this order.
    edges.par_sort_unstable();
    let mut at = vec![0u32; edges.len()];
    for (p, &(_, e)) in edges.iter().enumerate() {
        at[e as usize] = p as u32;
    }
    // `first[p]`: where the run of entries with entry p's edge begins.
    let mut first = vec![0u32; edges.len()];
    for p in 1..edges.len() {
        first[p] = if edges[p].0 == edges[p - 1].0 {
            first[p - 1]
        } else {
            p as u32
        };
    }
    // The triangles that have triangle i's edge k (i among them), in input order; none if
    // more than `MAX_SHARING` have it.
    let sharing = |i: usize, k: usize| {
        let p = at[3 * (i - start) + k] as usize;
        let (e, f) = (edges[p].0, first[p] as usize);
        let run = edges[f..].iter().take_while(move |x| x.0 == e);
        let few = run.clone().nth(MAX_SHARING).is_none();
        run.take(if few { MAX_SHARING } else { 0 })
            .map(move |&(_, te)| start + te as usize / 3)
    };
    // Every triangle's parallelograms with its neighbours, in the order the greedy pass
    // tries them (found in parallel: `Quad::from_pair` depends on the two triangles only).
    let found: Vec<(u32, u32, Quad)> = range
        .into_par_iter()
        .flat_map_iter(|i| {
            let t = tri(i);
            (0..3)
                .filter(move |_| t.is_some())
                .flat_map(move |k| sharing(i, k).filter(move |&j| j != i))
                .filter_map(move |j| Some((i as u32, j as u32, Quad::from_pair(t?, tri(j)?)?)))
        })
        .collect();
    // Greedy in input order: each triangle not yet taken takes its first neighbour not
    // yet taken.
    for &(i, j, quad) in &found {
        let (i, j) = (i as usize, j as usize);
        if !taken[i] && !taken[j] {
            taken[i] = true;
            taken[j] = true;
            partner[i] = Some((j as u32, quad));
        }
    }
}

/// A number per vertex, shared by the vertices at the same position (bit for bit): the
/// least index among them.
fn same_position(positions: &[Vec3]) -> Vec<u32> {
    let mut sorted: Vec<([u32; 3], u32)> = positions
        .par_iter()
        .enumerate()
        .map(|(i, p)| (p.to_array().map(f32::to_bits), i as u32))
        .collect();
    sorted.par_sort_unstable();
    let mut same = vec![0u32; positions.len()];
    let mut first = 0;
    for (k, &(key, i)) in sorted.iter().enumerate() {
        if k == 0 || key != sorted[k - 1].0 {
            first = i;
        }
        same[i as usize] = first;
    }
    same
}

#[cfg(test)]
mod tests {
    use super::*;

    const B: Vec3 = Vec3::new(0.0, 0.0, 0.0);
    const A: Vec3 = Vec3::new(2.0, 0.0, 0.0);
    const C: Vec3 = Vec3::new(0.5, 1.0, 0.0);
    const D: Vec3 = Vec3::new(2.5, 1.0, 0.0);

    #[test]
    fn parallelogram_pairs_in_any_vertex_order() {
        let t1 = [B, A, C];
        for rot in 0..3 {
            let t2 = [[A, D, C], [D, C, A], [C, A, D]][rot];
            let q = Quad::from_pair(t1, t2).unwrap();
            assert_eq!((q.corner, q.e1 + q.e2), (B, D - B), "rot {rot}");
            // The fourth corner has weight 1 on the second triangle's vertex D.
            let (k, b1, b2) = Quad::barycentrics(&q.maps(), 1.0, 1.0);
            let w = [1.0 - b1 - b2, b1, b2];
            assert_eq!((k, w[t2.iter().position(|&p| p == D).unwrap()]), (1, 1.0));
            // A point maps back to the same position through either triangle.
            for (u, v) in [(0.3, 0.2), (0.7, 0.6), (0.5, 0.5)] {
                let p = q.corner + u * q.e1 + v * q.e2;
                let (k, b1, b2) = Quad::barycentrics(&q.maps(), u, v);
                let t = if k == 0 { t1 } else { t2 };
                let back = (1.0 - b1 - b2) * t[0] + b1 * t[1] + b2 * t[2];
                assert!(back.is_finite() && back.distance(p) < 1e-6, "{u} {v} {k}");
            }
        }
    }

    #[test]
    fn rejects_non_parallelograms_non_planar_and_unshared() {
        let t1 = [B, A, C];
        // Fourth vertex off by 1e-4 in the plane, or out of it.
        assert!(Quad::from_pair(t1, [A, D + Vec3::X * 1e-4, C]).is_none());
        assert!(Quad::from_pair(t1, [A, D + Vec3::Z * 1e-4, C]).is_none());
        // A trapezoid, a triangle sharing only a vertex, the same triangle twice.
        assert!(Quad::from_pair(t1, [A, D * 1.5, C]).is_none());
        assert!(Quad::from_pair(t1, [A, D, Vec3::Y * 7.0]).is_none());
        assert!(Quad::from_pair(t1, t1).is_none());
        // A sliver parallelogram (corner angle ~1e-6 rad) stays two triangles.
        let c = Vec3::new(1.0, 1e-6, 0.0);
        assert!(Quad::from_pair([B, A, c], [A, A + c, c]).is_none());
        // Within tolerance: an error of 4.8e-7 (edges 2 and 1.1) is accepted.
        let near = D + Vec3::X * 5e-7;
        assert!(near != D && Quad::from_pair(t1, [A, near, C]).is_some());
    }

    #[test]
    fn barycentrics_are_clamped_into_the_triangle() {
        let q = Quad::from_pair([B, A, C], [A, D, C]).unwrap();
        for (u, v) in [
            (-1e-5, 0.5),
            (1.0 + 1e-5, 0.2),
            (0.5, -1e-5),
            (1.0 + 1e-5, 1.0 + 1e-5),
        ] {
            let (_, b1, b2) = Quad::barycentrics(&q.maps(), u, v);
            let b0 = 1.0 - b1 - b2;
            assert!(b1.is_finite() && b2.is_finite());
            assert!(
                b0 >= 0.0 && b1 >= 0.0 && b2 >= 0.0,
                "{u} {v}: {b0} {b1} {b2}"
            );
        }
    }
}

#[cfg(test)]
#[path = "pairing_tests.rs"]
mod unit_tests;
