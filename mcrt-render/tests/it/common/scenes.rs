//! Scenes and rays shared by the acceleration-structure tests (`tests/it/accel.rs`) and
//! benchmarks (`benches/accel.rs`): random rays, triangle soups, a tessellated sphere and the
//! Cornell box's shapes, all from fixed-seed PCG streams.
#![allow(dead_code)] // each user takes a subset

use mcrt::glam::{Mat4, Vec3};
use mcrt_render::description::{ShapeDesc, ShapeKind};
use mcrt_render::geometry::Ray;
use rand::Rng;
use rand_pcg::Pcg64;

pub fn unit_vec(r: &mut Pcg64) -> Vec3 {
    let z = r.random_range(-1.0f32..1.0);
    let phi = r.random_range(0.0f32..std::f32::consts::TAU);
    let s = (1.0 - z * z).max(0.0).sqrt();
    Vec3::new(s * phi.cos(), s * phi.sin(), z)
}

pub fn point(r: &mut Pcg64, h: f32) -> Vec3 {
    Vec3::new(
        r.random_range(-h..h),
        r.random_range(-h..h),
        r.random_range(-h..h),
    )
}

pub fn random_rays(r: &mut Pcg64, n: usize, h: f32) -> Vec<Ray> {
    (0..n)
        .map(|_| Ray {
            origin: point(r, h),
            dir: unit_vec(r),
        })
        .collect()
}

pub fn mesh(positions: Vec<Vec3>, indices: Vec<[u32; 3]>) -> ShapeDesc {
    ShapeDesc::new(ShapeKind::Mesh {
        positions,
        normals: vec![],
        indices,
    })
}

/// A triangle soup with every tenth triangle degenerate (collinear or repeated vertices).
pub fn soup(r: &mut Pcg64, n: usize) -> ShapeDesc {
    let mut pos = Vec::new();
    for k in 0..n {
        let c = point(r, 1.0);
        let a = c + point(r, 0.15);
        let (b, d) = match k % 10 {
            0 => (a, c),                         // repeated vertex
            5 => (c + (a - c) * 2.0, a + a - c), // collinear
            _ => (c + point(r, 0.15), c + point(r, 0.15)),
        };
        pos.extend([a, b, d]);
    }
    let idx = (0..n as u32)
        .map(|k| [3 * k, 3 * k + 1, 3 * k + 2])
        .collect();
    mesh(pos, idx)
}

pub fn row_major(m: [f32; 16]) -> Mat4 {
    Mat4::from_cols_array(&m).transpose()
}

/// The Cornell box shapes of `tests/data/cornell-box.xml`, in file order.
pub fn cornell_box() -> Vec<ShapeDesc> {
    let rect = |m| {
        let mut s = ShapeDesc::new(ShapeKind::Rectangle);
        s.to_world = row_major(m);
        s
    };
    let cube = |m| {
        let mut s = ShapeDesc::new(ShapeKind::Cube);
        s.to_world = row_major(m);
        s
    };
    vec![
        rect([
            0.23, 0., 0., 0., 0., 0., -0.19, 0.99, 0., 0.19, 0., 0.01, 0., 0., 0., 1.,
        ]),
        rect([
            1., 0., 0., 0., 0., 0., 1., -1., 0., -1., 0., 0., 0., 0., 0., 1.,
        ]),
        rect([
            1., 0., 0., 0., 0., 0., -1., 1., 0., 1., 0., 0., 0., 0., 0., 1.,
        ]),
        rect([
            1., 0., 0., 0., 0., 1., 0., 0., 0., 0., 1., -1., 0., 0., 0., 1.,
        ]),
        rect([
            0., 0., -1., 1., 0., 1., 0., 0., 1., 0., 0., 0., 0., 0., 0., 1.,
        ]),
        rect([
            0., 0., 1., -1., 0., 1., 0., 0., -1., 0., 0., 0., 0., 0., 0., 1.,
        ]),
        cube([
            0.286891, 0., -0.0877115, 0.335, 0., 0.3, 0., -0.7, 0.0877115, 0., 0.286891, 0.38, 0.,
            0., 0., 1.,
        ]),
        cube([
            0.28491, 0., 0.0939491, -0.33, 0., 0.61, 0., -0.4, -0.0939491, 0., 0.28491, -0.28, 0.,
            0., 0., 1.,
        ]),
    ]
}

/// A closed latitude–longitude sphere mesh of radius 1 with shared vertices.
pub fn tessellated_sphere(n_theta: u32, n_phi: u32) -> ShapeDesc {
    let mut pos = vec![Vec3::Z, -Vec3::Z];
    for i in 1..n_theta {
        let th = std::f32::consts::PI * i as f32 / n_theta as f32;
        for j in 0..n_phi {
            let ph = std::f32::consts::TAU * j as f32 / n_phi as f32;
            pos.push(Vec3::new(
                th.sin() * ph.cos(),
                th.sin() * ph.sin(),
                th.cos(),
            ));
        }
    }
    let v = |i: u32, j: u32| 2 + (i - 1) * n_phi + j % n_phi;
    let mut idx = Vec::new();
    for j in 0..n_phi {
        idx.push([0, v(1, j), v(1, j + 1)]);
        idx.push([1, v(n_theta - 1, j + 1), v(n_theta - 1, j)]);
        for i in 1..n_theta - 1 {
            idx.push([v(i, j), v(i + 1, j), v(i + 1, j + 1)]);
            idx.push([v(i, j), v(i + 1, j + 1), v(i, j + 1)]);
        }
    }
    mesh(pos, idx)
}
