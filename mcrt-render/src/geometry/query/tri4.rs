//! Four triangles tested against one ray at once: the watertight test of Woop, Benthin &
//! Wald 2013 ("Watertight Ray/Triangle Intersection", JCGT 2(1)) with triangle `i` in SIMD
//! lane `i`.
//!
//! Every lane computes exactly the same floating-point operations in the same order as the
//! one-triangle test ([`super::scalar::TriRay::hit`]), so both agree bit for bit on
//! every triangle (including the exact-zero edge case, redone in f64 per lane).

use glam::{BVec4A, DVec3, Vec3, Vec4};

/// Up to four triangles by coordinate: `v[j][a]` holds coordinate `a` (world axis) of vertex
/// `j` of the four triangles in its lanes. Missing triangles repeat the last one, so every
/// lane holds a real triangle and a duplicate never wins a tie (lower lanes win).
#[derive(Debug, Clone, Copy)]
pub(crate) struct TriPacket {
    /// The fourth axis is padding, so that indexing by `k & 3` needs no bounds check.
    v: [[Vec4; 4]; 3],
}

impl TriPacket {
    /// Packs 1 to 4 triangles (more are ignored; none gives an empty, never-hit packet).
    pub(crate) fn new(tris: &[[Vec3; 3]]) -> Self {
        debug_assert!(tris.len() <= 4);
        let Some(last) = tris.len().checked_sub(1) else {
            let mut v = [[Vec4::NAN; 4]; 3];
            v.iter_mut().for_each(|vj| vj[3] = Vec4::ZERO);
            return Self { v };
        };
        let mut v = [[Vec4::ZERO; 4]; 3];
        for l in 0..4 {
            let t = tris[l.min(last)];
            for (vj, p) in v.iter_mut().zip(t) {
                for a in 0..3 {
                    vj[a][l] = p[a];
                }
            }
        }
        Self { v }
    }

    /// The vertices of the triangle in lane `l`.
    #[cfg(test)]
    pub(crate) fn vertices(&self, l: usize) -> [Vec3; 3] {
        [0, 1, 2].map(|j| Vec3::new(self.v[j][0][l], self.v[j][1][l], self.v[j][2][l]))
    }
}

/// A ray prepared for [`TriPacket`] tests: the axis permutation that makes the direction's
/// largest component z (kept right-handed), the origin and the shear in splatted lanes.
#[derive(Debug, Clone, Copy)]
pub(crate) struct TriRay4 {
    /// World axes (kx, ky, kz).
    k: [usize; 3],
    /// Origin coordinates along kx, ky, kz.
    o: [Vec4; 3],
    /// Shear `Sx = dx/dz`, `Sy = dy/dz`, `Sz = 1/dz` (each as `d · (1/dz)`, as the
    /// one-triangle test rounds them).
    s: [Vec4; 3],
}

/// The nearest hit in a packet: its lane, distance and barycentrics of vertices 1 and 2.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PacketHit {
    pub(crate) lane: u32,
    pub(crate) t: f32,
    pub(crate) b1: f32,
    pub(crate) b2: f32,
}

/// Per-lane results that survive the edge tests: edge functions, scaled distance, and the
/// lanes still in play.
struct Edges {
    e: [Vec4; 3],
    det: Vec4,
    tt: Vec4,
    live: BVec4A,
}

impl TriRay4 {
    #[inline]
    pub(crate) fn new(origin: Vec3, dir: Vec3) -> Self {
        let (k, o, s) = shear(origin, dir);
        Self {
            k,
            o: o.map(Vec4::splat),
            s: s.map(Vec4::splat),
        }
    }

