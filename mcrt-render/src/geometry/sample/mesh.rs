//! Sampling triangle meshes (and cubes) triangle by triangle (rectangles as a whole, through
//! [`super::rectangle`]), by solid angle through the spherical warp (which fall back to area sampling themselves for
//! tiny or sliver solid angles); by area where a warp cannot be built (the reference in the
//! shape's plane, non-finite input).

use super::{area_to_solid_angle, ShapeSampling};
use crate::geometry::data::MeshData;
use crate::geometry::ShapeSample;
use glam::{Vec2, Vec3};
use mcrt::sampling::warp::{SphericalTriangle, Warp};

/// The spherical warp, if solid-angle sampling is asked for at `reference` and the warp
/// can be built.
fn solid_angle<W, E>(
    how: ShapeSampling,
    reference: Vec3,
    [a, b, c]: [Vec3; 3],
    build: impl FnOnce() -> Result<W, E>,
) -> Option<W> {
    let distances = || {
        let longest2 = (b - a)
            .length_squared()
            .max((c - b).length_squared())
            .max((a - c).length_squared());
        (reference.distance_squared((a + b + c) / 3.0), longest2)
    };
    if how.by_solid_angle(distances) {
        build().ok()
    } else {
        None
    }
}

/// The vertices of triangle `k`.
fn triangle(m: &MeshData, k: usize) -> [Vec3; 3] {
    m.indices[k].map(|v| m.positions[v as usize])
}

/// The front normal of a triangle.
pub(crate) fn front_normal(m: &MeshData, [a, b, c]: [Vec3; 3]) -> Vec3 {
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

pub(super) fn sample(
    m: &MeshData,
    how: ShapeSampling,
    reference: Vec3,
    u_pick: f32,
    u: Vec2,
) -> Option<ShapeSample> {
    if let Some(r) = &m.rectangle {
        return r.sample(how, reference, u);
    }
    let (k, pmf) = m.pick.as_ref()?.sample_with_pmf(u_pick);
    let (p, n, pdf) = on_triangle(m, how, reference, k, u)?;
    let pdf = pmf * pdf;
    (pdf.is_finite() && pdf > 0.0).then_some(ShapeSample { p, n, pdf })
}

/// A point on triangle `k` (by solid angle or by area, as `how` says at `reference`), its
/// front normal, and its density per steradian among the points of that triangle.
#[inline]
fn on_triangle(
    m: &MeshData,
    how: ShapeSampling,
    reference: Vec3,
    k: usize,
    u: Vec2,
) -> Option<(Vec3, Vec3, f32)> {
    let tri = triangle(m, k);
    let n = front_normal(m, tri);
    let (p, pdf) = match solid_angle(how, reference, tri, || {
        SphericalTriangle::new(reference, tri[0], tri[1], tri[2])
    }) {
        Some(st) => st.sample_point(u)?,
        None => {
            let p = uniform_point(tri, u);
            (
                p,
                area_to_solid_angle(1.0 / triangle_area(tri), reference, p, n)?,
            )
        }
    };
    Some((p, n, pdf))
}

/// A point on triangle `k` alone (the light BVH chooses triangles itself): as [`sample`]
/// without the choice of the triangle, density per steradian among its points.
pub(super) fn sample_triangle(
    m: &MeshData,
    how: ShapeSampling,
    reference: Vec3,
    k: usize,
    u: Vec2,
) -> Option<ShapeSample> {
    if k >= m.indices.len() || m.rectangle.is_some() {
        return None;
    }
    let (p, n, pdf) = on_triangle(m, how, reference, k, u)?;
    (pdf.is_finite() && pdf > 0.0).then_some(ShapeSample { p, n, pdf })
}

/// The density of [`sample_triangle`] at point `p` of triangle `prim`.
pub(super) fn pdf_triangle(
    m: &MeshData,
    how: ShapeSampling,
    reference: Vec3,
    at: (Vec3, Vec3, u32),
) -> Option<f32> {
    if (at.2 as usize) >= m.indices.len() || m.rectangle.is_some() {
        return None;
    }
    triangle_density(m, how, reference, at)
}

/// Each triangle's vertices and front normal (a `rectangle`'s two triangles too).
pub(super) fn triangles(m: &MeshData) -> impl Iterator<Item = ([Vec3; 3], Vec3)> + '_ {
    (0..m.indices.len()).map(|k| {
        let tri = triangle(m, k);
        (tri, front_normal(m, tri))
    })
}

/// A point uniform by area over the whole mesh (a triangle by its area, then a uniform
/// point on it) and the front normal there.
pub(super) fn sample_area(m: &MeshData, u_pick: f32, u: Vec2) -> Option<(Vec3, Vec3)> {
    if let Some(r) = &m.rectangle {
        return Some((r.point(u), r.normal()));
    }
    let (k, _) = m.pick.as_ref()?.sample_with_pmf(u_pick);
    let tri = triangle(m, k);
    Some((uniform_point(tri, u), front_normal(m, tri)))
}

/// The density of [`sample`] at point `p` (front normal `ng`) of triangle `prim`.
pub(super) fn pdf(
    m: &MeshData,
    how: ShapeSampling,
    reference: Vec3,
    (p, ng, prim): (Vec3, Vec3, u32),
) -> Option<f32> {
    if let Some(r) = &m.rectangle {
        return r.pdf(how, reference, p);
    }
    let k = prim as usize;
    if k >= m.indices.len() {
        return None;
    }
    let pmf = m.pick.as_ref()?.pmf(k);
    let pdf = triangle_density(m, how, reference, (p, ng, prim))?;
    Some(pmf * pdf)
}

/// The density per steradian of a point `p` (front normal `ng`) on triangle `prim` (in
/// range) among that triangle's points.
#[inline]
fn triangle_density(
    m: &MeshData,
    how: ShapeSampling,
    reference: Vec3,
    (p, ng, prim): (Vec3, Vec3, u32),
) -> Option<f32> {
    let tri = triangle(m, prim as usize);
    match solid_angle(how, reference, tri, || {
        SphericalTriangle::new(reference, tri[0], tri[1], tri[2])
    }) {
        Some(st) => Some(st.pdf((p - reference).normalize_or_zero())),
        None => area_to_solid_angle(1.0 / triangle_area(tri), reference, p, ng),
    }
}

fn triangle_area([a, b, c]: [Vec3; 3]) -> f32 {
    0.5 * (b - a).cross(c - a).length()
}
