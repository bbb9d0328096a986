//! A summed-area table of a piecewise-constant function on the unit square, and the
//! piecewise-constant 2D distribution restricted to a window of it.

use glam::Vec2;

use super::piecewise_1d::{clamp_unit, validate_grid};
use crate::sampling::warp::{InvertibleWarp, Warp};
use crate::sampling::SamplingError;

/// The integral of a piecewise-constant function over any axis-aligned rectangle of `[0,1]²`
/// in `O(1)`: a summed-area table (Crow 1984) of a `width × height` table of cell values
/// (row-major; cell `(x, y)` spans `[x/width, (x+1)/width) × [y/height, (y+1)/height)`).
///
/// The table holds `S(i, j) = ∫₀^{i/w} ∫₀^{j/h} f` at the cell corners, in `f64`. Within a
/// cell `∫₀ˣ∫₀ʸ f` is bilinear in `(x, y)`, so bilinear interpolation of `S` gives it exactly
/// anywhere, and the integral over `[x₀, x₁] × [y₀, y₁]` is
/// `S(x₁, y₁) − S(x₀, y₁) − S(x₁, y₀) + S(x₀, y₀)`.
///
/// Citation: F. C. Crow, 1984, "Summed-area tables for texture mapping", SIGGRAPH; as in
/// M. Pharr, W. Jakob, G. Humphreys, 2023, "Physically Based Rendering", 4th ed., §A.5.4.
///
/// ```
/// use mcrt::glam::Vec2;
/// use mcrt::sampling::distribution::SummedAreaTable;
///
/// let sat = SummedAreaTable::new(&[1.0, 2.0, 3.0, 4.0], 2, 2).unwrap();
/// assert!((sat.integral(Vec2::ZERO, Vec2::ONE) - 2.5).abs() < 1e-12);
/// // The top-right cell (value 4) and half of the top-left one (value 3).
/// assert!((sat.integral(Vec2::new(0.25, 0.5), Vec2::ONE) - (1.0 + 0.375)).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct SummedAreaTable {
    width: usize,
    height: usize,
    /// `S` at the `(width + 1) × (height + 1)` cell corners, row-major.
    sums: Vec<f64>,
}

impl SummedAreaTable {
    /// The table of the row-major cell `values` (`height` rows of `width`).
    ///
    /// # Errors
    /// [`SamplingError::ShapeMismatch`] when `values.len() != width · height`,
    /// [`SamplingError::EmptyTable`] for a zero dimension, [`SamplingError::InvalidEntry`] for
    /// a negative, NaN or infinite value.
    pub fn new(values: &[f32], width: usize, height: usize) -> Result<Self, SamplingError> {
        let n = validate_grid(values, width, height)?;
        let cell = 1.0 / n as f64;
        let stride = width + 1;
        let mut sums = vec![0.0; stride * (height + 1)];
        for y in 0..height {
            let mut row = 0.0;
            for x in 0..width {
                row += f64::from(values[y * width + x]) * cell;
                sums[(y + 1) * stride + x + 1] = sums[y * stride + x + 1] + row;
            }
        }
        Ok(Self {
            width,
            height,
            sums,
        })
    }

    /// `∫₀ˣ∫₀ʸ f` at a point of the square (clamped into it), by bilinear interpolation of the
    /// corner sums.
    fn cumulative(&self, x: f64, y: f64) -> f64 {
        let fx = x.clamp(0.0, 1.0) * self.width as f64;
        let fy = y.clamp(0.0, 1.0) * self.height as f64;
        let (i, j) = (
            (fx as usize).min(self.width - 1),
            (fy as usize).min(self.height - 1),
        );
        let (s, t) = (fx - i as f64, fy - j as f64);
        let stride = self.width + 1;
        let at = |i: usize, j: usize| self.sums[j * stride + i];
        let bottom = at(i, j) + s * (at(i + 1, j) - at(i, j));
        let top = at(i, j + 1) + s * (at(i + 1, j + 1) - at(i, j + 1));
        bottom + t * (top - bottom)
    }

    /// `∫∫ f` over the rectangle from `min` to `max` (clamped into the square; 0 when empty).
    #[must_use]
    pub fn integral(&self, min: Vec2, max: Vec2) -> f64 {
        self.integral_f64(
            [f64::from(min.x), f64::from(min.y)],
            [f64::from(max.x), f64::from(max.y)],
        )
    }

    fn integral_f64(&self, min: [f64; 2], max: [f64; 2]) -> f64 {
        if !(max[0] > min[0] && max[1] > min[1]) {
            return 0.0;
        }
        let v = self.cumulative(max[0], max[1])
            - self.cumulative(min[0], max[1])
            - self.cumulative(max[0], min[1])
            + self.cumulative(min[0], min[1]);
        v.max(0.0)
    }
}