    /// The edge functions and the tests that need no division; `None` when no lane is left.
    #[inline(always)]
    fn edges(&self, p: &TriPacket, t_max: f32) -> Option<Edges> {
        let [kx, ky, kz] = [self.k[0] & 3, self.k[1] & 3, self.k[2] & 3];
        // Vertices relative to the origin, sheared: (x, y) per vertex; z kept unscaled.
        let rel = |j: usize| {
            let z = p.v[j][kz] - self.o[2];
            let x = (p.v[j][kx] - self.o[0]) - self.s[0] * z;
            let y = (p.v[j][ky] - self.o[1]) - self.s[1] * z;
            (x, y, z)
        };
        let (ax, ay, az) = rel(0);
        let (bx, by, bz) = rel(1);
        let (cx, cy, cz) = rel(2);
        let mut e = [cx * by - cy * bx, ax * cy - ay * cx, bx * ay - by * ax];
        let zero = Vec4::ZERO;
        let on_edge = e[0].cmpeq(zero) | e[1].cmpeq(zero) | e[2].cmpeq(zero);
        if on_edge.any() {
            edges_f64(&mut e, on_edge.bitmask(), [ax, bx, cx], [ay, by, cy]);
        }
        // Edges of both signs: the ray passes outside. (A NaN edge, possible only for
        // coordinates near f32::MAX, makes det NaN, and NaN lanes fail every test below.)
        let neg = e[0].min(e[1]).min(e[2]).cmplt(zero);
        let pos = e[0].max(e[1]).max(e[2]).cmpgt(zero);
        let det = e[0] + e[1] + e[2];
        let sure = !(neg & pos) & det.cmpne(zero);
        if !sure.any() {
            return None;
        }
        let sz = self.s[2];
        let tt = e[0] * (sz * az) + e[1] * (sz * bz) + e[2] * (sz * cz);
        let bound = det * Vec4::splat(t_max);
        let front = det.cmpgt(zero) & tt.cmpgt(zero) & tt.cmplt(bound);
        let back = det.cmplt(zero) & tt.cmplt(zero) & tt.cmpgt(bound);
        let live = sure & (front | back);
        live.any().then_some(Edges { e, det, tt, live })
    }

    /// The nearest hit with `0 < t < t_max` among the packet's triangles, each tested
    /// against the same `t_max` (the lowest lane on a tie).
    #[inline(always)]
    pub(crate) fn closest(&self, p: &TriPacket, t_max: f32) -> Option<PacketHit> {
        let ed = self.edges(p, t_max)?;
        let inv = ed.det.recip();
        let t = ed.tt * inv;
        let ok = ed.live & t.cmpgt(Vec4::ZERO) & t.cmplt(Vec4::splat(t_max));
        if !ok.any() {
            return None;
        }
        let t = Vec4::select(ok, t, Vec4::INFINITY);
        let best = t.min_element();
        let lane = (t.cmpeq(Vec4::splat(best)) & ok).bitmask().trailing_zeros() as usize;
        let inv = inv.to_array()[lane];
        Some(PacketHit {
            lane: lane as u32,
            t: best,
            b1: ed.e[1].to_array()[lane] * inv,
            b2: ed.e[2].to_array()[lane] * inv,
        })
    }

    /// True when some triangle of the packet is hit with `0 < t < t_max`.
    #[inline(always)]
    pub(crate) fn any(&self, p: &TriPacket, t_max: f32) -> bool {
        self.edges(p, t_max).is_some_and(|ed| {
            let t = ed.tt * ed.det.recip();
            (ed.live & t.cmpgt(Vec4::ZERO) & t.cmplt(Vec4::splat(t_max))).any()
        })
    }
}

/// The ray's set-up for the test: the world axes (kx, ky, kz) that make the direction's
/// largest component z (kept right-handed), the origin along them and the shear
/// `Sx = dx/dz`, `Sy = dy/dz`, `Sz = 1/dz` (each as `d · (1/dz)`, as the one-triangle test
/// rounds them).
#[inline(always)]
pub(crate) fn shear(origin: Vec3, dir: Vec3) -> ([usize; 3], [f32; 3], [f32; 3]) {
    // (kx, ky) follow kz cyclically, swapped when dz < 0 to keep the winding.
    const NEXT: [[usize; 2]; 3] = [[1, 2], [2, 0], [0, 1]];
    let kz = dir.abs().max_position();
    let [kx, ky] = if dir[kz] < 0.0 {
        let [a, b] = NEXT[kz];
        [b, a]
    } else {
        NEXT[kz]
    };
    let sz = 1.0 / dir[kz];
    (
        [kx, ky, kz],
        [kx, ky, kz].map(|a| origin[a]),
        [dir[kx] * sz, dir[ky] * sz, sz],
    )
}

