//! Sampling triangle meshes (and cubes) triangle by triangle, rectangles as a whole.

use super::area_to_solid_angle;
use crate::scene::geometry::build::MeshData;
use crate::scene::geometry::{Hit, ShapeSample};
use glam::{Vec2, Vec3};

/// The vertices of triangle `k`.
fn triangle(m: &MeshData, k: usize) -> [Vec3; 3] {
    m.indices[k].map(|v| m.positions[v as usize])
}

/// The front normal of a triangle.
fn front_normal(m: &MeshData, [a, b, c]: [Vec3; 3]) -> Vec3 {
    let n = (b - a).cross(c - a).normalize_or_zero();
    if m.flip {
        -n
    } else {
        n
    }
}

/// A uniform point on the triangle (b₁ = 1 − √u₁ weighs `a`, as in the seeds' warp).
fn uniform_point([a, b, c]: [Vec3; 3], u: Vec2) -> Vec3 {
    let su = u.x.sqrt();
    let (wb, wc) = (u.y * su, 1.0 - su);
    a * (1.0 - wb - wc) + b * wb + c * wc
}

pub(super) fn sample(m: &MeshData, reference: Vec3, u_pick: f32, u: Vec2) -> Option<ShapeSample> {
    if let Some(par) = &m.parallelogram {
        return sample_parallelogram(m, par, reference, u);
    }
    let (k, pmf) = m.pick.as_ref()?.sample_with_pmf(u_pick);
    let tri = triangle(m, k);
    let n = front_normal(m, tri);
    let p = uniform_point(tri, u);
    let area = 0.5 * (tri[1] - tri[0]).cross(tri[2] - tri[0]).length();
    let pdf = pmf * area_to_solid_angle(1.0 / area, reference, p, n)?;
    Some(ShapeSample { p, n, pdf })
}

pub(super) fn pdf(m: &MeshData, reference: Vec3, hit: &Hit) -> Option<f32> {
    if let Some(par) = &m.parallelogram {
        return pdf_parallelogram(m, par, reference, hit);
    }
    let k = hit.prim as usize;
    if k >= m.indices.len() {
        return None;
    }
    let pmf = m.pick.as_ref()?.pmf(k);
    let tri = triangle(m, k);
    let area = 0.5 * (tri[1] - tri[0]).cross(tri[2] - tri[0]).length();
    Some(pmf * area_to_solid_angle(1.0 / area, reference, hit.p, hit.ng)?)
}

/// A rectangle: `corner + s·ex + t·ey`; uniform by area for now.
fn sample_parallelogram(
    m: &MeshData,
    &[corner, ex, ey]: &[Vec3; 3],
    reference: Vec3,
    u: Vec2,
) -> Option<ShapeSample> {
    let n = front_normal(m, triangle(m, 0));
    let p = corner + u.x * ex + u.y * ey;
    let pdf = area_to_solid_angle(1.0 / m.area, reference, p, n)?;
    Some(ShapeSample { p, n, pdf })
}

fn pdf_parallelogram(m: &MeshData, _par: &[Vec3; 3], reference: Vec3, hit: &Hit) -> Option<f32> {
    area_to_solid_angle(1.0 / m.area, reference, hit.p, hit.ng)
}
