//! Sampling a sphere by the cone of directions it subtends.
//!
//! From a reference point at distance `d > r` from the centre, the direction is uniform in
//! the cone of half-angle θ_max, `sin θ_max = r/d`: `1 − cos θ = u₁ (1 − cos θ_max)`,
//! azimuth `2π u₂`, pdf `1/(2π (1 − cos θ_max))` per steradian. The point is the nearer
//! intersection of that direction with the sphere, built from the angle α it makes at the
//! centre (between the normal and the way back to the reference) rather than by tracing:
//! `r cos α = d sin²θ + cos θ √(r² − d² sin²θ)` and `r sin α = sin θ · t` with the distance
//! `t = (d² − r²)/(d cos θ + √(r² − d² sin²θ))`, sums of non-negative terms that cancel
//! nowhere (derivation in `docs/geometry.md`, "Sphere lights: the point from the cone's
//! angle"). The point `c + r n` is then on the sphere to rounding, with no normalisation.
//! The cone needs only `d²`: `1 − cos θ_max = s²/(1 + √(1 − s²))` with `s² = r²/d²`.

use super::area_to_solid_angle;
use crate::geometry::ShapeSample;
use glam::{Vec2, Vec3};
use mcrt::sampling::warp::polar::azimuth_polynomial;
use mcrt::sampling::warp::{UniformSphere, Warp};
use mcrt::sampling::Frame;
use std::f32::consts::{PI, TAU};

/// A reference point closer to the centre than `radius · OUTSIDE` counts as inside.
const OUTSIDE: f32 = 1.0 + 1e-4;

/// The smallest `1 − cos θ_max` sampled by the cone (as
/// [`UniformCone`](mcrt::sampling::warp::UniformCone) accepts): narrower cones, and a
/// reference so far that `d²` overflows, fall back to sampling by area.
const MIN_ONE_MINUS_COS: f32 = 1e-30;

/// The cone a sphere subtends from a reference point outside it.
struct Cone {
    /// Centre minus reference.
    to_c: Vec3,
    /// `d²`, the squared distance from the reference to the centre.
    d2: f32,
    /// `r²`.
    r2: f32,
    /// `1 − cos θ_max`.
    one_minus_cos_max: f32,
}

impl Cone {
    /// The cone from `reference`, or `None` when the reference is inside (or on) the sphere,
    /// a coordinate is NaN, or the cone is too narrow for f32.
    #[inline]
    fn new(center: Vec3, radius: f32, reference: Vec3) -> Option<Self> {
        let to_c = center - reference;
        let d2 = to_c.length_squared();
        let r2 = radius * radius;
        if d2.is_nan() || d2 <= r2 * (OUTSIDE * OUTSIDE) {
            return None;
        }
        let s2 = r2 / d2;
        let one_minus_cos_max = s2 / (1.0 + (1.0 - s2).sqrt());
        (one_minus_cos_max >= MIN_ONE_MINUS_COS).then_some(Self {
            to_c,
            d2,
            r2,
            one_minus_cos_max,
        })
    }

    /// The density of every direction in the cone, `1/(2π(1 − cos θ_max))` per steradian.
    #[inline]
    fn pdf(&self) -> f32 {
        1.0 / (TAU * self.one_minus_cos_max)
    }
}

/// A point on the sphere for lighting `reference` (module docs) with its density per
/// steradian; `None` where that is not finite.
#[inline(always)]
pub(super) fn sample(
    center: Vec3,
    radius: f32,
    flip: bool,
    reference: Vec3,
    u: Vec2,
) -> Option<ShapeSample> {
    let front = |n: Vec3| if flip { -n } else { n };
    let Some(cone) = Cone::new(center, radius, reference) else {
        // Inside: uniform by area, converted.
        let n = UniformSphere.sample(u);
        let p = center + radius * n;
        let pdf = area_to_solid_angle(1.0 / (4.0 * PI * radius * radius), reference, p, n)?;
        return Some(ShapeSample {
            p,
            n: front(n),
            pdf,
        });
    };
    // The direction: 1 − cos θ = u₁ (1 − cos θ_max), sin²θ = (1 − cos θ)(1 + cos θ).
    let one_minus_cos = u.x * cone.one_minus_cos_max;
    let cos_theta = 1.0 - one_minus_cos;
    let sin2_theta = one_minus_cos * (2.0 - one_minus_cos);
    let sin_theta = sin2_theta.sqrt();
    // The nearer intersection by the angle α at the centre (module docs).
    let d = cone.d2.sqrt();
    let disc = (cone.r2 - cone.d2 * sin2_theta).max(0.0).sqrt();
    let dist = (cone.d2 - cone.r2) / (d * cos_theta + disc);
    let inv_r = 1.0 / radius;
    let cos_alpha = (d * sin2_theta + cos_theta * disc) * inv_r;
    let sin_alpha = sin_theta * dist * inv_r;
    // n = −cos α · axis + sin α · (cos φ s + sin φ t), the axis pointing to the centre.
    let axis = cone.to_c / d;
    let Frame { s, t, .. } = Frame::from_normal(axis);
    let (cos_phi, sin_phi) = azimuth_polynomial(u.y);
    let n = (s * cos_phi + t * sin_phi) * sin_alpha - axis * cos_alpha;
    let p = center + radius * n;
    // Finite for a finite sphere and reference (every factor above is bounded) unless the
    // coordinates overflow; one test of the sum catches that (an infinite or NaN
    // coordinate makes it infinite or NaN; it drops, harmlessly, a finite point whose
    // coordinates sum beyond f32::MAX).
    (p.x + p.y + p.z).is_finite().then(|| ShapeSample {
        p,
        n: front(n),
        pdf: cone.pdf(),
    })
}

