//! A rectangle (any parallelogram) sampled as a whole: the one sampler behind
//! [`Geometry::sample_shape`](crate::geometry::Geometry::sample_shape) for `rectangle`
//! shapes and behind rectangle area lights.

use super::{area_to_solid_angle, ShapeSampling};
use crate::geometry::ShapeSample;
use glam::{Vec2, Vec3};
use mcrt::sampling::warp::{RectangleFrame, Warp};

/// Relative margin of [`RectangleSampler::surely_behind`]: about a thousand times the `f32`
/// rounding of the quantities it bounds.
const BEHIND_MARGIN: f32 = 1e-4;

/// The parallelogram `corner + s·ex + t·ey`, s, t ∈ [0, 1], with everything that does not
/// depend on the reference point computed once: its unit front normal, its area, and the
/// frame of the spherical-rectangle warp (Ureña, Fajardo & King 2013, "An Area-Preserving
/// Parametrization for Spherical Rectangles", EGSR).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct RectangleSampler {
    corner: Vec3,
    ex: Vec3,
    ey: Vec3,
    /// Unit normal of the front side (after `flip_normals`).
    n: Vec3,
    area: f32,
    /// Area density 1/A.
    inv_area: f32,
    /// A bound on the magnitude of the rectangle's coordinates: `|corner|∞ + |ex| + |ey|`.
    reach: f32,
    /// The centre, `corner + (ex + ey)/2`.
    center: Vec3,
    /// The squared diagonal `|ex|² + |ey|²` (of a rectangle; a parallelogram's is close).
    diagonal2: f32,
    /// `None` when the warp rejects the rectangle (no area, non-finite input).
    frame: Option<Box<RectangleFrame>>,
}

impl RectangleSampler {
    /// The rectangle from its corner, edges, unit front normal and area.
    pub(crate) fn new([corner, ex, ey]: [Vec3; 3], n: Vec3, area: f32) -> Self {
        Self {
            corner,
            ex,
            ey,
            n,
            area,
            inv_area: 1.0 / area,
            reach: corner.abs().max_element() + ex.length() + ey.length(),
            center: corner + 0.5 * (ex + ey),
            diagonal2: ex.length_squared() + ey.length_squared(),
            frame: RectangleFrame::new(corner, ex, ey).ok().map(Box::new),
        }
    }

    /// The unit normal of the front side.
    #[inline]
    pub(crate) fn normal(&self) -> Vec3 {
        self.n
    }

    /// Whether `from` lies behind the front side's plane by clearly more than rounding: then
    /// every point of the rectangle is seen from behind, and a light that emits from its
    /// front rejects every sample. The margin, [`BEHIND_MARGIN`] times
    /// `1 + |from|∞ + reach`, exceeds the rounding of the sampled point, of the normal and of
    /// the dot products by orders of magnitude.
    #[inline]
    pub(crate) fn surely_behind(&self, from: Vec3) -> bool {
        let h = (from - self.corner).dot(self.n);
        h < -BEHIND_MARGIN * (1.0 + from.abs().max_element() + self.reach)
    }

    /// Whether `how` samples this rectangle by solid angle from `reference` (see
    /// [`ShapeSampling::Auto`]).
    #[inline]
    pub(crate) fn by_solid_angle(&self, how: ShapeSampling, reference: Vec3) -> bool {
        how.by_solid_angle(|| (reference.distance_squared(self.center), self.diagonal2))
    }

    /// The point `corner + u.x·ex + u.y·ey`: uniform by area.
    #[inline]
    pub(crate) fn point(&self, u: Vec2) -> Vec3 {
        self.corner + u.x * self.ex + u.y * self.ey
    }

    /// A point for lighting `reference`, its density per unit solid angle there: by solid
    /// angle through the spherical-rectangle warp when `how` asks for it at `reference`
    /// ([`RectangleSampler::by_solid_angle`]) and the warp can be built
    /// from `reference`, else uniform by area, `p_ω = d² / (A·|cos θ'|)`. `None` where the
    /// density is not finite and positive (the point edge-on or at `reference`).
    #[inline]
    pub(crate) fn sample(
        &self,
        how: ShapeSampling,
        reference: Vec3,
        u: Vec2,
    ) -> Option<ShapeSample> {
        let seen = match &self.frame {
            Some(f) if self.by_solid_angle(how, reference) => f.seen_from(reference).ok(),
            _ => None,
        };
        let (p, pdf) = match seen {
            Some(sr) => sr.sample_point(u)?,
            None => {
                let p = self.point(u);
                let d = p - reference;
                let dist2 = d.length_squared();
                let cos = self.n.dot(d / dist2.sqrt()).abs();
                (p, dist2 * self.inv_area / cos)
            }
        };
        (pdf.is_finite() && pdf > 0.0).then_some(ShapeSample { p, n: self.n, pdf })
    }

