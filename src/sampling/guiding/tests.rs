//! Unit tests of the SD-tree: the map, the uniform fallback, refinement, exact agreement of
//! `sample` and `pdf`, the integral of the density, NaN-free edges and the schedule.

use super::*;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// A lattice of `n × n` points of the unit square (cell centres).
fn lattice(n: u32) -> impl Iterator<Item = Vec2> {
    (0..n * n).map(move |i| {
        Vec2::new(
            ((i % n) as f32 + 0.5) / n as f32,
            ((i / n) as f32 + 0.5) / n as f32,
        )
    })
}

/// A tree trained twice on radiance peaked about `axis` (so the structure is adaptive and
/// the energies uneven).
fn trained(axis: Vec3) -> DQuadTree {
    let mut t = DQuadTree::new();
    for _ in 0..2 {
        let mut next = t.refined(0.01, 20);
        for u in lattice(64) {
            let d = square_to_sphere(u);
            next.record(d, f64::from(d.dot(axis).max(0.0).powi(8) + 0.01));
        }
        t = next;
    }
    t
}

#[test]
fn map_round_trip_and_unit_length() {
    for u in lattice(32) {
        let d = square_to_sphere(u);
        assert!((d.length() - 1.0).abs() < 1e-5);
        let v = sphere_to_square(d);
        assert!((v - u).abs().max_element() < 1e-4, "{u} {v}");
    }
}

#[test]
fn empty_tree_is_uniform() {
    let t = DQuadTree::new();
    for u in lattice(8) {
        let (d, pdf) = t.sample(u);
        assert!(d.is_finite());
        assert!((pdf - 1.0 / (4.0 * PI)).abs() < 1e-7);
    }
    let s = SdTree::new(Vec3::ZERO, Vec3::ONE);
    let d = s.distribution(Vec3::splat(0.5));
    assert!((d.pdf(Vec3::X) - 1.0 / (4.0 * PI)).abs() < 1e-7);
    // A tree refined from nothing has structure but still no energy: uniform.
    let r = s.refined(1.0, 0.01, 20);
    let d = r.distribution(Vec3::splat(0.5));
    assert!(d.node_count() > 1);
    assert!((d.pdf(Vec3::X) - 1.0 / (4.0 * PI)).abs() < 1e-6);
}

#[test]
fn sample_and_pdf_agree_and_integrate_to_one() {
    let t = trained(Vec3::new(0.3, -0.5, 0.8).normalize());
    assert!(t.depth() > 3, "depth {}", t.depth());
    for u in lattice(100) {
        let (d, pdf) = t.sample(u);
        assert!(pdf.is_finite() && pdf > 0.0);
        assert_eq!(pdf, t.pdf(d));
    }
    // Midpoint rule on the square (pdf_square is constant on cells coarser than the grid).
    let n = 1024;
    let sum: f64 = lattice(n).map(|u| f64::from(t.pdf_square(u))).sum();
    let integral = sum / f64::from(n * n);
    assert!(integral.is_finite());
    assert!((integral - 1.0).abs() < 1e-3, "{integral}");
}

#[test]
fn refinement_follows_energy() {
    let t = trained(Vec3::Z);
    assert!(t.pdf(Vec3::Z) > 20.0 * t.pdf(-Vec3::Z));
    // Every quadrant holding more than 1 % of the energy was subdivided: so no leaf cell
    // holds much more than that (up to the unevenness of one refinement step).
    assert!(t.node_count() > 20);
}

#[test]
fn no_nan_on_any_input() {
    let t = trained(Vec3::X);
    let odd = [
        Vec3::ZERO,
        Vec3::NAN,
        Vec3::INFINITY,
        Vec3::new(f32::NAN, 1.0, 0.0),
        Vec3::new(0.0, 0.0, -1.0),
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(-1.0, -0.0, 0.0),
    ];
    for d in odd {
        assert!(t.pdf(d).is_finite(), "{d}");
    }
    for u in [
        Vec2::ZERO,
        Vec2::ONE,
        Vec2::NAN,
        Vec2::new(-1.0, 2.0),
        Vec2::splat(crate::sampling::ONE_MINUS_EPSILON),
    ] {
        let (d, pdf) = t.sample(u);
        assert!(d.is_finite() && pdf.is_finite(), "{u}");
    }
    let mut s = SdTree::new(Vec3::NAN, Vec3::ONE);
    s.record(Vec3::NAN, Vec3::NAN, f32::NAN, 1.0);
    s.record(Vec3::ZERO, Vec3::Z, f32::INFINITY, 1.0);
    s.record(Vec3::ZERO, Vec3::Z, 1.0, 0.0);
    s.record(Vec3::ZERO, Vec3::Z, 1.0, f32::NAN);
    assert_eq!(s.sample_count(), 2);
    let d = s.distribution(Vec3::NAN);
    assert!(d.pdf(Vec3::Z).is_finite());
}

