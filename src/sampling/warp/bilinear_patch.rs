//! Area sampling of a bilinear patch (a quad whose corners need not be coplanar).

use glam::{DVec2, DVec3, Vec2, Vec3};

use super::linear::Bilinear;
use super::spherical_triangle::planar::widen;
use super::{InvertibleWarp, Warp};
use crate::sampling::SamplingError;

/// Relative tolerance under which the patch counts as a parallelogram (sampled uniformly in
/// its parameters, which is then exact).
const PARALLELOGRAM_TOL: f64 = 1e-9;

/// Points on the bilinear patch `p(s, t) = (1−s)(1−t) p₀₀ + s(1−t) p₁₀ + (1−s)t p₀₁ + st p₁₁`,
/// nearly uniform in area; pdf `b(s, t) / |∂p/∂s × ∂p/∂t|` per unit area (exact for this
/// sampler), with `b` the density of the parameters.
///
/// Mapping: a parallelogram is sampled uniformly in `(s, t) = u` (its area element is
/// constant, so the points are exactly uniform). Otherwise `(s, t)` is drawn with the
/// [`Bilinear`] density through the area elements `|∂p/∂s × ∂p/∂t|` at the four corners, which
/// follows the true area element closely (exactly where it is bilinear), so the points are
/// nearly uniform in area and the pdf above is the exact density of what is drawn. Inverse:
/// the patch parameters of the point (Gauss–Newton on `|p(s, t) − x|²`, a few steps), then
/// the bilinear inverse.
///
/// Citation: M. Pharr, W. Jakob, G. Humphreys, 2023, "Physically Based Rendering", 4th ed.,
/// §6.6.2 (sampling bilinear patches). Derivation: `docs/derivations.md`.
///
/// ```
/// use mcrt::glam::{Vec2, Vec3};
/// use mcrt::sampling::warp::{BilinearPatch, InvertibleWarp, Warp};
///
/// // A twisted quad: one corner lifted out of the plane.
/// let q = BilinearPatch::new([Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(1.0, 1.0, 0.5)]).unwrap();
/// let (p, pdf) = q.sample_with_pdf(Vec2::new(0.3, 0.6));
/// assert!(pdf > 0.0 && (q.pdf(p) - pdf).abs() < 1e-4 * pdf);
/// assert!((q.invert(p) - Vec2::new(0.3, 0.6)).length() < 1e-4);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BilinearPatch {
    /// `p₀₀, p₁₀, p₀₁, p₁₁` in f64.
    corners: [DVec3; 4],
    /// The parameter density: `None` for a parallelogram (uniform).
    weights: Option<Bilinear>,
    /// The size of the patch (its longest edge), for the on-surface test.
    scale: f64,
}

impl BilinearPatch {
    /// The patch through `[p₀₀, p₁₀, p₀₁, p₁₁]` (the corners at `(s, t)` = (0,0), (1,0),
    /// (0,1), (1,1)). Errors on non-finite corners or a patch of zero area.
    pub fn new(corners: [Vec3; 4]) -> Result<Self, SamplingError> {
        let names = ["p00", "p10", "p01", "p11"];
        let mut c = [DVec3::ZERO; 4];
        for k in 0..4 {
            c[k] = widen(names[k], corners[k])?;
        }
        let [p00, p10, p01, p11] = c;
        let scale = [p10 - p00, p01 - p00, p11 - p10, p11 - p01]
            .iter()
            .fold(0.0f64, |m, e| m.max(e.length()));
        let area = |a: DVec3, b: DVec3| a.cross(b).length();
        let j = [
            area(p10 - p00, p01 - p00),
            area(p10 - p00, p11 - p10),
            area(p11 - p01, p01 - p00),
            area(p11 - p01, p11 - p10),
        ];
        let top = j.iter().fold(0.0f64, |m, &v| m.max(v));
        if !(top > 1e-12 * scale * scale && top.is_finite()) {
            return Err(SamplingError::Degenerate {
                what: "the bilinear patch has zero area",
            });
        }
        let parallelogram = ((p11 - p10) - (p01 - p00)).length() <= PARALLELOGRAM_TOL * scale;
        let weights = if parallelogram {
            None
        } else {
            Some(Bilinear::new(j.map(|v| (v / top) as f32))?)
        };
        Ok(Self {
            corners: c,
            weights,
            scale,
        })
    }

    /// The point at parameters `(s, t)`.
    #[must_use]
    pub fn position(&self, st: Vec2) -> Vec3 {
        self.position_f64(st.as_dvec2()).as_vec3()
    }

