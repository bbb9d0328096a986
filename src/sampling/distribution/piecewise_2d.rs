//! A piecewise-constant density on the unit square, sampled by the marginal/conditional
//! method.

use glam::Vec2;

use crate::sampling::warp::{InvertibleWarp, Warp};

use super::piecewise_1d::{drop_underflowing, validate_grid, PiecewiseConstant1D};
use crate::sampling::SamplingError;

/// A piecewise-constant density on `[0,1)²` proportional to a `width × height` table stored
/// row-major: column `x` spans `u ∈ [x/width, (x+1)/width)`, row `y` spans
/// `v ∈ [y/height, (y+1)/height)`.
///
/// The density is `p(u, v) = f[y][x] / I` per unit area of `[0,1)²`, where
/// `I = Σ f / (width · height)` is the [`integral`](Self::integral). Sampling uses the
/// marginal/conditional method: `v` is drawn from the marginal density of the rows (row sums)
/// with `u.y`, then `u` from the chosen row's conditional density with `u.x` (see
/// `docs/derivations.md`). Rows that are all zero are allowed (they are never
/// chosen); no zero-valued cell is ever sampled. Cells whose density underflows `f32`
/// (below about 10⁻⁴⁵) count as zero.
///
/// **Environment maps.** For a latitude–longitude map with `u = φ / 2π` and `v = θ / π`,
/// the density of the direction per unit solid angle is `p(ω) = p(u, v) / (2π² sin θ)`
/// ([`crate::sampling::jacobian::solid_angle_pdf_from_lat_long`]). Weight each row's values
/// by `sin θ` of its centre before building the table, so that sampling follows the
/// radiance per solid angle. [`LatLong`](crate::sampling::warp::LatLong) maps directions to
/// `(u, v) ∈ [0,1)²` and back (the south pole stays on the last row: at `v = 1` this
/// table's pdf is 0).
///
/// Reference: Pharr, Jakob & Humphreys, 2023, *Physically Based Rendering* (4th ed.),
/// section A.5.2, "Piecewise-constant 2D distributions".
///
/// ```
/// use mcrt::glam::Vec2;
/// use mcrt::sampling::distribution::PiecewiseConstant2D;
///
/// // 2 columns × 2 rows; the top-left cell is empty.
/// let d = PiecewiseConstant2D::new(&[0.0, 1.0, 1.0, 2.0], 2, 2).unwrap();
/// let (p, pdf, cell) = d.sample_cell(Vec2::new(0.1, 0.2));
/// assert_ne!(cell, [0, 0]);
/// assert!((pdf - d.pdf(p)).abs() < 1e-6);
/// assert!((d.cell_mass(1, 1) - 0.5).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct PiecewiseConstant2D {
    /// One conditional distribution per row; `None` for an all-zero row.
    conditional: Vec<Option<PiecewiseConstant1D>>,
    /// The marginal distribution of the rows (proportional to row sums).
    marginal: PiecewiseConstant1D,
    /// The table, row-major (entries whose density underflows `f32` set to 0).
    values: Vec<f64>,
    /// Columns.
    width: usize,
    /// Rows.
    height: usize,
    /// `width · height / Σ f`: multiplies a value into a density per unit area.
    pdf_scale: f64,
}

impl PiecewiseConstant2D {
    /// A distribution on `[0,1)²` proportional to the row-major `values` (`height` rows of
    /// `width` columns).
    ///
    /// # Errors
    /// [`SamplingError::ShapeMismatch`] when `values.len() != width · height`,
    /// [`SamplingError::EmptyTable`] for a zero dimension, [`SamplingError::InvalidEntry`]
    /// for a negative, NaN or infinite value, [`SamplingError::ZeroTable`] when every value
    /// is 0, [`SamplingError::InvalidParameter`] when `width` or `height` exceeds 2²⁴ (a
    /// cell would be narrower than an `f32` step).
    pub fn new(values: &[f32], width: usize, height: usize) -> Result<Self, SamplingError> {
        let n = validate_grid(values, width, height)?;
        let mut cells: Vec<f64> = values.iter().map(|&v| f64::from(v)).collect();
        let sum: f64 = cells.iter().sum();
        if sum <= 0.0 {
            return Err(SamplingError::ZeroTable);
        }
        drop_underflowing(&mut cells, n as f64 / sum);
        let mut conditional = Vec::with_capacity(height);
        let mut row_sums = Vec::with_capacity(height);
        for row in cells.chunks_exact(width) {
            let row_sum: f64 = row.iter().sum();
            row_sums.push(row_sum);
            conditional.push(if row_sum > 0.0 {
                Some(PiecewiseConstant1D::from_validated(row.to_vec(), 0.0, 1.0)?)
            } else {
                None
            });
        }
        let marginal = PiecewiseConstant1D::from_validated(row_sums, 0.0, 1.0)?;
        let pdf_scale = n as f64 / marginal.total();
        Ok(Self {
            conditional,
            marginal,
            values: cells,
            width,
            height,
            pdf_scale,
        })
    }