#[test]
fn spatial_split_and_determinism() {
    let mut a = SdTree::new(Vec3::splat(-1.0), Vec3::ONE);
    let mut recs = GuidingRecords::new();
    for i in 0..4000u32 {
        let x = (i as f32 * 0.618_034).fract() * 2.0 - 1.0;
        let y = (i as f32 * 0.754_878).fract() * 2.0 - 1.0;
        recs.push(GuidingRecord {
            p: Vec3::new(x, y, 0.0),
            dir: if x > 0.0 { Vec3::Z } else { -Vec3::Z },
            radiance: 1.0,
            pdf: 0.25,
        });
    }
    a.merge(&recs);
    let mut b = SdTree::new(Vec3::splat(-1.0), Vec3::ONE);
    for r in recs.iter() {
        b.record(r.p, r.dir, r.radiance, r.pdf);
    }
    assert_eq!(a, b);
    let next = a.refined(1000.0, 0.01, 20);
    // 4000 records over a threshold of 1000: split until each share is ≤ 1000, i.e. twice.
    assert_eq!(next.leaf_count(), 4);
    assert_eq!(next.sample_count(), 0);
    // The directions differ by side: after one more iteration the leaves tell them apart.
    let mut n2 = next.clone();
    n2.merge(&recs);
    let right = n2.distribution(Vec3::new(0.9, 0.0, 0.0));
    let left = n2.distribution(Vec3::new(-0.9, 0.0, 0.0));
    assert!(right.pdf(Vec3::Z) > 10.0 * right.pdf(-Vec3::Z));
    assert!(left.pdf(-Vec3::Z) > 10.0 * left.pdf(Vec3::Z));
}

#[test]
fn schedule_passes() {
    let spp = |n| {
        GuidingSchedule::new(n)
            .passes()
            .map(|p| p.spp)
            .collect::<Vec<_>>()
    };
    assert_eq!(spp(0), Vec::<u32>::new());
    assert_eq!(spp(1), [1]);
    assert_eq!(spp(3), [1, 2]);
    assert_eq!(spp(16), [1, 2, 4, 9]);
    assert_eq!(spp(1024), [1, 2, 4, 8, 16, 32, 64, 128, 256, 513]);
    for n in [1, 5, 100, 4096, 100_000] {
        let s = GuidingSchedule::new(n);
        let passes: Vec<_> = s.passes().collect();
        assert_eq!(
            passes.iter().map(|p| u64::from(p.spp)).sum::<u64>(),
            u64::from(n)
        );
        assert!(passes.last().unwrap().is_final);
        assert!(passes.iter().rev().skip(1).all(|p| !p.is_final));
    }
}

/// Two directions of equal measure ½ where the guide puts 1.8 and 0.2 and the BSDF 0.2 and
/// 1.8 (both densities integrate to 1), sampled from the even mixture (density 1 on both):
/// `n` records of each direction with the integrand `f` of each.
fn two_directions(t: &mut DQuadTree, n: usize, f: [f32; 2]) {
    for _ in 0..n {
        t.record_selection(f[0], 1.8, 0.2, 1.0);
        t.record_selection(f[1], 0.2, 1.8, 1.0);
    }
}

