//! Uniform sampling of the solid angle subtended by a rectangle (Ureña, Fajardo & King's
//! area-preserving parametrisation), with a documented fallback to area sampling.

use std::f64::consts::TAU;

use glam::{DVec2, DVec3, Vec2, Vec3};

use super::spherical_triangle::planar::{triangle_solid_angle, widen, Planar};
use super::Warp;
use crate::sampling::SamplingError;

/// Below this solid angle (sr) the warp samples the rectangle by area instead.
pub const SPHERICAL_RECTANGLE_MIN_SOLID_ANGLE: f32 = 1e-4;

/// Below this interior angle (radians) of the spherical quadrilateral the warp samples by
/// area.
pub const SPHERICAL_RECTANGLE_MIN_ANGLE: f32 = 1e-3;

/// Edges whose directions have |cos| ≤ this are treated as orthogonal (edge_y is
/// orthogonalised against edge_x); otherwise the shape is a parallelogram, sampled by area.
pub const SPHERICAL_RECTANGLE_ORTHOGONALITY: f32 = 1e-5;

/// Precomputed quantities of Ureña et al.'s method, in the rectangle's local frame where the
/// rectangle is [x0, x1] × [y0, y1] at height z0 < 0.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Urena {
    frame: [DVec3; 3],
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    z0: f64,
    /// n0.z and n2.z (normals of the planes through the edges y = y0 and y = y1).
    b0: f64,
    b1: f64,
    /// 2π − γ2 − γ3.
    k: f64,
    /// The solid angle S = Σγ − 2π.
    omega: f64,
}

/// Directions toward a rectangle, uniform in solid angle: pdf 1/Ω per steradian on the
/// directions that hit it, 0 elsewhere.
///
/// Mapping: u₁ picks the fraction of the solid angle left of a plane through the origin and
/// one x-coordinate, u₂ the height along that strip by its sine; computed in `f64`.
///
/// **Fallback** (same rules as [`SphericalTriangle`](super::SphericalTriangle)): when
/// Ω < [`SPHERICAL_RECTANGLE_MIN_SOLID_ANGLE`], an interior angle of the spherical
/// quadrilateral is below [`SPHERICAL_RECTANGLE_MIN_ANGLE`], or the edges are not orthogonal
/// (beyond [`SPHERICAL_RECTANGLE_ORTHOGONALITY`]; the shape is then the parallelogram),
/// the shape is sampled uniformly by area, with pdf d²/(A |cos θ′|) per steradian in both
/// `sample` and `pdf`. See [`SphericalRectangle::is_area_sampled`].
///
/// Ureña, Fajardo, King 2013, "An Area-Preserving Parametrization for Spherical
/// Rectangles", EGSR (Computer Graphics Forum 32(4)).
///
/// ```
/// use mcrt::glam::{Vec2, Vec3};
/// use mcrt::sampling::warp::{SphericalRectangle, Warp};
///
/// let rect = SphericalRectangle::new(Vec3::ZERO, Vec3::new(-1.0, -1.0, 1.0),
///     Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0)).unwrap();
/// let (w, pdf) = rect.sample_with_pdf(Vec2::new(0.5, 0.5));
/// assert!((w - Vec3::Z).length() < 1e-5);
/// assert!((rect.solid_angle() - 2.0 * std::f32::consts::PI / 3.0).abs() < 1e-5);
/// assert!((pdf * rect.solid_angle() - 1.0).abs() < 1e-5);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SphericalRectangle {
    planar: Planar,
    urena: Option<Urena>,
    omega: f64,
}

/// The interior angle between the planes with unit normals `a` and `b`: atan2(|a×b|, −a·b).
fn dihedral(a: DVec3, b: DVec3) -> f64 {
    a.cross(b).length().atan2(-a.dot(b))
}

