//! Textbook f32 formulations, for contrast with the crate's stable ones: cos θ computed
//! first and sin θ recovered from it as √(1 − cos²θ), which throws away the digits of
//! 1 − cos θ near the pole.

use mcrt::glam::{Vec2, Vec3};
use mcrt::sampling::warp::Warp;
use std::f32::consts::TAU;

fn direction(sin_t: f32, cos_t: f32, u2: f32) -> Vec3 {
    let (s, c) = (TAU * u2).sin_cos();
    Vec3::new(sin_t * c, sin_t * s, cos_t)
}

/// Uniform cone, naive: cos θ = 1 − u₁ (1 − cos θmax) with cos θmax stored in f32.
pub struct NaiveCone {
    cos_max: f32,
}

impl NaiveCone {
    /// The cone of half-angle `theta_max`.
    pub fn from_angle(theta_max: f32) -> Self {
        Self {
            cos_max: theta_max.cos(),
        }
    }
}

impl Warp for NaiveCone {
    type Point = Vec3;
    fn sample(&self, u: Vec2) -> Vec3 {
        let z = 1.0 - u.x * (1.0 - self.cos_max);
        direction((1.0 - z * z).max(0.0).sqrt(), z, u.y)
    }
    fn pdf(&self, w: Vec3) -> f32 {
        if w.z >= self.cos_max {
            1.0 / (TAU * (1.0 - self.cos_max))
        } else {
            0.0
        }
    }
}

/// Power-cosine lobe, naive: cos θ = u₁^(1/(n+1)), density (n + 1)/(2π) · zⁿ via `powf`.
pub struct NaivePowerCosine {
    /// The exponent n.
    pub n: f32,
}

impl Warp for NaivePowerCosine {
    type Point = Vec3;
    fn sample(&self, u: Vec2) -> Vec3 {
        let z = u.x.powf(1.0 / (self.n + 1.0));
        direction((1.0 - z * z).max(0.0).sqrt(), z, u.y)
    }
    fn pdf(&self, w: Vec3) -> f32 {
        if w.z >= 0.0 {
            (self.n + 1.0) / TAU * w.z.powf(self.n)
        } else {
            0.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The failure the study documents: a 1e-4 rad cone collapses in f32 (cos θmax rounds to
    /// 1, so every sample is the pole and the pdf is infinite).
    #[test]
    fn tiny_naive_cone_collapses() {
        let cone = NaiveCone::from_angle(1e-4);
        let w = cone.sample(Vec2::new(0.9, 0.3));
        assert!(w.is_finite() && w.x == 0.0 && w.y == 0.0);
        assert!(cone.pdf(w).is_infinite());
    }

    #[test]
    fn wide_naive_cone_is_fine() {
        let cone = NaiveCone::from_angle(1.0);
        let w = cone.sample(Vec2::new(1.0, 0.0));
        assert!(w.is_finite() && (w.z - 1f32.cos()).abs() < 1e-6);
    }
}
