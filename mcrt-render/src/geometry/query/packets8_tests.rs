//! The 8-lane triangle and quad tests against the 4-lane ones, lane by lane and bit for
//! bit, on the detected lanes and on the portable ones.

use super::pairing::Quad;
use super::quad4::{QuadPacket, QuadRay4};
use super::quad8::{QuadPacket8, QuadRay8};
use super::tri4::{PacketHit, TriPacket, TriRay4};
use super::tri8::{TriPacket8, TriRay8};
use crate::accel::{Lanes8, Simd8, WithLanes8};
use glam::Vec3;
use rand_core::{RngCore, SeedableRng};

/// Both lane paths (the detected one is AVX2 on most x86-64 machines).
fn paths() -> [Simd8; 2] {
    [Simd8::detect(), Simd8::Portable]
}

/// One ray against one packet of each kind: (closest, any) for triangles and quads.
struct Probe<'a> {
    o: Vec3,
    d: Vec3,
    t_max: f32,
    tris: &'a TriPacket8,
    quads: &'a QuadPacket8,
}

type Found = (Option<PacketHit>, bool, Option<[f32; 3]>, Option<u32>, bool);

impl WithLanes8 for Probe<'_> {
    type Output = Found;
    fn run<L: Lanes8>(self, l: L) -> Found {
        let tri = TriRay8::new(l, self.o, self.d);
        let quad = QuadRay8::new(l, self.o, self.d);
        let q = quad.closest(self.quads, self.t_max);
        (
            tri.closest(self.tris, self.t_max),
            tri.any(self.tris, self.t_max),
            q.map(|h| [h.t, h.u, h.v]),
            q.map(|h| h.lane),
            quad.any(self.quads, self.t_max),
        )
    }
}

/// What the 4-lane tests give: each primitive alone in a 4-lane packet against the same
/// bound, the nearest winning, the lowest lane on a tie.
fn four_lane(o: Vec3, d: Vec3, t_max: f32, tris: &[[Vec3; 3]], quads: &[Quad]) -> Found {
    let mut tri: Option<PacketHit> = None;
    for (l, t) in tris.iter().enumerate() {
        if let Some(h) = TriRay4::new(o, d).closest(&TriPacket::new(&[*t]), t_max) {
            if tri.is_none_or(|b| h.t < b.t) {
                tri = Some(PacketHit {
                    lane: l as u32,
                    ..h
                });
            }
        }
    }
    let mut quad: Option<(u32, [f32; 3])> = None;
    for (l, q) in quads.iter().enumerate() {
        if let Some(h) = QuadRay4::new(o, d).closest(&QuadPacket::new(&[*q]), t_max) {
            if quad.is_none_or(|(_, b)| h.t < b[0]) {
                quad = Some((l as u32, [h.t, h.u, h.v]));
            }
        }
    }
    (
        tri,
        tri.is_some(),
        quad.map(|q| q.1),
        quad.map(|q| q.0),
        quad.is_some(),
    )
}

/// Random triangles (a tenth collinear, some sharing an edge with their neighbour) and
/// parallelograms, rays aimed at vertices, edge midpoints and at random: packets of 1 to 8
/// give bit for bit what the 4-lane tests give, on both lane paths.
#[test]
fn eight_lanes_agree_with_four_lanes_bit_for_bit() {
    let mut rng = rand_pcg::Pcg32::seed_from_u64(27);
    let mut f = move || (rng.next_u32() >> 8) as f32 / (1u32 << 24) as f32 * 2.0 - 1.0;
    let mut point = || Vec3::new(f(), f(), f());
    let (mut tri_hits, mut quad_hits, mut checked) = (0, 0, 0);
    for round in 0..2000 {
        let mut tris: Vec<[Vec3; 3]> = Vec::new();
        let mut quads = Vec::new();
        for k in 0..8 {
            let t = match (round + k) % 10 {
                0 => {
                    let (a, b) = (point(), point());
                    [a, b, a + (b - a) * 0.5]
                }
                1..=3 if k > 0 => [tris[k - 1][2], tris[k - 1][1], point()],
                _ => [point(), point(), point()],
            };
            tris.push(t);
            quads.push(Quad {
                corner: point(),
                e1: point() * 0.7,
                e2: point() * 0.7,
                roles: [[0; 2]; 2],
            });
        }
        let o = point() * 3.0;
        let aim = match round % 4 {
            0 => tris[round % 8][round % 3],
            1 => 0.5 * (tris[1][1] + tris[1][2]),
            2 => quads[round % 8].corner + 0.5 * quads[round % 8].e1,
            _ => point(),
        };
        let d = aim - o;
        if d == Vec3::ZERO {
            continue;
        }
        let t_max = if round % 5 == 0 { 1.0 } else { f32::INFINITY };
        for n in 1..=8 {
            let want = four_lane(o, d, t_max, &tris[..n], &quads[..n]);
            let (tp, qp) = (TriPacket8::new(&tris[..n]), QuadPacket8::new(&quads[..n]));
            for simd in paths() {
                let got = simd.dispatch(Probe {
                    o,
                    d,
                    t_max,
                    tris: &tp,
                    quads: &qp,
                });
                if let Some(h) = got.0 {
                    assert!(h.t.is_finite() && h.b1.is_finite() && h.b2.is_finite());
                }
                // Bits, so that -0.0 and 0.0 differ.
                let bits = |x: &Found| {
                    (
                        x.0.map(|h| (h.lane, [h.t, h.b1, h.b2].map(f32::to_bits))),
                        x.1,
                        x.2.map(|q| q.map(f32::to_bits)),
                        x.3,
                        x.4,
                    )
                };
                assert_eq!(bits(&got), bits(&want), "round {round} n {n} {simd:?}");
            }
            tri_hits += usize::from(want.0.is_some());
            quad_hits += usize::from(want.2.is_some());
            checked += 1;
        }
    }
    assert!(tri_hits > checked / 10, "{tri_hits} of {checked}");
    assert!(quad_hits > checked / 10, "{quad_hits} of {checked}");
}

/// Empty packets are never hit.
#[test]
fn empty_packets_are_never_hit() {
    let (tp, qp) = (TriPacket8::new(&[]), QuadPacket8::new(&[]));
    for simd in paths() {
        let got = simd.dispatch(Probe {
            o: Vec3::ZERO,
            d: Vec3::Z,
            t_max: f32::INFINITY,
            tris: &tp,
            quads: &qp,
        });
        assert_eq!(got, (None, false, None, None, false));
    }
}