impl SphericalRectangle {
    /// The rectangle `corner + s·edge_x + t·edge_y`, s, t ∈ [0, 1] (world space), seen from
    /// `origin`. Errors: non-finite input, zero area, `origin` in the rectangle's plane.
    pub fn new(
        origin: Vec3,
        corner: Vec3,
        edge_x: Vec3,
        edge_y: Vec3,
    ) -> Result<Self, SamplingError> {
        let o = widen("origin", origin)?;
        let (p0, ex) = (widen("corner", corner)?, widen("edge_x", edge_x)?);
        let mut ey = widen("edge_y", edge_y)?;
        let lx = ex.length();
        let orthogonal = lx > 0.0
            && ex.dot(ey).abs() <= f64::from(SPHERICAL_RECTANGLE_ORTHOGONALITY) * lx * ey.length();
        if orthogonal {
            ey -= ex.dot(ey) / (lx * lx) * ex;
        }
        let planar = Planar::new(o, p0, ex, ey, false)?;
        let urena = Urena::new(&planar);
        let corners = [p0, p0 + ex, p0 + ex + ey, p0 + ey].map(|p| (p - o).normalize());
        let vos = triangle_solid_angle(corners[0], corners[1], corners[2])
            + triangle_solid_angle(corners[0], corners[2], corners[3]);
        let usable = urena.filter(|&(_, s, g)| {
            orthogonal
                && s >= f64::from(SPHERICAL_RECTANGLE_MIN_SOLID_ANGLE)
                && g >= f64::from(SPHERICAL_RECTANGLE_MIN_ANGLE)
        });
        Ok(Self {
            planar,
            urena: usable.map(|(u, _, _)| u),
            omega: usable.map_or(vos, |(_, s, _)| s),
        })
    }

    /// The solid angle Ω subtended by the shape (steradians).
    pub fn solid_angle(&self) -> f32 {
        self.omega as f32
    }

    /// Whether the area-sampling fallback is in use (see the type's docs).
    pub fn is_area_sampled(&self) -> bool {
        self.urena.is_none()
    }

    /// The sampled point on the rectangle and the pdf of its direction per steradian; `None`
    /// only if rounding produced a non-finite value.
    pub fn sample_point(&self, u: Vec2) -> Option<(Vec3, f32)> {
        let (p, pdf) = match &self.urena {
            Some(urena) => (
                self.planar.origin + urena.sample_offset(u.as_dvec2()),
                1.0 / self.omega,
            ),
            None => {
                let p = self.planar.sample_area(u.as_dvec2());
                let to = p - self.planar.origin;
                let cos = self.planar.normal.dot(to.normalize()).abs();
                (p, to.length_squared() / (self.planar.area * cos))
            }
        };
        (p.is_finite() && pdf.is_finite()).then(|| (p.as_vec3(), pdf as f32))
    }
}

impl Urena {
    /// The local frame and constants, the solid angle S and the smallest interior angle.
    fn new(planar: &Planar) -> Option<(Self, f64, f64)> {
        let (lx, ly) = (planar.e1.length(), planar.e2.length());
        let x = planar.e1 / lx;
        let y = planar.e2 / ly;
        let mut z = x.cross(y);
        let d = planar.p0 - planar.origin;
        let (x0, y0, mut z0) = (d.dot(x), d.dot(y), d.dot(z));
        if z0 > 0.0 {
            z0 = -z0;
            z = -z;
        }
        let (x1, y1) = (x0 + lx, y0 + ly);
        let n0 = DVec3::new(0.0, z0, -y0).normalize();
        let n1 = DVec3::new(-z0, 0.0, x1).normalize();
        let n2 = DVec3::new(0.0, -z0, y1).normalize();
        let n3 = DVec3::new(z0, 0.0, -x0).normalize();
        let g = [
            dihedral(n0, n1),
            dihedral(n1, n2),
            dihedral(n2, n3),
            dihedral(n3, n0),
        ];
        let s = g.iter().sum::<f64>() - TAU;
        let min_angle = g.iter().copied().fold(f64::INFINITY, f64::min);
        let urena = Self {
            frame: [x, y, z],
            x0,
            x1,
            y0,
            y1,
            z0,
            b0: n0.z,
            b1: n2.z,
            k: TAU - g[2] - g[3],
            omega: s,
        };
        (s.is_finite() && min_angle.is_finite()).then_some((urena, s, min_angle))
    }

    /// The local (x, y) of the sampled point: x by the solid-angle fraction u₁, y by u₂.
    fn sample_local(&self, u: DVec2, omega: f64) -> (f64, f64) {
        let au = u.x * omega + self.k;
        let (sin_au, cos_au) = au.sin_cos();
        let fu = (cos_au * self.b0 - self.b1) / sin_au;
        let cu = (fu.signum() / (fu * fu + self.b0 * self.b0).sqrt()).clamp(-1.0, 1.0);
        let xu = -(cu * self.z0) / ((1.0 - cu) * (1.0 + cu)).sqrt();
        let xu = if xu.is_nan() {
            self.x0
        } else {
            xu.clamp(self.x0, self.x1)
        };
        let d2 = xu * xu + self.z0 * self.z0;
        let h0 = self.y0 / (d2 + self.y0 * self.y0).sqrt();
        let h1 = self.y1 / (d2 + self.y1 * self.y1).sqrt();
        let hv = h0 + u.y * (h1 - h0);
        let one_minus_hv2 = (1.0 - hv) * (1.0 + hv);
        let yv = if one_minus_hv2 > 1e-30 {
            (hv * d2.sqrt() / one_minus_hv2.sqrt()).clamp(self.y0, self.y1)
        } else {
            self.y1
        };
        (xu, yv)
    }

