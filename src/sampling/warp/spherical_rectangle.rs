//! Uniform sampling of the solid angle subtended by a rectangle (Ureña, Fajardo & King's
//! area-preserving parametrisation), with a documented fallback to area sampling.

use glam::{DVec3, Vec2, Vec3};

use super::spherical_triangle::planar::{clamp_unit_f64, triangle_solid_angle, widen, Planar};
use super::{InvertibleWarp, Warp};
use crate::sampling::SamplingError;
use urena::Urena;

mod urena;

/// Below this solid angle (sr) the warp samples the rectangle by area instead.
pub const SPHERICAL_RECTANGLE_MIN_SOLID_ANGLE: f32 = 1e-4;

/// Below this interior angle (radians) of the spherical quadrilateral the warp samples by
/// area.
pub const SPHERICAL_RECTANGLE_MIN_ANGLE: f32 = 1e-3;

/// Edges whose directions have |cos| ≤ this are treated as orthogonal (edge_y is
/// orthogonalised against edge_x); otherwise the shape is a parallelogram, sampled by area.
pub const SPHERICAL_RECTANGLE_ORTHOGONALITY: f32 = 1e-5;

/// Directions toward a rectangle, uniform in solid angle: pdf 1/Ω per steradian on the
/// directions that hit it, 0 elsewhere.
///
/// Mapping: u₁ picks the fraction of the solid angle left of a plane through the origin and
/// one x-coordinate, u₂ the height along that strip by its sine; computed in `f64`. Inverse
/// ([`InvertibleWarp`]): the hit point `(x, y)`, then `u₁` = the solid angle of the strip left
/// of `x` over Ω and `u₂` = the fraction of the strip's height sine below `y`.
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
}

impl SphericalRectangle {
    /// The rectangle `corner + s·edge_x + t·edge_y`, s, t ∈ [0, 1] (world space), seen from
    /// `origin`. Errors: non-finite input, zero area, `origin` in the rectangle's plane, or
    /// a solid angle below
    /// [`SPHERICAL_MIN_SOLID_ANGLE`](super::SPHERICAL_MIN_SOLID_ANGLE) (sample such a
    /// rectangle by area).
    ///
    /// To see one rectangle from many origins, build a [`RectangleFrame`] once and call
    /// [`RectangleFrame::seen_from`]: it skips the origin-independent work.
    pub fn new(
        origin: Vec3,
        corner: Vec3,
        edge_x: Vec3,
        edge_y: Vec3,
    ) -> Result<Self, SamplingError> {
        let o = widen("origin", origin)?;
        RectangleFrame::new(corner, edge_x, edge_y)?.seen_from_f64(o)
    }

    /// The solid angle Ω subtended by the shape (steradians).
    pub fn solid_angle(&self) -> f32 {
        self.omega() as f32
    }

    /// Ω in `f64`: Ureña et al.'s when in use, else Van Oosterom–Strackee on two triangles
    /// (computed on demand: the fallback's sampling never needs it).
    fn omega(&self) -> f64 {
        match &self.urena {
            Some(u) => u.omega,
            None => {
                let p = &self.planar;
                let corners = [p.p0, p.p0 + p.e1, p.p0 + p.e1 + p.e2, p.p0 + p.e2]
                    .map(|c| (c - p.origin).normalize());
                triangle_solid_angle(corners[0], corners[1], corners[2])
                    + triangle_solid_angle(corners[0], corners[2], corners[3])
            }
        }
    }

    /// Whether the area-sampling fallback is in use (see the type's docs).
    pub fn is_area_sampled(&self) -> bool {
        self.urena.is_none()
    }

