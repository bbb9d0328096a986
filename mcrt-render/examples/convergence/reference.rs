//! f64 reference versions of the crate's warps: the same mappings, evaluated in f64 with the
//! formulas that keep their digits (1 − cos θ from sin²(θ/2), `exp_m1`, `ln_1p`), so that
//! the error of the f32 warps can be measured against them. They live with the study, not in
//! the library.
//!
//! Each support is widened by [`RIM`] (relative), so a point our f32 warp rounds a hair
//! outside the rim is not counted as a support error.

use mcrt::glam::{DVec2, DVec3};
use std::f64::consts::{FRAC_1_PI, FRAC_PI_2, FRAC_PI_4, PI, TAU};

/// Relative widening of every support.
pub const RIM: f64 = 1e-6;

/// A warp evaluated in f64: points are [`DVec3`] (planar domains use `z = 0`).
pub trait Reference {
    /// The point for `u` and the density there.
    fn sample(&self, u: DVec2) -> (DVec3, f64);
    /// The density at `p` (directions need not be exactly unit length).
    fn pdf(&self, p: DVec3) -> f64;
}

/// `(cos φ, sin φ)` for `φ = 2π u`.
fn azimuth(u: f64) -> (f64, f64) {
    let (s, c) = (TAU * u).sin_cos();
    (c, s)
}

/// A unit direction from sin θ, cos θ and the azimuth parameter.
fn direction(sin_t: f64, cos_t: f64, u2: f64) -> DVec3 {
    let (c, s) = azimuth(u2);
    DVec3::new(sin_t * c, sin_t * s, cos_t)
}

/// 1 − cos θ of a direction, stable at both poles.
pub fn one_minus_cos(w: DVec3) -> f64 {
    let w = w.normalize();
    let s2 = w.x * w.x + w.y * w.y;
    if w.z > 0.0 {
        s2 / (1.0 + w.z)
    } else {
        1.0 - w.z
    }
}

/// The polar angle θ of a direction.
pub fn theta(w: DVec3) -> f64 {
    w.x.hypot(w.y).atan2(w.z)
}

/// Uniform disk, polar mapping: r = √u₁, φ = 2πu₂.
pub struct RefDisk;

impl Reference for RefDisk {
    fn sample(&self, u: DVec2) -> (DVec3, f64) {
        let r = u.x.sqrt();
        let (c, s) = azimuth(u.y);
        (DVec3::new(r * c, r * s, 0.0), FRAC_1_PI)
    }
    fn pdf(&self, p: DVec3) -> f64 {
        if p.x * p.x + p.y * p.y <= 1.0 + RIM {
            FRAC_1_PI
        } else {
            0.0
        }
    }
}

/// Shirley–Chiu concentric map of the square to the disk, as `(r, φ)`.
fn concentric(u: DVec2) -> (f64, f64) {
    let (a, b) = (2.0 * u.x - 1.0, 2.0 * u.y - 1.0);
    if a == 0.0 && b == 0.0 {
        (0.0, 0.0)
    } else if a.abs() > b.abs() {
        (a, FRAC_PI_4 * (b / a))
    } else {
        (b, FRAC_PI_2 - FRAC_PI_4 * (a / b))
    }
}

/// Uniform disk, concentric mapping.
pub struct RefConcentric;

impl Reference for RefConcentric {
    fn sample(&self, u: DVec2) -> (DVec3, f64) {
        let (r, phi) = concentric(u);
        let (s, c) = phi.sin_cos();
        (DVec3::new(r * c, r * s, 0.0), FRAC_1_PI)
    }
    fn pdf(&self, p: DVec3) -> f64 {
        RefDisk.pdf(p)
    }
}

/// Uniform triangle in barycentrics: (1 − √u₁, u₂√u₁), density 2.
pub struct RefTriangle;

impl Reference for RefTriangle {
    fn sample(&self, u: DVec2) -> (DVec3, f64) {
        let s = u.x.sqrt();
        (DVec3::new(1.0 - s, u.y * s, 0.0), 2.0)
    }
    fn pdf(&self, p: DVec3) -> f64 {
        if p.x >= -RIM && p.y >= -RIM && p.x + p.y <= 1.0 + RIM {
            2.0
        } else {
            0.0
        }
    }
}

/// Uniform hemisphere: 1 − cos θ = u₁.
pub struct RefUniformHemisphere;

impl Reference for RefUniformHemisphere {
    fn sample(&self, u: DVec2) -> (DVec3, f64) {
        let t = u.x;
        (direction((t * (2.0 - t)).sqrt(), 1.0 - t, u.y), 0.5 / PI)
    }
    fn pdf(&self, w: DVec3) -> f64 {
        if w.z >= 0.0 {
            0.5 / PI
        } else {
            0.0
        }
    }
}

/// Cosine-weighted hemisphere: concentric disk lifted to the hemisphere (Malley's method).
pub struct RefCosineHemisphere;

impl Reference for RefCosineHemisphere {
    fn sample(&self, u: DVec2) -> (DVec3, f64) {
        let (r, phi) = concentric(u);
        let (s, c) = phi.sin_cos();
        let z = ((1.0 - r.abs()) * (1.0 + r.abs())).max(0.0).sqrt();
        (DVec3::new(r * c, r * s, z), z * FRAC_1_PI)
    }
    fn pdf(&self, w: DVec3) -> f64 {
        let w = w.normalize();
        if w.z >= 0.0 {
            w.z * FRAC_1_PI
        } else {
            0.0
        }
    }
}