/// Recomputes in f64 the edge functions of the lanes in `lanes` (a bitmask) where some edge
/// is exactly 0 in f32, as the paper does so that shared edges are claimed consistently.
#[cold]
#[inline(never)]
fn edges_f64(e: &mut [Vec4; 3], lanes: u32, x: [Vec4; 3], y: [Vec4; 3]) {
    let mut out = e.map(|v| v.to_array());
    for l in (0..4).filter(|l| lanes & (1 << l) != 0) {
        let w = edge_f64([x[0][l], x[1][l], x[2][l]], [y[0][l], y[1][l], y[2][l]]);
        [out[0][l], out[1][l], out[2][l]] = w;
    }
    *e = out.map(Vec4::from_array);
}

/// One lane's three edge functions in f64 from its sheared vertices' `x` and `y` (vertices
/// 0, 1, 2), rounded back to f32.
#[inline(always)]
pub(crate) fn edge_f64(x: [f32; 3], y: [f32; 3]) -> [f32; 3] {
    let px = DVec3::new(x[0].into(), x[1].into(), x[2].into());
    let py = DVec3::new(y[0].into(), y[1].into(), y[2].into());
    let u = px.z * py.y - py.z * px.y;
    let v = px.x * py.z - py.x * px.z;
    let w = px.y * py.x - py.y * px.x;
    [u as f32, v as f32, w as f32]
}

#[cfg(test)]
mod tests {
    use super::super::scalar::{TriRay, TriSoa};
    use super::*;

    /// The one-triangle test on each lane's triangle against the same bound; the nearest
    /// hit wins, the lowest lane on a tie. (A scalar loop that lowers the bound after each
    /// hit can differ in the last ulp: `tt < t_max · det` is not `tt / det < t_max`.)
    fn scalar(r: Vec3, d: Vec3, tris: &[[Vec3; 3]], t_max: f32) -> Option<PacketHit> {
        let ray = TriRay::new(r, d);
        let mut best: Option<PacketHit> = None;
        for (l, t) in tris.iter().enumerate() {
            if let Some((t, b1, b2)) = ray.hit(&TriSoa::new(*t), t_max) {
                if best.is_none_or(|b| t < b.t) {
                    best = Some(PacketHit {
                        lane: l as u32,
                        t,
                        b1,
                        b2,
                    });
                }
            }
        }
        best
    }

    #[test]
    fn packing_pads_with_the_last_triangle() {
        let a = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let b = [Vec3::Z, Vec3::ONE, Vec3::NEG_ONE];
        let p = TriPacket::new(&[a, b]);
        assert_eq!(p.vertices(0), a);
        assert_eq!([p.vertices(1), p.vertices(2), p.vertices(3)], [b; 3]);
    }

    #[test]
    fn one_lane_hit_with_barycentrics() {
        let tri = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let r = TriRay4::new(Vec3::new(0.25, 0.5, 2.0), Vec3::new(0.0, 0.0, -2.0));
        let h = r.closest(&TriPacket::new(&[tri]), f32::INFINITY).unwrap();
        assert!(h.t.is_finite() && h.b1.is_finite() && h.b2.is_finite());
        assert_eq!(h.lane, 0);
        assert!((h.t - 1.0).abs() < 1e-6);
        assert!((h.b1 - 0.25).abs() < 1e-6 && (h.b2 - 0.5).abs() < 1e-6);
        assert!(r.closest(&TriPacket::new(&[tri]), 0.5).is_none());
        assert!(!r.any(&TriPacket::new(&[tri]), 1.0));
        assert!(r.any(&TriPacket::new(&[tri]), 1.0 + 1e-6));
        assert!(r.closest(&TriPacket::new(&[]), f32::INFINITY).is_none());
    }