    fn position_f64(&self, st: DVec2) -> DVec3 {
        let [p00, p10, p01, p11] = self.corners;
        let bottom = p00.lerp(p10, st.x);
        let top = p01.lerp(p11, st.x);
        bottom.lerp(top, st.y)
    }

    /// `(∂p/∂s, ∂p/∂t)` at `(s, t)`.
    fn tangents(&self, st: DVec2) -> (DVec3, DVec3) {
        let [p00, p10, p01, p11] = self.corners;
        let ds = (p10 - p00).lerp(p11 - p01, st.y);
        let dt = (p01 - p00).lerp(p11 - p10, st.x);
        (ds, dt)
    }

    /// The density of the sampled point per unit area at parameters `(s, t)`:
    /// `b(s, t) / |∂p/∂s × ∂p/∂t|` (0 where the area element vanishes).
    #[must_use]
    pub fn area_pdf_at(&self, st: Vec2) -> f32 {
        let (ds, dt) = self.tangents(st.as_dvec2());
        let element = ds.cross(dt).length();
        let b = self.weights.map_or(1.0, |w| f64::from(w.pdf(st)));
        let pdf = b / element;
        if element > 0.0 && pdf.is_finite() {
            pdf as f32
        } else {
            0.0
        }
    }

    /// The parameters `(s, t) ∈ [0, 1]²` of the patch point nearest `x`, by Gauss–Newton
    /// steps on `|p(s, t) − x|²` from the centre, and whether that point is within
    /// 10⁻⁵ of the patch's size of `x` (that is, whether `x` is on the patch).
    pub fn parameters_of(&self, x: Vec3) -> (Vec2, bool) {
        let x = x.as_dvec3();
        let mut st = DVec2::splat(0.5);
        for _ in 0..30 {
            let r = self.position_f64(st) - x;
            let (ds, dt) = self.tangents(st);
            let (a, b, c) = (ds.dot(ds), ds.dot(dt), dt.dot(dt));
            let det = a * c - b * b;
            if det.is_nan() || det <= 0.0 {
                break;
            }
            let (gs, gt) = (ds.dot(r), dt.dot(r));
            let step = DVec2::new((c * gs - b * gt) / det, (a * gt - b * gs) / det);
            let next = (st - step).clamp(DVec2::ZERO, DVec2::ONE);
            let moved = (next - st).length();
            st = next;
            if moved.is_nan() || moved <= 1e-13 {
                break;
            }
        }
        let on = (self.position_f64(st) - x).length() <= 1e-5 * self.scale;
        (st.as_vec2(), on && st.is_finite())
    }
}

impl Warp for BilinearPatch {
    type Point = Vec3;

    #[inline]
    fn sample(&self, u: Vec2) -> Vec3 {
        let st = self.weights.map_or(u, |w| w.sample(u));
        self.position(st)
    }

    /// `b(s, t)/|∂p/∂s × ∂p/∂t|` per unit area at the parameters of `p` when `p` lies on the
    /// patch, else 0.
    #[inline]
    fn pdf(&self, p: Vec3) -> f32 {
        if !p.is_finite() {
            return 0.0;
        }
        match self.parameters_of(p) {
            (st, true) => self.area_pdf_at(st),
            _ => 0.0,
        }
    }

    #[inline]
    fn sample_with_pdf(&self, u: Vec2) -> (Vec3, f32) {
        let st = self.weights.map_or(u, |w| w.sample(u));
        (self.position(st), self.area_pdf_at(st))
    }
}

impl InvertibleWarp for BilinearPatch {
    #[inline]
    fn invert(&self, p: Vec3) -> Vec2 {
        let (st, _) = self.parameters_of(p);
        let st = st.clamp(Vec2::ZERO, Vec2::splat(crate::sampling::ONE_MINUS_EPSILON));
        self.weights.map_or(st, |w| w.invert(st))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parallelogram_is_uniform_and_round_trips() {
        let q = BilinearPatch::new([Vec3::ZERO, 2.0 * Vec3::X, Vec3::Y, Vec3::new(2.0, 1.0, 0.0)])
            .unwrap();
        for i in 1..10 {
            for j in 1..10 {
                let u = Vec2::new(i as f32 / 10.0, j as f32 / 10.0);
                let (p, pdf) = q.sample_with_pdf(u);
                assert!(pdf.is_finite() && (pdf - 0.5).abs() < 1e-6, "{pdf}");
                assert!((q.invert(p) - u).abs().max_element() < 1e-5);
            }
        }
        assert_eq!(q.pdf(Vec3::new(0.5, 0.5, 1.0)), 0.0);
        assert!(BilinearPatch::new([Vec3::ZERO, Vec3::X, 2.0 * Vec3::X, 3.0 * Vec3::X]).is_err());
    }
}
