//! The unit interval `[0, 1)` of sample values: its largest `f32`, and the clamps that keep
//! inverses and table lookups inside it.

use glam::Vec2;

/// The largest `f32` below 1, `1 − 2⁻²⁴`: the largest sample value `u`. Every sampler's
/// values are at most this, every warp accepts it, and every inverse returns at most it.
pub const ONE_MINUS_EPSILON: f32 = 1.0 - f32::EPSILON / 2.0;

/// Clamps `x` into `[0, 1 − 2⁻²⁴]`; NaN maps to 0.
#[inline]
pub(crate) fn clamp_unit(x: f32) -> f32 {
    if x >= 0.0 {
        x.min(ONE_MINUS_EPSILON)
    } else {
        0.0
    }
}

/// Clamps both coordinates into `[0, 1)` ([`clamp_unit`] each).
#[inline]
pub(crate) fn clamp_unit2(u1: f32, u2: f32) -> Vec2 {
    Vec2::new(clamp_unit(u1), clamp_unit(u2))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_minus_epsilon_is_the_largest_f32_below_one() {
        assert_eq!(ONE_MINUS_EPSILON, 1.0 - 2f32.powi(-24));
        assert_eq!(f32::from_bits(ONE_MINUS_EPSILON.to_bits() + 1), 1.0);
    }

    #[test]
    fn clamp_handles_nan_and_edges() {
        assert_eq!(clamp_unit(f32::NAN), 0.0);
        assert_eq!(clamp_unit(-1.0), 0.0);
        assert_eq!(clamp_unit(-0.0), 0.0);
        assert_eq!(clamp_unit(0.25), 0.25);
        assert_eq!(clamp_unit(1.0), ONE_MINUS_EPSILON);
        assert_eq!(clamp_unit(f32::INFINITY), ONE_MINUS_EPSILON);
        assert_eq!(
            clamp_unit2(2.0, f32::NAN),
            Vec2::new(ONE_MINUS_EPSILON, 0.0)
        );
    }
}
