//! Eight triangles tested against one ray at once, on the lanes the 8-wide BVH chose
//! ([`Lanes8`]: AVX2, or two 4-lane halves): [`super::tri4`]'s watertight test (Woop,
//! Benthin & Wald 2013) with triangle `i` in lane `i`.
//!
//! Every lane computes the same floating-point operations in the same order as
//! [`super::tri4::TriRay4`] (and so as the one-triangle test), so a triangle gets the same
//! bits whichever packet width or lanes test it.

use super::tri4::edge_f64;
use super::tri4::PacketHit;
use crate::accel::Lanes8;
use glam::Vec3;

/// Up to eight triangles by coordinate: `v[j][a]` holds coordinate `a` (world axis) of
/// vertex `j` of the eight triangles in its lanes. Missing triangles repeat the last one (a
/// duplicate never wins a tie: lower lanes win); an empty packet has NaN lanes.
#[derive(Debug, Clone, Copy)]
pub(crate) struct TriPacket8 {
    /// The fourth axis is padding, so that indexing by `k & 3` needs no bounds check.
    v: [[[f32; 8]; 4]; 3],
}

impl TriPacket8 {
    /// Packs 0 to 8 triangles (more are ignored).
    pub(crate) fn new(tris: &[[Vec3; 3]]) -> Self {
        debug_assert!(tris.len() <= 8);
        let mut v = [[[f32::NAN; 8]; 4]; 3];
        if let Some(last) = tris.len().checked_sub(1) {
            for l in 0..8 {
                for (vj, p) in v.iter_mut().zip(tris[l.min(last)]) {
                    for a in 0..3 {
                        vj[a][l] = p[a];
                    }
                }
            }
        }
        v.iter_mut().for_each(|vj| vj[3] = [0.0; 8]);
        Self { v }
    }
}

/// A ray prepared for [`TriPacket8`] tests on lanes `L`: [`super::tri4::TriRay4`]'s axis
/// permutation, origin and shear.
#[derive(Clone, Copy)]
pub(crate) struct TriRay8<L: Lanes8> {
    l: L,
    k: [usize; 3],
    o: [L::V; 3],
    s: [L::V; 3],
}

/// Per-lane results that survive the edge tests.
struct Edges<L: Lanes8> {
    e: [L::V; 3],
    det: L::V,
    tt: L::V,
    live: L::M,
}

impl<L: Lanes8> TriRay8<L> {
    #[inline(always)]
    pub(crate) fn new(l: L, origin: Vec3, dir: Vec3) -> Self {
        let (k, o, s) = super::tri4::shear(origin, dir);
        // (Arrays written out: `array::map` is left out of line, and the lane operations
        // inside it then become calls.)
        Self {
            l,
            k,
            o: [l.splat(o[0]), l.splat(o[1]), l.splat(o[2])],
            s: [l.splat(s[0]), l.splat(s[1]), l.splat(s[2])],
        }
    }

    /// Vertex `j` relative to the origin, sheared: `(x, y, z)`, z unscaled.
    #[inline(always)]
    fn rel(&self, p: &TriPacket8, j: usize) -> (L::V, L::V, L::V) {
        let l = self.l;
        let [kx, ky, kz] = [self.k[0] & 3, self.k[1] & 3, self.k[2] & 3];
        let z = l.sub(l.load(&p.v[j][kz]), self.o[2]);
        let x = l.sub(l.sub(l.load(&p.v[j][kx]), self.o[0]), l.mul(self.s[0], z));
        let y = l.sub(l.sub(l.load(&p.v[j][ky]), self.o[1]), l.mul(self.s[1], z));
        (x, y, z)
    }

