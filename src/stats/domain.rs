//! Domains of the chi-square test and their cells: an interval, a rectangle of the plane and
//! a set of categories. Directions live in [`super::Directions`].

use super::quadrature::{integrate_1d, integrate_2d, Rect, REFINED_MIN_DEPTH};
use crate::sampling::jacobian::WarpPoint;
use glam::Vec2;

/// A point type the harness can bin, difference and share between threads: any
/// [`WarpPoint`] (`f32`, [`Vec2`], [`glam::Vec3`], `usize`) that is `Send + Sync + 'static`.
/// Implemented for every such type; the point trait itself is [`WarpPoint`].
pub trait StatPoint: WarpPoint + Send + Sync + 'static {}

impl<P: WarpPoint + Send + Sync + 'static> StatPoint for P {}

/// Absolute tolerance of each cell's integral (probability mass).
pub(crate) const CELL_ABS_TOL: f64 = 1e-13;

/// A density `p ↦ pdf(p)` in `f64`, as the harness hands it to a domain.
pub type PdfRef<'a, P> = &'a (dyn Fn(P) -> f64 + Sync);

/// A domain cut into cells: where samples are counted and the pdf is integrated.
///
/// Cells `0..grid().0 * grid().1` form a row-major grid (drawn in the failure images); a
/// domain may have more cells after those (the complement of a spherical cap).
pub trait Domain: Sync {
    /// The sampled point type.
    type Point: StatPoint;
    /// The number of cells.
    fn cell_count(&self) -> usize;
    /// The cell that holds `p`, or `None` when `p` is outside the domain or not finite.
    fn cell_of(&self, p: Self::Point) -> Option<usize>;
    /// The probability mass `∫_cell pdf` (adaptive quadrature in `f64`).
    fn cell_mass(&self, cell: usize, pdf: PdfRef<'_, Self::Point>) -> f64;
    /// [`Domain::cell_mass`] with a much finer forced subdivision; the harness calls it for
    /// cells that hold samples but whose mass came out 0, in case the quadrature nodes
    /// missed a sliver of support. Defaults to `cell_mass`.
    fn cell_mass_refined(&self, cell: usize, pdf: PdfRef<'_, Self::Point>) -> f64 {
        self.cell_mass(cell, pdf)
    }
    /// `(columns, rows)` of the grid formed by the first `columns · rows` cells.
    fn grid(&self) -> (usize, usize);
    /// The cell's extent in words, for reports.
    fn describe_cell(&self, cell: usize) -> String;
}

/// The interval `[min, max]` cut into `bins` equal cells; points are `f32`.
///
/// ```
/// use mcrt::stats::{Domain, Interval};
/// let d = Interval::new(0.0, 2.0, 4);
/// assert_eq!(d.cell_of(1.2), Some(2));
/// assert_eq!(d.cell_of(2.5), None);
/// ```
#[derive(Clone, Debug)]
pub struct Interval {
    min: f64,
    max: f64,
    bins: usize,
}

impl Interval {
    /// The interval `[min, max]` with `bins` cells (`min < max`, `bins ≥ 1`; both clamped
    /// to sane values).
    pub fn new(min: f64, max: f64, bins: usize) -> Self {
        let max = if max > min { max } else { min + 1.0 };
        Self {
            min,
            max,
            bins: bins.max(1),
        }
    }

    fn edges(&self, cell: usize) -> (f64, f64) {
        let w = (self.max - self.min) / self.bins as f64;
        (self.min + w * cell as f64, self.min + w * (cell + 1) as f64)
    }
}

/// The cell of `x` among `n` equal cells of `[lo, hi]` (`hi` itself in the last one).
pub(crate) fn bin(x: f64, lo: f64, hi: f64, n: usize) -> Option<usize> {
    if !(x >= lo && x <= hi) {
        return None;
    }
    let t = (x - lo) / (hi - lo) * n as f64;
    Some((t as usize).min(n - 1))
}

impl Domain for Interval {
    type Point = f32;
    fn cell_count(&self) -> usize {
        self.bins
    }
    fn cell_of(&self, p: f32) -> Option<usize> {
        bin(f64::from(p), self.min, self.max, self.bins)
    }
    fn cell_mass(&self, cell: usize, pdf: PdfRef<'_, f32>) -> f64 {
        let (a, b) = self.edges(cell);
        integrate_1d(&|x| pdf(x as f32), a, b, CELL_ABS_TOL, 0)
    }
    fn cell_mass_refined(&self, cell: usize, pdf: PdfRef<'_, f32>) -> f64 {
        let (a, b) = self.edges(cell);
        integrate_1d(
            &|x| pdf(x as f32),
            a,
            b,
            CELL_ABS_TOL,
            2 * REFINED_MIN_DEPTH,
        )
    }
    fn grid(&self) -> (usize, usize) {
        (self.bins, 1)
    }
    fn describe_cell(&self, cell: usize) -> String {
        let (a, b) = self.edges(cell);
        format!("x ∈ [{a:.6}, {b:.6})")
    }
}

/// The rectangle `[min.x, max.x] × [min.y, max.y]` cut into `nx × ny` equal cells; points
/// are [`Vec2`]. Disks and triangles fit in one (cells outside the support have zero mass).
///
/// ```
/// use mcrt::glam::Vec2;
/// use mcrt::stats::{Domain, Rectangle};
/// let d = Rectangle::new(Vec2::splat(-1.0), Vec2::splat(1.0), 4, 2);
/// assert_eq!(d.cell_of(Vec2::new(0.6, 0.5)), Some(4 + 3));
/// ```
#[derive(Clone, Debug)]
pub struct Rectangle {
    min: [f64; 2],
    max: [f64; 2],
    n: [usize; 2],
}

impl Rectangle {
    /// The rectangle from `min` to `max` with `nx × ny` cells (degenerate input is widened
    /// to a unit extent, counts to at least 1).
    pub fn new(min: Vec2, max: Vec2, nx: usize, ny: usize) -> Self {
        let fix = |lo: f32, hi: f32| {
            let (lo, hi) = (f64::from(lo), f64::from(hi));
            if hi > lo {
                hi
            } else {
                lo + 1.0
            }
        };
        Self {
            min: [f64::from(min.x), f64::from(min.y)],
            max: [fix(min.x, max.x), fix(min.y, max.y)],
            n: [nx.max(1), ny.max(1)],
        }
    }

