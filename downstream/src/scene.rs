//! A scene of the user's own: a Lambertian ball inside a glowing Lambertian shell, with an
//! analytic answer at every path depth.
//!
//! The ball (radius `r`, albedo `ρᵢ`, not emitting) sits at the centre of the shell (radius
//! `R`, albedo `ρₒ`, emitting `Lₑ` inward). By symmetry every point of the shell has the same
//! outgoing radiance `Lₒ` in every direction, and so has every point of the ball (`Lᵢ`); the
//! ball sees nothing but the shell, and a point of the shell sees the ball with the form
//! factor `F = (r/R)²` (a sphere of radius `r` at distance `R` straight above a surface
//! element) and the shell elsewhere. So
//!
//! - `Lᵢ = ρᵢ Lₒ`,
//! - `Lₒ = Lₑ + ρₒ (F Lᵢ + (1 − F) Lₒ)`, i.e. `Lₒ = Lₑ / (1 − ρₒ (F ρᵢ + 1 − F))`.
//!
//! Along paths of at most `d` segments (the path tracer's `max_depth`), `Lᵢ⁽ᵈ⁾ = ρᵢ Lₒ⁽ᵈ⁻¹⁾`
//! and `Lₒ⁽ᵈ⁾ = Lₑ + ρₒ (F Lᵢ⁽ᵈ⁻¹⁾ + (1 − F) Lₒ⁽ᵈ⁻¹⁾)` with `Lᵢ⁽⁰⁾ = Lₒ⁽⁰⁾ = 0`
//! ([`Shell::ball_radiance`]).
//!
//! Lights: the shell, sampled uniformly by area (the ball occludes part of it from the
//! shell's own points, and the half behind the tangent plane from the ball's).

use mcrt::glam::{Vec2, Vec3};
use mcrt::integrator::BsdfFlags;
use mcrt::sampling::jacobian::solid_angle_pdf_from_area;
use mcrt::{
    Bsdf, BsdfSample, CosineHemisphere, Frame, LightSample, Scene, SurfacePoint, UniformSphere,
    Warp,
};
use std::f32::consts::PI;

/// A Lambertian BSDF, `f = albedo / π`, in mcrt's z-up shading frame (one-sided: the front
/// side, `z > 0`).
#[derive(Clone, Copy, Debug)]
pub struct Lambert {
    /// The albedo, in `[0, 1]`.
    pub albedo: f32,
}

impl Bsdf for Lambert {
    fn flags(&self) -> BsdfFlags {
        BsdfFlags {
            smooth: true,
            ..BsdfFlags::default()
        }
    }

    /// `f · cos θᵢ`.
    fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Vec3::ZERO;
        }
        Vec3::splat(self.albedo / PI * wi.z)
    }

    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z <= 0.0 {
            return 0.0;
        }
        CosineHemisphere.pdf(wi)
    }

    fn sample(&self, wo: Vec3, _u1: f32, u2: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let (wi, pdf) = CosineHemisphere.sample_with_pdf(u2);
        (pdf > 0.0).then_some(BsdfSample {
            wi,
            weight: Vec3::splat(self.albedo),
            pdf,
            delta: false,
            eta: 1.0,
        })
    }

    fn samples_component(&self) -> bool {
        false
    }
}

/// The `shape` index of the ball's surface points.
pub const BALL: u32 = 0;
/// The `shape` index of the shell's surface points.
pub const SHELL: u32 = 1;

/// A Lambertian ball at the origin inside a concentric glowing Lambertian shell (see the
/// module's documentation for the analytic answer).
#[derive(Clone, Copy, Debug)]
pub struct Shell {
    /// The ball's radius `r`.
    pub ball_radius: f32,
    /// The ball's material.
    pub ball: Lambert,
    /// The shell's radius `R > r`.
    pub shell_radius: f32,
    /// The shell's material (its inner side).
    pub shell: Lambert,
    /// The radiance `Lₑ` the shell emits inward.
    pub emitted: f32,
}

impl Shell {
    /// The form factor from a point of the shell to the ball, `(r/R)²`.
    pub fn form_factor(&self) -> f64 {
        (f64::from(self.ball_radius) / f64::from(self.shell_radius)).powi(2)
    }

    /// The radiance leaving the ball along paths of at most `max_depth` segments (counting
    /// the one that reaches the ball; −1: unlimited), `Lᵢ⁽ᵈ⁾`.
    pub fn ball_radiance(&self, max_depth: i32) -> f64 {
        let (le, rho_i, rho_o) = (
            f64::from(self.emitted),
            f64::from(self.ball.albedo),
            f64::from(self.shell.albedo),
        );
        let f = self.form_factor();
        match u32::try_from(max_depth) {
            Ok(d) => {
                let (mut ball, mut shell) = (0.0, 0.0);
                for _ in 0..d {
                    (ball, shell) = (rho_i * shell, le + rho_o * (f * ball + (1.0 - f) * shell));
                }
                ball
            }
            Err(_) => rho_i * le / (1.0 - rho_o * (f * rho_i + 1.0 - f)),
        }
    }

