//! Sampling points on shapes (for area lights), with densities per unit solid angle as seen
//! from a reference point.
//!
//! Current strategy for every shape: a point uniformly distributed over the shape's area
//! (meshes: a triangle chosen with probability proportional to its area, then a uniform
//! point on it), with the area density converted to solid angle:
//! `p_ω = p_A · d² / |cos θ'|`, `d` the distance and `θ'` the angle at the sampled point
//! between its normal and the direction to the reference point.

use super::build::{MeshData, ShapeData};
use super::{Geometry, Hit, ShapeSample};
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// Choice of a triangle with probability proportional to its area (own small CDF).
#[derive(Debug, Clone)]
pub(crate) struct TriangleCdf {
    /// Inclusive CDF, normalised, exactly 1 from the last triangle of nonzero area on.
    cdf: Vec<f32>,
    total: f32,
}

impl TriangleCdf {
    pub(crate) fn new(areas: &[f32]) -> Self {
        let total: f64 = areas.iter().map(|&a| f64::from(a)).sum();
        let mut acc = 0.0f64;
        let mut cdf: Vec<f32> = areas
            .iter()
            .map(|&a| {
                acc += f64::from(a);
                if total > 0.0 {
                    (acc / total) as f32
                } else {
                    0.0
                }
            })
            .collect();
        if let Some(last) = areas.iter().rposition(|&a| a > 0.0) {
            cdf[last..].iter_mut().for_each(|c| *c = 1.0);
        }
        Self {
            cdf,
            total: total as f32,
        }
    }

    /// Total area.
    pub(crate) fn total(&self) -> f32 {
        self.total
    }

    /// The triangle chosen by `u ∈ [0,1)`: the first whose inclusive CDF exceeds `u`.
    /// Triangles of zero area are never chosen.
    pub(crate) fn pick(&self, u: f32) -> Option<usize> {
        if self.total <= 0.0 {
            return None;
        }
        let k = self.cdf.partition_point(|&c| c <= u);
        Some(k.min(self.cdf.len() - 1))
    }
}

/// `p_A · d² / |cos θ'|`: the solid-angle density at `reference` of an area density
/// `pdf_area` at point `p` with normal `n`; `None` where it is infinite or undefined.
#[inline]
fn area_to_solid_angle(pdf_area: f32, reference: Vec3, p: Vec3, n: Vec3) -> Option<f32> {
    let d = reference - p;
    let dist2 = d.length_squared();
    let cos = n.dot(d).abs() / dist2.sqrt();
    let pdf = pdf_area * dist2 / cos;
    (pdf.is_finite() && pdf > 0.0).then_some(pdf)
}

/// Shirley & Chiu 1997, "A Low Distortion Map Between Disk and Square", JGT 2(3): the
/// concentric map of `u` to the unit disk.
fn concentric_disk(u: Vec2) -> Vec2 {
    let s = 2.0 * u - Vec2::ONE;
    if s == Vec2::ZERO {
        return Vec2::ZERO;
    }
    let (r, phi) = if s.x.abs() > s.y.abs() {
        (s.x, PI / 4.0 * (s.y / s.x))
    } else {
        (s.y, PI / 2.0 - PI / 4.0 * (s.x / s.y))
    };
    r * Vec2::new(phi.cos(), phi.sin())
}

impl Geometry {
    /// The surface area of shape `shape` (world space); 0 for an index out of range.
    pub fn shape_area(&self, shape: u32) -> f32 {
        match self.shapes.get(shape as usize) {
            Some(ShapeData::Mesh(m)) => m.cdf.total(),
            Some(ShapeData::Sphere { radius, .. }) => 4.0 * PI * radius * radius,
            Some(ShapeData::Disk(d)) => d.area,
            None => 0.0,
        }
    }

    /// A point on shape `shape` for lighting `reference`: `u_pick` chooses a triangle of a
    /// mesh (ignored for spheres and disks), `u` the point. The returned `pdf` is per unit
    /// solid angle at `reference` (see the module docs of `geometry` for the strategy per
    /// shape). `None` when the shape has no area, the index is out of range, or the density
    /// is infinite (the sample lies edge-on or at `reference`).
    pub fn sample_shape(
        &self,
        shape: u32,
        reference: Vec3,
        u_pick: f32,
        u: Vec2,
    ) -> Option<ShapeSample> {
        let area = self.shape_area(shape);
        let (p, n) = match self.shapes.get(shape as usize)? {
            ShapeData::Mesh(m) => sample_mesh_area(m, u_pick, u)?,
            &ShapeData::Sphere {
                center,
                radius,
                flip,
            } => {
                let z = 1.0 - 2.0 * u.x;
                let r = (1.0 - z * z).max(0.0).sqrt();
                let (s, c) = (2.0 * PI * u.y).sin_cos();
                let n = Vec3::new(r * c, r * s, z);
                (center + radius * n, if flip { -n } else { n })
            }
            ShapeData::Disk(d) => {
                let q = concentric_disk(u);
                (d.to_world.transform_point3(q.extend(0.0)), d.normal)
            }
        };
        let pdf = area_to_solid_angle(1.0 / area, reference, p, n)?;
        Some(ShapeSample { p, n, pdf })
    }

    /// The density per unit solid angle at `reference` with which
    /// [`Geometry::sample_shape`] produces the point `hit` (a hit on shape `shape`); 0 if it
    /// never does.
    pub fn shape_pdf(&self, shape: u32, reference: Vec3, hit: &Hit) -> f32 {
        let area = self.shape_area(shape);
        if hit.shape != shape || area <= 0.0 || area.is_nan() {
            return 0.0;
        }
        area_to_solid_angle(1.0 / area, reference, hit.p, hit.ng).unwrap_or(0.0)
    }
}

/// A uniform point on a mesh: (point, front normal).
fn sample_mesh_area(m: &MeshData, u_pick: f32, u: Vec2) -> Option<(Vec3, Vec3)> {
    let k = m.cdf.pick(u_pick)?;
    let [a, b, c] = m.indices[k].map(|v| m.positions[v as usize]);
    // Uniform barycentrics: b1 = 1 − √u₁ weight of a... (Shirley 1992 / the seeds' warp).
    let su = u.x.sqrt();
    let (w1, w2) = (u.y * su, 1.0 - su);
    let p = a * (1.0 - w1 - w2) + b * w1 + c * w2;
    let n = (b - a).cross(c - a).normalize_or_zero();
    Some((p, if m.flip { -n } else { n }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cdf_skips_zero_area_triangles() {
        let cdf = TriangleCdf::new(&[0.0, 1.0, 0.0, 3.0, 0.0]);
        assert_eq!(cdf.pick(0.0), Some(1));
        assert_eq!(cdf.pick(0.2499), Some(1));
        assert_eq!(cdf.pick(0.25), Some(3));
        assert_eq!(cdf.pick(1.0 - 2f32.powi(-24)), Some(3));
        assert_eq!(TriangleCdf::new(&[0.0, 0.0]).pick(0.5), None);
    }

    #[test]
    fn concentric_disk_stays_inside() {
        for i in 0..=16 {
            for j in 0..=16 {
                let q = concentric_disk(Vec2::new(i as f32, j as f32) / 16.0);
                assert!(q.is_finite() && q.length() <= 1.0 + 1e-6);
            }
        }
    }
}
