//! Uniform sampling of the solid angle subtended by a triangle (Arvo's spherical triangle
//! sampling), with a documented fallback to area sampling for tiny or sliver triangles.

use glam::{DVec2, DVec3, Vec2, Vec3};

use super::{InvertibleWarp, Warp};
use crate::sampling::SamplingError;

mod cosine;
pub(crate) mod planar;

pub use cosine::CosineSphericalTriangle;

use planar::{clamp_unit_f64, triangle_solid_angle, widen, Planar};

/// Smallest solid angle (sr) the spherical triangle and rectangle warps accept: below it no
/// density per steradian fits `f32` safely, and callers sample the shape by area (per unit
/// area) instead, as the scene's light sampling does.
pub use planar::MIN_SOLID_ANGLE as SPHERICAL_MIN_SOLID_ANGLE;

/// Below this solid angle (sr) the warp samples the triangle by area instead.
pub const SPHERICAL_TRIANGLE_MIN_SOLID_ANGLE: f32 = 1e-4;

/// Below this interior angle (radians) of the spherical triangle the warp samples by area.
pub const SPHERICAL_TRIANGLE_MIN_ANGLE: f32 = 1e-3;

/// Precomputed quantities of Arvo's method; vertex A has the largest interior angle.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Arvo {
    a: DVec3,
    b: DVec3,
    c: DVec3,
    /// Interior angle at A, its cosine and sine.
    alpha: f64,
    cos_alpha: f64,
    sin_alpha: f64,
    /// cos of the arc AB.
    cos_ab: f64,
    /// The unit tangent at A toward C (normalised C − (C·A)A).
    c_perp: DVec3,
}

/// Directions toward a triangle, uniform in solid angle: pdf 1/Ω per steradian on the
/// directions that hit the triangle, 0 elsewhere.
///
/// Mapping: u₁ picks the sub-triangle area u₁Ω (which fixes its third vertex C′ on arc AC),
/// u₂ the point on arc BC′ by its cosine. Computed in `f64`; the vertex with the largest
/// interior angle plays A. Inverse ([`InvertibleWarp`]): C′ is where the great circle
/// through B and the direction meets arc AC; `u₁ = Ω(ABC′)/Ω`, `u₂ = (1 − B·ω)/(1 − B·C′)`
/// (pbrt-v4's `InvertSphericalTriangleSample` inverts the same map).
///
/// **Fallback:** when Ω < [`SPHERICAL_TRIANGLE_MIN_SOLID_ANGLE`] or an interior angle of the
/// spherical triangle is below [`SPHERICAL_TRIANGLE_MIN_ANGLE`], the warp samples the
/// triangle uniformly by area and its pdf is the converted density d² / (A |cos θ′|) per
/// steradian (d the distance, θ′ the angle at the triangle); [`Warp::pdf`] uses the same
/// conversion, so `sample` and `pdf` always agree. [`SphericalTriangle::is_area_sampled`]
/// tells which mode is in use. The inside test of `pdf` accepts directions within 1e-7 rad
/// of the triangle, so `f32` rounding of a sample never makes its pdf 0.
///
/// Arvo 1995, "Stratified Sampling of Spherical Triangles", SIGGRAPH.
///
/// ```
/// use mcrt::glam::{Vec2, Vec3};
/// use mcrt::sampling::warp::{SphericalTriangle, Warp};
///
/// let tri = SphericalTriangle::new(Vec3::ZERO, Vec3::new(-1.0, -1.0, 2.0),
///     Vec3::new(1.0, -1.0, 2.0), Vec3::new(0.0, 1.0, 2.0)).unwrap();
/// let (w, pdf) = tri.sample_with_pdf(Vec2::new(0.3, 0.6));
/// assert!((w.length() - 1.0).abs() < 1e-6);
/// assert!((pdf * tri.solid_angle() - 1.0).abs() < 1e-4);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SphericalTriangle {
    planar: Planar,
    arvo: Option<Arvo>,
    omega: f64,
}

/// The interior angle at `a` of the spherical triangle (a, b, c) and the unit tangent at
/// `a` toward `c`.
fn interior_angle(a: DVec3, b: DVec3, c: DVec3) -> (f64, DVec3) {
    let tb = (b - a.dot(b) * a).normalize_or_zero();
    let tc = (c - a.dot(c) * a).normalize_or_zero();
    (tb.cross(tc).length().atan2(tb.dot(tc)), tc)
}

