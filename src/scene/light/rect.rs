//! A rectangle light sampled uniformly by area, with everything that does not depend on the
//! shading point computed once per scene.

use crate::integrator::{is_positive, LightSample};
use crate::sampling::warp::RectangleFrame;
use glam::{Vec2, Vec3};

/// The rectangle `corner + s·ex + t·ey`, s, t ∈ [0, 1], of an area light, with its unit
/// front normal and its area: the data [`crate::scene::geometry::ShapeSampling::Area`]
/// sampling needs, extracted once so that a light sample is a few dozen instructions (no
/// shape lookup, no per-call normal, no `Option` chain through the geometry).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct AreaRect {
    corner: Vec3,
    ex: Vec3,
    ey: Vec3,
    /// Unit normal of the front (emitting) side.
    n: Vec3,
    /// Area density 1/A.
    inv_area: f32,
    /// A bound on the magnitude of the rectangle's coordinates: `|corner|∞ + |ex| + |ey|`.
    reach: f32,
}

/// Relative margin of [`AreaRect::surely_behind`]: about a thousand times the `f32` rounding of the
/// quantities it bounds.
const BEHIND_MARGIN: f32 = 1e-4;

/// A direction toward a point of the rectangle: unit `wi`, distance, and the density per
/// unit solid angle at the shading point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct RectSample {
    pub wi: Vec3,
    pub dist: f32,
    pub pdf: f32,
}

impl AreaRect {
    /// The rectangle from its corner, edges, front normal and area; `None` without area.
    pub(super) fn new([corner, ex, ey]: [Vec3; 3], n: Vec3, area: f32) -> Option<Self> {
        let ok = area.is_finite() && area > 0.0 && n.is_finite() && n != Vec3::ZERO;
        ok.then(|| Self {
            corner,
            ex,
            ey,
            n,
            inv_area: 1.0 / area,
            reach: corner.abs().max_element() + ex.length() + ey.length(),
        })
    }

    /// The unit normal of the front (emitting) side.
    #[inline]
    pub(super) fn normal(&self) -> Vec3 {
        self.n
    }

    /// Whether `from` lies behind the emitting side's plane by clearly more than rounding:
    /// then every point of the rectangle is seen from behind, and every way of sampling it
    /// (by area here, by solid angle through the geometry) rejects the sample. The margin,
    /// [`BEHIND_MARGIN`] times `1 + |from|∞ + reach`, exceeds the rounding of the sampled
    /// point, of the normal and of the dot products by orders of magnitude, so a point
    /// reported here would be rejected by the full computation too.
    #[inline]
    pub(super) fn surely_behind(&self, from: Vec3) -> bool {
        let h = (from - self.corner).dot(self.n);
        h < -BEHIND_MARGIN * (1.0 + from.abs().max_element() + self.reach)
    }

    /// A point uniform by area (`u` ↦ corner + u.x·ex + u.y·ey, as the geometry's area
    /// sampling of a rectangle), seen from `from`: `p_ω = d² / (A · cos θ')`, θ' between
    /// the front normal and the way back. `None` when the point is on or behind the
    /// emitting side's plane as seen from `from`, or the density is not finite.
    #[inline]
    pub(super) fn sample(&self, from: Vec3, u: Vec2) -> Option<RectSample> {
        let p = self.corner + u.x * self.ex + u.y * self.ey;
        let d = p - from;
        let dist2 = d.length_squared();
        let dist = dist2.sqrt();
        let wi = d / dist;
        let cos = -self.n.dot(wi);
        // Also rejects NaN (`from` on the sampled point).
        if !is_positive(cos) {
            return None;
        }
        let pdf = dist2 * self.inv_area / cos;
        (pdf.is_finite() && pdf > 0.0).then_some(RectSample { wi, dist, pdf })
    }
}

/// A direction toward the rectangle of `frame` (unit front normal `n`) sampled by solid angle
/// from `from`, exactly as `Geometry::sample_shape` and `sample_shape_light` do for a
/// rectangle light chosen with probability 1, without the shape lookup, the per-call front
/// normal and the `Option` chain. The outer `None`: the warp cannot be built from `from`
/// (the geometry then samples by area; the caller takes that path).
#[inline]
pub(super) fn solid_angle_sample(
    frame: &RectangleFrame,
    n: Vec3,
    radiance: Vec3,
    from: Vec3,
    u: Vec2,
) -> Option<Option<LightSample>> {
    let sr = frame.seen_from(from).ok()?;
    let Some((p, pdf)) = sr.sample_point(u) else {
        return Some(None);
    };
    // The checks of the shape sample, then those of the light sample (in that order).
    if !(pdf.is_finite() && pdf > 0.0) {
        return Some(None);
    }
    let d = p - from;
    let dist = d.length();
    if !is_positive(dist) {
        return Some(None);
    }
    let wi = d / dist;
    if n.dot(wi) >= 0.0 || !is_positive(pdf) || !pdf.is_finite() {
        return Some(None);
    }
    Some(Some(LightSample {
        wi,
        dist,
        radiance,
        pdf: pdf * 1.0,
        delta: false,
    }))
}

