//! Points the harness can bin and difference: `f32` (an interval), `Vec2` (the plane),
//! `Vec3` (directions) and `usize` (categories).

use glam::{Vec2, Vec3};

/// A point type the harness can convert to `f64` coordinates.
///
/// Implemented for `f32`, [`Vec2`], [`Vec3`] and `usize`; the Jacobian check uses
/// [`StatPoint::DIM`] to pick `|dx/du₁|`, `|det D|` or `‖∂p/∂u₁ × ∂p/∂u₂‖`.
pub trait StatPoint: Copy + Send + Sync + 'static {
    /// Number of coordinates (1, 2 or 3; 0 for categories).
    const DIM: usize;
    /// The coordinates in `f64`, unused ones 0.
    fn to_f64(self) -> [f64; 3];
    /// Whether every coordinate is finite.
    fn is_finite_point(self) -> bool {
        self.to_f64().iter().all(|c| c.is_finite())
    }
}

impl StatPoint for f32 {
    const DIM: usize = 1;
    fn to_f64(self) -> [f64; 3] {
        [f64::from(self), 0.0, 0.0]
    }
}

impl StatPoint for Vec2 {
    const DIM: usize = 2;
    fn to_f64(self) -> [f64; 3] {
        [f64::from(self.x), f64::from(self.y), 0.0]
    }
}

impl StatPoint for Vec3 {
    const DIM: usize = 3;
    fn to_f64(self) -> [f64; 3] {
        [f64::from(self.x), f64::from(self.y), f64::from(self.z)]
    }
}

impl StatPoint for usize {
    const DIM: usize = 0;
    fn to_f64(self) -> [f64; 3] {
        [self as f64, 0.0, 0.0]
    }
}