impl SphericalTriangle {
    /// The triangle `a`, `b`, `c` (world space) seen from `origin`. Errors: non-finite input,
    /// zero area, `origin` in the triangle's plane (relative distance ≤ 1e-9), or a solid
    /// angle below [`SPHERICAL_MIN_SOLID_ANGLE`] (sample such a triangle by area).
    pub fn new(origin: Vec3, a: Vec3, b: Vec3, c: Vec3) -> Result<Self, SamplingError> {
        let o = widen("origin", origin)?;
        let (pa, pb, pc) = (widen("a", a)?, widen("b", b)?, widen("c", c)?);
        let planar = Planar::new(o, pa, pb - pa, pc - pa, true)?;
        let dirs = [pa, pb, pc].map(|p| (p - o).normalize());
        let omega = triangle_solid_angle(dirs[0], dirs[1], dirs[2]);
        let angles =
            [0, 1, 2].map(|i| interior_angle(dirs[i], dirs[(i + 1) % 3], dirs[(i + 2) % 3]).0);
        let usable = omega >= f64::from(SPHERICAL_TRIANGLE_MIN_SOLID_ANGLE)
            && angles
                .iter()
                .all(|&t| t >= f64::from(SPHERICAL_TRIANGLE_MIN_ANGLE));
        let arvo = usable.then(|| {
            let k = (0..3)
                .max_by(|&i, &j| angles[i].total_cmp(&angles[j]))
                .unwrap_or(0);
            let (a, b, c) = (dirs[k], dirs[(k + 1) % 3], dirs[(k + 2) % 3]);
            let (alpha, c_perp) = interior_angle(a, b, c);
            Arvo {
                a,
                b,
                c,
                alpha,
                cos_alpha: alpha.cos(),
                sin_alpha: alpha.sin(),
                cos_ab: a.dot(b),
                c_perp,
            }
        });
        Ok(Self {
            planar,
            arvo,
            omega,
        })
    }

    /// The solid angle Ω subtended by the triangle (steradians, Van Oosterom–Strackee).
    pub fn solid_angle(&self) -> f32 {
        self.omega as f32
    }

    /// Whether the area-sampling fallback is in use (see the type's docs).
    pub fn is_area_sampled(&self) -> bool {
        self.arvo.is_none()
    }

    /// The sampled point on the triangle and the pdf of its direction per steradian; `None`
    /// only if rounding makes the sampled ray miss the triangle's plane.
    pub fn sample_point(&self, u: Vec2) -> Option<(Vec3, f32)> {
        let (p, pdf) = match &self.arvo {
            Some(arvo) => {
                let dir = arvo.sample(u.as_dvec2(), self.omega);
                let (dist, _) = self.planar.hit(dir)?;
                (self.planar.origin + dist * dir, 1.0 / self.omega)
            }
            None => {
                let p = self.planar.sample_area(u.as_dvec2());
                let dir = (p - self.planar.origin).normalize();
                let cos = self.planar.normal.dot(dir).abs();
                (
                    p,
                    (p - self.planar.origin).length_squared() / (self.planar.area * cos),
                )
            }
        };
        (p.is_finite() && pdf.is_finite()).then(|| (p.as_vec3(), pdf as f32))
    }
}

impl Arvo {
    /// Arvo's map in `f64`: u₁ → sub-area and vertex C′ on arc AC; u₂ → point on arc BC′.
    #[inline]
    fn sample(&self, u: DVec2, omega: f64) -> DVec3 {
        let sub = u.x * omega;
        let (s, t) = (sub - self.alpha).sin_cos();
        let p = t - self.cos_alpha;
        let q = s + self.sin_alpha * self.cos_ab;
        let cos_b = ((q * t - p * s) * self.cos_alpha - q) / ((q * s + p * t) * self.sin_alpha);
        let cos_b = cos_b.clamp(-1.0, 1.0);
        let sin_b = ((1.0 - cos_b) * (1.0 + cos_b)).sqrt();
        let c1 = (cos_b * self.a + sin_b * self.c_perp).normalize();
        // Cosine of the arc B→P is uniform between 1 and B·C′: 1 − cos = u₂ |C′ − B|²/2.
        let one_minus_z = u.y * 0.5 * (c1 - self.b).length_squared();
        let z = 1.0 - one_minus_z;
        let sin_z = (one_minus_z * (2.0 - one_minus_z)).max(0.0).sqrt();
        let perp = (c1 - c1.dot(self.b) * self.b).normalize_or_zero();
        (z * self.b + sin_z * perp).normalize()
    }

    /// The inverse of [`Arvo::sample`]: `C′` is where the great circle through B and the
    /// direction meets arc AC; `u₁` is the area of the sub-triangle ABC′ over Ω, and `u₂` the
    /// ratio `(1 − B·w)/(1 − B·C′)`, each `1 − cos` taken as half a squared chord.
    #[inline]
    fn invert(&self, w: DVec3, omega: f64) -> DVec2 {
        let bw = self.b.cross(w);
        // Within f32 rounding of B (where u₂ = 0 and every u₁ maps to B), the great circle
        // through B and w is noise: return u₂ = 0.
        if bw.length_squared() < 1e-14 {
            return DVec2::ZERO;
        }
        let mut c1 = bw.cross(self.a.cross(self.c)).normalize_or_zero();
        if c1.dot(self.a + self.c) < 0.0 {
            c1 = -c1;
        }
        let u1 = triangle_solid_angle(self.a, self.b, c1) / omega;
        let chord = (c1 - self.b).length_squared();
        let u2 = if chord > 0.0 {
            (w - self.b).length_squared() / chord
        } else {
            0.0
        };
        DVec2::new(u1, u2)
    }
}

