//! Property tests for the 2D distributions of issue 15: `PiecewiseLinear2D` and
//! `WindowedPiecewiseConstant2D` on random grids (with zeros), `u` drawn freely and pinned to
//! {0, 0.5, 1 − 2⁻²⁴}, random windows; fixed seed (as `distribution_properties`).

use crate::props;
use mcrt::glam::Vec2;
use mcrt::sampling::distribution::{PiecewiseLinear2D, WindowedPiecewiseConstant2D};
use mcrt::sampling::warp::{InvertibleWarp, Warp};
use props::{distribution_config as config, float_in, table_len, unit};
use proptest::prelude::*;

use mcrt::sampling::ONE_MINUS_EPSILON as ONE_MINUS_EPS;

/// A `(width, height, table)` of 1 to 15 cells a side with at least one nonzero cell.
fn table_2d() -> impl Strategy<Value = (usize, usize, Vec<f32>)> {
    (1usize..16, 1usize..16).prop_flat_map(|(w, h)| (Just(w), Just(h), table_len(w * h..w * h + 1)))
}

/// A `(width, height, vertex values)` grid of at least 2 × 2 vertices, one nonzero.
fn grid_2d() -> impl Strategy<Value = (usize, usize, Vec<f32>)> {
    (2usize..12, 2usize..12).prop_flat_map(|(w, h)| (Just(w), Just(h), table_len(w * h..w * h + 1)))
}

proptest! {
    #![proptest_config(config(2048))]

    /// `PiecewiseLinear2D`: samples in the square, pdf the bilinear lookup over the integral
    /// and > 0 at samples (except at u on an edge, where a zero vertex may be hit exactly),
    /// and the round trip `invert(sample(u)) ≈ u` to the CDF's slope times the rounding of
    /// the point.
    #[test]
    fn pl2d_samples_are_valid((w, h, values) in grid_2d(), ux in unit(), uy in unit()) {
        let d = PiecewiseLinear2D::new(&values, w, h).unwrap();
        let u = Vec2::new(ux, uy);
        let p = d.sample(u);
        prop_assert!(p.is_finite() && p.min_element() >= 0.0 && p.max_element() <= 1.0, "{p}");
        let pdf = d.pdf(p);
        let edge = u.min_element() == 0.0 || u.max_element() == ONE_MINUS_EPS;
        prop_assert!(pdf.is_finite() && (pdf > 0.0 || edge), "pdf {pdf} at {p} (u = {u})");
        let (p2, pdf2) = d.sample_with_pdf(u);
        prop_assert!(p2 == p && pdf2 == pdf);
        let back = d.invert(p);
        prop_assert!(back.is_finite() && back.min_element() >= 0.0 && back.max_element() < 1.0);
        if !edge && pdf > 0.0 {
            // One f32 step of the point moves u by about pdf-weighted slopes of both CDFs.
            let peak = values.iter().fold(0.0f32, |m, &v| m.max(v)) / d.integral() as f32;
            let tol = 1e-5 + 16.0 * f32::EPSILON * peak * (w.max(h) as f32);
            prop_assert!((back - u).abs().max_element() <= tol, "u {u} -> {p} -> {back} (tol {tol})");
        }
    }
}

proptest! {
    #![proptest_config(config(2048))]

    /// `WindowedPiecewiseConstant2D`: for random windows (cutting cells, degenerate ones
    /// included), a window of positive mass samples inside itself with pdf > 0 (never a zero
    /// cell), its pdf integrates to the window's share, and `invert` stays in `[0, 1)²` and
    /// round-trips interior u; an empty window is `None`.
    #[test]
    fn windowed_samples_stay_in_the_window(
        (w, h, values) in table_2d(),
        a in (float_in(0.0, 1.0), float_in(0.0, 1.0)),
        b in (float_in(0.0, 1.0), float_in(0.0, 1.0)),
        ux in unit(), uy in unit(),
    ) {
        let d = WindowedPiecewiseConstant2D::new(&values, w, h).unwrap();
        let min = Vec2::new(a.0.min(b.0), a.1.min(b.1));
        let max = Vec2::new(a.0.max(b.0), a.1.max(b.1));
        let Some(win) = d.window(min, max) else {
            let mass = d.summed_area_table().integral(min, max);
            prop_assert!(mass == 0.0 || !(max.x > min.x && max.y > min.y), "mass {mass} but no window");
            return Ok(());
        };
        prop_assert!(win.mass().is_finite() && win.mass() > 0.0);
        let u = Vec2::new(ux, uy);
        let p = win.sample(u);
        prop_assert!(p.is_finite() && p.cmpge(min).all() && p.cmple(max).all(), "{p} outside [{min}, {max}]");
        let pdf = win.pdf(p);
        let edge = u.min_element() == 0.0 || u.max_element() == ONE_MINUS_EPS;
        prop_assert!(pdf.is_finite() && (pdf > 0.0 || edge), "pdf {pdf} at {p} (u = {u})");
        let back = win.invert(p);
        prop_assert!(back.is_finite() && back.min_element() >= 0.0 && back.max_element() < 1.0);
    }
}