    /// Draws a point of `[0,1)²` from `u ∈ [0,1)²` (`u.y` picks the row, `u.x` the column):
    /// returns `(point, pdf(point), [column, row])`, the pdf per unit area of `[0,1)²`.
    /// Never returns a zero-valued cell. [`Warp::sample`] and [`Warp::sample_with_pdf`]
    /// return the same point without the cell.
    #[must_use]
    pub fn sample_cell(&self, u: Vec2) -> (Vec2, f32, [usize; 2]) {
        let (v, _, row) = self.marginal.sample(u.y);
        // The marginal never returns a zero row, so the conditional exists.
        let Some(cond) = self.conditional[row].as_ref() else {
            debug_assert!(false, "the marginal chose an empty row");
            return (Vec2::new(0.0, v), 0.0, [0, row]);
        };
        let (x, _, col) = cond.sample(u.x);
        (Vec2::new(x, v), self.pdf_of_cell(col, row), [col, row])
    }

    /// The density of [`sample_cell`](Self::sample_cell) at `p`, per unit area of `[0,1)²`; 0 outside
    /// the square.
    #[must_use]
    #[inline]
    pub fn pdf(&self, p: Vec2) -> f32 {
        match self.cell_of(p) {
            Some([x, y]) => self.pdf_of_cell(x, y),
            None => 0.0,
        }
    }

    /// The `u` that [`sample_cell`](Self::sample_cell) maps to `p`: the marginal CDF at `p.y` and the
    /// conditional CDF of that row at `p.x`. In an all-zero row (never sampled) `u.x` is
    /// `p.x` clamped into `[0,1)`.
    #[must_use]
    #[inline]
    pub fn invert(&self, p: Vec2) -> Vec2 {
        let uy = self.marginal.invert(p.y);
        let row = self
            .marginal
            .bin_of(p.y)
            .unwrap_or(if p.y < 0.5 { 0 } else { self.height - 1 });
        let ux = match self.conditional[row].as_ref() {
            Some(cond) => cond.invert(p.x),
            None => super::piecewise_1d::clamp_unit(p.x.max(0.0)),
        };
        Vec2::new(ux, uy)
    }

    /// `∫∫ f(u, v) du dv` over `[0,1)²`: the mean value of the table.
    #[must_use]
    pub fn integral(&self) -> f32 {
        (self.marginal.total() / (self.width * self.height) as f64) as f32
    }

    /// The exact probability of cell (`x` = column, `y` = row), in `f64`; 0 outside the
    /// table. For the chi-square harness's expected counts.
    #[must_use]
    pub fn cell_mass(&self, x: usize, y: usize) -> f64 {
        if x >= self.width || y >= self.height {
            return 0.0;
        }
        self.values[y * self.width + x] / self.marginal.total()
    }

    /// The cell `[column, row]` holding `p`, or `None` outside `[0,1)²`.
    #[must_use]
    pub fn cell_of(&self, p: Vec2) -> Option<[usize; 2]> {
        let row = self.marginal.bin_of(p.y)?;
        // The same bin arithmetic as the conditional distributions' `bin_of` on [0, 1).
        let t = f64::from(p.x) * self.width as f64;
        if t >= 0.0 && t < self.width as f64 {
            Some([t as usize, row])
        } else {
            None
        }
    }

    /// The number of columns.
    #[must_use]
    pub fn width(&self) -> usize {
        self.width
    }

    /// The number of rows.
    #[must_use]
    pub fn height(&self) -> usize {
        self.height
    }

    /// The marginal distribution of the rows (over `v`).
    #[must_use]
    pub fn marginal(&self) -> &PiecewiseConstant1D {
        &self.marginal
    }