impl Warp for SphericalTriangle {
    type Point = Vec3;

    #[inline]
    fn sample(&self, u: Vec2) -> Vec3 {
        let exact = self.arvo.as_ref().map(|a| |u| a.sample(u, self.omega));
        self.planar.sample_with(u, exact)
    }

    /// 1/Ω per steradian on directions hitting the triangle (area fallback: d²/(A|cos θ′|)).
    #[inline]
    fn pdf(&self, w: Vec3) -> f32 {
        self.planar
            .pdf_with(w, self.arvo.as_ref().map(|_| self.omega))
    }
}

impl InvertibleWarp for SphericalTriangle {
    /// The `u` whose sample is the direction `w` (unit length expected; normalised here):
    /// the inverse of Arvo's map (see [`SphericalTriangle`]), or of the area fallback's
    /// `b₁ = 1 − √u₁, b₂ = u₂√u₁` on the point hit. Directions outside the triangle give
    /// values clamped into `[0, 1)²`.
    #[inline]
    fn invert(&self, w: Vec3) -> Vec2 {
        let dir = w.as_dvec3().normalize_or_zero();
        match &self.arvo {
            Some(arvo) => {
                let u = arvo.invert(dir, self.omega);
                clamp_unit_f64(u.x, u.y)
            }
            None => self.planar.invert_area(dir),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_exact_and_fallback() {
        for t in [
            SphericalTriangle::new(Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z).unwrap(),
            unit_tri(1.0),
            unit_tri(1000.0),
        ] {
            for i in 1..20 {
                for j in 1..20 {
                    let u = Vec2::new(i as f32 / 20.0, j as f32 / 20.0);
                    let back = t.invert(t.sample(u));
                    let err = (back - u).abs().max_element();
                    assert!(back.is_finite() && err < 1e-4, "{u}: {back}");
                }
            }
        }
    }

    fn unit_tri(dist: f32) -> SphericalTriangle {
        SphericalTriangle::new(
            Vec3::ZERO,
            Vec3::new(0.0, 0.0, dist),
            Vec3::new(1.0, 0.0, dist),
            Vec3::new(0.0, 1.0, dist),
        )
        .unwrap()
    }

    #[test]
    fn rejects_degenerate() {
        let (a, b) = (Vec3::X, Vec3::Y);
        assert!(SphericalTriangle::new(Vec3::Z, a, b, 2.0 * b - a).is_err()); // collinear
        assert!(SphericalTriangle::new(Vec3::ZERO, a, b, a + b).is_err()); // origin in plane
        assert!(SphericalTriangle::new(Vec3::NAN, a, b, Vec3::Z).is_err());
    }

    #[test]
    fn octant_has_solid_angle_pi_over_2() {
        let t = SphericalTriangle::new(Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z).unwrap();
        let want = std::f32::consts::FRAC_PI_2;
        assert!(t.solid_angle().is_finite() && (t.solid_angle() - want).abs() < 1e-6);
        assert!(!t.is_area_sampled());
        for u in [
            Vec2::ZERO,
            Vec2::splat(0.5),
            Vec2::new(0.999, 0.001),
            Vec2::ONE * 0.99999,
        ] {
            let (w, pdf) = t.sample_with_pdf(u);
            assert!(w.is_finite() && w.min_element() >= -1e-6, "{u}: {w}");
            assert!(
                pdf.is_finite() && (pdf * want - 1.0).abs() < 1e-5,
                "{u}: {pdf}"
            );
        }
    }

    #[test]
    fn distant_triangle_uses_area_fallback_consistently() {
        let t = unit_tri(1000.0);
        assert!(t.is_area_sampled());
        let (w, pdf) = t.sample_with_pdf(Vec2::new(0.2, 0.7));
        let (p, pdf_point) = t.sample_point(Vec2::new(0.2, 0.7)).unwrap();
        assert!(pdf.is_finite() && pdf > 0.0);
        assert!((pdf / pdf_point - 1.0).abs() < 1e-4, "{pdf} vs {pdf_point}");
        assert!(((p.normalize() - w).length()) < 1e-6);
        assert!((pdf * t.solid_angle() - 1.0).abs() < 1e-3);
    }

    #[test]
    fn misses_have_zero_pdf() {
        let t = unit_tri(1.0);
        assert_eq!(t.pdf(-Vec3::Z), 0.0);
        assert_eq!(t.pdf(Vec3::new(-0.5, -0.5, 1.0).normalize()), 0.0);
    }
}
