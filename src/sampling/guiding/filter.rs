//! How an [`SdTree`](super::SdTree) spreads each record over its neighbourhood while it
//! trains (Müller 2019, "Practical Path Guiding in Production", SIGGRAPH course notes,
//! its spatial and directional box filters), and the deterministic jitter of the
//! stochastic spatial filter.

use crate::sampling::sampler::hash::{combine, mix64, unit_f32};
use glam::{Vec2, Vec3};

/// Which filters an [`SdTree`](super::SdTree) applies to the records it takes
/// ([`SdTree::set_filter`](super::SdTree::set_filter)). Both off by default: each record goes
/// to the cell of its direction in the leaf of its position.
///
/// Filtering changes only what the tree learns, never the estimator that samples it, so a
/// guided path tracer stays unbiased with either (docs/renderer.md).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct GuidingFilter {
    /// The stochastic spatial box filter: the record goes to the leaf containing a point
    /// drawn uniformly in a box of the size of its own leaf, centred on it (clamped to the
    /// scene's bounds). The draw is a hash of the record, so the tree is deterministic.
    pub spatial: bool,
    /// The directional box filter: the record's energy is spread over a square of the size
    /// of the quadtree leaf cell its direction falls in, centred on the direction's point of
    /// the square, to the cells it overlaps in proportion to the overlap's area.
    pub directional: bool,
}

impl GuidingFilter {
    /// Neither filter.
    pub const NONE: Self = Self {
        spatial: false,
        directional: false,
    };
    /// Both filters.
    pub const BOTH: Self = Self {
        spatial: true,
        directional: true,
    };
}

/// The key of a record for its jitter: a hash of its position, its direction's point of the
/// square and its index in its buffer (what a record is, not when a thread merged it).
#[inline]
pub(crate) fn record_key(p: Vec3, square: Vec2, index: u64) -> u64 {
    let pos = u64::from(p.x.to_bits()) | (u64::from(p.y.to_bits()) << 32);
    let rest = u64::from(p.z.to_bits()) | (u64::from(square.x.to_bits()) << 32);
    let h = combine(combine(mix64(index), pos), rest);
    combine(h, u64::from(square.y.to_bits()))
}

/// Three values in `[0, 1)` from the key `key`.
#[inline]
pub(crate) fn jitter(key: u64) -> Vec3 {
    let a = mix64(key);
    let b = mix64(key ^ 0x5851_f42d_4c95_7f2d);
    Vec3::new(
        unit_f32(a as u32),
        unit_f32((a >> 32) as u32),
        unit_f32(b as u32),
    )
}

#[cfg(test)]
mod tests {
    use super::super::{DQuadTree, GuidingRecord, GuidingRecords, SdTree};
    use super::*;

    /// A tree over `[-1, 1]³` split once, at x = 0 (a record count of 10 over a threshold
    /// of 5), with the filter `filter`.
    fn two_leaves(filter: GuidingFilter) -> SdTree {
        let mut t = SdTree::new(Vec3::splat(-1.0), Vec3::ONE);
        t.set_filter(filter);
        for _ in 0..10 {
            t.record(Vec3::ZERO, Vec3::Z, 1.0, 1.0);
        }
        let t = t.refined(5.0, 0.01, 20);
        assert_eq!(t.leaf_count(), 2);
        assert_eq!(t.filter(), filter);
        t
    }

    /// `n` records at `p` from +z, of radiance 1 and density 1.
    fn records_at(p: Vec3, n: u32) -> GuidingRecords {
        let mut recs = GuidingRecords::new();
        for _ in 0..n {
            recs.push(GuidingRecord {
                p,
                dir: Vec3::Z,
                radiance: 1.0,
                pdf: 1.0,
            });
        }
        recs
    }