    /// The conditional distribution of row `y` (over `u`), or `None` for an all-zero row or
    /// past the end.
    #[must_use]
    pub fn conditional(&self, y: usize) -> Option<&PiecewiseConstant1D> {
        self.conditional.get(y)?.as_ref()
    }

    /// The density per unit area in cell (`x`, `y`).
    fn pdf_of_cell(&self, x: usize, y: usize) -> f32 {
        (self.values[y * self.width + x] * self.pdf_scale) as f32
    }
}

/// The distribution as a warp of the unit square onto itself, so generic code (the
/// chi-square harness, property tests) can take it. The inherent
/// [`sample_cell`](PiecewiseConstant2D::sample_cell) also returns the cell.
impl Warp for PiecewiseConstant2D {
    type Point = Vec2;

    #[inline]
    fn sample(&self, u: Vec2) -> Vec2 {
        self.sample_cell(u).0
    }

    #[inline]
    fn pdf(&self, p: Vec2) -> f32 {
        PiecewiseConstant2D::pdf(self, p)
    }

    #[inline]
    fn sample_with_pdf(&self, u: Vec2) -> (Vec2, f32) {
        let (p, pdf, _) = self.sample_cell(u);
        (p, pdf)
    }
}

impl InvertibleWarp for PiecewiseConstant2D {
    #[inline]
    fn invert(&self, p: Vec2) -> Vec2 {
        PiecewiseConstant2D::invert(self, p)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::ONE_MINUS_EPSILON;

    #[test]
    fn rejects_bad_tables() {
        let e = PiecewiseConstant2D::new(&[1.0; 5], 2, 3).unwrap_err();
        assert_eq!(
            e,
            SamplingError::ShapeMismatch {
                expected: 6,
                got: 5
            }
        );
        assert_eq!(
            PiecewiseConstant2D::new(&[], 0, 3),
            Err(SamplingError::EmptyTable)
        );
        assert_eq!(
            PiecewiseConstant2D::new(&[0.0; 4], 2, 2),
            Err(SamplingError::ZeroTable)
        );
        let e = PiecewiseConstant2D::new(&[1.0, 1.0, -1.0, 1.0], 2, 2).unwrap_err();
        assert!(matches!(e, SamplingError::InvalidEntry { index: 2, .. }));
    }

    #[test]
    fn zero_rows_and_cells_are_never_sampled() {
        // 3 columns × 3 rows; the middle row is empty, and so are several cells.
        let t = [0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0];
        let d = PiecewiseConstant2D::new(&t, 3, 3).unwrap();
        for ux in [0.0, 0.5, ONE_MINUS_EPSILON] {
            for uy in [0.0, 1.0 / 3.0, 0.5, ONE_MINUS_EPSILON] {
                let (p, pdf, [x, y]) = d.sample_cell(Vec2::new(ux, uy));
                assert!(p.is_finite() && pdf.is_finite() && pdf > 0.0);
                assert!(t[y * 3 + x] > 0.0, "u = ({ux}, {uy}) gave cell ({x}, {y})");
                assert_eq!(d.cell_of(p), Some([x, y]));
                assert_eq!(pdf, d.pdf(p));
            }
        }
    }

    #[test]
    fn pdf_mass_and_round_trip() {
        let d = PiecewiseConstant2D::new(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0], 3, 2).unwrap();
        assert!((d.integral() - 3.5).abs() < 1e-6);
        let pdf = d.pdf(Vec2::new(0.9, 0.9));
        assert!(pdf.is_finite() && (pdf - 6.0 / 3.5).abs() < 1e-6);
        assert_eq!(d.pdf(Vec2::new(1.0, 0.5)), 0.0);
        let total: f64 = (0..3)
            .flat_map(|x| (0..2).map(move |y| (x, y)))
            .map(|(x, y)| d.cell_mass(x, y))
            .sum();
        assert!((total - 1.0).abs() < 1e-12);
        let u = Vec2::new(0.3, 0.7);
        let (p, _, _) = d.sample_cell(u);
        let back = d.invert(p);
        assert!(back.is_finite() && (back - u).abs().max_element() < 1e-6);
        // The same through the warp traits.
        let (q, pdf) = Warp::sample_with_pdf(&d, u);
        assert_eq!((q, pdf), (p, d.pdf(p)));
        assert_eq!(InvertibleWarp::invert(&d, q), back);
    }
}
