//! Directional domains: the sphere, the hemisphere and a spherical cap about any axis, cut
//! into cells that resolve narrow lobes.

use super::domain::{Domain, PdfRef, CELL_ABS_TOL};
use super::quadrature::{integrate_2d, Rect, REFINED_MIN_DEPTH};
use glam::{DVec3, Vec3};
use std::f64::consts::{PI, TAU};

/// Bands and sectors into which the complement of a cap is split for its quadrature.
const COMPLEMENT_BANDS: usize = 48;
const COMPLEMENT_SECTORS: usize = 16;

/// Unit directions (points are [`Vec3`]) in a cap `θ ≤ θ_max` about an axis, where θ is the
/// angle to the axis, plus one complement cell for the rest of the sphere when
/// `θ_max < π`.
///
/// The cap is cut into `rows` rings and `cols` sectors. Ring `i` spans
/// `θ ∈ θ_max·[(i/rows)^k, ((i+1)/rows)^k]` with refinement exponent `k` (default 2): rings
/// are finest near the axis, so a cone of half-angle 10⁻³ rad or a GGX lobe of α = 0.01
/// about the axis is resolved. For narrower lobes, or lobes off the pole (a reflected
/// lobe), use [`Directions::cap`] about the lobe's axis with `θ_max` a few lobe widths.
/// θ is computed as `atan2(√(x² + y²), z)` in the cap's frame, in `f64`, so directions near
/// the axis are binned from `x² + y²` rather than from `z` (which has too few `f32` values
/// there).
///
/// ```
/// use mcrt::glam::Vec3;
/// use mcrt::stats::{Directions, Domain};
/// let cap = Directions::cap(Vec3::X, 0.01).resolution(8, 16);
/// assert_eq!(cap.cell_count(), 8 * 16 + 1); // the cap's cells and the complement
/// assert_eq!(cap.cell_of(-Vec3::X), Some(8 * 16));
/// ```
#[derive(Clone, Debug)]
pub struct Directions {
    axis: DVec3,
    tangent: DVec3,
    bitangent: DVec3,
    theta_max: f64,
    rows: usize,
    cols: usize,
    refine: f64,
}

impl Directions {
    /// The whole sphere (about +z); no complement cell.
    pub fn sphere() -> Self {
        Self::cap(Vec3::Z, std::f32::consts::PI)
    }

    /// The upper hemisphere `z ≥ 0`, with the lower one as the complement cell.
    pub fn hemisphere() -> Self {
        Self::cap(Vec3::Z, std::f32::consts::FRAC_PI_2)
    }

    /// The cap of half-angle `theta_max` (radians, clamped to `(0, π]`) about `axis`
    /// (normalised; `+z` if it cannot be). 64 rings × 128 sectors, refinement 2.
    pub fn cap(axis: Vec3, theta_max: f32) -> Self {
        let axis = axis.as_dvec3().try_normalize().unwrap_or(DVec3::Z);
        let (tangent, bitangent) = axis.any_orthonormal_pair();
        let theta_max = f64::from(theta_max);
        let theta_max = if theta_max > 0.0 {
            theta_max.min(PI)
        } else {
            PI
        };
        Self {
            axis,
            tangent,
            bitangent,
            theta_max,
            rows: 64,
            cols: 128,
            refine: 2.0,
        }
    }

    /// Sets the number of rings and sectors (each at least 1).
    #[must_use]
    pub fn resolution(mut self, rows: usize, cols: usize) -> Self {
        self.rows = rows.max(1);
        self.cols = cols.max(1);
        self
    }

    /// Sets the ring refinement exponent `k` (1 = rings equal in θ; larger = finer near the
    /// axis; clamped to `[1, 4]`).
    #[must_use]
    pub fn refinement(mut self, k: f64) -> Self {
        self.refine = if k.is_finite() {
            k.clamp(1.0, 4.0)
        } else {
            2.0
        };
        self
    }

    fn has_complement(&self) -> bool {
        self.theta_max < PI
    }

    fn ring_edge(&self, i: usize) -> f64 {
        self.theta_max * (i as f64 / self.rows as f64).powf(self.refine)
    }

    /// `(θ, φ)` of a unit `p` in the cap's frame, or `None` if `p` is not unit length.
    fn angles(&self, p: Vec3) -> Option<(f64, f64)> {
        let p = p.as_dvec3();
        let len2 = p.length_squared();
        if len2.is_nan() || (len2 - 1.0).abs() > 2e-3 {
            return None;
        }
        let (x, y, z) = (p.dot(self.tangent), p.dot(self.bitangent), p.dot(self.axis));
        let theta = (x * x + y * y).sqrt().atan2(z);
        let phi = y.atan2(x);
        Some((theta, if phi < 0.0 { phi + TAU } else { phi }))
    }

