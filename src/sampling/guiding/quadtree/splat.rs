//! The directional box filter of the records (Müller 2019, "Practical Path Guiding in
//! Production"): a record's energy spread over a square the size of its leaf cell.

use super::{fixed_point, next_quadrant, DQuadTree, ONE_MINUS_EPS_F64};
use glam::Vec2;

impl DQuadTree {
    /// The side of the leaf cell of the square containing `u` (`2^-depth`).
    fn leaf_side(&self, u: Vec2) -> f64 {
        let mut c = fixed_point(u);
        let (mut n, mut side) = (0usize, 0.5f64);
        loop {
            let q = next_quadrant(&mut c);
            match self.nodes[n].child[q] {
                0 => return side,
                c => (n, side) = (c as usize, side * 0.5),
            }
        }
    }

    /// [`DQuadTree::record_square`] through the directional box filter (Müller 2019,
    /// "Practical Path Guiding in Production"): `value` is spread over the
    /// square of the side of the leaf cell containing `u`, centred on `u`, each cell taking
    /// the share of it that it overlaps. The box is shifted inside the square along
    /// `cos θ` (x; the poles are its edges) and wraps around along `φ` (y, periodic), so
    /// the whole `value` is recorded. A value that is negative, NaN or infinite is ignored.
    pub(crate) fn record_square_filtered(&mut self, u: Vec2, value: f64) {
        if !(value >= 0.0 && value.is_finite()) {
            return;
        }
        let u = [
            f64::from(u.x).clamp(0.0, ONE_MINUS_EPS_F64),
            f64::from(u.y).clamp(0.0, ONE_MINUS_EPS_F64),
        ];
        if u.iter().any(|v| v.is_nan()) {
            return;
        }
        let side = self.leaf_side(Vec2::new(u[0] as f32, u[1] as f32));
        let density = value / (side * side);
        let x0 = (u[0] - 0.5 * side).clamp(0.0, 1.0 - side);
        let y0 = u[1] - 0.5 * side;
        let x = [x0, x0 + side];
        if y0 < 0.0 {
            self.splat([x, [y0 + 1.0, 1.0]], density);
            self.splat([x, [0.0, y0 + side]], density);
        } else if y0 + side > 1.0 {
            self.splat([x, [y0, 1.0]], density);
            self.splat([x, [0.0, y0 + side - 1.0]], density);
        } else {
            self.splat([x, [y0, y0 + side]], density);
        }
    }

    /// Adds `density` times the area of overlap with the box `[x0, x1] × [y0, y1]` (inside
    /// the unit square) to every quadrant that overlaps it, at every level.
    fn splat(&mut self, b: [[f64; 2]; 2], density: f64) {
        self.derived.take();
        self.splat_node(0, [0.0; 2], 1.0, &b, density);
    }

    /// [`DQuadTree::splat`] below node `n`, whose square has the lower corner `origin` and
    /// the side `side` (recursive: at most 20 levels).
    fn splat_node(&mut self, n: usize, origin: [f64; 2], side: f64, b: &[[f64; 2]; 2], d: f64) {
        let h = 0.5 * side;
        for q in 0..4 {
            let o = [
                origin[0] + (q & 1) as f64 * h,
                origin[1] + (q >> 1) as f64 * h,
            ];
            let w = |k: usize| (b[k][1].min(o[k] + h) - b[k][0].max(o[k])).max(0.0);
            let area = w(0) * w(1);
            if area > 0.0 {
                let node = &mut self.nodes[n];
                node.sum[q] += d * area;
                let c = node.child[q];
                if c != 0 {
                    self.splat_node(c as usize, o, h, b, d);
                }
            }
        }
    }
}
