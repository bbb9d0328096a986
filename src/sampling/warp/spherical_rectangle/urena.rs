//! Ureña, Fajardo & King's parametrisation of a rectangle's solid angle, set up for one
//! reference point from a precomputed [`RectangleFrame`].

use std::f64::consts::TAU;

use glam::{DVec2, DVec3};

use super::super::spherical_triangle::planar::triangle_solid_angle;
use super::{RectangleFrame, SPHERICAL_RECTANGLE_MIN_SOLID_ANGLE};

/// cos and sin of [`SPHERICAL_RECTANGLE_MIN_ANGLE`](super::SPHERICAL_RECTANGLE_MIN_ANGLE) (`1e-3_f32` widened to `f64`), to compare an angle given
/// by its (cos, sin) pair with the threshold without an `atan2`.
const COS_MIN_ANGLE: f64 = 0.999_999_499_999_994_2;
const SIN_MIN_ANGLE: f64 = 9.999_998_808_307_693e-4;

/// Precomputed quantities of Ureña et al.'s method, in the rectangle's local frame where the
/// rectangle is [x0, x1] × [y0, y1] at height z0 < 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Urena {
    frame: [DVec3; 3],
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    z0: f64,
    /// n0.z and n2.z (normals of the planes through the edges y = y0 and y = y1).
    b0: f64,
    b1: f64,
    /// 2π − γ2 − γ3.
    k: f64,
    /// The solid angle S = Σγ − 2π.
    pub(super) omega: f64,
}

/// The interior angle between the planes with unit normals `a` and `b` as the unit complex
/// number (cos γ, sin γ) = (−a·b, |a×b|).
#[inline]
fn corner(a: DVec3, b: DVec3) -> DVec2 {
    DVec2::new(-a.dot(b), a.cross(b).length())
}

/// Complex product: the angles add.
#[inline]
fn mul(a: DVec2, b: DVec2) -> DVec2 {
    DVec2::new(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x)
}

/// The argument of `z` in [0, 2π).
#[inline]
fn arg(z: DVec2) -> f64 {
    let a = z.y.atan2(z.x);
    if a < 0.0 {
        a + TAU
    } else {
        a
    }
}

/// Whether the angle (cos γ, sin γ), γ ∈ [0, π], is at least the minimum interior angle:
/// sin(γ − γ_min) ≥ 0.
#[inline]
fn wide_enough(z: DVec2) -> bool {
    z.y * COS_MIN_ANGLE - z.x * SIN_MIN_ANGLE >= 0.0
}

impl Urena {
    /// The constants for `origin`, or `None` when the fallback applies: the solid angle
    /// below [`SPHERICAL_RECTANGLE_MIN_SOLID_ANGLE`], an interior angle below
    /// [`SPHERICAL_RECTANGLE_MIN_ANGLE`](super::SPHERICAL_RECTANGLE_MIN_ANGLE), or a
    /// non-finite value.
    ///
    /// The four interior angles γᵢ ∈ (0, π) are kept as unit complex numbers; the sums
    /// γ0 + γ1 and γ2 + γ3 lie in (0, 2π) and come from one `atan2` each (instead of four),
    /// and S = (γ0 + γ1) + (γ2 + γ3) − 2π.
    #[inline]
    pub(super) fn new(f: &RectangleFrame, origin: DVec3) -> Option<Self> {
        let d = f.planar.p0 - origin;
        let (x0, y0, mut z0) = (d.dot(f.x), d.dot(f.y), d.dot(f.z));
        let mut z = f.z;
        if z0 > 0.0 {
            z0 = -z0;
            z = -z;
        }
        let (x1, y1) = (x0 + f.lx, y0 + f.ly);
        let n0 = DVec3::new(0.0, z0, -y0).normalize();
        let n1 = DVec3::new(-z0, 0.0, x1).normalize();
        let n2 = DVec3::new(0.0, -z0, y1).normalize();
        let n3 = DVec3::new(z0, 0.0, -x0).normalize();
        let g = [
            corner(n0, n1),
            corner(n1, n2),
            corner(n2, n3),
            corner(n3, n0),
        ];
        // Non-short-circuit `&`: four cheap tests, no branches.
        if !(wide_enough(g[0]) & wide_enough(g[1]) & wide_enough(g[2]) & wide_enough(g[3])) {
            return None;
        }
        let g23 = arg(mul(g[2], g[3]));
        let s = arg(mul(g[0], g[1])) + g23 - TAU;
        let usable = s.is_finite() && s >= f64::from(SPHERICAL_RECTANGLE_MIN_SOLID_ANGLE);
        usable.then_some(Self {
            frame: [f.x, f.y, z],
            x0,
            x1,
            y0,
            y1,
            z0,
            b0: n0.z,
            b1: n2.z,
            k: TAU - g23,
            omega: s,
        })
    }