    /// The unit square `[0,1]²` with `n × n` cells.
    pub fn unit_square(n: usize) -> Self {
        Self::new(Vec2::ZERO, Vec2::ONE, n, n)
    }

    fn rect(&self, cell: usize) -> Rect {
        let (i, j) = (cell % self.n[0], cell / self.n[0]);
        let w = [
            (self.max[0] - self.min[0]) / self.n[0] as f64,
            (self.max[1] - self.min[1]) / self.n[1] as f64,
        ];
        Rect {
            a0: self.min[0] + w[0] * i as f64,
            a1: self.min[0] + w[0] * (i + 1) as f64,
            b0: self.min[1] + w[1] * j as f64,
            b1: self.min[1] + w[1] * (j + 1) as f64,
        }
    }
}

impl Domain for Rectangle {
    type Point = Vec2;
    fn cell_count(&self) -> usize {
        self.n[0] * self.n[1]
    }
    fn cell_of(&self, p: Vec2) -> Option<usize> {
        let i = bin(f64::from(p.x), self.min[0], self.max[0], self.n[0])?;
        let j = bin(f64::from(p.y), self.min[1], self.max[1], self.n[1])?;
        Some(j * self.n[0] + i)
    }
    fn cell_mass(&self, cell: usize, pdf: PdfRef<'_, Vec2>) -> f64 {
        let f = |a: f64, b: f64| pdf(Vec2::new(a as f32, b as f32));
        integrate_2d(&f, self.rect(cell), CELL_ABS_TOL, 0)
    }
    fn cell_mass_refined(&self, cell: usize, pdf: PdfRef<'_, Vec2>) -> f64 {
        let f = |a: f64, b: f64| pdf(Vec2::new(a as f32, b as f32));
        integrate_2d(&f, self.rect(cell), CELL_ABS_TOL, REFINED_MIN_DEPTH)
    }
    fn grid(&self) -> (usize, usize) {
        (self.n[0], self.n[1])
    }
    fn describe_cell(&self, cell: usize) -> String {
        let r = self.rect(cell);
        format!(
            "x ∈ [{:.5}, {:.5}), y ∈ [{:.5}, {:.5})",
            r.a0, r.a1, r.b0, r.b1
        )
    }
}

/// `n` categories `0..n` (an alias table's outcomes); points are `usize` and the "pdf" is
/// the probability mass function.
///
/// ```
/// use mcrt::stats::{Discrete, Domain};
/// assert_eq!(Discrete::new(3).cell_of(2), Some(2));
/// assert_eq!(Discrete::new(3).cell_of(3), None);
/// ```
#[derive(Clone, Debug)]
pub struct Discrete {
    n: usize,
}

impl Discrete {
    /// Categories `0..n` (`n ≥ 1`).
    pub fn new(n: usize) -> Self {
        Self { n: n.max(1) }
    }
}

impl Domain for Discrete {
    type Point = usize;
    fn cell_count(&self) -> usize {
        self.n
    }
    fn cell_of(&self, p: usize) -> Option<usize> {
        (p < self.n).then_some(p)
    }
    fn cell_mass(&self, cell: usize, pmf: PdfRef<'_, usize>) -> f64 {
        pmf(cell)
    }
    fn grid(&self) -> (usize, usize) {
        (self.n, 1)
    }
    fn describe_cell(&self, cell: usize) -> String {
        format!("category {cell}")
    }
}
