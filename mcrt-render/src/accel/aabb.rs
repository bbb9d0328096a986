//! Axis-aligned bounding boxes and the ray–box slab test.

use glam::{Vec3, Vec3A};

/// An axis-aligned box `[min, max]`. The empty box has `min = +∞`, `max = −∞`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    /// The lower corner.
    pub min: Vec3,
    /// The upper corner.
    pub max: Vec3,
}

impl Default for Aabb {
    fn default() -> Self {
        Self::EMPTY
    }
}

impl Aabb {
    /// The empty box: the identity of [`Aabb::union`].
    pub const EMPTY: Self = Self {
        min: Vec3::splat(f32::INFINITY),
        max: Vec3::splat(f32::NEG_INFINITY),
    };

    /// The smallest box holding every point given.
    pub fn from_points(points: &[Vec3]) -> Self {
        points.iter().fold(Self::EMPTY, |b, &p| b.grow(p))
    }

    /// This box grown to hold `p`.
    #[inline]
    #[must_use]
    pub fn grow(self, p: Vec3) -> Self {
        Self {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    /// The smallest box holding both boxes.
    #[inline]
    #[must_use]
    pub fn union(self, o: Self) -> Self {
        Self {
            min: self.min.min(o.min),
            max: self.max.max(o.max),
        }
    }

    /// The box grown by a relative 2⁻²⁰ of its largest coordinate magnitude (plus 10⁻³⁰):
    /// what the BVH stores, so that rays running exactly along a face of a primitive's box
    /// (origin on the face, direction parallel to it) still enter it.
    #[must_use]
    pub fn padded(self) -> Self {
        let m = self.min.abs().max(self.max.abs()).max_element();
        let pad = Vec3::splat(m * (1.0 / 1_048_576.0) + 1e-30);
        Self {
            min: self.min - pad,
            max: self.max + pad,
        }
    }

    /// True when the box holds no point.
    pub fn is_empty(&self) -> bool {
        self.min.x > self.max.x || self.min.y > self.max.y || self.min.z > self.max.z
    }

    /// The centre of the box.
    #[inline]
    pub fn center(&self) -> Vec3 {
        0.5 * (self.min + self.max)
    }

    /// The edge lengths (zero for the empty box).
    #[inline]
    pub fn extent(&self) -> Vec3 {
        (self.max - self.min).max(Vec3::ZERO)
    }

    /// The surface area (zero for the empty box).
    #[inline]
    pub fn surface_area(&self) -> f32 {
        let e = self.extent();
        2.0 * (e.x * e.y + e.y * e.z + e.z * e.x)
    }
}

/// A ray prepared for slab tests: origin and reciprocal direction (SIMD lanes).
#[derive(Debug, Clone, Copy)]
pub(crate) struct RayBoxTest {
    /// The ray origin.
    pub origin: Vec3A,
    /// `1 / dir` per component, with zero components replaced by ±10⁻³⁰ first, so that no
    /// slab distance is NaN: a ray parallel to a slab gets distances of ±10³⁰ scale, so the
    /// slab constrains nothing when the origin is strictly inside it. An origin exactly on
    /// the slab plane may count as outside; callers pad their boxes ([`Aabb::padded`]).
    pub inv_dir: Vec3A,
}

/// `1 + 2γ₃` with γₙ = nε/(1 − nε): scales the far slab distance so that rounding cannot
/// make a box that the ray touches look missed (Ize 2013, "Robust BVH Ray Traversal", JCGT 2(2)).
pub(super) const SLAB_GROW: f32 =
    1.0 + 2.0 * (3.0 * f32::EPSILON * 0.5) / (1.0 - 3.0 * f32::EPSILON * 0.5);

impl RayBoxTest {
    /// Prepares a ray with the given origin and direction.
    #[inline]
    pub(crate) fn new(origin: Vec3, dir: Vec3) -> Self {
        let d = Vec3A::from(dir);
        let tiny = Vec3A::splat(1e-30);
        let d = Vec3A::select(d.abs().cmplt(tiny), tiny.copysign(d), d);
        Self {
            origin: origin.into(),
            inv_dir: d.recip(),
        }
    }

    /// The parametric interval `[t0, t1]` where the ray is inside `[min, max]`, clipped to
    /// `[0, t_max]`; `None` if empty.
    #[inline(always)]
    pub(crate) fn clip(&self, min: Vec3A, max: Vec3A, t_max: f32) -> Option<(f32, f32)> {
        let a = (min - self.origin) * self.inv_dir;
        let b = (max - self.origin) * self.inv_dir;
        let t0 = a.min(b).max_element();
        let t1 = a.max(b).min_element() * SLAB_GROW;
        let t0 = if t0 > 0.0 { t0 } else { 0.0 };
        let t1 = if t1 < t_max { t1 } else { t_max };
        (t0 <= t1).then_some((t0, t1))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clip_hits_and_misses() {
        let b = Aabb {
            min: Vec3::splat(-1.0),
            max: Vec3::splat(1.0),
        };
        let r = RayBoxTest::new(Vec3::new(0.0, 0.0, -5.0), Vec3::Z);
        let (lo, hi) = (Vec3A::from(b.min), Vec3A::from(b.max));
        let (t0, t1) = r.clip(lo, hi, f32::INFINITY).unwrap();
        assert!(t0.is_finite() && t1.is_finite());
        assert!((t0 - 4.0).abs() < 1e-5 && (t1 - 6.0).abs() < 1e-4);
        let miss = RayBoxTest::new(Vec3::new(2.0, 0.0, -5.0), Vec3::Z);
        assert!(miss.clip(lo, hi, f32::INFINITY).is_none());
        // Parallel to a slab: inside it or not, never NaN.
        let inside = RayBoxTest::new(Vec3::new(0.999, 0.0, -5.0), Vec3::Z);
        assert!(inside.clip(lo, hi, f32::INFINITY).is_some());
        let outside = RayBoxTest::new(Vec3::new(1.001, 0.0, -5.0), Vec3::Z);
        assert!(outside.clip(lo, hi, f32::INFINITY).is_none());
        assert!(r.clip(lo, hi, 3.0).is_none());
    }

    #[test]
    fn surface_area_of_unit_cube() {
        let b = Aabb::from_points(&[Vec3::ZERO, Vec3::ONE]);
        assert_eq!(b.surface_area(), 6.0);
        assert!(Aabb::EMPTY.is_empty());
        assert_eq!(Aabb::EMPTY.surface_area(), 0.0);
    }
}
