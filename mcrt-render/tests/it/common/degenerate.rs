//! Degenerate but valid triangle soups of issue 26 ("hostile inputs"), generated (nothing is
//! stored): each must build in bounded time and memory with every acceleration structure.
//! Shared by `tests/it/hostile_geometry.rs` and `benches/accel.rs`.

#![allow(dead_code)]

use mcrt::glam::Vec3;
use mcrt_render::description::{ShapeDesc, ShapeKind};

/// The triangle of the soups that repeat one: (−½, −½, 0), (½, −½, 0), (0, ½, 0), facing +z.
pub const TRIANGLE: [Vec3; 3] = [
    Vec3::new(-0.5, -0.5, 0.0),
    Vec3::new(0.5, -0.5, 0.0),
    Vec3::new(0.0, 0.5, 0.0),
];

fn mesh(positions: Vec<Vec3>, indices: Vec<[u32; 3]>) -> ShapeDesc {
    ShapeDesc::new(ShapeKind::Mesh {
        positions,
        normals: vec![],
        indices,
    })
}

/// `n` copies of [`TRIANGLE`] on three shared vertices.
pub fn identical(n: usize) -> ShapeDesc {
    mesh(TRIANGLE.to_vec(), vec![[0, 1, 2]; n])
}

/// `n` copies of [`TRIANGLE`], each with its own three vertices (at the same positions).
pub fn stacked(n: usize) -> ShapeDesc {
    let positions = (0..n).flat_map(|_| TRIANGLE).collect();
    let indices = (0..n as u32)
        .map(|i| [3 * i, 3 * i + 1, 3 * i + 2])
        .collect();
    mesh(positions, indices)
}

/// Copy `i` of [`TRIANGLE`] moved by `i · 10⁻⁵` along x: all in the plane z = 0, all
/// overlapping (`n ≤ 20 000` keeps x = 0.1 inside every one of them).
pub fn shifted(n: usize) -> ShapeDesc {
    let positions = (0..n)
        .flat_map(|i| TRIANGLE.map(|p| p + Vec3::X * (i as f32 * 1e-5)))
        .collect();
    let indices = (0..n as u32)
        .map(|i| [3 * i, 3 * i + 1, 3 * i + 2])
        .collect();
    mesh(positions, indices)
}

/// `n` triangles on the edge from (0, −½, 0) to (0, ½, 0), their third vertices on a
/// half circle of radius ½ about it (angles `π i / n`, from +x towards +z).
pub fn fan(n: usize) -> ShapeDesc {
    let mut positions = vec![Vec3::new(0.0, -0.5, 0.0), Vec3::new(0.0, 0.5, 0.0)];
    positions.extend((0..n).map(|i| {
        let a = std::f32::consts::PI * i as f32 / n as f32;
        Vec3::new(0.5 * a.cos(), 0.0, 0.5 * a.sin())
    }));
    let indices = (0..n as u32).map(|i| [0, 1, i + 2]).collect();
    mesh(positions, indices)
}

/// `n` zero-area triangles in the square [−½, ½]² of z = 0 (alternately a repeated
/// vertex and three collinear vertices), then [`TRIANGLE`] lifted to z = ½.
pub fn zero_area(n: usize) -> ShapeDesc {
    let mut positions = Vec::with_capacity(3 * n + 3);
    for i in 0..n {
        let p = Vec3::new(
            (i % 100) as f32 / 100.0 - 0.5,
            (i / 100 % 100) as f32 / 100.0 - 0.5,
            0.0,
        );
        let q = p + Vec3::new(0.01, 0.005, 0.0);
        positions.extend(if i % 2 == 0 {
            [p, p, q]
        } else {
            [p, 0.5 * (p + q), q]
        });
    }
    positions.extend(TRIANGLE.map(|p| p + Vec3::Z * 0.5));
    let indices = (0..=n as u32)
        .map(|i| [3 * i, 3 * i + 1, 3 * i + 2])
        .collect();
    mesh(positions, indices)
}

/// `n` small triangles scattered in the cube [−½, ½]³ (a fixed xorshift sequence): the
/// ordinary soup of the same size that the others are compared with.
pub fn random(n: usize) -> ShapeDesc {
    let mut s = 0x9e37_79b9_7f4a_7c15_u64;
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 40) as f32 / (1u64 << 24) as f32 - 0.5
    };
    let mut positions = Vec::with_capacity(3 * n);
    for _ in 0..n {
        let c = Vec3::new(next(), next(), next());
        for _ in 0..3 {
            positions.push(c + 0.1 * Vec3::new(next(), next(), next()));
        }
    }
    let indices = (0..n as u32)
        .map(|i| [3 * i, 3 * i + 1, 3 * i + 2])
        .collect();
    mesh(positions, indices)
}

/// Every soup above with `n` triangles, by name.
pub fn all(n: usize) -> Vec<(&'static str, ShapeDesc)> {
    vec![
        ("identical", identical(n)),
        ("stacked", stacked(n)),
        ("shifted", shifted(n)),
        ("fan", fan(n)),
        ("zero_area", zero_area(n)),
        ("random", random(n)),
    ]
}
