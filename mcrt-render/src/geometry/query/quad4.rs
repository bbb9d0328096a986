//! Four parallelograms ("quads", each two mesh triangles; see [`super::pairing`]) tested
//! against one ray at once, parallelogram `i` in SIMD lane `i`.
//!
//! With `w = corner − o`, the test intersects the plane, `t = n·w / n·d` (`n = e1 × e2`),
//! then takes the parameters of the hit point relative to the corner, `r = t d − w`, from
//! precomputed dual vectors, `u = a*·r`, `v = b*·r` (`a*·e1 = b*·e2 = 1`,
//! `a*·e2 = b*·e1 = 0`), and accepts `u, v ∈ [−SLACK, 1 + SLACK]`. Working relative to the
//! ray origin keeps `t` accurate for rays starting close to the plane, and exact up to the
//! final roundings for axis-aligned planes (as the triangle test is).
//!
//! Unlike the triangle test, which is watertight by construction, this one is not exact at
//! edges: it is leak-free *by slack*. Rounding moves `u`, `v` of a hit exactly on an edge;
//! for rays whose length to the hit is up to a hundred times the quad's edges, a quarter of
//! [`SLACK`] already covers that (tested on a cube's shared edges and corners; a sixteenth of
//! it leaks there), so a ray through an edge shared with another quad or a triangle is
//! caught by one side or both. The price: every quad reaches `SLACK` times its edge lengths
//! past its true border.

use super::pairing::Quad;
use glam::{DVec3, Vec3, Vec4};

/// Slack on the parallelogram parameters: hits with `u, v ∈ [−SLACK, 1 + SLACK]` count.
pub(crate) const SLACK: f32 = 1.0 / 16_384.0;

/// Up to four parallelograms by coordinate (lane = parallelogram). Missing lanes repeat the
/// last parallelogram (a duplicate never wins a tie: lower lanes win); an empty packet has
/// NaN lanes and is never hit.
#[derive(Debug, Clone, Copy)]
pub(crate) struct QuadPacket {
    /// Plane normal `e1 × e2`, corner, dual vectors of `e1` and `e2`.
    n: [Vec4; 3],
    c: [Vec4; 3],
    a: [Vec4; 3],
    b: [Vec4; 3],
}

/// One lane's normal and dual vectors (computed in f64) and corner.
#[derive(Clone, Copy)]
struct Lane {
    n: DVec3,
    a: DVec3,
    b: DVec3,
    c: DVec3,
}

impl Lane {
    fn new(q: &Quad) -> Self {
        let (e1, e2) = (q.e1.as_dvec3(), q.e2.as_dvec3());
        let n = e1.cross(e2);
        let inv = 1.0 / n.length_squared();
        Self {
            n,
            a: e2.cross(n) * inv,
            b: n.cross(e1) * inv,
            c: q.corner.as_dvec3(),
        }
    }

    const NAN: Self = Self {
        n: DVec3::NAN,
        a: DVec3::NAN,
        b: DVec3::NAN,
        c: DVec3::NAN,
    };
}

/// Quad `q`'s normal, corner and dual vectors (`n`, `c`, `a`, `b`), computed in f64 and
/// rounded to f32 as a packet stores them; NaN for no quad.
pub(crate) fn lane_vectors(q: Option<&Quad>) -> [[f32; 3]; 4] {
    let l = q.map_or(Lane::NAN, Lane::new);
    [l.n, l.c, l.a, l.b].map(|v| v.to_array().map(|x| x as f32))
}

impl QuadPacket {
    /// Packs 0 to 4 parallelograms (more are ignored).
    pub(crate) fn new(quads: &[Quad]) -> Self {
        debug_assert!(quads.len() <= 4);
        let lanes = [0, 1, 2, 3].map(|l| {
            quads
                .get(l.min(quads.len().saturating_sub(1)))
                .map_or(Lane::NAN, Lane::new)
        });
        let axis = |f: fn(&Lane) -> DVec3| {
            [0, 1, 2].map(|a| Vec4::from_array(lanes.map(|l| f(&l)[a] as f32)))
        };
        Self {
            n: axis(|l| l.n),
            c: axis(|l| l.c),
            a: axis(|l| l.a),
            b: axis(|l| l.b),
        }
    }
}