/// A piecewise-constant density on `[0,1]²` (as
/// [`PiecewiseConstant2D`](super::PiecewiseConstant2D)) that can be sampled restricted to any
/// axis-aligned window, chosen per call: a light seen through a portal, a region of a texture.
///
/// [`WindowedPiecewiseConstant2D::window`] returns a [`Warp`] with pdf `f(p)/∫_W f` per unit
/// area on the window `W`, 0 outside. Mapping: `x` by inverting the marginal CDF
/// `∫_{x₀}^{x} ∫_{y₀}^{y₁} f / ∫_W f` (a binary search over columns, each evaluated from the
/// [`SummedAreaTable`] in `O(1)`, then a linear solve within the column, where the marginal is
/// constant), then `y` likewise in the column of `x`. `O(log w + log h)` per sample, nothing
/// built per window. Inverse: the two CDFs.
///
/// Citation: M. Pharr, W. Jakob, G. Humphreys, 2023, "Physically Based Rendering", 4th ed.,
/// §A.5.4 (`WindowedPiecewiseConstant2D`). Derivation: `docs/derivations.md`.
///
/// ```
/// use mcrt::glam::Vec2;
/// use mcrt::sampling::distribution::WindowedPiecewiseConstant2D;
/// use mcrt::sampling::warp::{InvertibleWarp, Warp};
///
/// let d = WindowedPiecewiseConstant2D::new(&[1.0, 0.0, 2.0, 5.0], 2, 2).unwrap();
/// let w = d.window(Vec2::new(0.25, 0.25), Vec2::new(0.75, 1.0)).unwrap();
/// let (p, pdf) = w.sample_with_pdf(Vec2::new(0.3, 0.6));
/// assert!(p.x >= 0.25 && p.x <= 0.75 && p.y >= 0.25 && pdf > 0.0);
/// assert!((w.invert(p) - Vec2::new(0.3, 0.6)).length() < 1e-5);
/// assert!(d.window(Vec2::new(0.5, 0.0), Vec2::new(1.0, 0.5)).is_none()); // zero mass
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct WindowedPiecewiseConstant2D {
    sat: SummedAreaTable,
    values: Vec<f64>,
}

impl WindowedPiecewiseConstant2D {
    /// The density proportional to the row-major cell `values`. Errors as
    /// [`SummedAreaTable::new`]; an all-zero table is allowed (every window is then empty).
    pub fn new(values: &[f32], width: usize, height: usize) -> Result<Self, SamplingError> {
        let sat = SummedAreaTable::new(values, width, height)?;
        Ok(Self {
            sat,
            values: values.iter().map(|&v| f64::from(v)).collect(),
        })
    }

    /// The summed-area table.
    #[must_use]
    pub fn summed_area_table(&self) -> &SummedAreaTable {
        &self.sat
    }

    /// The distribution restricted to the window from `min` to `max` (clamped into the
    /// square), or `None` when the window is empty or the function integrates to 0 over it.
    #[must_use]
    pub fn window(&self, min: Vec2, max: Vec2) -> Option<Window<'_>> {
        let c = |v: f32| f64::from(v).clamp(0.0, 1.0);
        let (min, max) = ([c(min.x), c(min.y)], [c(max.x), c(max.y)]);
        let mass = self.sat.integral_f64(min, max);
        (mass > 0.0 && mass.is_finite()).then_some(Window {
            dist: self,
            min,
            max,
            mass,
        })
    }
}

/// [`WindowedPiecewiseConstant2D`] restricted to a window: a [`Warp`] onto the window with
/// pdf `f(p)/∫_W f` per unit area. Built by [`WindowedPiecewiseConstant2D::window`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Window<'a> {
    dist: &'a WindowedPiecewiseConstant2D,
    min: [f64; 2],
    max: [f64; 2],
    mass: f64,
}

