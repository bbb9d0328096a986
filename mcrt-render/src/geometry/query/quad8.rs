//! Eight parallelograms tested against one ray at once, on the lanes the 8-wide BVH chose
//! ([`Lanes8`]): [`super::quad4`]'s test (plane, then parameters from the dual vectors,
//! accepted within [`SLACK`]) with parallelogram `i` in lane `i`, each lane computing the
//! same operations in the same order as [`super::quad4::QuadRay4`], so the same bits.

use super::pairing::Quad;
use super::quad4::{lane_vectors, QuadHit, SLACK};
use super::tri8::nearest_lane;
use crate::accel::Lanes8;
use glam::Vec3;

/// Up to eight parallelograms by coordinate (lane = parallelogram). Missing lanes repeat
/// the last one (a duplicate never wins a tie: lower lanes win); an empty packet has NaN
/// lanes and is never hit.
#[derive(Debug, Clone, Copy)]
pub(crate) struct QuadPacket8 {
    /// Plane normal `e1 × e2`, corner, dual vectors of `e1` and `e2`.
    n: [[f32; 8]; 3],
    c: [[f32; 8]; 3],
    a: [[f32; 8]; 3],
    b: [[f32; 8]; 3],
}

impl QuadPacket8 {
    /// Packs 0 to 8 parallelograms (more are ignored).
    pub(crate) fn new(quads: &[Quad]) -> Self {
        debug_assert!(quads.len() <= 8);
        let mut f = [[[0.0; 8]; 3]; 4];
        for l in 0..8 {
            let v = lane_vectors(quads.get(l.min(quads.len().saturating_sub(1))));
            for (fi, vi) in f.iter_mut().zip(v) {
                for a in 0..3 {
                    fi[a][l] = vi[a];
                }
            }
        }
        let [n, c, a, b] = f;
        Self { n, c, a, b }
    }
}

/// Per lane: accepted, distance, parameters.
struct Hits<L: Lanes8> {
    ok: L::M,
    t: L::V,
    u: L::V,
    v: L::V,
}

/// A ray splatted for [`QuadPacket8`] tests on lanes `L`.
#[derive(Clone, Copy)]
pub(crate) struct QuadRay8<L: Lanes8> {
    l: L,
    o: [L::V; 3],
    d: [L::V; 3],
}

impl<L: Lanes8> QuadRay8<L> {
    #[inline(always)]
    pub(crate) fn new(l: L, origin: Vec3, dir: Vec3) -> Self {
        // (Arrays written out: `array::map` is left out of line, and the lane operations
        // inside it then become calls.)
        Self {
            l,
            o: [l.splat(origin.x), l.splat(origin.y), l.splat(origin.z)],
            d: [l.splat(dir.x), l.splat(dir.y), l.splat(dir.z)],
        }
    }

    /// `v · w` per lane, summed in axis order.
    #[inline(always)]
    fn dot(&self, v: [L::V; 3], w: &[L::V; 3]) -> L::V {
        let l = self.l;
        l.add(
            l.add(l.mul(v[0], w[0]), l.mul(v[1], w[1])),
            l.mul(v[2], w[2]),
        )
    }

    /// The lanes hit with `0 < t < t_max`; `None` when there are none.
    #[inline(always)]
    fn lanes(&self, p: &QuadPacket8, t_max: f32) -> Option<Hits<L>> {
        let l = self.l;
        let c = load3(l, &p.c);
        let w = [
            l.sub(c[0], self.o[0]),
            l.sub(c[1], self.o[1]),
            l.sub(c[2], self.o[2]),
        ];
        let n = load3(l, &p.n);
        let t = l.div(self.dot(n, &w), self.dot(n, &self.d));
        // NaN and infinite t (rays in the plane, or parallel to it) fail here.
        let ok = l.and(l.gt(t, l.splat(0.0)), l.lt(t, l.splat(t_max)));
        if l.bits(ok) == 0 {
            return None;
        }
        let r = [
            l.sub(l.mul(t, self.d[0]), w[0]),
            l.sub(l.mul(t, self.d[1]), w[1]),
            l.sub(l.mul(t, self.d[2]), w[2]),
        ];
        let (u, v) = (self.dot(load3(l, &p.a), &r), self.dot(load3(l, &p.b), &r));
        let (lo, hi) = (l.splat(-SLACK), l.splat(1.0 + SLACK));
        let in_u = l.and(l.ge(u, lo), l.le(u, hi));
        let in_v = l.and(l.ge(v, lo), l.le(v, hi));
        let ok = l.and(ok, l.and(in_u, in_v));
        (l.bits(ok) != 0).then_some(Hits { ok, t, u, v })
    }

    /// The nearest hit with `0 < t < t_max` among the packet's parallelograms, each tested
    /// against the same `t_max` (the lowest lane on a tie).
    #[inline(always)]
    pub(crate) fn closest(&self, p: &QuadPacket8, t_max: f32) -> Option<QuadHit> {
        let l = self.l;
        let h = self.lanes(p, t_max)?;
        let (best, lane) = nearest_lane(l, h.ok, h.t)?;
        Some(QuadHit {
            lane: lane as u32,
            t: best,
            u: l.to_array(h.u)[lane],
            v: l.to_array(h.v)[lane],
        })
    }

    /// True when some parallelogram of the packet is hit with `0 < t < t_max`.
    #[inline(always)]
    pub(crate) fn any(&self, p: &QuadPacket8, t_max: f32) -> bool {
        self.lanes(p, t_max).is_some()
    }
}

/// Three vectors of lanes from memory.
#[inline(always)]
fn load3<L: Lanes8>(l: L, x: &[[f32; 8]; 3]) -> [L::V; 3] {
    [l.load(&x[0]), l.load(&x[1]), l.load(&x[2])]
}
