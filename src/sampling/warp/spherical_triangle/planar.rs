//! A planar triangle or parallelogram seen from a point, in `f64`: ray hits with a tolerant
//! inside test, uniform area sampling, and the area → solid angle conversion. Shared by the
//! spherical triangle and rectangle warps.

use glam::{DVec2, DVec3, Vec2, Vec3};

use crate::sampling::SamplingError;

/// Angular tolerance (radians) of the inside test, about two `f32` ulps of a unit direction
/// (rounding a unit direction to `f32` moves it by at most ~5·10⁻⁸ rad):
/// a sampled direction rounded to `f32` must still count as hitting the shape. On the
/// shape's plane the band is this angle times d/|cos θ'|.
pub(crate) const ANGULAR_TOLERANCE: f64 = 1e-7;

/// Smallest solid angle (sr) a shape may subtend: below it the density per steradian
/// (1/Ω, or d²/(A |cos θ'|) in the area fallback) comes within a factor 10⁸ of `f32::MAX`.
pub const MIN_SOLID_ANGLE: f64 = 1e-30;

/// The shape p0 + s e1 + t e2 with s, t ≥ 0 and s + t ≤ 1 (triangle) or s, t ≤ 1
/// (parallelogram), seen from `origin`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Planar {
    pub(crate) origin: DVec3,
    pub(crate) p0: DVec3,
    pub(crate) e1: DVec3,
    pub(crate) e2: DVec3,
    /// e1 × e2.
    cross: DVec3,
    /// Unit normal.
    pub(crate) normal: DVec3,
    /// The shape's area.
    pub(crate) area: f64,
    triangle: bool,
}

/// Widens a `Vec3` to `f64`, rejecting non-finite input.
pub(crate) fn widen(name: &'static str, v: Vec3) -> Result<DVec3, SamplingError> {
    if v.is_finite() {
        Ok(v.as_dvec3())
    } else {
        Err(SamplingError::InvalidDirection {
            name,
            expected: "finite coordinates",
        })
    }
}

impl Planar {
    /// Validates the shape: nonzero area, origin off its plane (relative distance > 1e-9).
    pub(crate) fn new(
        origin: DVec3,
        p0: DVec3,
        e1: DVec3,
        e2: DVec3,
        triangle: bool,
    ) -> Result<Self, SamplingError> {
        Self::shape(p0, e1, e2, triangle)?.seen_from(origin)
    }

    /// The shape alone (origin at zero, unchecked): validates a nonzero area. Reference-point
    /// independent, so it can be built once per light and reused through
    /// [`Planar::seen_from`].
    pub(crate) fn shape(
        p0: DVec3,
        e1: DVec3,
        e2: DVec3,
        triangle: bool,
    ) -> Result<Self, SamplingError> {
        let cross = e1.cross(e2);
        let len = cross.length();
        if !len.is_finite() || len <= 1e-12 * e1.length() * e2.length() {
            return Err(SamplingError::Degenerate {
                what: "the shape has zero area (collinear or zero-length edges)",
            });
        }
        let area = if triangle { 0.5 * len } else { len };
        Ok(Self {
            origin: DVec3::ZERO,
            p0,
            e1,
            e2,
            cross,
            normal: cross / len,
            area,
            triangle,
        })
    }

    /// This shape seen from `origin`, which must lie off its plane (relative distance
    /// > 1e-9).
    #[inline]
    pub(crate) fn seen_from(mut self, origin: DVec3) -> Result<Self, SamplingError> {
        let to = self.p0 - origin;
        let scale = to
            .length_squared()
            .max(self.e1.length_squared())
            .max(self.e2.length_squared())
            .sqrt();
        let off_plane = self.normal.dot(to).abs();
        if off_plane.is_nan() || off_plane <= 1e-9 * scale {
            return Err(SamplingError::Degenerate {
                what: "the origin lies in the plane of the shape (zero solid angle)",
            });
        }
        // Ω ≈ A |cos θ'| / d² from the centre: exact enough for the small shapes it refuses.
        let centre = to + 0.5 * (self.e1 + self.e2);
        let d2 = centre.length_squared();
        let omega = self.area * self.normal.dot(centre).abs() / (d2 * d2.sqrt());
        if omega.is_nan() || omega < MIN_SOLID_ANGLE {
            return Err(SamplingError::Degenerate {
                what: "the shape subtends less than 1e-30 sr, so no density per steradian \
                       fits f32: sample it by area",
            });
        }
        self.origin = origin;
        Ok(self)
    }