    /// The sampled point relative to the origin (world axes).
    fn sample_offset(&self, u: DVec2) -> DVec3 {
        let (xu, yv) = self.sample_local(u, self.omega);
        let [x, y, z] = self.frame;
        xu * x + yv * y + self.z0 * z
    }
}

impl Warp for SphericalRectangle {
    type Point = Vec3;

    fn sample(&self, u: Vec2) -> Vec3 {
        let dir = match &self.urena {
            Some(urena) => urena.sample_offset(u.as_dvec2()).normalize().as_vec3(),
            None => self
                .planar
                .direction_to(self.planar.sample_area(u.as_dvec2())),
        };
        debug_assert!(dir.is_finite());
        dir
    }

    /// 1/Ω per steradian on directions hitting the shape (area fallback: d²/(A|cos θ′|)).
    fn pdf(&self, w: Vec3) -> f32 {
        let dir = w.as_dvec3().normalize_or_zero();
        match self.urena {
            Some(_) => {
                if self.planar.hit(dir).is_some() {
                    (1.0 / self.omega) as f32
                } else {
                    0.0
                }
            }
            None => self.planar.area_pdf(dir) as f32,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(origin: Vec3, dist: f32) -> SphericalRectangle {
        SphericalRectangle::new(
            origin,
            Vec3::new(-1.0, -1.0, dist),
            2.0 * Vec3::X,
            2.0 * Vec3::Y,
        )
        .unwrap()
    }

    #[test]
    fn rejects_degenerate() {
        assert!(SphericalRectangle::new(Vec3::Z, Vec3::ZERO, Vec3::X, 2.0 * Vec3::X).is_err());
        assert!(SphericalRectangle::new(Vec3::ZERO, Vec3::X, Vec3::X, Vec3::Y).is_err());
        assert!(SphericalRectangle::new(Vec3::Z, Vec3::ZERO, Vec3::X, Vec3::INFINITY).is_err());
    }

    #[test]
    fn solid_angle_matches_van_oosterom_strackee() {
        for origin in [
            Vec3::ZERO,
            Vec3::new(3.0, -2.0, 0.5),
            Vec3::new(0.5, 0.5, 1.9),
        ] {
            let r = square(origin, 2.0);
            assert!(!r.is_area_sampled(), "{origin}");
            let o = origin.as_dvec3();
            let c = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
                .map(|(x, y)| (DVec3::new(x, y, 2.0) - o).normalize());
            let want =
                triangle_solid_angle(c[0], c[1], c[2]) + triangle_solid_angle(c[0], c[2], c[3]);
            let got = f64::from(r.solid_angle());
            assert!(
                got.is_finite() && (got / want - 1.0).abs() < 1e-6,
                "{origin}: {got} vs {want}"
            );
        }
    }

    #[test]
    fn edges_and_corners_hit_the_rectangle() {
        let r = square(Vec3::new(0.3, -0.2, 0.0), 1.0);
        let edges = [0.0, 0.5, 1.0 - f32::EPSILON / 2.0];
        for u1 in edges {
            for u2 in edges {
                let (w, pdf) = r.sample_with_pdf(Vec2::new(u1, u2));
                assert!(
                    w.is_finite() && (w.length() - 1.0).abs() < 1e-6,
                    "{u1} {u2}: {w}"
                );
                assert!(
                    pdf.is_finite() && (pdf * r.solid_angle() - 1.0).abs() < 1e-5,
                    "{pdf}"
                );
            }
        }
    }

    #[test]
    fn fallbacks_are_consistent() {
        let far = square(Vec3::ZERO, 1e3);
        assert!(far.is_area_sampled());
        let skew = SphericalRectangle::new(Vec3::ZERO, Vec3::Z, Vec3::X, Vec3::new(0.5, 1.0, 0.0))
            .unwrap();
        assert!(skew.is_area_sampled());
        for r in [far, skew] {
            let u = Vec2::new(0.4, 0.9);
            let (w, pdf) = r.sample_with_pdf(u);
            let (p, pdf_point) = r.sample_point(u).unwrap();
            assert!(pdf.is_finite() && pdf > 0.0 && (pdf / pdf_point - 1.0).abs() < 1e-4);
            assert!((p.normalize() - w).length() < 1e-5);
        }
        assert_eq!(far.pdf(-Vec3::Z), 0.0);
    }
}