    /// The edge functions and the tests that need no division; `None` when no lane is left.
    #[inline(always)]
    fn edges(&self, p: &TriPacket8, t_max: f32) -> Option<Edges<L>> {
        let l = self.l;
        let (ax, ay, az) = self.rel(p, 0);
        let (bx, by, bz) = self.rel(p, 1);
        let (cx, cy, cz) = self.rel(p, 2);
        let mut e = [
            cross(l, cx, by, cy, bx),
            cross(l, ax, cy, ay, cx),
            cross(l, bx, ay, by, ax),
        ];
        let zero = l.splat(0.0);
        let on_edge = l.bits(l.or(l.or(l.eq(e[0], zero), l.eq(e[1], zero)), l.eq(e[2], zero)));
        if on_edge != 0 {
            let out = edges_f64(
                arrays(l, e),
                on_edge,
                arrays(l, [ax, bx, cx]),
                arrays(l, [ay, by, cy]),
            );
            e = [l.load(&out[0]), l.load(&out[1]), l.load(&out[2])];
        }
        let neg = l.lt(l.min(l.min(e[0], e[1]), e[2]), zero);
        let pos = l.gt(l.max(l.max(e[0], e[1]), e[2]), zero);
        let det = l.add(l.add(e[0], e[1]), e[2]);
        let sure = l.and_not(l.and(neg, pos), l.ne(det, zero));
        if l.bits(sure) == 0 {
            return None;
        }
        let sz = self.s[2];
        let tt = l.add(
            l.add(l.mul(e[0], l.mul(sz, az)), l.mul(e[1], l.mul(sz, bz))),
            l.mul(e[2], l.mul(sz, cz)),
        );
        let bound = l.mul(det, l.splat(t_max));
        let front = l.and(l.and(l.gt(det, zero), l.gt(tt, zero)), l.lt(tt, bound));
        let back = l.and(l.and(l.lt(det, zero), l.lt(tt, zero)), l.gt(tt, bound));
        let live = l.and(sure, l.or(front, back));
        (l.bits(live) != 0).then_some(Edges { e, det, tt, live })
    }

    /// The nearest hit with `0 < t < t_max` among the packet's triangles, each tested
    /// against the same `t_max` (the lowest lane on a tie).
    #[inline(always)]
    pub(crate) fn closest(&self, p: &TriPacket8, t_max: f32) -> Option<PacketHit> {
        let l = self.l;
        let ed = self.edges(p, t_max)?;
        let inv = l.div(l.splat(1.0), ed.det);
        let t = l.mul(ed.tt, inv);
        let ok = l.and(
            l.and(ed.live, l.gt(t, l.splat(0.0))),
            l.lt(t, l.splat(t_max)),
        );
        let (best, lane) = nearest_lane(l, ok, t)?;
        let inv = l.to_array(inv)[lane];
        Some(PacketHit {
            lane: lane as u32,
            t: best,
            b1: l.to_array(ed.e[1])[lane] * inv,
            b2: l.to_array(ed.e[2])[lane] * inv,
        })
    }

    /// True when some triangle of the packet is hit with `0 < t < t_max`.
    #[inline(always)]
    pub(crate) fn any(&self, p: &TriPacket8, t_max: f32) -> bool {
        let l = self.l;
        self.edges(p, t_max).is_some_and(|ed| {
            let t = l.mul(ed.tt, l.div(l.splat(1.0), ed.det));
            let ok = l.and(
                l.and(ed.live, l.gt(t, l.splat(0.0))),
                l.lt(t, l.splat(t_max)),
            );
            l.bits(ok) != 0
        })
    }
}

/// `a·b − c·d` per lane.
#[inline(always)]
fn cross<L: Lanes8>(l: L, a: L::V, b: L::V, c: L::V, d: L::V) -> L::V {
    l.sub(l.mul(a, b), l.mul(c, d))
}

/// Three vectors of lanes as arrays.
#[inline(always)]
fn arrays<L: Lanes8>(l: L, v: [L::V; 3]) -> [[f32; 8]; 3] {
    [l.to_array(v[0]), l.to_array(v[1]), l.to_array(v[2])]
}

/// [`super::tri4`]'s f64 edge functions for the lanes in `lanes` (a bitmask) where some
/// edge is exactly 0 in f32.
#[cold]
#[inline(never)]
fn edges_f64(e: [[f32; 8]; 3], lanes: u32, x: [[f32; 8]; 3], y: [[f32; 8]; 3]) -> [[f32; 8]; 3] {
    let mut out = e;
    for i in (0..8).filter(|i| lanes & (1 << i) != 0) {
        let w = edge_f64([x[0][i], x[1][i], x[2][i]], [y[0][i], y[1][i], y[2][i]]);
        [out[0][i], out[1][i], out[2][i]] = w;
    }
    out
}

/// The smallest `t` of the lanes in `ok` and the lowest such lane; `None` when `ok` is
/// empty. (The lanes of `ok` hold no NaN, so the minimum does not depend on the order.)
#[inline(always)]
pub(crate) fn nearest_lane<L: Lanes8>(l: L, ok: L::M, t: L::V) -> Option<(f32, usize)> {
    if l.bits(ok) == 0 {
        return None;
    }
    let t = l.select(ok, t, l.splat(f32::INFINITY));
    let lanes = l.to_array(t);
    let mut best = lanes[0];
    for x in lanes {
        best = best.min(x);
    }
    let lane = l.bits(l.and(l.eq(t, l.splat(best)), ok)).trailing_zeros() as usize & 7;
    Some((best, lane))
}
