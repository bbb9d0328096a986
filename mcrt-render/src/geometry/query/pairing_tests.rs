//! Unit tests of the pairing of whole meshes ([`units`]): shared edges found by position,
//! greedy order, and edges shared by too many triangles.

use super::*;
use crate::description::{ShapeDesc, ShapeKind};

/// The units of one mesh shape.
fn units_of(positions: Vec<Vec3>, indices: Vec<[u32; 3]>) -> Vec<Unit> {
    let desc = ShapeDesc::new(ShapeKind::Mesh {
        positions,
        normals: vec![],
        indices,
    });
    units(
        &super::super::super::build::build(&[desc], None)
            .expect("builds")
            .view(),
    )
}

#[test]
fn shared_edges_are_found_by_position_not_by_index() {
    let (b, a, c, d) = (Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(1.0, 1.0, 0.0));
    // Six vertices, each triangle its own three: the shared edge a c is found through
    // equal positions.
    let split = units_of(vec![b, a, c, a, d, c], vec![[0, 1, 2], [3, 4, 5]]);
    assert!(matches!(
        split[..],
        [Unit::Pair {
            first: 0,
            second: 1,
            ..
        }]
    ));
    // The same with one copy of `c` off by one bit: no shared edge, two triangles.
    let c2 = Vec3::new(0.0, f32::from_bits(1.0f32.to_bits() + 1), 0.0);
    let apart = units_of(vec![b, a, c, a, d, c2], vec![[0, 1, 2], [3, 4, 5]]);
    assert!(matches!(apart[..], [Unit::One(0), Unit::One(1)]));
    // Two candidate partners for triangle 0 (triangle 2 copies triangle 1): the first
    // in input order wins, the copy stays a triangle, as does triangle 3 (no shared
    // edge).
    let e = Vec3::new(1.0, -1.0, 0.0);
    let u = units_of(
        vec![b, a, c, d, e, Vec3::new(2.0, -1.0, 0.0)],
        vec![[0, 1, 2], [1, 3, 2], [1, 3, 2], [1, 4, 5]],
    );
    let pairs: Vec<(u32, u32)> = u
        .iter()
        .filter_map(|u| match u {
            Unit::Pair { first, second, .. } => Some((*first, *second)),
            Unit::One(_) => None,
        })
        .collect();
    assert_eq!(pairs, vec![(0, 1)], "{u:?}");
    assert_eq!(u.len(), 3);
}

/// Pairs of units, as (first, second).
fn pairs(u: &[Unit]) -> Vec<(u32, u32)> {
    u.iter()
        .filter_map(|u| match u {
            Unit::Pair { first, second, .. } => Some((*first, *second)),
            Unit::One(_) => None,
        })
        .collect()
}

#[test]
fn crowded_edges_are_not_paired_across() {
    let (b, a, c, d) = (Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(1.0, 1.0, 0.0));
    // Triangle 0 and `copies` copies of its parallelogram partner on the edge a c.
    let with = |copies: usize| {
        let mut indices = vec![[0, 1, 2]];
        indices.extend(std::iter::repeat_n([1, 3, 2], copies));
        pairs(&units_of(vec![b, a, c, d], indices))
    };
    // `MAX_SHARING` triangles on the edge: paired; one more: not.
    assert_eq!(with(MAX_SHARING - 1), vec![(0, 1)]);
    assert_eq!(with(MAX_SHARING), vec![]);
    // Many copies of one triangle (on shared vertices), and a fan on one edge: no
    // pairs, every triangle its own unit (each tries at most 3 MAX_SHARING partners;
    // all 20 000 on one edge made pairing quadratic).
    let n = 20_000;
    let same = units_of(vec![b, a, c], vec![[0, 1, 2]; n]);
    assert_eq!((same.len(), pairs(&same).len()), (n, 0));
    let mut fan_pos = vec![b, c];
    fan_pos.extend((0..n).map(|i| Vec3::new(1.0, i as f32 / n as f32, 1.0 + i as f32)));
    let fan = units_of(fan_pos, (0..n as u32).map(|i| [0, 1, i + 2]).collect());
    assert_eq!((fan.len(), pairs(&fan).len()), (n, 0));
}