#[cfg(test)]
mod tests {
    use super::super::{sample_shape_light, Light, Lights};
    use super::*;
    use crate::integrator::{Frame, SurfacePoint};
    use crate::scene::geometry::{AccelKind, Geometry, ShapeSampling};

    fn cornell(sampling: ShapeSampling) -> (Geometry, Lights) {
        let desc = crate::scene::cornell_box::cornell_box();
        let geo = Geometry::new(&desc.shapes, None, AccelKind::Bvh)
            .unwrap()
            .with_shape_sampling(sampling);
        let lights = Lights::new(&desc, &geo, 10.0).unwrap();
        (geo, lights)
    }

    fn point(p: Vec3) -> SurfacePoint {
        SurfacePoint {
            p,
            ng: Vec3::Y,
            frame: Frame::from_normal(Vec3::Y),
            t: 1.0,
            shape: 0,
            prim: 0,
            uv: Vec2::ZERO,
        }
    }

    fn close(a: f32, b: f32, rel: f32) -> bool {
        a.is_finite() && b.is_finite() && (a - b).abs() <= rel * a.abs().max(b.abs())
    }

    /// The precomputed rectangle gives the same direction, distance and density as sampling
    /// the shape through the geometry, and its density is what `pdf_hit` reports for the
    /// point a ray in that direction hits.
    #[test]
    fn fast_rectangle_matches_geometry_sampling() {
        let (geo, lights) = cornell(ShapeSampling::Area);
        let (i, shape, radiance) = lights
            .lights()
            .iter()
            .enumerate()
            .find_map(|(i, l)| match *l {
                Light::Area { shape, radiance } => Some((i, shape, radiance)),
                _ => None,
            })
            .unwrap();
        assert!(lights.single && lights.rects[i].is_some() && lights.only_rect.is_some());
        let froms = [
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(-0.9, 0.5, 0.3),
            Vec3::new(0.7, 1.5, -0.8),
        ];
        let mut checked = 0;
        for from in froms {
            let sp = point(from);
            for k in 0..64 {
                let u = Vec2::new((k % 8) as f32 / 8.0 + 0.03, (k / 8) as f32 / 8.0 + 0.05);
                let fast = lights.sample(&geo, &sp, Vec2::new(0.4, 0.6), u);
                let slow = sample_shape_light(&geo, shape, radiance, from, (0.6, u), 1.0);
                let (Some(f), Some(s)) = (fast, slow) else {
                    assert_eq!(fast.is_some(), slow.is_some(), "{from} {u}");
                    continue;
                };
                assert!((f.wi - s.wi).length() < 1e-5 && close(f.dist, s.dist, 1e-5));
                assert!(close(f.pdf, s.pdf, 1e-4), "{} vs {}", f.pdf, s.pdf);
                assert_eq!(f.radiance, radiance);
                let p = from + f.wi * f.dist;
                let mut hit = point(p);
                (hit.ng, hit.shape) = (geo.parallelogram(shape).unwrap().1, shape);
                let back = lights.pdf_hit(&geo, &sp, &hit);
                assert!(close(back, f.pdf, 1e-4), "{back} vs {}", f.pdf);
                checked += 1;
            }
        }
        assert!(checked > 100, "{checked}");
    }

    /// Shading points over the whole Cornell box, on the ceiling (behind the light), in and
    /// next to the light's plane, and on the light.
    fn box_points() -> Vec<Vec3> {
        let mut v = Vec::new();
        for i in 0..6 {
            for j in 0..7 {
                for k in 0..6 {
                    let y = [0.0, 0.4, 0.98, 0.99, 0.990001, 0.995, 1.0][j];
                    v.push(Vec3::new(-1.0 + 0.4 * i as f32, y, -1.0 + 0.4 * k as f32));
                }
            }
        }
        v.extend([Vec3::new(0.0, 0.99, 0.0), Vec3::new(0.1, 0.99, -0.05)]);
        v
    }

