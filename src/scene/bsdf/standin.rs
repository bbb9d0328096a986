//! Temporary stand-in for the microfacet warps (`Ggx`, `Beckmann`, `GgxVisible`,
//! `BeckmannVisible`) until branch warps-microfacet lands; deleted then.

use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// Isotropic microfacet distribution with Mitsuba's Smith G1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Ndf {
    pub(crate) ggx: bool,
    pub(crate) alpha: f32,
}

impl Ndf {
    /// Normal distribution D(m), per unit solid angle of m (projected area normalised).
    pub(crate) fn d(&self, m: Vec3) -> f32 {
        if m.z <= 0.0 {
            return 0.0;
        }
        let a2 = self.alpha * self.alpha;
        let c2 = m.z * m.z;
        let s2 = (m.x * m.x + m.y * m.y).max(0.0);
        if self.ggx {
            let x = s2 / a2 + c2;
            1.0 / (PI * a2 * x * x)
        } else {
            (-(s2 / c2) / a2).exp() / (PI * a2 * c2 * c2)
        }
    }

    /// Smith masking of one direction `v` for microfacet `m`.
    pub(crate) fn g1(&self, v: Vec3, m: Vec3) -> f32 {
        if v.dot(m) * v.z <= 0.0 {
            return 0.0;
        }
        let xy2 = (v.x * v.x + v.y * v.y) * self.alpha * self.alpha;
        if xy2 <= 0.0 {
            return 1.0;
        }
        let t2 = xy2 / (v.z * v.z);
        if self.ggx {
            2.0 / (1.0 + (1.0 + t2).sqrt())
        } else {
            let a = 1.0 / t2.sqrt();
            if a >= 1.6 {
                1.0
            } else {
                (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a)
            }
        }
    }

    /// Samples a microfacet normal seen from `wi` (`wi.z > 0`); GGX with visible normals
    /// (Heitz 2018), Beckmann from D(m) cos θ_m (stand-in).
    pub(crate) fn sample(&self, wi: Vec3, u: Vec2) -> Vec3 {
        let a = self.alpha;
        if self.ggx {
            let vh = Vec3::new(a * wi.x, a * wi.y, wi.z).normalize();
            let l2 = vh.x * vh.x + vh.y * vh.y;
            let t1 = if l2 > 0.0 {
                Vec3::new(-vh.y, vh.x, 0.0) / l2.sqrt()
            } else {
                Vec3::X
            };
            let t2v = vh.cross(t1);
            let r = u.x.sqrt();
            let (s, c) = (2.0 * PI * u.y).sin_cos();
            let p1 = r * c;
            let mut p2 = r * s;
            let sh = 0.5 * (1.0 + vh.z);
            p2 = (1.0 - sh) * (1.0 - p1 * p1).max(0.0).sqrt() + sh * p2;
            let nh = t1 * p1 + t2v * p2 + vh * (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt();
            Vec3::new(a * nh.x, a * nh.y, nh.z.max(1e-7)).normalize()
        } else {
            let t2 = -a * a * (1.0 - u.x).ln();
            let c = 1.0 / (1.0 + t2).sqrt();
            let s = (1.0 - c * c).max(0.0).sqrt();
            let (sp, cp) = (2.0 * PI * u.y).sin_cos();
            Vec3::new(s * cp, s * sp, c)
        }
    }

    /// Density of [`Ndf::sample`] per unit solid angle of m.
    pub(crate) fn pdf(&self, wi: Vec3, m: Vec3) -> f32 {
        if self.ggx {
            if wi.z <= 0.0 {
                return 0.0;
            }
            self.g1(wi, m) * wi.dot(m).max(0.0) * self.d(m) / wi.z
        } else {
            self.d(m) * m.z.max(0.0)
        }
    }
}