    /// The local (x, y) of the sampled point: x by the solid-angle fraction u₁, y by u₂.
    #[inline]
    fn sample_local(&self, u: DVec2) -> (f64, f64) {
        let au = u.x * self.omega + self.k;
        let (sin_au, cos_au) = au.sin_cos();
        let fu = (cos_au * self.b0 - self.b1) / sin_au;
        let cu = (fu.signum() / (fu * fu + self.b0 * self.b0).sqrt()).clamp(-1.0, 1.0);
        let xu = -(cu * self.z0) / ((1.0 - cu) * (1.0 + cu)).sqrt();
        let xu = if xu.is_nan() {
            self.x0
        } else {
            xu.clamp(self.x0, self.x1)
        };
        let d2 = xu * xu + self.z0 * self.z0;
        let h0 = self.y0 / (d2 + self.y0 * self.y0).sqrt();
        let h1 = self.y1 / (d2 + self.y1 * self.y1).sqrt();
        let hv = h0 + u.y * (h1 - h0);
        let one_minus_hv2 = (1.0 - hv) * (1.0 + hv);
        let yv = if one_minus_hv2 > 1e-30 {
            (hv * d2.sqrt() / one_minus_hv2.sqrt()).clamp(self.y0, self.y1)
        } else {
            self.y1
        };
        (xu, yv)
    }

    /// The inverse of [`Urena::sample_local`] for the unit direction `dir`: the local hit
    /// point `(x, y)` on the plane `z = z0` (clamped into the rectangle), then `u₁` = the
    /// solid angle of the strip `[x0, x] × [y0, y1]` over Ω (two Van Oosterom–Strackee
    /// triangles) and `u₂ = (h − h0)/(h1 − h0)` with `h = y/√(x² + z0² + y²)`. `None` when
    /// the ray does not meet the plane ahead.
    pub(super) fn invert_local(&self, dir: DVec3) -> Option<DVec2> {
        let [fx, fy, fz] = self.frame;
        let t = self.z0 / dir.dot(fz);
        if !(t.is_finite() && t > 0.0) {
            return None;
        }
        let xu = (t * dir.dot(fx)).clamp(self.x0, self.x1);
        let yv = (t * dir.dot(fy)).clamp(self.y0, self.y1);
        let c = [
            (self.x0, self.y0),
            (xu, self.y0),
            (xu, self.y1),
            (self.x0, self.y1),
        ]
        .map(|(x, y)| DVec3::new(x, y, self.z0).normalize());
        let strip = triangle_solid_angle(c[0], c[1], c[2]) + triangle_solid_angle(c[0], c[2], c[3]);
        let d2 = xu * xu + self.z0 * self.z0;
        let h = |y: f64| y / (d2 + y * y).sqrt();
        let (h0, h1) = (h(self.y0), h(self.y1));
        let u2 = if h1 > h0 {
            (h(yv) - h0) / (h1 - h0)
        } else {
            0.0
        };
        Some(DVec2::new(strip / self.omega, u2))
    }

    /// The sampled point relative to the origin (world axes).
    #[inline]
    pub(super) fn sample_offset(&self, u: DVec2) -> DVec3 {
        let (xu, yv) = self.sample_local(u);
        let [x, y, z] = self.frame;
        xu * x + yv * y + self.z0 * z
    }
}

#[cfg(test)]
mod tests {
    use super::super::SPHERICAL_RECTANGLE_MIN_ANGLE;
    use super::*;

    #[test]
    fn min_angle_constants() {
        let t = f64::from(SPHERICAL_RECTANGLE_MIN_ANGLE);
        assert!((COS_MIN_ANGLE - t.cos()).abs() < 1e-16);
        assert!((SIN_MIN_ANGLE - t.sin()).abs() < 1e-16);
    }

    #[test]
    fn wide_enough_matches_atan2() {
        let t = f64::from(SPHERICAL_RECTANGLE_MIN_ANGLE);
        for g in [
            0.0,
            0.5e-3,
            0.99e-3,
            1.01e-3,
            0.1,
            1.0,
            3.0,
            std::f64::consts::PI,
        ] {
            let z = DVec2::new(f64::cos(g), f64::sin(g));
            assert_eq!(wide_enough(z), g >= t, "{g}");
        }
    }

    #[test]
    fn arg_of_products_adds_angles() {
        for (a, b) in [(0.3, 0.4), (3.0, 3.1), (1e-3, 2.0), (1.5, 1.7)] {
            let z = mul(
                DVec2::new(f64::cos(a), f64::sin(a)),
                DVec2::new(f64::cos(b), f64::sin(b)),
            );
            let got = arg(z);
            assert!(got.is_finite() && (got - (a + b)).abs() < 1e-14, "{got}");
        }
    }
}