    /// The spatial filter moves a record at x = −0.2 of the left leaf (x < 0, its box
    /// 1.002 wide along x with the cube's margin) to the right leaf with the probability
    /// that its box's point lies beyond x = 0: 0.301/1.002 = 0.3004. At 20000 records
    /// the binomial standard error is 64.8 records; the test allows 4 of them
    /// (significance 6·10⁻⁵). Energy and counts are conserved, and without the filter
    /// every record stays.
    #[test]
    fn spatial_filter_moves_records_to_the_neighbour_with_the_box_probability() {
        let n = 20_000u32;
        let recs = records_at(Vec3::new(-0.2, 0.3, -0.1), n);
        let mut on = two_leaves(GuidingFilter {
            spatial: true,
            directional: false,
        });
        on.merge(&recs);
        let right = on.distribution(Vec3::new(0.5, 0.0, 0.0)).total();
        let left = on.distribution(Vec3::new(-0.5, 0.0, 0.0)).total();
        assert!(right.is_finite() && left.is_finite());
        assert_eq!(right + left, f64::from(n));
        assert_eq!(on.sample_count(), u64::from(n));
        let expected = f64::from(n) * 0.301 / 1.002;
        let sd = (expected * (1.0 - 0.301 / 1.002)).sqrt();
        assert!(
            (right - expected).abs() < 4.0 * sd,
            "{right} vs {expected} ± {sd}"
        );
        let mut off = two_leaves(GuidingFilter::NONE);
        off.merge(&recs);
        assert_eq!(off.distribution(Vec3::new(0.5, 0.0, 0.0)).total(), 0.0);
        // A record far from the boundary (x = −0.9: its box reaches x = −0.399) stays.
        let mut far = two_leaves(GuidingFilter::BOTH);
        far.merge(&records_at(Vec3::new(-0.9, 0.99, -0.99), 1000));
        assert_eq!(far.distribution(Vec3::new(0.5, 0.0, 0.0)).total(), 0.0);
        assert_eq!(far.distribution(Vec3::new(-0.5, 0.0, 0.0)).total(), 1000.0);
    }

    /// The spatial filter's draws are a function of the records alone: merging the same
    /// buffers in the same order into two trees gives equal trees, and recording the
    /// jittered records is not the same as recording them unfiltered.
    #[test]
    fn spatial_filter_is_deterministic() {
        let mut recs = GuidingRecords::new();
        for i in 0..3000u32 {
            let f = i as f32 / 3000.0;
            recs.push(GuidingRecord {
                p: Vec3::new(f * 0.1 - 0.05, (f * 7.0).fract() - 0.5, 0.2),
                dir: Vec3::new(f - 0.5, 0.3, 1.0).normalize(),
                radiance: 1.0 + f,
                pdf: 0.5,
            });
        }
        let filtered = |f: GuidingFilter| {
            let mut t = two_leaves(f);
            t.merge(&recs);
            t.merge(&recs);
            t
        };
        assert_eq!(filtered(GuidingFilter::BOTH), filtered(GuidingFilter::BOTH));
        assert_ne!(filtered(GuidingFilter::BOTH), filtered(GuidingFilter::NONE));
    }

    /// A quadtree whose leaf cells are all of side 1/16 (the uniform refinement: a quadrant
    /// of depth `d` holds 4^-d of the energy, subdivided while above ρ = 0.01).
    fn uniform_16() -> DQuadTree {
        let t = DQuadTree::new().refined(0.01, 20);
        assert_eq!(t.depth(), 4);
        t
    }

    /// The share of the energy of `t` in the leaf cell of side 1/16 at `u`.
    fn share(t: &DQuadTree, u: Vec2) -> f64 {
        f64::from(t.pdf_square(u)) / 256.0
    }