/// Uniform sphere: z = 1 − 2u₁.
pub struct RefSphere;

impl Reference for RefSphere {
    fn sample(&self, u: DVec2) -> (DVec3, f64) {
        let z = 1.0 - 2.0 * u.x;
        let sin_t = 2.0 * (u.x * (1.0 - u.x)).sqrt();
        (direction(sin_t, z, u.y), 0.25 / PI)
    }
    fn pdf(&self, _: DVec3) -> f64 {
        0.25 / PI
    }
}

/// Uniform cone of half-angle θmax: 1 − cos θ = u₁ (1 − cos θmax).
pub struct RefCone {
    omc_max: f64,
}

impl RefCone {
    /// The cone of half-angle `theta_max` radians.
    pub fn from_angle(theta_max: f64) -> Self {
        let h = (0.5 * theta_max).sin();
        Self {
            omc_max: 2.0 * h * h,
        }
    }
}

impl Reference for RefCone {
    fn sample(&self, u: DVec2) -> (DVec3, f64) {
        let t = u.x * self.omc_max;
        let w = direction((t * (2.0 - t)).sqrt(), 1.0 - t, u.y);
        (w, 1.0 / (TAU * self.omc_max))
    }
    fn pdf(&self, w: DVec3) -> f64 {
        if one_minus_cos(w) <= self.omc_max * (1.0 + RIM) {
            1.0 / (TAU * self.omc_max)
        } else {
            0.0
        }
    }
}

/// Power-cosine lobe (n + 1)/(2π) cosⁿθ: cos θ = u₁^(1/(n+1)).
pub struct RefPowerCosine {
    /// The exponent n.
    pub n: f64,
}

impl Reference for RefPowerCosine {
    fn sample(&self, u: DVec2) -> (DVec3, f64) {
        let l = u.x.ln() / (self.n + 1.0);
        let t = -l.exp_m1();
        let w = direction((t * (2.0 - t)).max(0.0).sqrt(), l.exp(), u.y);
        (w, (self.n + 1.0) / TAU * (self.n * l).exp())
    }
    fn pdf(&self, w: DVec3) -> f64 {
        if w.z < 0.0 {
            return 0.0;
        }
        let ln_cos = (-one_minus_cos(w)).ln_1p();
        (self.n + 1.0) / TAU * (self.n * ln_cos).exp()
    }
}

/// The θ/sin θ hemisphere: θ = (π/2)√u₁, density 4/π³ · θ / sin θ.
pub struct RefThetaOverSin;

fn theta_over_sin(t: f64) -> f64 {
    if t == 0.0 {
        1.0
    } else {
        t / t.sin()
    }
}

impl Reference for RefThetaOverSin {
    fn sample(&self, u: DVec2) -> (DVec3, f64) {
        let t = FRAC_PI_2 * u.x.sqrt();
        let (s, c) = t.sin_cos();
        (direction(s, c, u.y), 4.0 / PI.powi(3) * theta_over_sin(t))
    }
    fn pdf(&self, w: DVec3) -> f64 {
        if w.z < 0.0 {
            return 0.0;
        }
        4.0 / PI.powi(3) * theta_over_sin(theta(w))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn refs() -> Vec<Box<dyn Reference>> {
        vec![
            Box::new(RefUniformHemisphere),
            Box::new(RefCosineHemisphere),
            Box::new(RefSphere),
            Box::new(RefCone::from_angle(0.3)),
            Box::new(RefPowerCosine { n: 20.0 }),
            Box::new(RefThetaOverSin),
        ]
    }

    #[test]
    fn directions_are_unit_and_pdf_agrees_with_sample() {
        for r in refs() {
            for i in 0..10 {
                let u = DVec2::new((i as f64 + 0.3) / 10.0, (i as f64 + 0.7) / 10.0);
                let (w, p) = r.sample(u);
                let again = r.pdf(w);
                assert!(w.is_finite() && (w.length() - 1.0).abs() < 1e-14);
                assert!(p.is_finite() && again.is_finite() && ((again - p) / p).abs() < 1e-12);
            }
        }
    }

    /// The pdf is the reciprocal of the mapping's Jacobian determinant |∂w/∂u₁ × ∂w/∂u₂|,
    /// measured by central differences at interior points.
    #[test]
    fn pdf_is_the_inverse_jacobian() {
        let h = 1e-6;
        for r in refs() {
            for i in 1..8 {
                for j in 1..8 {
                    let u = DVec2::new(i as f64 / 8.0 + 0.01, j as f64 / 8.0 - 0.02);
                    let d = |e: DVec2| (r.sample(u + e).0 - r.sample(u - e).0) / (2.0 * h);
                    let jac = d(DVec2::new(h, 0.0)).cross(d(DVec2::new(0.0, h))).length();
                    let p = r.sample(u).1;
                    let err = (p * jac - 1.0).abs();
                    assert!(p.is_finite() && jac.is_finite() && err < 1e-6, "{u} {err}");
                }
            }
        }
    }

    #[test]
    fn tiny_cone_keeps_its_digits() {
        let cone = RefCone::from_angle(1e-4);
        let (rim, _) = cone.sample(DVec2::new(1.0, 0.0));
        assert!(((theta(rim) - 1e-4) / 1e-4).abs() < 1e-12);
        assert!(((one_minus_cos(rim) - cone.omc_max) / cone.omc_max).abs() < 1e-9);
    }
}
