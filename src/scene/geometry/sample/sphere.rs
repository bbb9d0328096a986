//! Sampling a sphere by the cone of directions it subtends.

use super::area_to_solid_angle;
use crate::sampling::warp::{UniformCone, UniformSphere, Warp};
use crate::scene::geometry::ShapeSample;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// A reference point closer to the centre than `radius · (1 + INSIDE)` counts as inside.
const INSIDE: f32 = 1e-4;

/// The cone from `reference` that the sphere subtends, or `None` when the reference is
/// inside (or on) the sphere or the cone is too narrow for [`UniformCone`].
fn cone(center: Vec3, radius: f32, reference: Vec3) -> Option<(UniformCone, Vec3, f32)> {
    let to_c = center - reference;
    let d = to_c.length();
    if d.is_nan() || d <= radius * (1.0 + INSIDE) {
        return None;
    }
    let cone = UniformCone::from_sin_theta_max(radius / d).ok()?;
    Some((cone, to_c / d, d))
}

/// An orthonormal basis (s, t) completing the unit `n` (Duff et al. 2017, "Building an
/// Orthonormal Basis, Revisited", JCGT 6(1)).
fn basis(n: Vec3) -> (Vec3, Vec3) {
    let sign = 1.0f32.copysign(n.z);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    (
        Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x),
        Vec3::new(b, sign + n.y * n.y * a, -n.y),
    )
}

pub(super) fn sample(
    center: Vec3,
    radius: f32,
    flip: bool,
    reference: Vec3,
    u: Vec2,
) -> Option<ShapeSample> {
    let front = |n: Vec3| if flip { -n } else { n };
    let Some((cone, axis, d)) = cone(center, radius, reference) else {
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
    let w = cone.sample(u);
    let (s, t) = basis(axis);
    let dir = (s * w.x + t * w.y + axis * w.z).normalize();
    // Distance to the nearer intersection: d cos θ − √(r² − d² sin² θ), with sin² θ from
    // x² + y² (accurate for narrow cones).
    let sin2 = w.x * w.x + w.y * w.y;
    let disc = (radius * radius - d * d * sin2).max(0.0);
    let ds = d * w.z - disc.sqrt();
    let n = (reference + ds * dir - center).normalize_or(-axis);
    let p = center + radius * n;
    let pdf = 1.0 / cone.solid_angle();
    (p.is_finite() && pdf.is_finite()).then_some(ShapeSample {
        p,
        n: front(n),
        pdf,
    })
}

/// The density of [`sample`] at point `p` of the sphere.
pub(super) fn pdf(center: Vec3, radius: f32, reference: Vec3, p: Vec3) -> Option<f32> {
    let Some((cone, _, d)) = cone(center, radius, reference) else {
        let n = (p - center).normalize_or_zero();
        return area_to_solid_angle(1.0 / (4.0 * PI * radius * radius), reference, p, n);
    };
    // Only the cap visible from the reference is ever sampled: (p − c)·(ref − c) ≥ r²
    // (with slack for rounding at the silhouette).
    let visible = (p - center).dot(reference - center) >= radius * radius - 1e-3 * radius * d;
    visible.then(|| 1.0 / cone.solid_angle())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn basis_is_orthonormal() {
        for n in [
            Vec3::Z,
            -Vec3::Z,
            Vec3::new(0.6, 0.0, -0.8),
            Vec3::new(0.0, 1.0, 0.0),
        ] {
            let (s, t) = basis(n);
            assert!(s.is_finite() && t.is_finite());
            assert!(s.dot(t).abs() < 1e-6 && s.dot(n).abs() < 1e-6 && t.dot(n).abs() < 1e-6);
            assert!((s.length() - 1.0).abs() < 1e-6 && (t.length() - 1.0).abs() < 1e-6);
        }
    }

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
}