    /// The density per unit solid angle at `reference` with which
    /// [`RectangleSampler::sample`] returns the point `p` of the rectangle.
    pub(crate) fn pdf(&self, how: ShapeSampling, reference: Vec3, p: Vec3) -> Option<f32> {
        let seen = match &self.frame {
            Some(f) if self.by_solid_angle(how, reference) => f.seen_from(reference).ok(),
            _ => None,
        };
        match seen {
            Some(sr) => Some(sr.pdf((p - reference).normalize_or_zero())),
            None => area_to_solid_angle(self.inv_area, reference, p, self.n),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_square() -> RectangleSampler {
        RectangleSampler::new([Vec3::ZERO, Vec3::X, Vec3::Z], -Vec3::Y, 1.0)
    }

    #[test]
    fn area_sampling_density_and_edges() {
        let r = unit_square();
        let u = Vec2::new(0.5, 0.5);
        let below = r
            .sample(ShapeSampling::Area, Vec3::new(0.5, -1.0, 0.5), u)
            .unwrap();
        assert!(below.pdf.is_finite() && (below.pdf - 1.0).abs() < 1e-6);
        assert!((below.p - Vec3::new(0.5, 0.0, 0.5)).length() < 1e-6);
        let back = r.sample(ShapeSampling::Area, Vec3::new(0.5, 1.0, 0.5), u);
        assert!(
            back.is_some_and(|s| s.pdf.is_finite()),
            "two-sided, as shapes are"
        );
        let at = Vec3::new(0.5, 0.0, 0.5);
        assert!(
            r.sample(ShapeSampling::Area, at, u).is_none(),
            "on the point"
        );
        let edge_on = Vec3::new(3.0, 0.0, 0.5);
        assert!(
            r.sample(ShapeSampling::Area, edge_on, u).is_none(),
            "in the plane"
        );
    }

    /// `Auto` is solid-angle sampling within 1.5 diagonals of the centre and area sampling
    /// beyond, in the sample and in the density alike.
    #[test]
    fn auto_is_solid_angle_near_and_area_far() {
        let r = unit_square();
        let u = Vec2::new(0.3, 0.7);
        // The diagonal is √2, so "near" ends 1.5·√2 ≈ 2.12 from the centre (0.5, 0, 0.5).
        for (from, near) in [
            (Vec3::new(0.5, -0.3, 0.5), true),
            (Vec3::new(0.5, -2.0, 0.5), true),
            (Vec3::new(0.5, -2.2, 0.5), false),
            (Vec3::new(4.0, -9.0, 1.0), false),
        ] {
            assert_eq!(r.by_solid_angle(ShapeSampling::Auto, from), near, "{from}");
            let same = if near {
                ShapeSampling::SolidAngle
            } else {
                ShapeSampling::Area
            };
            let auto = r.sample(ShapeSampling::Auto, from, u).unwrap();
            assert_eq!(Some(auto), r.sample(same, from, u), "{from}");
            let pdf = r.pdf(ShapeSampling::Auto, from, auto.p).unwrap();
            assert!(
                pdf.is_finite() && (pdf - auto.pdf).abs() <= 1e-4 * auto.pdf,
                "{from}: {pdf} against {}",
                auto.pdf
            );
        }
    }

    #[test]
    fn surely_behind_only_behind() {
        let r = unit_square();
        assert!(r.surely_behind(Vec3::new(0.5, 0.1, 0.5)));
        assert!(!r.surely_behind(Vec3::new(0.5, 0.0, 0.5)));
        assert!(!r.surely_behind(Vec3::new(0.5, -0.1, 0.5)));
    }

    #[test]
    fn sample_and_pdf_agree() {
        let r = unit_square();
        for how in [ShapeSampling::Area, ShapeSampling::SolidAngle] {
            let from = Vec3::new(0.2, -0.7, 0.9);
            let s = r.sample(how, from, Vec2::new(0.3, 0.8)).unwrap();
            let pdf = r.pdf(how, from, s.p).unwrap();
            assert!(s.pdf.is_finite() && pdf.is_finite());
            assert!(
                (s.pdf - pdf).abs() <= 1e-4 * pdf,
                "{how:?}: {} vs {pdf}",
                s.pdf
            );
        }
    }
}
