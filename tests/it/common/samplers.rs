//! Samplers and pdfs written as closures, shared by the harness's own tests.

use mcrt::glam::{Vec2, Vec3};
use mcrt::stats::Rectangle;
use std::f32::consts::{FRAC_1_PI, TAU};

pub fn square() -> Rectangle {
    Rectangle::new(Vec2::splat(-1.0), Vec2::splat(1.0), 48, 48)
}

pub fn polar(r: f32, phi: f32) -> Vec2 {
    Vec2::new(r * phi.cos(), r * phi.sin())
}

pub fn disk_sqrt(u: Vec2) -> Vec2 {
    polar(u.x.sqrt(), TAU * u.y)
}

pub fn disk_pdf(p: Vec2) -> f32 {
    if p.length_squared() <= 1.0 {
        FRAC_1_PI
    } else {
        0.0
    }
}

pub fn cosine_hemisphere(u: Vec2) -> Vec3 {
    let d = disk_sqrt(u);
    Vec3::new(d.x, d.y, (1.0 - u.x).max(0.0).sqrt())
}

pub fn cosine_pdf(w: Vec3) -> f32 {
    w.z.max(0.0) * FRAC_1_PI
}

pub fn uniform_hemisphere_pdf(w: Vec3) -> f32 {
    if w.z >= 0.0 {
        0.5 * FRAC_1_PI
    } else {
        0.0
    }
}

pub fn triangle_pdf(b: Vec2) -> f32 {
    if b.x >= 0.0 && b.y >= 0.0 && b.x + b.y <= 1.0 {
        2.0
    } else {
        0.0
    }
}

/// A uniform cone of half-angle `theta_max` about `axis`, computed so that narrow cones are
/// exact: `1 − cos θ` is sampled directly and sin θ derived from it.
pub struct Cone {
    pub axis: Vec3,
    t: Vec3,
    b: Vec3,
    one_minus_cos_max: f32,
}

impl Cone {
    pub fn new(axis: Vec3, theta_max: f32) -> Self {
        let axis = axis.normalize();
        let (t, b) = axis.any_orthonormal_pair();
        let s = (0.5 * theta_max).sin();
        Self {
            axis,
            t,
            b,
            one_minus_cos_max: 2.0 * s * s,
        }
    }
    pub fn sample(&self, u: Vec2) -> Vec3 {
        let omc = u.x * self.one_minus_cos_max;
        let sin = (omc * (2.0 - omc)).sqrt();
        let phi = TAU * u.y;
        self.t * (sin * phi.cos()) + self.b * (sin * phi.sin()) + self.axis * (1.0 - omc)
    }
    pub fn pdf(&self, w: Vec3) -> f32 {
        // 1 − cos θ from the tangential components, stable near the axis.
        let (x, y) = (w.dot(self.t), w.dot(self.b));
        let s2 = x * x + y * y;
        let omc = if w.dot(self.axis) > 0.0 {
            s2 / (1.0 + (1.0 - s2).max(0.0).sqrt())
        } else {
            2.0
        };
        if omc <= self.one_minus_cos_max {
            1.0 / (TAU * self.one_minus_cos_max)
        } else {
            0.0
        }
    }
}
