//! Helpers shared by the basic-warp tests (`warp_properties_basic`, `warp_accuracy_basic`):
//! parameters, tolerances, points seen in f64, and the numerical Jacobian.

use mcrt::glam::{DVec3, Vec2, Vec3};
use mcrt::sampling::warp::Warp;

/// Round-trip tests hold `invert(sample(u)) ≈ u` for u in `[INTERIOR, 1 − INTERIOR]²`.
pub const INTERIOR: f32 = 1e-3;
/// Interior round-trip tolerance (absolute, in u): 64 ulps of 1.
pub const RT_TOL: f64 = 4e-6;
/// Step of the central differences of the numerical Jacobian.
pub const JAC_H: f64 = 1e-3;
/// The Jacobian is checked for u in `[JAC_MARGIN, 1 − JAC_MARGIN]²`.
pub const JAC_MARGIN: f32 = 0.01;
/// Tolerance of `|pdf · J − 1|`.
pub const JAC_TOL: f64 = 1e-2;

/// Power-cosine exponents under test, extremes included.
pub const EXPONENTS: [f32; 5] = [0.0, 1.0, 10.0, 1e3, 1e6];
/// Cone half-angles under test (radians), extremes included.
pub const CONE_ANGLES: [f32; 5] = [
    1e-4,
    1e-2,
    1.0,
    std::f32::consts::FRAC_PI_2,
    std::f32::consts::PI,
];

/// Whether u lies within 4h (in u) of the concentric map's diagonals, where it has kinks.
pub fn near_concentric_diagonal(u: Vec2) -> bool {
    let (a, b) = (2.0 * f64::from(u.x) - 1.0, 2.0 * f64::from(u.y) - 1.0);
    (a.abs() - b.abs()).abs() < 8.0 * JAC_H
}

/// A point of a warp's domain, seen in f64 3D (planar points get z = 0).
pub trait Point: Copy + std::fmt::Debug {
    /// The point in f64, z = 0 for planar points.
    fn d3(self) -> DVec3;
    /// Whether the domain is planar.
    fn planar() -> bool;
}

impl Point for Vec2 {
    fn d3(self) -> DVec3 {
        DVec3::new(self.x.into(), self.y.into(), 0.0)
    }
    fn planar() -> bool {
        true
    }
}

impl Point for Vec3 {
    fn d3(self) -> DVec3 {
        self.as_dvec3()
    }
    fn planar() -> bool {
        false
    }
}

/// The angle between `p` and +z, from atan2 (accurate near the axis).
pub fn angle_to_z(p: DVec3) -> f64 {
    p.x.hypot(p.y).atan2(p.z)
}

/// The distance between two values of u₂ on the circle [0, 1).
pub fn circular_diff(a: f64, b: f64) -> f64 {
    let d = (a - b).abs();
    d.min(1.0 - d)
}

/// |det| of the numerical Jacobian of `w` at `u` (central differences, f64).
pub fn numerical_jacobian<W: Warp>(w: &W, u: Vec2) -> f64
where
    W::Point: Point,
{
    let at = |du1: f64, du2: f64| {
        let v = Vec2::new((f64::from(u.x) + du1) as f32, (f64::from(u.y) + du2) as f32);
        w.sample(v).d3()
    };
    let d1 = (at(JAC_H, 0.0) - at(-JAC_H, 0.0)) / (2.0 * JAC_H);
    let d2 = (at(0.0, JAC_H) - at(0.0, -JAC_H)) / (2.0 * JAC_H);
    if W::Point::planar() {
        (d1.x * d2.y - d1.y * d2.x).abs()
    } else {
        d1.cross(d2).dot(at(0.0, 0.0)).abs()
    }
}