/// A ray splatted for [`QuadPacket`] tests.
#[derive(Debug, Clone, Copy)]
pub(crate) struct QuadRay4 {
    o: [Vec4; 3],
    d: [Vec4; 3],
}

/// The nearest hit in a quad packet: lane, distance and parameters (unclamped).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct QuadHit {
    pub(crate) lane: u32,
    pub(crate) t: f32,
    pub(crate) u: f32,
    pub(crate) v: f32,
}

/// Per lane: accepted, distance, parameters.
struct Lanes {
    ok: glam::BVec4A,
    t: Vec4,
    u: Vec4,
    v: Vec4,
}

impl QuadRay4 {
    #[inline]
    pub(crate) fn new(origin: Vec3, dir: Vec3) -> Self {
        Self {
            o: [origin.x, origin.y, origin.z].map(Vec4::splat),
            d: [dir.x, dir.y, dir.z].map(Vec4::splat),
        }
    }

    #[inline(always)]
    fn dot(v: &[Vec4; 3], w: &[Vec4; 3]) -> Vec4 {
        v[0] * w[0] + v[1] * w[1] + v[2] * w[2]
    }

    /// The lanes hit with `0 < t < t_max`; `None` when there are none.
    #[inline(always)]
    fn lanes(&self, p: &QuadPacket, t_max: f32) -> Option<Lanes> {
        let w = per_axis(|a| p.c[a] - self.o[a]);
        let t = Self::dot(&p.n, &w) / Self::dot(&p.n, &self.d);
        // NaN and infinite t (rays in the plane, or parallel to it) fail here.
        let ok = t.cmpgt(Vec4::ZERO) & t.cmplt(Vec4::splat(t_max));
        if !ok.any() {
            return None;
        }
        let r = per_axis(|a| t * self.d[a] - w[a]);
        let (u, v) = (Self::dot(&p.a, &r), Self::dot(&p.b, &r));
        let (lo, hi) = (Vec4::splat(-SLACK), Vec4::splat(1.0 + SLACK));
        let ok = ok & u.cmpge(lo) & u.cmple(hi) & v.cmpge(lo) & v.cmple(hi);
        ok.any().then_some(Lanes { ok, t, u, v })
    }

    /// The nearest hit with `0 < t < t_max` among the packet's parallelograms, each tested
    /// against the same `t_max` (the lowest lane on a tie).
    #[inline(always)]
    pub(crate) fn closest(&self, p: &QuadPacket, t_max: f32) -> Option<QuadHit> {
        let h = self.lanes(p, t_max)?;
        let t = Vec4::select(h.ok, h.t, Vec4::INFINITY);
        let best = t.min_element();
        let lane = (t.cmpeq(Vec4::splat(best)) & h.ok)
            .bitmask()
            .trailing_zeros() as usize;
        Some(QuadHit {
            lane: lane as u32,
            t: best,
            u: h.u.to_array()[lane],
            v: h.v.to_array()[lane],
        })
    }

    /// True when some parallelogram of the packet is hit with `0 < t < t_max`.
    #[inline(always)]
    pub(crate) fn any(&self, p: &QuadPacket, t_max: f32) -> bool {
        self.lanes(p, t_max).is_some()
    }
}

/// `[f(0), f(1), f(2)]`, written out: `[0, 1, 2].map(f)` is left as a call where the
/// test is inlined into a large traversal.
#[inline(always)]
fn per_axis(f: impl Fn(usize) -> Vec4) -> [Vec4; 3] {
    [f(0), f(1), f(2)]
}

#[cfg(test)]
#[path = "quad4_tests.rs"]
mod tests;
