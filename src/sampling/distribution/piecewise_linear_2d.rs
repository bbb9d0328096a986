//! A density on the unit square that is the bilinear interpolation of a grid of vertex
//! values, sampled exactly by the marginal/conditional method (Mitsuba 3's `Marginal2D`
//! with continuous interpolation).

use glam::Vec2;

use super::piecewise_1d::{clamp_unit, validate_grid};
use crate::sampling::warp::linear::{
    linear_cdf_normalised, normalise_ends, sample_linear_normalised,
};
use crate::sampling::warp::{InvertibleWarp, Warp};
use crate::sampling::SamplingError;

/// A density on `[0, 1]²` proportional to the bilinear interpolation of a `width × height`
/// grid of non-negative vertex values (row-major, vertex `(i, j)` at
/// `(i/(width − 1), j/(height − 1))`); pdf `f(x, y)/I` per unit area, `I = ∫∫ f`.
///
/// Mapping (marginal and conditional, both piecewise linear, so both inverted exactly):
/// the marginal `m(y) = ∫ f(x, y) dx` is linear between rows, so `y` comes from a binary
/// search over the rows' cumulative trapezoids and a linear inversion within the row interval
/// ([`Linear`](crate::sampling::warp::Linear)'s map); the conditional `f(x, y)` is the blend
/// `(1 − t) f(x, y_j) + t f(x, y_{j+1})` of two rows, whose cumulative integral is the same
/// blend of the two rows' precomputed cumulative integrals, so `x` comes from a binary
/// search over that blend and a linear inversion within the cell. `O(width · height)` to
/// build, `O(log width + log height)` per sample. Inverse: the two CDFs. The pdf is exactly
/// the bilinear lookup of the grid, so an environment map sampled with it is sampled by the
/// density it is looked up with.
///
/// Citation: W. Jakob et al., Mitsuba 3, `include/mitsuba/core/distr_2d.h` (`Marginal2D`),
/// after W. Jakob, 2019, "An Adaptive Parameterization for Efficient Material Acquisition and
/// Rendering", ACM Transactions on Graphics 38(6). Derivation: `docs/derivations.md`.
///
/// ```
/// use mcrt::glam::Vec2;
/// use mcrt::sampling::distribution::PiecewiseLinear2D;
/// use mcrt::sampling::warp::{InvertibleWarp, Warp};
///
/// // 2 × 2 vertices: the bilinear density through 0, 1, 1, 2 (that is, x + y).
/// let d = PiecewiseLinear2D::new(&[0.0, 1.0, 1.0, 2.0], 2, 2).unwrap();
/// let (p, pdf) = d.sample_with_pdf(Vec2::new(0.4, 0.7));
/// assert!((pdf - (p.x + p.y)).abs() < 1e-5);
/// assert!((d.invert(p) - Vec2::new(0.4, 0.7)).length() < 1e-5);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct PiecewiseLinear2D {
    width: usize,
    height: usize,
    /// Vertex values, row-major.
    values: Vec<f64>,
    /// Per row, the cumulative integral of the row's function at each vertex (`width` per row,
    /// starting at 0), in units of x.
    row_cdf: Vec<f64>,
    /// The cumulative integral of the marginal at each row (`height` entries, from 0).
    marginal_cdf: Vec<f64>,
}

impl PiecewiseLinear2D {
    /// The density through the row-major vertex `values` (`height` rows of `width`).
    ///
    /// # Errors
    /// [`SamplingError::ShapeMismatch`] when `values.len() != width · height`,
    /// [`SamplingError::InvalidParameter`] when `width` or `height` is below 2 or above 2²⁴,
    /// [`SamplingError::InvalidEntry`] for a negative, NaN or infinite value,
    /// [`SamplingError::ZeroTable`] when every value is 0.
    pub fn new(values: &[f32], width: usize, height: usize) -> Result<Self, SamplingError> {
        for (name, n) in [("width", width), ("height", height)] {
            if !(2..=1 << 24).contains(&n) {
                return Err(SamplingError::InvalidParameter {
                    name,
                    value: n as f64,
                    expected: "between 2 and 2^24 vertices",
                });
            }
        }
        let n = validate_grid(values, width, height)?;
        let values: Vec<f64> = values.iter().map(|&v| f64::from(v)).collect();
        let dx = 1.0 / (width - 1) as f64;
        let dy = 1.0 / (height - 1) as f64;
        let mut row_cdf = Vec::with_capacity(n);
        for row in values.chunks_exact(width) {
            let mut acc = 0.0;
            row_cdf.push(0.0);
            for pair in row.windows(2) {
                acc += 0.5 * (pair[0] + pair[1]) * dx;
                row_cdf.push(acc);
            }
        }
        let mut marginal_cdf = Vec::with_capacity(height);
        let mut acc = 0.0;
        marginal_cdf.push(0.0);
        for j in 1..height {
            let (m0, m1) = (row_cdf[j * width - 1], row_cdf[(j + 1) * width - 1]);
            acc += 0.5 * (m0 + m1) * dy;
            marginal_cdf.push(acc);
        }
        if !(acc > 0.0 && acc.is_finite()) {
            return Err(SamplingError::ZeroTable);
        }
        Ok(Self {
            width,
            height,
            values,
            row_cdf,
            marginal_cdf,
        })
    }

    /// `∫∫ f` over the unit square.
    #[must_use]
    pub fn integral(&self) -> f64 {
        self.marginal_cdf[self.height - 1]
    }

    /// The number of vertices per row.
    #[must_use]
    pub fn width(&self) -> usize {
        self.width
    }

    /// The number of rows of vertices.
    #[must_use]
    pub fn height(&self) -> usize {
        self.height
    }