    #[test]
    fn nearest_lane_wins_and_ties_go_to_the_lower_lane() {
        let at = |z: f32| {
            [
                Vec3::new(-1.0, -1.0, z),
                Vec3::new(1.0, -1.0, z),
                Vec3::new(0.0, 1.0, z),
            ]
        };
        let r = TriRay4::new(Vec3::new(0.0, 0.0, 5.0), -Vec3::Z);
        let p = TriPacket::new(&[at(0.0), at(2.0), at(1.0), at(2.0)]);
        let h = r.closest(&p, f32::INFINITY).unwrap();
        assert_eq!((h.lane, h.t), (1, 3.0));
        // The bound is strict.
        assert!(r.closest(&p, 3.0).is_none() && !r.any(&p, 3.0));
        assert!(r.any(&p, 3.0001));
        // Lanes behind the origin never count; the nearest of the rest wins.
        let q = TriPacket::new(&[at(0.0), at(9.0), at(1.0), at(6.0)]);
        assert_eq!(r.closest(&q, 9.0).map(|h| (h.lane, h.t)), Some((2, 4.0)));
        assert_eq!(r.closest(&q, 4.5).map(|h| (h.lane, h.t)), Some((2, 4.0)));
        assert!(r.closest(&q, 4.0).is_none());
        // Lane 0 (t = 5) alone, with only 1 to 3 lanes packed.
        for n in 1..=3 {
            let q = TriPacket::new(&[at(0.0), at(9.0), at(9.0)][..n]);
            assert_eq!(
                r.closest(&q, 9.0).map(|h| (h.lane, h.t)),
                Some((0, 5.0)),
                "n {n}"
            );
        }
    }

    #[test]
    fn degenerate_and_edge_lanes_match_the_scalar_test() {
        let v = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let square = [v[1], Vec3::new(1.0, 1.0, 0.0), v[2]];
        let flat = [Vec3::ZERO, Vec3::X, Vec3::X * 2.0];
        let tris = [v, square, flat, v];
        for i in 1..64 {
            let s = i as f32 / 64.0;
            let d = Vec3::new(0.1, -0.2, -1.0);
            let o = Vec3::new(s, 1.0 - s, 0.0) - d;
            for n in 1..=4 {
                let p = TriPacket::new(&tris[..n]);
                let want = scalar(o, d, &tris[..n], 9.0);
                assert_eq!(TriRay4::new(o, d).closest(&p, 9.0), want, "i {i} n {n}");
                assert_eq!(TriRay4::new(o, d).any(&p, 9.0), want.is_some());
            }
        }
    }

    /// Random triangles (a tenth degenerate, many sharing edges with their neighbour) and
    /// rays (random, and aimed exactly at vertices and edge midpoints): every packet of 1 to
    /// 4 of them gives bit for bit what the one-triangle test gives in a scalar loop.
    #[test]
    fn random_packets_agree_with_the_scalar_test() {
        use rand_core::{RngCore, SeedableRng};
        let mut rng = rand_pcg::Pcg32::seed_from_u64(17);
        let mut f = move || (rng.next_u32() >> 8) as f32 / (1u32 << 24) as f32 * 2.0 - 1.0;
        let mut point = || Vec3::new(f(), f(), f());
        let (mut hits, mut checked) = (0, 0);
        for round in 0..3000 {
            let mut tris = Vec::new();
            for k in 0..4 {
                let t = match (round + k) % 10 {
                    0 => {
                        let (a, b) = (point(), point());
                        [a, b, a + (b - a) * 0.5] // collinear
                    }
                    1..=3 if k > 0 => {
                        let prev: [Vec3; 3] = tris[k - 1];
                        [prev[2], prev[1], point()] // shares an edge
                    }
                    _ => [point(), point(), point()],
                };
                tris.push(t);
            }
            let o = point() * 3.0;
            let aim = match round % 3 {
                0 => tris[round % 4][round % 3],
                1 => 0.5 * (tris[1][1] + tris[1][2]),
                _ => point(),
            };
            let d = if round % 7 == 0 {
                point() * Vec3::Z // axis-parallel
            } else {
                aim - o
            };
            if d == Vec3::ZERO {
                continue;
            }
            let t_max = if round % 5 == 0 { 1.0 } else { f32::INFINITY };
            for n in 1..=4 {
                let want = scalar(o, d, &tris[..n], t_max);
                let p = TriPacket::new(&tris[..n]);
                let got = TriRay4::new(o, d).closest(&p, t_max);
                if let Some(h) = got {
                    assert!(h.t.is_finite() && h.b1.is_finite() && h.b2.is_finite());
                }
                assert_eq!(got, want, "round {round} n {n}");
                assert_eq!(TriRay4::new(o, d).any(&p, t_max), want.is_some());
                hits += usize::from(want.is_some());
                checked += 1;
            }
        }
        assert!(hits > checked / 10, "{hits} hits of {checked}");
    }
}