/// The density of [`sample`] at point `p` of the sphere.
pub(super) fn pdf(center: Vec3, radius: f32, reference: Vec3, p: Vec3) -> Option<f32> {
    let Some(cone) = Cone::new(center, radius, reference) else {
        let n = (p - center).normalize_or_zero();
        return area_to_solid_angle(1.0 / (4.0 * PI * radius * radius), reference, p, n);
    };
    // Only the cap visible from the reference is ever sampled: (p − c)·(ref − c) ≥ r²
    // (with slack for rounding at the silhouette).
    let d = cone.d2.sqrt();
    let visible = -(p - center).dot(cone.to_c) >= cone.r2 - 1e-3 * radius * d;
    visible.then(|| cone.pdf())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiny_distant_sphere_samples_near_its_centre() {
        let c = Vec3::new(0.0, 0.0, 1e4);
        let s = sample(c, 1.0, false, Vec3::ZERO, Vec2::new(0.7, 0.2)).unwrap();
        assert!(s.p.is_finite() && s.pdf.is_finite());
        assert!(((s.p - c).length() - 1.0).abs() < 1e-3);
        assert!(s.n.z < 0.0, "the visible cap faces the reference");
        let omega = 2.0 * PI * (1.0 - (1.0f64 - 1e-8).sqrt()) as f32;
        assert!((s.pdf * omega - 1.0).abs() < 1e-3);
    }

    /// A sphere of radius 10⁻⁴ seen from afar and from just outside: samples on the sphere,
    /// finite, with the density `pdf` reports.
    #[test]
    fn tiny_spheres_stay_finite() {
        // (Coordinates of the sphere's size, so that f32's spacing of the point's
        // coordinates does not swamp the radius.)
        let c = Vec3::new(3e-4, 1e-4, -2e-4);
        let r = 1e-4;
        for reference in [
            c + Vec3::new(0.0, 10.0, 0.0),
            c - Vec3::new(0.0, 0.0, r * 1.01),
        ] {
            for u in [
                Vec2::ZERO,
                Vec2::new(0.5, 0.3),
                Vec2::splat(1.0 - f32::EPSILON / 2.0),
            ] {
                let smp = sample(c, r, true, reference, u).unwrap();
                assert!(smp.p.is_finite() && smp.n.is_finite() && smp.pdf.is_finite());
                assert!(
                    ((smp.p - c).length() / r - 1.0).abs() < 1e-3,
                    "{reference} {u}"
                );
                assert!((smp.n + (smp.p - c) / r).length() < 1e-3, "flipped normal");
                assert_eq!(Some(smp.pdf), pdf(c, r, reference, smp.p));
            }
        }
    }

    /// The sample lies on the sphere, on the cap visible from the reference, along a
    /// direction at the angle `1 − cos θ = u₁ (1 − cos θ_max)` from the axis, and its pdf is
    /// what `pdf` reports there, bit for bit: for a reference far away, at a few radii, and
    /// just outside the surface, with `u` at the ends of [0, 1).
    #[test]
    fn samples_lie_on_the_visible_cap_at_the_sampled_angle() {
        let c = Vec3::new(0.5, -1.0, 2.0);
        let r = 0.75;
        let top = 1.0 - f32::EPSILON / 2.0;
        for (reference, check_angle) in [
            (c + Vec3::new(0.0, 0.0, 30.0), true),
            (c + Vec3::new(1.0, 1.5, -0.5), true),
            (c + Vec3::new(0.0, r * 1.001, 0.0), true),
            (c + Vec3::new(r * 1.000_2, 0.0, 0.0), false),
        ] {
            let to_c = (c - reference).as_dvec3();
            let (d2, r2) = (to_c.length_squared(), f64::from(r * r));
            let s2 = r2 / d2;
            let omc = s2 / (1.0 + (1.0 - s2).sqrt());
            for ux in [0.0, 0.3, 0.9, top] {
                for uy in [0.0, 0.2, 0.7, top] {
                    let smp = sample(c, r, false, reference, Vec2::new(ux, uy)).unwrap();
                    assert!(smp.p.is_finite() && smp.n.is_finite() && smp.pdf.is_finite());
                    let on = (smp.p - c).length() / r - 1.0;
                    assert!(on.abs() < 1e-5, "{reference} {ux} {uy}: off by {on}");
                    assert!((smp.n - (smp.p - c) / r).length() < 1e-5);
                    assert_eq!(Some(smp.pdf), pdf(c, r, reference, smp.p));
                    if check_angle {
                        let w = (smp.p - reference).as_dvec3().normalize();
                        let got = 1.0 - w.dot(to_c.normalize());
                        let want = f64::from(ux) * omc;
                        assert!(
                            got.is_finite() && (got - want).abs() < 1e-4 * omc + 1e-7,
                            "{reference} {ux}: 1 - cos θ {got} against {want}"
                        );
                    }
                }
            }
        }
    }
}
