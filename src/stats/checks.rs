//! Companion checks: the pdf integrates to 1, the Jacobian identity
//! `pdf(sample(u)) · J(u) = 1`, the inverse round trip, and BSDF-like sample weights.

use super::domain::Domain;
use super::domain::StatPoint;
use super::parallel::{default_threads, map_indexed};
use crate::sampling::jacobian::numerical_jacobian_of;
use crate::sampling::warp::{InvertibleWarp, Warp};
use glam::Vec2;

/// The result of a companion check.
#[derive(Clone, Debug)]
pub struct CheckOutcome {
    /// What was checked.
    pub check: &'static str,
    /// Whether it passed ([`CheckOutcome::passed`]).
    passed: bool,
    /// The largest error found (its meaning depends on the check).
    pub worst_error: f64,
    /// The `u` (or point) where the worst error occurred, when there is one.
    pub worst_at: Option<Vec2>,
    /// Points checked.
    pub checked: usize,
    /// Points skipped (seams, singular points, zero pdf).
    pub skipped: usize,
    /// The tolerance applied.
    pub tolerance: f64,
}

impl CheckOutcome {
    /// Whether the check passed (a method, as [`Chi2Outcome::passed`](super::Chi2Outcome::passed)).
    #[must_use]
    pub fn passed(&self) -> bool {
        self.passed
    }

    /// A one-paragraph report.
    pub fn report(&self) -> String {
        format!(
            "{} check: {}; worst error {:.3e} (tolerance {:.1e}) at u = {:?}; {} points checked, {} skipped",
            self.check,
            if self.passed { "PASSED" } else { "FAILED" },
            self.worst_error,
            self.tolerance,
            self.worst_at,
            self.checked,
            self.skipped
        )
    }

    /// Panics with the report unless the check passed.
    ///
    /// # Panics
    /// When the check failed.
    #[track_caller]
    pub fn assert_passed(&self) -> &Self {
        assert!(self.passed, "{}", self.report());
        self
    }
}

impl std::fmt::Display for CheckOutcome {
    /// Writes [`CheckOutcome::report`].
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.report())
    }
}

/// Checks `|∫_domain pdf − 1| ≤ tolerance` (same quadrature as the chi-square test).
///
/// ```
/// use mcrt::glam::Vec3;
/// use mcrt::stats::{check_integral, Directions};
/// let pdf = |_: Vec3| 1.0 / (4.0 * std::f32::consts::PI);
/// check_integral(&Directions::sphere().resolution(8, 8), pdf, 1e-4).assert_passed();
/// ```
pub fn check_integral<D: Domain>(
    domain: &D,
    pdf: impl Fn(D::Point) -> f32 + Sync,
    tolerance: f64,
) -> CheckOutcome {
    let pdf64 = |p: D::Point| f64::from(pdf(p));
    let masses = map_indexed(domain.cell_count(), default_threads(), &|c| {
        domain.cell_mass(c, &pdf64)
    });
    let integral: f64 = masses.iter().sum();
    let err = (integral - 1.0).abs();
    CheckOutcome {
        check: "pdf integral",
        passed: err <= tolerance,
        worst_error: if err.is_nan() { f64::INFINITY } else { err },
        worst_at: None,
        checked: masses.len(),
        skipped: 0,
        tolerance,
    }
}

/// Settings of [`check_jacobian`].
#[derive(Clone, Copy, Debug)]
pub struct JacobianCheck {
    /// `u` is checked on a `grid × grid` lattice of cell centres (`u.x` only for 1D points).
    pub grid: usize,
    /// Central-difference step in `u`.
    pub step: f64,
    /// Tolerance of `|pdf · J − 1|`.
    pub tolerance: f64,
    /// Fraction of lattice points that may be skipped as seams before the check fails.
    pub max_skipped: f64,
}

impl Default for JacobianCheck {
    /// 64 × 64 points, step 2⁻⁹
    /// ([`DEFAULT_JACOBIAN_STEP`](crate::sampling::jacobian::DEFAULT_JACOBIAN_STEP), which
    /// balances truncation against `f32` rounding), tolerance 10⁻², at most 10 % skipped.
    fn default() -> Self {
        Self {
            grid: 64,
            step: crate::sampling::jacobian::DEFAULT_JACOBIAN_STEP,
            tolerance: 1e-2,
            max_skipped: 0.1,
        }
    }
}