impl Window<'_> {
    /// `∫_W f`, the function's integral over the window.
    #[must_use]
    pub fn mass(&self) -> f64 {
        self.mass
    }

    /// The mass of `[x₀, x] × [y₀, y₁]`.
    fn left_of(&self, x: f64) -> f64 {
        self.dist.sat.integral_f64(self.min, [x, self.max[1]])
    }

    /// The mass of column `c` (full cell width) between `y₀` and `y`.
    fn column_below(&self, c: usize, y: f64) -> f64 {
        let w = self.dist.sat.width as f64;
        let (a, b) = (c as f64 / w, (c + 1) as f64 / w);
        self.dist.sat.integral_f64([a, self.min[1]], [b, y])
    }

    fn column_of(&self, x: f64) -> usize {
        let w = self.dist.sat.width;
        ((x * w as f64) as usize).min(w - 1)
    }

    /// Inverts a piecewise-linear cumulative `cum(t)` on `[lo, hi]` over `n` equal cells of
    /// `[0, 1]` (boundaries `k/n`): the first cell whose end exceeds `target`, then a linear
    /// solve in it. `cum` must be non-decreasing with `cum(lo) = 0`.
    fn solve(target: f64, lo: f64, hi: f64, n: usize, cum: impl Fn(f64) -> f64) -> f64 {
        let nf = n as f64;
        let first = ((lo * nf) as usize).min(n - 1);
        let last = (((hi * nf).ceil() as usize).max(first + 1)).min(n) - 1;
        let end = |k: usize| ((k + 1) as f64 / nf).min(hi);
        let (mut a, mut b) = (first, last);
        while a < b {
            let mid = (a + b) / 2;
            if cum(end(mid)) <= target {
                a = mid + 1;
            } else {
                b = mid;
            }
        }
        let start = (a as f64 / nf).max(lo);
        let (c0, c1) = (cum(start), cum(end(a)));
        let t = if c1 > c0 {
            ((target - c0) / (c1 - c0)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        start + t * (end(a) - start)
    }
}

impl Warp for Window<'_> {
    type Point = Vec2;

    #[inline]
    fn sample(&self, u: Vec2) -> Vec2 {
        let sat = &self.dist.sat;
        let tx = f64::from(clamp_unit(u.x)) * self.mass;
        let x = Self::solve(tx, self.min[0], self.max[0], sat.width, |x| self.left_of(x));
        let c = self.column_of(x);
        let col = self.column_below(c, self.max[1]);
        let ty = f64::from(clamp_unit(u.y)) * col;
        let y = Self::solve(ty, self.min[1], self.max[1], sat.height, |y| {
            self.column_below(c, y)
        });
        Vec2::new(x as f32, y as f32)
    }

    /// `f(p)/∫_W f` per unit area inside the window, 0 outside.
    #[inline]
    fn pdf(&self, p: Vec2) -> f32 {
        let (x, y) = (f64::from(p.x), f64::from(p.y));
        if !(x >= self.min[0] && x <= self.max[0] && y >= self.min[1] && y <= self.max[1]) {
            return 0.0;
        }
        let sat = &self.dist.sat;
        let c = self.column_of(x);
        let r = ((y * sat.height as f64) as usize).min(sat.height - 1);
        (self.dist.values[r * sat.width + c] / self.mass) as f32
    }
}

impl InvertibleWarp for Window<'_> {
    #[inline]
    fn invert(&self, p: Vec2) -> Vec2 {
        let x = f64::from(p.x).clamp(self.min[0], self.max[0]);
        let y = f64::from(p.y).clamp(self.min[1], self.max[1]);
        let ux = self.left_of(x) / self.mass;
        let c = self.column_of(x);
        let col = self.column_below(c, self.max[1]);
        let uy = if col > 0.0 {
            self.column_below(c, y) / col
        } else {
            0.0
        };
        Vec2::new(clamp_unit(ux as f32), clamp_unit(uy as f32))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integrals_match_brute_force() {
        let v = [1.0, 2.0, 0.0, 4.0, 5.0, 6.0];
        let sat = SummedAreaTable::new(&v, 3, 2).unwrap();
        let f = |x: f64, y: f64| {
            let (i, j) = (((x * 3.0) as usize).min(2), ((y * 2.0) as usize).min(1));
            f64::from(v[j * 3 + i])
        };
        let (min, max) = ([0.1, 0.2], [0.85, 0.9]);
        let n = 600;
        let mut brute = 0.0;
        for a in 0..n {
            for b in 0..n {
                let x = min[0] + (max[0] - min[0]) * (a as f64 + 0.5) / n as f64;
                let y = min[1] + (max[1] - min[1]) * (b as f64 + 0.5) / n as f64;
                brute += f(x, y);
            }
        }
        brute *= (max[0] - min[0]) * (max[1] - min[1]) / (n * n) as f64;
        let got = sat.integral_f64(min, max);
        assert!(
            got.is_finite() && (got - brute).abs() < 1e-3 * brute,
            "{got} {brute}"
        );
        assert_eq!(sat.integral(Vec2::ONE, Vec2::ZERO), 0.0);
    }

    #[test]
    fn window_round_trip_skips_zero_cells() {
        let v = [0.0, 1.0, 0.0, 3.0, 0.0, 2.0, 0.0, 0.0, 1.0];
        let d = WindowedPiecewiseConstant2D::new(&v, 3, 3).unwrap();
        let w = d.window(Vec2::new(0.2, 0.1), Vec2::new(0.9, 0.95)).unwrap();
        for i in 1..25 {
            for j in 1..25 {
                let u = Vec2::new(i as f32 / 25.0, j as f32 / 25.0);
                let p = w.sample(u);
                assert!(p.is_finite() && w.pdf(p) > 0.0, "{u}: {p}");
                let back = w.invert(p);
                assert!((back - u).abs().max_element() < 1e-5, "{u}: {p} {back}");
            }
        }
    }
}
