//! A warp of the user's own: the product of two tents on `[−1, 1]²`.

use mcrt::glam::Vec2;
use mcrt::{InvertibleWarp, Warp};

/// Points of `[−1, 1]²` with density `(1 − |x|)(1 − |y|)` per unit area: the sum of two
/// uniform values in each coordinate (the pixel filter of many renderers), sampled by
/// inverting each coordinate's CDF: `x = √(2u) − 1` for `u < ½`, `1 − √(2(1 − u))` above.
#[derive(Clone, Copy, Debug, Default)]
pub struct Tent2D;

/// The inverse CDF of the tent `1 − |x|` on `[−1, 1]`.
fn tent(u: f32) -> f32 {
    if u < 0.5 {
        (2.0 * u).sqrt() - 1.0
    } else {
        1.0 - (2.0 * (1.0 - u)).max(0.0).sqrt()
    }
}

/// The CDF of the tent, clamped into `[0, 1)`.
fn tent_cdf(x: f32) -> f32 {
    let c = if x < 0.0 {
        0.5 * (1.0 + x).max(0.0).powi(2)
    } else {
        1.0 - 0.5 * (1.0 - x).max(0.0).powi(2)
    };
    c.clamp(0.0, mcrt::sampling::ONE_MINUS_EPSILON)
}

impl Warp for Tent2D {
    type Point = Vec2;

    fn sample(&self, u: Vec2) -> Vec2 {
        Vec2::new(tent(u.x), tent(u.y))
    }

    /// Per unit area; 0 outside `[−1, 1]²` (and for NaN).
    fn pdf(&self, p: Vec2) -> f32 {
        let (ax, ay) = (p.x.abs(), p.y.abs());
        if ax <= 1.0 && ay <= 1.0 {
            (1.0 - ax) * (1.0 - ay)
        } else {
            0.0
        }
    }
}

impl InvertibleWarp for Tent2D {
    fn invert(&self, p: Vec2) -> Vec2 {
        Vec2::new(tent_cdf(p.x), tent_cdf(p.y))
    }
}