#[test]
fn the_selection_probability_follows_the_density_that_matches_the_integrand() {
    // Light from the guide's direction alone: sample the guide as much as allowed (½, the
    // largest candidate, though 0.9 would have a lower second moment).
    let mut t = DQuadTree::new();
    two_directions(&mut t, 40, [1.0, 0.0]);
    assert_eq!(t.selection_probability(), Some(0.5));
    // From the BSDF's: never the guide.
    let mut t = DQuadTree::new();
    two_directions(&mut t, 40, [0.0, 1.0]);
    assert_eq!(t.selection_probability(), Some(0.0));
    // Twice as much light from the BSDF's direction: the mixture closest to the integrand,
    // `(0.2 + 1.6α)/(1.8 − 1.6α) = ½` at α ≈ 0.29 (second moments 4.63, 4.50, 4.64 at 0.2,
    // 0.3, 0.4).
    let mut t = DQuadTree::new();
    two_directions(&mut t, 40, [1.0, 2.0]);
    assert_eq!(t.selection_probability(), Some(0.3));
    // Too few records (63 < 64): none.
    let mut t = DQuadTree::new();
    two_directions(&mut t, 31, [1.0, 0.0]);
    t.record_selection(1.0, 1.8, 0.2, 1.0);
    assert_eq!(t.selection_probability(), None);
    // A direction the BSDF cannot reach rules out α = 0; bad records are ignored.
    let mut t = DQuadTree::new();
    for _ in 0..64 {
        t.record_selection(1.0, 1.0, 0.0, 0.5);
        t.record_selection(f32::NAN, 1.0, 1.0, 1.0);
        t.record_selection(1.0, 1.0, 1.0, 0.0);
    }
    assert_eq!(t.selection_probability(), Some(0.5));
    // A new record forgets the derived choice.
    two_directions(&mut t, 1000, [0.0, 1.0]);
    assert_ne!(t.selection_probability(), Some(0.5));
}

#[test]
fn an_sd_tree_learns_the_selection_probability_only_when_asked() {
    let mut records = GuidingRecords::new();
    for k in 0..100 {
        let f = [1.0, 0.0][k % 2];
        let (pg, pb) = [(1.8, 0.2), (0.2, 1.8)][k % 2];
        records.push_stored(records::StoredRecord {
            record: GuidingRecord {
                p: Vec3::ZERO,
                dir: Vec3::Z,
                radiance: 1.0,
                pdf: 1.0,
            },
            square: sphere_to_square(Vec3::Z),
            selection: Some(records::SelectionRecord {
                integrand: f,
                p_guide: pg,
                p_bsdf: pb,
            }),
        });
    }
    let mut off = SdTree::new(Vec3::splat(-1.0), Vec3::ONE);
    off.merge(&records);
    assert!(!off.learns_selection());
    assert_eq!(off.distribution(Vec3::ZERO).selection_probability(), None);
    assert_eq!(off.selection_gain(), None);
    let mut on = SdTree::new(Vec3::splat(-1.0), Vec3::ONE);
    on.learn_selection(true);
    on.merge(&records);
    assert_eq!(
        on.distribution(Vec3::ZERO).selection_probability(),
        Some(0.5)
    );
    assert_eq!(on.sample_count(), 100);
    // What it promises: 50 records of F = 1 at p_bsdf 0.2 give M_0 = 50/0.2 = 250, and at
    // α = ½ (density 1) M = 50, a gain of 5.
    let gain = on.selection_gain().expect("a leaf learned");
    assert!(gain.is_finite() && (gain - 5.0).abs() < 1e-6, "{gain}");
    // The refined tree keeps learning, with nothing learned yet.
    let next = on.refined(1e9, 0.01, 20);
    assert!(next.learns_selection());
    assert_eq!(next.distribution(Vec3::ZERO).selection_probability(), None);
}

/// `sample_on_square` is `sample` with the direction's point of the square, and recording
/// at that point is recording the direction (what the tracer and the merge rely on).
#[test]
fn sample_on_square_matches_sample_and_record() {
    let mut t = DQuadTree::new();
    t.record(Vec3::new(0.3, -0.2, 0.9).normalize(), 1.0);
    t.record(-Vec3::X, 0.5);
    let t = t.refined(0.01, 20);
    let (mut a, mut b) = (t.refined(0.01, 20), t.refined(0.01, 20));
    for i in 0..500u32 {
        let u = Vec2::new(
            (i as f32 * 0.618_034).fract(),
            (i as f32 * 0.754_878).fract(),
        );
        let (d, pdf, s) = t.sample_on_square(u);
        assert!(pdf.is_finite() && pdf > 0.0, "{pdf}");
        assert_eq!((d, pdf), t.sample(u));
        assert_eq!(s, sphere_to_square(d));
        a.record(d, 1.0 + f64::from(i));
        b.record_square(s, 1.0 + f64::from(i));
    }
    assert_eq!(a, b);
}