/// Checks `pdf(sample(u)) · J(u) = 1`, with `J = √det(DᵀD)` of the map `u ↦ sample(u)` by
/// central differences in `f64`
/// ([`numerical_jacobian_of`](crate::sampling::jacobian::numerical_jacobian_of):
/// `|dx/du₁|` for `f32` points, `|det D|` for `Vec2`, `‖∂p/∂u₁ × ∂p/∂u₂‖` for `Vec3`).
///
/// Points where `J` with step `h` and with step `2h` disagree by more than the tolerance
/// (seams such as the concentric map's diagonals, singular points such as `√u` at 0),
/// where the stencil leaves `[0,1)²`, or where the pdf is 0 or the sample not finite are
/// skipped and counted.
pub fn check_jacobian<P: StatPoint>(
    sample: impl Fn(Vec2) -> P + Sync,
    pdf: impl Fn(P) -> f32 + Sync,
    settings: JacobianCheck,
) -> CheckOutcome {
    let n = settings.grid.max(1);
    let rows = if P::DIM == 1 { 1 } else { n };
    let eval = |k: usize| -> Option<(f64, Vec2)> {
        let u = Vec2::new(
            ((k % n) as f32 + 0.5) / n as f32,
            ((k / n) as f32 + 0.5) / rows as f32,
        );
        let p = sample(u);
        let density = f64::from(pdf(p));
        if !p.is_finite_point() || density.is_nan() || density <= 0.0 {
            return None;
        }
        let j1 = numerical_jacobian_of(&sample, u, settings.step)?;
        let j2 = numerical_jacobian_of(&sample, u, 2.0 * settings.step)?;
        ((j1 - j2).abs() <= settings.tolerance * j1.abs()).then(|| ((density * j1 - 1.0).abs(), u))
    };
    let results = map_indexed(n * rows, default_threads(), &eval);
    summarise(
        "Jacobian",
        &results,
        settings.tolerance,
        settings.max_skipped,
    )
}

/// [`check_jacobian`] for a [`Warp`].
pub fn check_warp_jacobian<W: Warp + Sync>(warp: &W, settings: JacobianCheck) -> CheckOutcome
where
    W::Point: StatPoint,
{
    check_jacobian(|u| warp.sample(u), |p| warp.pdf(p), settings)
}

/// Checks the inverse round trip on a `grid × grid` lattice of `u` strictly inside
/// `[margin, 1 − margin]²` (`u.x` only when `dims == 1`): `|invert(sample(u)) − u|∞ ≤
/// tolerance`. Points whose sample is not finite count as failures.
pub fn check_inverse<P: StatPoint>(
    sample: impl Fn(Vec2) -> P + Sync,
    invert: impl Fn(P) -> Vec2 + Sync,
    dims: usize,
    grid: usize,
    tolerance: f64,
) -> CheckOutcome {
    let n = grid.max(2);
    let rows = if dims == 1 { 1 } else { n };
    let margin = 1e-3;
    let eval = |k: usize| -> Option<(f64, Vec2)> {
        let at = |i: usize, m: usize| {
            (margin + (1.0 - 2.0 * margin) * (i as f64 + 0.5) / m as f64) as f32
        };
        let u = Vec2::new(at(k % n, n), if dims == 1 { 0.5 } else { at(k / n, rows) });
        let p = sample(u);
        let back = invert(p);
        let mut err = f64::from((back.x - u.x).abs());
        if dims != 1 {
            err = err.max(f64::from((back.y - u.y).abs()));
        }
        let err = if p.is_finite_point() && err.is_finite() {
            err
        } else {
            f64::INFINITY
        };
        Some((err, u))
    };
    let results = map_indexed(n * rows, default_threads(), &eval);
    summarise("inverse round trip", &results, tolerance, 0.0)
}

/// [`check_inverse`] for an [`InvertibleWarp`] (two-dimensional `u`).
pub fn check_warp_inverse<W: InvertibleWarp + Sync>(
    warp: &W,
    grid: usize,
    tolerance: f64,
) -> CheckOutcome
where
    W::Point: StatPoint,
{
    check_inverse(|u| warp.sample(u), |p| warp.invert(p), 2, grid, tolerance)
}

/// Checks the weights of a BSDF-like sampler on a `grid × grid` lattice: for each returned
/// `(point, weight)`, `weight = value(point) / pdf(point)` to a relative `tolerance`,
/// where `value` is what the weight estimates (e.g. `f · |cos θ|`). Rejected samples are
/// skipped.
pub fn check_weights<P: StatPoint>(
    sample: impl Fn(Vec2) -> Option<(P, f32)> + Sync,
    pdf: impl Fn(P) -> f32 + Sync,
    value: impl Fn(P) -> f32 + Sync,
    grid: usize,
    tolerance: f64,
) -> CheckOutcome {
    let n = grid.max(1);
    let eval = |k: usize| -> Option<(f64, Vec2)> {
        let u = Vec2::new(
            ((k % n) as f32 + 0.5) / n as f32,
            ((k / n) as f32 + 0.5) / n as f32,
        );
        let (p, w) = sample(u)?;
        let expected = f64::from(value(p)) / f64::from(pdf(p));
        let w = f64::from(w);
        let err = (w - expected).abs() / expected.abs().max(1e-12);
        Some((if err.is_finite() { err } else { f64::INFINITY }, u))
    };
    let results = map_indexed(n * n, default_threads(), &eval);
    summarise("sample weight", &results, tolerance, 1.0)
}

fn summarise(
    check: &'static str,
    results: &[Option<(f64, Vec2)>],
    tolerance: f64,
    max_skipped: f64,
) -> CheckOutcome {
    let mut out = CheckOutcome {
        check,
        passed: true,
        worst_error: 0.0,
        worst_at: None,
        checked: 0,
        skipped: 0,
        tolerance,
    };
    for r in results {
        match r {
            Some((e, u)) => {
                out.checked += 1;
                if e.is_nan() || *e > out.worst_error {
                    out.worst_error = *e;
                    out.worst_at = Some(*u);
                }
            }
            None => out.skipped += 1,
        }
    }
    let skipped_ok = out.skipped as f64 <= max_skipped * results.len() as f64;
    out.passed = out.checked > 0 && out.worst_error <= tolerance && skipped_ok;
    out
}
