//! A small central-difference Jacobian in `f64` of a map from `[0,1)²` to points.

use super::point::StatPoint;
use glam::Vec2;

/// `J = √det(DᵀD)` of `sample` at `u` by central differences with step `h`, or `None` when
/// the stencil leaves `[0,1)²` or a sample is not finite. One-dimensional points use `u.x`
/// only (`J = |dx/du₁|`).
pub(crate) fn jacobian_f64<P: StatPoint>(
    sample: &impl Fn(Vec2) -> P,
    u: Vec2,
    h: f64,
) -> Option<f64> {
    let at = |dx: f64, dy: f64| -> Option<[f64; 3]> {
        let v = Vec2::new((f64::from(u.x) + dx) as f32, (f64::from(u.y) + dy) as f32);
        if !(v.x >= 0.0 && v.x < 1.0 && v.y >= 0.0 && v.y < 1.0) {
            return None;
        }
        let p = sample(v);
        p.is_finite_point().then(|| p.to_f64())
    };
    let diff = |a: [f64; 3], b: [f64; 3], step: f64| [0, 1, 2].map(|i| (a[i] - b[i]) / step);
    // The actual f32 step taken, so rounding of u ± h does not bias the derivative.
    let step_x = f64::from((f64::from(u.x) + h) as f32) - f64::from((f64::from(u.x) - h) as f32);
    let du = diff(at(h, 0.0)?, at(-h, 0.0)?, step_x);
    if P::DIM == 1 {
        return Some(du[0].abs());
    }
    let step_y = f64::from((f64::from(u.y) + h) as f32) - f64::from((f64::from(u.y) - h) as f32);
    let dv = diff(at(0.0, h)?, at(0.0, -h)?, step_y);
    let cross = [
        du[1] * dv[2] - du[2] * dv[1],
        du[2] * dv[0] - du[0] * dv[2],
        du[0] * dv[1] - du[1] * dv[0],
    ];
    Some(if P::DIM == 2 {
        cross[2].abs()
    } else {
        (cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]).sqrt()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polar_map_has_jacobian_pi() {
        // (r, φ) = (√u₁, 2πu₂) maps onto the unit disk with J = π everywhere.
        let disk = |u: Vec2| {
            let (r, phi) = (u.x.sqrt(), std::f32::consts::TAU * u.y);
            Vec2::new(r * phi.cos(), r * phi.sin())
        };
        let j = jacobian_f64(&disk, Vec2::new(0.4, 0.3), 1e-3).unwrap();
        assert!(
            j.is_finite() && (j - std::f64::consts::PI).abs() < 1e-3,
            "{j}"
        );
        assert_eq!(jacobian_f64(&disk, Vec2::new(0.0, 0.3), 1e-3), None);
    }
}