    /// With solid-angle sampling the light's own path (a frame built once, points clearly
    /// behind skipped) gives exactly the geometry's sample, bit for bit, everywhere.
    #[test]
    fn solid_angle_sampling_is_the_geometrys_bit_for_bit() {
        let (geo, lights) = cornell(ShapeSampling::SolidAngle);
        let Light::Area { shape, radiance } = lights.lights()[0] else {
            panic!("the Cornell box's light is an area light");
        };
        let (mut some, mut none) = (0, 0);
        for from in box_points() {
            let sp = point(from);
            for k in 0..25 {
                let u = Vec2::new((k % 5) as f32 / 5.0 + 0.07, (k / 5) as f32 / 5.0 + 0.11);
                let got = lights.sample(&geo, &sp, Vec2::new(0.5, 0.5), u);
                let want = sample_shape_light(&geo, shape, radiance, from, (0.5, u), 1.0);
                assert_eq!(got, want, "from {from} u {u}");
                if let Some(s) = got {
                    assert!(s.pdf.is_finite() && s.pdf > 0.0 && s.wi.is_finite());
                    some += 1;
                } else {
                    none += 1;
                }
            }
        }
        assert!(some > 1000 && none > 500, "{some} samples, {none} rejected");
    }

    /// A point reported clearly behind the light gets no sample from any strategy; points
    /// in front or in the plane are never reported.
    #[test]
    fn surely_behind_only_where_every_sample_is_rejected() {
        let (geo, lights) = cornell(ShapeSampling::SolidAngle);
        let (r, radiance) = lights.only_rect.unwrap();
        let Light::Area { shape, .. } = lights.lights()[0] else {
            panic!("the Cornell box's light is an area light");
        };
        let mut behind = 0;
        for from in box_points() {
            let in_front_or_plane = from.y <= 0.990001;
            if !r.surely_behind(from) {
                continue;
            }
            assert!(!in_front_or_plane, "{from}");
            behind += 1;
            for k in 0..25 {
                let u = Vec2::new((k % 5) as f32 / 5.0 + 0.07, (k / 5) as f32 / 5.0 + 0.11);
                assert!(r.sample(from, u).is_none(), "{from} {u}");
                let slow = sample_shape_light(&geo, shape, radiance, from, (0.5, u), 1.0);
                assert!(slow.is_none(), "{from} {u}");
            }
        }
        assert!(behind >= 72, "{behind} points behind");
    }

    /// `u_pick` is read only with a light on a triangle mesh (the choice among several
    /// lights reuses `u.x`).
    #[test]
    fn light_choice_is_drawn_only_when_read() {
        use crate::scene::description::{EmitterDesc, ShapeKind};
        let (_, lights) = cornell(ShapeSampling::Area);
        assert!(!lights.reads_pick(), "one rectangle light");
        let mut desc = crate::scene::cornell_box::cornell_box();
        let i = desc
            .shapes
            .iter()
            .position(|s| s.emitter.is_some())
            .unwrap();
        desc.shapes[i].kind = ShapeKind::Cube;
        let geo = Geometry::new(&desc.shapes, None, AccelKind::Bvh).unwrap();
        assert!(
            Lights::new(&desc, &geo, 10.0).unwrap().reads_pick(),
            "a cube light"
        );
        desc.shapes[i].kind = ShapeKind::Rectangle;
        desc.emitters.push(EmitterDesc::Point {
            position: Vec3::Y,
            intensity: Vec3::ONE,
        });
        let geo = Geometry::new(&desc.shapes, None, AccelKind::Bvh).unwrap();
        assert!(
            !Lights::new(&desc, &geo, 10.0).unwrap().reads_pick(),
            "two lights"
        );
    }

    #[test]
    fn rejects_no_area_and_the_back_side() {
        let par = [Vec3::ZERO, Vec3::X, Vec3::Z];
        assert!(AreaRect::new(par, -Vec3::Y, 0.0).is_none());
        assert!(AreaRect::new(par, Vec3::ZERO, 1.0).is_none());
        let r = AreaRect::new(par, -Vec3::Y, 1.0).unwrap();
        let u = Vec2::new(0.5, 0.5);
        let below = r.sample(Vec3::new(0.5, -1.0, 0.5), u).unwrap();
        assert!(below.pdf.is_finite() && (below.pdf - 1.0).abs() < 1e-6);
        assert!((below.wi - Vec3::Y).length() < 1e-6 && (below.dist - 1.0).abs() < 1e-6);
        assert!(r.sample(Vec3::new(0.5, 1.0, 0.5), u).is_none(), "back side");
        assert!(
            r.sample(Vec3::new(0.5, 0.0, 0.5), u).is_none(),
            "on the point"
        );
        assert!(
            r.sample(Vec3::new(3.0, 0.0, 0.5), u).is_none(),
            "in the plane"
        );
    }
}