    /// The nearest hit beyond `t_min` of either sphere along `origin + t dir` (unit `dir`).
    fn hit(&self, origin: Vec3, dir: Vec3, t_min: f32) -> Option<SurfacePoint> {
        let mut best: Option<(f32, u32)> = None;
        for (shape, radius) in [(BALL, self.ball_radius), (SHELL, self.shell_radius)] {
            let b = origin.dot(dir);
            let c = origin.length_squared() - radius * radius;
            let disc = b * b - c;
            // No real root (or NaN): the ray misses this sphere.
            if disc.is_nan() || disc < 0.0 {
                continue;
            }
            let s = disc.sqrt();
            for t in [-b - s, -b + s] {
                if t > t_min && t.is_finite() && best.is_none_or(|(bt, _)| t < bt) {
                    best = Some((t, shape));
                }
            }
        }
        let (t, shape) = best?;
        let p = origin + t * dir;
        // Front sides: the ball's outside, the shell's inside.
        let outward = p.normalize();
        let ng = if shape == BALL { outward } else { -outward };
        Some(SurfacePoint {
            t,
            shape,
            ..SurfacePoint::new(p, ng, Frame::from_normal(ng))
        })
    }

    /// Density per steradian, seen from `from`, of the shell point `q` (front normal `nq`)
    /// sampled uniformly by area.
    fn shell_pdf(&self, from: Vec3, q: Vec3, nq: Vec3) -> f32 {
        let d = from - q;
        let dist_sq = d.length_squared();
        let cos_light = nq.dot(d) / dist_sq.sqrt();
        let area = 4.0 * PI * self.shell_radius * self.shell_radius;
        solid_angle_pdf_from_area(1.0 / area, dist_sq, cos_light)
    }
}

impl Scene for Shell {
    type Bsdf<'a> = &'a Lambert;

    fn intersect(&self, origin: Vec3, dir: Vec3, t_max: f32) -> Option<SurfacePoint> {
        self.hit(origin, dir, 0.0).filter(|h| h.t < t_max)
    }

    /// The origin moves off the surface, to the side `dir` leaves on.
    fn trace(&self, from: &SurfacePoint, dir: Vec3) -> Option<SurfacePoint> {
        let offset = 1e-4 * from.p.length().max(1.0);
        let side = if dir.dot(from.ng) >= 0.0 { 1.0 } else { -1.0 };
        self.hit(from.p + side * offset * from.ng, dir, 0.0)
    }

    fn occluded(&self, from: &SurfacePoint, dir: Vec3, dist: f32) -> bool {
        self.trace(from, dir).is_some_and(|h| h.t < dist)
    }

    fn bsdf(&self, sp: &SurfacePoint) -> &Lambert {
        if sp.shape == BALL {
            &self.ball
        } else {
            &self.shell
        }
    }

    fn is_emitter(&self, sp: &SurfacePoint) -> bool {
        sp.shape == SHELL
    }

    fn emitted(&self, sp: &SurfacePoint, wo: Vec3) -> Vec3 {
        if sp.shape == SHELL && sp.ng.dot(wo) > 0.0 {
            Vec3::splat(self.emitted)
        } else {
            Vec3::ZERO
        }
    }

    /// A point of the shell uniformly by area.
    fn sample_light(&self, from: &SurfacePoint, _u_pick: Vec2, u: Vec2) -> Option<LightSample> {
        let q = self.shell_radius * UniformSphere.sample(u);
        let to_light = q - from.p;
        let dist = to_light.length();
        if !(dist > 1e-6 && dist.is_finite()) {
            return None;
        }
        let wi = to_light / dist;
        let nq = -q / self.shell_radius;
        let pdf = self.shell_pdf(from.p, q, nq);
        let radiance = if nq.dot(-wi) > 0.0 {
            Vec3::splat(self.emitted)
        } else {
            Vec3::ZERO
        };
        (pdf > 0.0 && pdf.is_finite()).then_some(LightSample {
            wi,
            dist,
            radiance,
            pdf,
            delta: false,
        })
    }

    fn samples_light_choice(&self) -> bool {
        false
    }

    fn light_pdf(&self, from: &SurfacePoint, hit: &SurfacePoint) -> f32 {
        if hit.shape == SHELL {
            self.shell_pdf(from.p, hit.p, hit.ng)
        } else {
            0.0
        }
    }
}