    /// The sampled point on the rectangle and the pdf of its direction per steradian; `None`
    /// only if rounding produced a non-finite value.
    #[inline]
    pub fn sample_point(&self, u: Vec2) -> Option<(Vec3, f32)> {
        let (p, pdf) = match &self.urena {
            Some(urena) => (
                self.planar.origin + urena.sample_offset(u.as_dvec2()),
                1.0 / urena.omega,
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

/// A rectangle (or parallelogram) with everything that does not depend on the point it is
/// seen from precomputed: validation, the orthogonalised edges and the local frame. Build it
/// once per light; [`RectangleFrame::seen_from`] then makes the [`SphericalRectangle`] for
/// each reference point with only the origin-dependent work (3 dot products, 4 normalised
/// edge-plane normals and 2 `atan2`s).
///
/// ```
/// use mcrt::glam::{Vec2, Vec3};
/// use mcrt::sampling::warp::{RectangleFrame, SphericalRectangle};
///
/// let (corner, ex, ey) = (Vec3::new(-1.0, -1.0, 1.0), 2.0 * Vec3::X, 2.0 * Vec3::Y);
/// let frame = RectangleFrame::new(corner, ex, ey).unwrap();
/// let a = frame.seen_from(Vec3::ZERO).unwrap();
/// let b = SphericalRectangle::new(Vec3::ZERO, corner, ex, ey).unwrap();
/// assert_eq!(a.sample_point(Vec2::new(0.3, 0.8)), b.sample_point(Vec2::new(0.3, 0.8)));
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RectangleFrame {
    /// The shape (origin unset), with `e2` orthogonalised against `e1` when within
    /// [`SPHERICAL_RECTANGLE_ORTHOGONALITY`].
    planar: Planar,
    /// Unit edge directions and the unit normal x × y (the local frame).
    x: DVec3,
    y: DVec3,
    z: DVec3,
    /// Edge lengths.
    lx: f64,
    ly: f64,
    /// The edges are orthogonal (else the shape is always area sampled).
    orthogonal: bool,
}

impl RectangleFrame {
    /// The rectangle `corner + s·edge_x + t·edge_y`, s, t ∈ [0, 1] (world space). Errors:
    /// non-finite input, zero area.
    pub fn new(corner: Vec3, edge_x: Vec3, edge_y: Vec3) -> Result<Self, SamplingError> {
        let (p0, ex) = (widen("corner", corner)?, widen("edge_x", edge_x)?);
        let mut ey = widen("edge_y", edge_y)?;
        let lx = ex.length();
        let orthogonal = lx > 0.0
            && ex.dot(ey).abs() <= f64::from(SPHERICAL_RECTANGLE_ORTHOGONALITY) * lx * ey.length();
        if orthogonal {
            ey -= ex.dot(ey) / (lx * lx) * ex;
        }
        let planar = Planar::shape(p0, ex, ey, false)?;
        let ly = ey.length();
        let (x, y) = (ex / lx, ey / ly);
        Ok(Self {
            planar,
            x,
            y,
            z: x.cross(y),
            lx,
            ly,
            orthogonal,
        })
    }

    /// The rectangle seen from `origin`. Errors: non-finite `origin`, `origin` in the
    /// rectangle's plane, or too small a solid angle. Same result as
    /// [`SphericalRectangle::new`].
    #[inline]
    pub fn seen_from(&self, origin: Vec3) -> Result<SphericalRectangle, SamplingError> {
        self.seen_from_f64(widen("origin", origin)?)
    }

    #[inline]
    fn seen_from_f64(&self, origin: DVec3) -> Result<SphericalRectangle, SamplingError> {
        let planar = self.planar.seen_from(origin)?;
        let urena = if self.orthogonal {
            Urena::new(self, origin)
        } else {
            None
        };
        Ok(SphericalRectangle { planar, urena })
    }
}

impl Warp for SphericalRectangle {
    type Point = Vec3;

    #[inline]
    fn sample(&self, u: Vec2) -> Vec3 {
        let exact = self
            .urena
            .as_ref()
            .map(|r| |u| r.sample_offset(u).normalize());
        self.planar.sample_with(u, exact)
    }

    /// 1/Ω per steradian on directions hitting the shape (area fallback: d²/(A|cos θ′|)).
    #[inline]
    fn pdf(&self, w: Vec3) -> f32 {
        self.planar
            .pdf_with(w, self.urena.as_ref().map(|_| self.omega()))
    }
}

impl InvertibleWarp for SphericalRectangle {
    /// The `u` whose sample is the direction `w` (unit length expected; normalised here):
    /// the inverse of Ureña et al.'s map (the strip's solid angle over Ω, then the height's
    /// sine), or the shape coordinates of the point hit for the area fallback. Directions
    /// outside the rectangle give values clamped into `[0, 1)²`.
    #[inline]
    fn invert(&self, w: Vec3) -> Vec2 {
        let dir = w.as_dvec3().normalize_or_zero();
        match &self.urena {
            Some(urena) => match urena.invert_local(dir) {
                Some(u) => clamp_unit_f64(u.x, u.y),
                None => Vec2::ZERO,
            },
            None => self.planar.invert_area(dir),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_exact_and_fallback() {
        let skew = SphericalRectangle::new(Vec3::ZERO, Vec3::Z, Vec3::X, Vec3::new(0.5, 1.0, 0.0))
            .unwrap();
        for r in [
            square(Vec3::new(0.3, -0.2, 0.0), 1.0),
            square(Vec3::ZERO, 1e3),
            skew,
        ] {
            for i in 1..20 {
                for j in 1..20 {
                    let u = Vec2::new(i as f32 / 20.0, j as f32 / 20.0);
                    let back = r.invert(r.sample(u));
                    let err = (back - u).abs().max_element();
                    assert!(back.is_finite() && err < 1e-4, "{u}: {back}");
                }
            }
        }
    }

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
            // Almost in the plane, over the rectangle: Ω close to 2π.
            Vec3::new(0.2, -0.3, 1.999),
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
    fn frame_seen_from_matches_new() {
        let (corner, ex, ey) = (
            Vec3::new(-0.3, 0.2, 1.0),
            Vec3::new(1.5, 0.0, 0.5),
            Vec3::new(-0.2, 0.7, 0.6),
        );
        let frame = RectangleFrame::new(corner, ex, ey).unwrap();
        for origin in [
            Vec3::ZERO,
            Vec3::new(4.0, -1.0, 0.3),
            Vec3::new(0.0, 0.0, 1e3),
        ] {
            let a = frame.seen_from(origin).unwrap();
            let b = SphericalRectangle::new(origin, corner, ex, ey).unwrap();
            assert_eq!(a, b, "{origin}");
            let u = Vec2::new(0.3, 0.7);
            assert_eq!(a.sample_point(u), b.sample_point(u));
        }
        assert!(frame.seen_from(corner + 0.5 * ex).is_err());
        assert!(frame.seen_from(Vec3::NAN).is_err());
    }

    #[test]
    fn edges_and_corners_hit_the_rectangle() {
        let r = square(Vec3::new(0.3, -0.2, 0.0), 1.0);
        let edges = [0.0, 0.5, crate::sampling::ONE_MINUS_EPSILON];
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
