//! The steps of a walk down a quadtree: the quadrant of a point at each level, in `f64`
//! halves or fixed-point bits, a sample value's choice of half, and the leaf cell reached.

use super::ONE_MINUS_EPS_F64;
use glam::Vec2;

/// Where the quadrant's node, and in it the point `x` (rescaled to the quadrant), lies.
#[inline]
pub(super) fn quadrant(x: [f64; 2]) -> (usize, [f64; 2]) {
    let mut q = 0;
    let mut y = [0.0; 2];
    for k in 0..2 {
        if x[k] < 0.5 {
            y[k] = x[k] * 2.0;
        } else {
            y[k] = x[k] * 2.0 - 1.0;
            q |= 1 << k;
        }
        y[k] = y[k].clamp(0.0, ONE_MINUS_EPS_F64);
    }
    (q, y)
}

/// The point `u` of the unit square as fixed-point coordinates per axis, clamped into the
/// square (a NaN coordinate puts the point at the centre), whose bits from the highest are
/// the halves a descent takes: the same halves as halving the coordinates in `f64`
/// ([`quadrant`]), which is exact for the `f32` coordinates down to 63 levels. (`⌊u·2⁶³⌋`,
/// shifted up by one: the conversion to a signed integer is a few instructions fewer than to
/// an unsigned one; the lowest bit, a 64th level, is 0.)
#[inline]
pub(super) fn fixed_point(u: Vec2) -> [u64; 2] {
    if u.is_nan() {
        return [1 << 63; 2];
    }
    // `as` saturates: below 0 gives 0, 1 and above all ones but the lowest bit (the last
    // cell, as the clamp to just below 1 of the `f64` descent).
    let fix = |v: f32| ((f64::from(v) * 9_223_372_036_854_775_808.0) as i64 as u64) << 1;
    [fix(u.x), fix(u.y)]
}

/// The quadrant of the fixed-point point `c` ([`fixed_point`]) in its current node, and `c`
/// rescaled to that quadrant: the top bit of each coordinate, shifted out.
#[inline(always)]
pub(super) fn next_quadrant(c: &mut [u64; 2]) -> usize {
    let q = (c[0] >> 63) | ((c[1] >> 63) << 1);
    c[0] <<= 1;
    c[1] <<= 1;
    q as usize
}

/// The leaf cell a sample was drawn in (`DQuadTree::sample_cell`).
#[derive(Debug, Clone, Copy)]
pub(super) struct Cell {
    /// Per axis, the halves the walk took, the first in the highest of `depth` bits.
    pub(super) bits: [u64; 2],
    pub(super) depth: u32,
    /// The density of [`DQuadTree::pdf_square`](super::DQuadTree::pdf_square) in the cell.
    pub(super) pdf: f32,
}

impl Cell {
    /// Whether the point `u` of the square is in the cell: the highest `depth` bits of its
    /// fixed-point coordinates ([`fixed_point`]), the quadrants `pdf_square` would walk,
    /// are the cell's.
    #[inline]
    pub(super) fn contains(&self, u: Vec2) -> bool {
        if self.depth == 0 || self.depth > 63 {
            return false;
        }
        let c = fixed_point(u);
        let shift = 64 - self.depth;
        (c[0] >> shift) == self.bits[0] && (c[1] >> shift) == self.bits[1]
    }
}

/// Chooses the lower half with probability `p` and rescales `x` to the chosen half: 0 when
/// `x < p`, else 1.
#[inline]
pub(super) fn pick(x: &mut f64, p: f64) -> usize {
    let b = if *x < p {
        *x /= p;
        0
    } else {
        *x = (*x - p) / (1.0 - p);
        1
    };
    *x = x.clamp(0.0, ONE_MINUS_EPS_F64);
    if x.is_nan() {
        *x = 0.5;
    }
    b
}