    /// Where the ray from the origin along unit `dir` meets the shape (with the angular
    /// tolerance): (distance, |cos θ'| at the shape).
    pub(crate) fn hit(&self, dir: DVec3) -> Option<(f64, f64)> {
        let denom = self.normal.dot(dir);
        let dist = self.normal.dot(self.p0 - self.origin) / denom;
        if !dist.is_finite() || dist <= 0.0 {
            return None;
        }
        let p = self.origin + dist * dir - self.p0;
        let inv = 1.0 / self.cross.dot(self.normal);
        let s = p.cross(self.e2).dot(self.normal) * inv;
        let t = self.e1.cross(p).dot(self.normal) * inv;
        // Coordinate tolerances: the angular band, stretched by 1/|cos θ'| at grazing views
        // (where an angular error moves the hit point furthest), in units of each
        // coordinate's height.
        let band = ANGULAR_TOLERANCE * dist / denom.abs() * inv;
        let (ts, tt) = (band * self.e2.length(), band * self.e1.length());
        let inside = if self.triangle {
            let tu = band * (self.e2 - self.e1).length();
            s >= -ts && t >= -tt && s + t <= 1.0 + tu
        } else {
            s >= -ts && t >= -tt && s <= 1.0 + ts && t <= 1.0 + tt
        };
        inside.then_some((dist, denom.abs()))
    }

    /// The shape coordinates `(s, t)` of the point where the ray from the origin along `dir`
    /// meets the shape's plane, moved onto the shape when it lies outside, or `None` when the
    /// ray does not meet the plane ahead.
    ///
    /// A point just outside (an `f32`-rounded direction toward an edge) is moved to the
    /// nearest point of the boundary *in the plane*, not by clamping `(s, t)`: on a sliver the
    /// coordinates are ill-conditioned (a displacement of 10⁻⁸ across it changes them by
    /// 10⁻³), and clamping them would move the point along the sliver by that much.
    pub(crate) fn coords(&self, dir: DVec3) -> Option<(f64, f64)> {
        let dist = self.normal.dot(self.p0 - self.origin) / self.normal.dot(dir);
        if !(dist.is_finite() && dist > 0.0) {
            return None;
        }
        let p = self.origin + dist * dir - self.p0;
        let inv = 1.0 / self.cross.dot(self.normal);
        let s = p.cross(self.e2).dot(self.normal) * inv;
        let t = self.e1.cross(p).dot(self.normal) * inv;
        if !(s.is_finite() && t.is_finite()) {
            return None;
        }
        let inside = s >= 0.0
            && t >= 0.0
            && if self.triangle {
                s + t <= 1.0
            } else {
                s <= 1.0 && t <= 1.0
            };
        Some(if inside {
            (s, t)
        } else {
            self.nearest_on_boundary(p)
        })
    }

    /// The coordinates of the point of the shape's boundary nearest to `p` (relative to
    /// `p0`, in the plane).
    fn nearest_on_boundary(&self, p: DVec3) -> (f64, f64) {
        const TRIANGLE: [[(f64, f64); 2]; 3] = [
            [(0.0, 0.0), (1.0, 0.0)],
            [(1.0, 0.0), (0.0, 1.0)],
            [(0.0, 1.0), (0.0, 0.0)],
        ];
        const PARALLELOGRAM: [[(f64, f64); 2]; 4] = [
            [(0.0, 0.0), (1.0, 0.0)],
            [(1.0, 0.0), (1.0, 1.0)],
            [(1.0, 1.0), (0.0, 1.0)],
            [(0.0, 1.0), (0.0, 0.0)],
        ];
        let edges: &[[(f64, f64); 2]] = if self.triangle {
            &TRIANGLE
        } else {
            &PARALLELOGRAM
        };
        let at = |(s, t): (f64, f64)| s * self.e1 + t * self.e2;
        let mut best = (f64::INFINITY, (0.0, 0.0));
        for &[a, b] in edges {
            let (pa, pb) = (at(a), at(b));
            let d = pb - pa;
            let l = ((p - pa).dot(d) / d.length_squared()).clamp(0.0, 1.0);
            let gap = (p - (pa + l * d)).length_squared();
            if gap < best.0 {
                best = (gap, (a.0 + l * (b.0 - a.0), a.1 + l * (b.1 - a.1)));
            }
        }
        best.1
    }

