//! Sampling triangle meshes (and cubes) triangle by triangle, rectangles as a whole, by
//! solid angle through the spherical warps (which fall back to area sampling themselves for
//! tiny or sliver solid angles); by area where a warp cannot be built (the reference in the
//! shape's plane, non-finite input).

use super::{area_to_solid_angle, ShapeSampling};
use crate::sampling::warp::{SphericalRectangle, SphericalTriangle, Warp};
use crate::sampling::SamplingError;
use crate::scene::geometry::build::MeshData;
use crate::scene::geometry::{Hit, ShapeSample};
use glam::{Vec2, Vec3};

/// The spherical warp, if solid-angle sampling is asked for and the warp can be built.
fn solid_angle<W, E>(how: ShapeSampling, build: impl FnOnce() -> Result<W, E>) -> Option<W> {
    match how {
        ShapeSampling::SolidAngle => build().ok(),
        ShapeSampling::Area => None,
    }
}

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

pub(super) fn sample(
    m: &MeshData,
    how: ShapeSampling,
    reference: Vec3,
    u_pick: f32,
    u: Vec2,
) -> Option<ShapeSample> {
    if let Some(par) = &m.parallelogram {
        return sample_parallelogram(m, how, par, reference, u);
    }
    let (k, pmf) = m.pick.as_ref()?.sample_with_pmf(u_pick);
    let tri = triangle(m, k);
    let n = front_normal(m, tri);
    let (p, pdf) = match solid_angle(how, || {
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
    let pdf = pmf * pdf;
    (pdf.is_finite() && pdf > 0.0).then_some(ShapeSample { p, n, pdf })
}

/// A point uniform by area over the whole mesh (a triangle by its area, then a uniform
/// point on it) and the front normal there.
pub(super) fn sample_area(m: &MeshData, u_pick: f32, u: Vec2) -> Option<(Vec3, Vec3)> {
    if let Some([corner, ex, ey]) = m.parallelogram {
        return Some((
            corner + u.x * ex + u.y * ey,
            front_normal(m, triangle(m, 0)),
        ));
    }
    let (k, _) = m.pick.as_ref()?.sample_with_pmf(u_pick);
    let tri = triangle(m, k);
    Some((uniform_point(tri, u), front_normal(m, tri)))
}

pub(super) fn pdf(m: &MeshData, how: ShapeSampling, reference: Vec3, hit: &Hit) -> Option<f32> {
    if m.parallelogram.is_some() {
        return pdf_parallelogram(m, how, reference, hit);
    }
    let k = hit.prim as usize;
    if k >= m.indices.len() {
        return None;
    }
    let pmf = m.pick.as_ref()?.pmf(k);
    let tri = triangle(m, k);
    let pdf = match solid_angle(how, || {
        SphericalTriangle::new(reference, tri[0], tri[1], tri[2])
    }) {
        Some(st) => st.pdf((hit.p - reference).normalize_or_zero()),
        None => area_to_solid_angle(1.0 / triangle_area(tri), reference, hit.p, hit.ng)?,
    };
    Some(pmf * pdf)
}

/// The rectangle seen from `reference`, from the frame precomputed at build time.
#[inline]
fn rectangle(m: &MeshData, reference: Vec3) -> Result<SphericalRectangle, SamplingError> {
    match &m.rect_frame {
        Some(f) => f.seen_from(reference),
        None => Err(SamplingError::Degenerate {
            what: "not a valid rectangle",
        }),
    }
}

fn triangle_area([a, b, c]: [Vec3; 3]) -> f32 {
    0.5 * (b - a).cross(c - a).length()
}

/// A rectangle mesh's corner and edges, its unit front normal and its area (`None` for
/// other meshes).
pub(super) fn parallelogram(m: &MeshData) -> Option<([Vec3; 3], Vec3, f32)> {
    let par = m.parallelogram?;
    Some((par, front_normal(m, triangle(m, 0)), m.area))
}

/// A rectangle `corner + s·ex + t·ey`, s, t ∈ [0, 1], as a whole.
fn sample_parallelogram(
    m: &MeshData,
    how: ShapeSampling,
    &[corner, ex, ey]: &[Vec3; 3],
    reference: Vec3,
    u: Vec2,
) -> Option<ShapeSample> {
    let n = front_normal(m, triangle(m, 0));
    let (p, pdf) = match solid_angle(how, || rectangle(m, reference)) {
        Some(sr) => sr.sample_point(u)?,
        None => {
            let p = corner + u.x * ex + u.y * ey;
            (p, area_to_solid_angle(1.0 / m.area, reference, p, n)?)
        }
    };
    (pdf.is_finite() && pdf > 0.0).then_some(ShapeSample { p, n, pdf })
}

fn pdf_parallelogram(m: &MeshData, how: ShapeSampling, reference: Vec3, hit: &Hit) -> Option<f32> {
    match solid_angle(how, || rectangle(m, reference)) {
        Some(sr) => Some(sr.pdf((hit.p - reference).normalize_or_zero())),
        None => area_to_solid_angle(1.0 / m.area, reference, hit.p, hit.ng),
    }
}