    /// The directional box (side 1/16, the leaf's) spreads a record to the neighbouring
    /// cells by the area they overlap: at u = (0.26, 0.53) the box is
    /// [0.22875, 0.29125] × [0.49875, 0.56125], so the cell to the left (x < 0.25) takes
    /// 0.34 · 0.98, the cell of u 0.66 · 0.98, the cells below 0.34 · 0.02 and 0.66 · 0.02.
    /// Along φ the box wraps (u = (0.53125, 0.01), a cell's centre in x: 0.34 of it beyond y = 1), along cos θ it is shifted
    /// inside (u.x = 0.005: all of it in the first column).
    #[test]
    fn directional_filter_spreads_by_overlap_area() {
        let cases: [(Vec2, [(Vec2, f64); 4]); 3] = [
            (
                Vec2::new(0.26, 0.53),
                [
                    (Vec2::new(0.24, 0.53), 0.34 * 0.98),
                    (Vec2::new(0.26, 0.53), 0.66 * 0.98),
                    (Vec2::new(0.24, 0.49), 0.34 * 0.02),
                    (Vec2::new(0.26, 0.49), 0.66 * 0.02),
                ],
            ),
            (
                Vec2::new(0.53125, 0.01),
                [
                    (Vec2::new(0.53, 0.01), 0.66),
                    (Vec2::new(0.53, 0.99), 0.34),
                    (Vec2::new(0.49, 0.01), 0.0),
                    (Vec2::new(0.53, 0.07), 0.0),
                ],
            ),
            (
                Vec2::new(0.005, 0.53),
                [
                    (Vec2::new(0.03, 0.53), 0.98),
                    (Vec2::new(0.03, 0.49), 0.02),
                    (Vec2::new(0.07, 0.53), 0.0),
                    (Vec2::new(0.99, 0.53), 0.0),
                ],
            ),
        ];
        for (u, cells) in cases {
            let mut t = uniform_16();
            t.record_square_filtered(u, 2.5);
            assert!((t.total() - 2.5).abs() < 1e-12, "{}", t.total());
            for (c, expected) in cells {
                let got = share(&t, c);
                assert!(got.is_finite());
                assert!(
                    (got - expected).abs() < 1e-6,
                    "{u} {c}: {got} vs {expected}"
                );
            }
            let mut plain = uniform_16();
            plain.record_square(u, 2.5);
            assert!((share(&plain, u) - 1.0).abs() < 1e-6);
        }
    }

    /// The directional splat conserves the energy on an adaptive tree (cells of many
    /// sizes), at every level: the total is the sum of the values, and the densities still
    /// integrate to 1 over the square.
    #[test]
    fn directional_filter_conserves_energy() {
        let mut t = DQuadTree::new();
        for _ in 0..8 {
            t.record(Vec3::new(0.3, -0.2, 0.9).normalize(), 1.0);
            t.record(-Vec3::X, 0.5);
            t = t.refined(0.01, 20);
        }
        assert!(t.depth() > 12, "{}", t.depth());
        let mut sum = 0.0;
        for i in 0..5000u32 {
            let u = Vec2::new(
                (i as f32 * 0.618_034).fract(),
                (i as f32 * 0.754_878 + 0.001).fract(),
            );
            let v = 1.0 + f64::from(i % 7);
            t.record_square_filtered(u, v);
            sum += v;
        }
        t.record_square_filtered(Vec2::new(0.5, 0.5), f64::NAN);
        t.record_square_filtered(Vec2::new(f32::NAN, 0.5), 1.0);
        assert!(t.total().is_finite());
        assert!(
            (t.total() - sum).abs() < 1e-9 * sum,
            "{} vs {sum}",
            t.total()
        );
        // The density integrates to 1: a fine lattice's mean.
        let n = 1024u32;
        let mut integral = 0.0f64;
        for i in 0..n * n {
            let u = Vec2::new(
                ((i % n) as f32 + 0.5) / n as f32,
                ((i / n) as f32 + 0.5) / n as f32,
            );
            integral += f64::from(t.pdf_square(u));
        }
        integral /= f64::from(n * n);
        assert!((integral - 1.0).abs() < 1e-3, "{integral}");
    }

    /// The jitter of many keys is uniform per axis: each quarter of each axis holds its share
    /// 0.25 of 40000 draws within 0.0075 (3.46 binomial standard errors of 0.00217: each of
    /// the 12 bins at significance 5.4·10⁻⁴, all at 0.0065), and the axes differ.
    #[test]
    fn jitter_is_uniform_per_axis() {
        let n = 40_000u64;
        let mut bins = [[0u32; 4]; 3];
        let mut same = 0;
        for i in 0..n {
            let j = jitter(record_key(
                Vec3::new(0.5, 0.25, 0.125),
                Vec2::new(0.3, 0.7),
                i,
            ));
            assert!(j.is_finite());
            assert!(j.cmpge(Vec3::ZERO).all() && j.cmplt(Vec3::ONE).all(), "{j}");
            for (a, b) in bins.iter_mut().enumerate() {
                b[(j[a] * 4.0) as usize] += 1;
            }
            same += u32::from(j.x == j.y || j.y == j.z);
        }
        for b in bins {
            for c in b {
                let share = f64::from(c) / n as f64;
                assert!((share - 0.25).abs() < 0.0075, "{b:?}");
            }
        }
        assert!(same < 10, "{same}");
    }
}