    fn direction(&self, theta: f64, phi: f64) -> Vec3 {
        let (st, ct) = theta.sin_cos();
        let (sp, cp) = phi.sin_cos();
        (self.tangent * (st * cp) + self.bitangent * (st * sp) + self.axis * ct).as_vec3()
    }

    fn solid_angle_mass(&self, r: Rect, pdf: PdfRef<'_, Vec3>, min_depth: u32) -> f64 {
        let f = |theta: f64, phi: f64| pdf(self.direction(theta, phi)) * theta.sin();
        integrate_2d(&f, r, CELL_ABS_TOL, min_depth)
    }

    fn cap_rect(&self, cell: usize) -> Rect {
        let (i, j) = (cell / self.cols, cell % self.cols);
        let dphi = TAU / self.cols as f64;
        Rect {
            a0: self.ring_edge(i),
            a1: self.ring_edge(i + 1),
            b0: dphi * j as f64,
            b1: dphi * (j + 1) as f64,
        }
    }

    fn complement_mass(&self, pdf: PdfRef<'_, Vec3>, min_depth: u32) -> f64 {
        let span = PI - self.theta_max;
        let edge = |k: usize| self.theta_max + span * (k as f64 / COMPLEMENT_BANDS as f64).powi(2);
        let dphi = TAU / COMPLEMENT_SECTORS as f64;
        let mut sum = 0.0;
        for k in 0..COMPLEMENT_BANDS {
            for s in 0..COMPLEMENT_SECTORS {
                let r = Rect {
                    a0: edge(k),
                    a1: edge(k + 1),
                    b0: dphi * s as f64,
                    b1: dphi * (s + 1) as f64,
                };
                sum += self.solid_angle_mass(r, pdf, min_depth);
            }
        }
        sum
    }
}

impl Domain for Directions {
    type Point = Vec3;

    fn cell_count(&self) -> usize {
        self.rows * self.cols + usize::from(self.has_complement())
    }

    fn cell_of(&self, p: Vec3) -> Option<usize> {
        let (theta, phi) = self.angles(p)?;
        if theta > self.theta_max {
            return self.has_complement().then_some(self.rows * self.cols);
        }
        let t = (theta / self.theta_max).powf(1.0 / self.refine);
        let i = ((t * self.rows as f64) as usize).min(self.rows - 1);
        let j = ((phi / TAU * self.cols as f64) as usize).min(self.cols - 1);
        Some(i * self.cols + j)
    }

    fn cell_mass(&self, cell: usize, pdf: PdfRef<'_, Vec3>) -> f64 {
        if cell >= self.rows * self.cols {
            self.complement_mass(pdf, 0)
        } else {
            self.solid_angle_mass(self.cap_rect(cell), pdf, 0)
        }
    }

    fn cell_mass_refined(&self, cell: usize, pdf: PdfRef<'_, Vec3>) -> f64 {
        if cell >= self.rows * self.cols {
            self.complement_mass(pdf, REFINED_MIN_DEPTH - 2)
        } else {
            self.solid_angle_mass(self.cap_rect(cell), pdf, REFINED_MIN_DEPTH)
        }
    }

    fn grid(&self) -> (usize, usize) {
        (self.cols, self.rows)
    }

    fn describe_cell(&self, cell: usize) -> String {
        if cell >= self.rows * self.cols {
            return format!("complement θ > {:.6} rad", self.theta_max);
        }
        let r = self.cap_rect(cell);
        format!(
            "θ ∈ [{:.6}, {:.6}), φ ∈ [{:.4}, {:.4}) rad",
            r.a0, r.a1, r.b0, r.b1
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_sphere_masses_sum_to_one() {
        let d = Directions::cap(Vec3::new(1.0, 1.0, 0.0), 0.5).resolution(8, 8);
        let pdf = |_: Vec3| 1.0 / (4.0 * PI);
        let total: f64 = (0..d.cell_count()).map(|c| d.cell_mass(c, &pdf)).sum();
        assert!(total.is_finite() && (total - 1.0).abs() < 1e-9, "{total}");
    }

    #[test]
    fn near_axis_directions_bin_by_angle() {
        let d = Directions::cap(Vec3::Z, 1e-3)
            .resolution(10, 4)
            .refinement(1.0);
        let theta = 0.55e-3f32; // ring 5
        let p = Vec3::new(theta.sin(), 0.0, theta.cos());
        assert_eq!(d.cell_of(p), Some(5 * 4));
        assert_eq!(d.cell_of(Vec3::new(0.0, 0.0, 2.0)), None);
        assert_eq!(d.cell_of(Vec3::splat(f32::NAN)), None);
    }
}