    /// `∫ f(x, y_j) dx`, the marginal at row `j`.
    fn row_total(&self, j: usize) -> f64 {
        self.row_cdf[(j + 1) * self.width - 1]
    }

    /// The interval index and the fraction within it of a coordinate in `[0, 1]` on a grid
    /// of `n` vertices.
    fn locate(c: f32, n: usize) -> (usize, f64) {
        let s = f64::from(c).clamp(0.0, 1.0) * (n - 1) as f64;
        let k = (s as usize).min(n - 2);
        (k, (s - k as f64).clamp(0.0, 1.0))
    }

    /// The blended row at fraction `t` between rows `j` and `j + 1`: its value and cumulative
    /// integral at vertex `i`.
    fn blend(&self, j: usize, t: f64, i: usize) -> (f64, f64) {
        let (a, b) = (j * self.width + i, (j + 1) * self.width + i);
        (
            (1.0 - t) * self.values[a] + t * self.values[b],
            (1.0 - t) * self.row_cdf[a] + t * self.row_cdf[b],
        )
    }
}

impl Warp for PiecewiseLinear2D {
    type Point = Vec2;

    #[inline]
    fn sample(&self, u: Vec2) -> Vec2 {
        // The row interval: the first whose upper cumulative mass exceeds the target (never an
        // interval of zero mass).
        let total = self.integral();
        let target = f64::from(clamp_unit(u.y)) * total;
        let j = (self.marginal_cdf[1..].partition_point(|&c| c <= target)).min(self.height - 2);
        let (c0, c1) = (self.marginal_cdf[j], self.marginal_cdf[j + 1]);
        let r = if c1 > c0 {
            ((target - c0) / (c1 - c0)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let (ma, mb) = normalise_ends(self.row_total(j), self.row_total(j + 1));
        let t = sample_linear_normalised(r, ma, mb);
        // The cell within the blended row.
        let row_total = self.blend(j, t, self.width - 1).1;
        let target = f64::from(clamp_unit(u.x)) * row_total;
        let (mut lo, mut hi) = (0, self.width - 2);
        while lo < hi {
            let mid = (lo + hi) / 2;
            if self.blend(j, t, mid + 1).1 <= target {
                lo = mid + 1;
            } else {
                hi = mid;
            }
        }
        let i = lo;
        let ((fa, ga), (fb, gb)) = (self.blend(j, t, i), self.blend(j, t, i + 1));
        let s = if gb > ga {
            let (a, b) = normalise_ends(fa, fb);
            sample_linear_normalised(((target - ga) / (gb - ga)).clamp(0.0, 1.0), a, b)
        } else {
            f64::from(clamp_unit(u.x))
        };
        let x = (i as f64 + s) / (self.width - 1) as f64;
        let y = (j as f64 + t) / (self.height - 1) as f64;
        Vec2::new(x as f32, y as f32)
    }

    /// `f(x, y)/I` per unit area on `[0, 1]²` (the bilinear interpolation of the vertex
    /// values), 0 outside.
    #[inline]
    fn pdf(&self, p: Vec2) -> f32 {
        if !((0.0..=1.0).contains(&p.x) && (0.0..=1.0).contains(&p.y)) {
            return 0.0;
        }
        let (i, s) = Self::locate(p.x, self.width);
        let (j, t) = Self::locate(p.y, self.height);
        let (f0, f1) = (self.blend(j, t, i).0, self.blend(j, t, i + 1).0);
        (((1.0 - s) * f0 + s * f1) / self.integral()) as f32
    }
}

impl InvertibleWarp for PiecewiseLinear2D {
    #[inline]
    fn invert(&self, p: Vec2) -> Vec2 {
        let (j, t) = Self::locate(p.y, self.height);
        let (ma, mb) = normalise_ends(self.row_total(j), self.row_total(j + 1));
        let (c0, c1) = (self.marginal_cdf[j], self.marginal_cdf[j + 1]);
        let uy = (c0 + (c1 - c0) * linear_cdf_normalised(t, ma, mb)) / self.integral();
        let (i, s) = Self::locate(p.x, self.width);
        let ((fa, ga), (fb, gb)) = (self.blend(j, t, i), self.blend(j, t, i + 1));
        let (a, b) = normalise_ends(fa, fb);
        let row_total = self.blend(j, t, self.width - 1).1;
        let ux = if row_total > 0.0 {
            (ga + (gb - ga) * linear_cdf_normalised(s, a, b)) / row_total
        } else {
            f64::from(p.x)
        };
        Vec2::new(clamp_unit(ux as f32), clamp_unit(uy as f32))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_bad_grids() {
        assert!(PiecewiseLinear2D::new(&[1.0, 1.0], 1, 2).is_err());
        assert!(PiecewiseLinear2D::new(&[1.0; 4], 2, 3).is_err());
        assert!(PiecewiseLinear2D::new(&[0.0; 4], 2, 2).is_err());
        assert!(PiecewiseLinear2D::new(&[1.0, f32::NAN, 1.0, 1.0], 2, 2).is_err());
    }

    #[test]
    fn round_trip_with_zero_rows_and_columns() {
        #[rustfmt::skip]
        let v = [
            0.0, 0.0, 0.0, 0.0,
            0.0, 1.0, 3.0, 0.0,
            0.0, 0.0, 0.0, 0.0,
            2.0, 0.0, 5.0, 1.0,
        ];
        let d = PiecewiseLinear2D::new(&v, 4, 4).unwrap();
        for k in 1..30 {
            for l in 1..30 {
                let u = Vec2::new(k as f32 / 30.0, l as f32 / 30.0);
                let p = d.sample(u);
                assert!(p.is_finite() && d.pdf(p) > 0.0, "{u}: {p}");
                let back = d.invert(p);
                assert!((back - u).abs().max_element() < 1e-5, "{u}: {back}");
            }
        }
    }
}