    /// The `u` that [`Planar::sample_area`] maps to the point hit along `dir` (the area
    /// fallback's inverse): triangle `u₁ = (1 − s)²`, `u₂ = t/(1 − s)`; parallelogram
    /// `(s, t)`. Clamped into `[0, 1)²`; `(0, 0)` when the ray misses the plane.
    pub(crate) fn invert_area(&self, dir: DVec3) -> Vec2 {
        let Some((s, t)) = self.coords(dir) else {
            return Vec2::ZERO;
        };
        let (u1, u2) = if self.triangle {
            let r = (1.0 - s).clamp(0.0, 1.0);
            (r * r, if r > 0.0 { t / r } else { 0.0 })
        } else {
            (s, t)
        };
        clamp_unit_f64(u1, u2)
    }

    /// The solid-angle pdf of area sampling at unit `dir`: d² / (A |cos θ'|), 0 on a miss.
    pub(crate) fn area_pdf(&self, dir: DVec3) -> f64 {
        match self.hit(dir) {
            Some((d, cos)) if cos > 0.0 => d * d / (self.area * cos),
            _ => 0.0,
        }
    }

    /// A point uniform in area: triangle b₁ = 1 − √u₁, b₂ = u₂ √u₁; parallelogram (u₁, u₂).
    pub(crate) fn sample_area(&self, u: DVec2) -> DVec3 {
        let (s, t) = if self.triangle {
            let r = u.x.sqrt();
            (1.0 - r, u.y * r)
        } else {
            (u.x, u.y)
        };
        self.p0 + s * self.e1 + t * self.e2
    }

    /// The unit direction from the origin to `p`, in `f32`.
    pub(crate) fn direction_to(&self, p: DVec3) -> Vec3 {
        (p - self.origin).normalize().as_vec3()
    }

    /// A direction from the exact solid-angle sampler when there is one (it maps `u` to a
    /// unit direction), else toward a point uniform in area: the `sample` of the spherical
    /// triangle and rectangle warps.
    pub(crate) fn sample_with(&self, u: Vec2, exact: Option<impl FnOnce(DVec2) -> DVec3>) -> Vec3 {
        let u = u.as_dvec2();
        let dir = match exact {
            Some(sample) => sample(u).as_vec3(),
            None => self.direction_to(self.sample_area(u)),
        };
        // Outside the unit square the result is unspecified (see `warp`'s module docs).
        let in_square = (0.0..=1.0).contains(&u.x) && (0.0..=1.0).contains(&u.y);
        debug_assert!(dir.is_finite() || !in_square);
        dir
    }

    /// The density of [`Planar::sample_with`] per steradian at `w`: 1/Ω on directions that
    /// hit the shape when sampling is exact (`omega` = Ω), else the area fallback's
    /// d²/(A |cos θ'|).
    pub(crate) fn pdf_with(&self, w: Vec3, omega: Option<f64>) -> f32 {
        let dir = w.as_dvec3().normalize_or_zero();
        match omega {
            Some(omega) if self.hit(dir).is_some() => (1.0 / omega) as f32,
            Some(_) => 0.0,
            None => self.area_pdf(dir) as f32,
        }
    }
}

/// `(u₁, u₂)` in `f64` clamped into `[0, 1 − 2⁻²⁴]²` as `f32` (NaN to 0).
pub(crate) fn clamp_unit_f64(u1: f64, u2: f64) -> Vec2 {
    let c = |x: f64| {
        if x >= 0.0 {
            (x as f32).min(crate::sampling::ONE_MINUS_EPSILON)
        } else {
            0.0
        }
    };
    Vec2::new(c(u1), c(u2))
}

/// The solid angle of the triangle with unit vertex directions a, b, c: Van Oosterom &
/// Strackee 1983, "The Solid Angle of a Plane Triangle", IEEE Trans. Biomed. Eng.
pub(crate) fn triangle_solid_angle(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let num = a.dot(b.cross(c)).abs();
    let den = 1.0 + a.dot(b) + b.dot(c) + c.dot(a);
    2.0 * num.atan2(den)
}
