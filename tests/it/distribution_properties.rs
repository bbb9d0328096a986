//! Property tests for the distributions and the MIS weights: random tables (with zeros),
//! `u` drawn freely and pinned to {0, 0.5, 1 − 2⁻²⁴}; fixed seeds throughout.

use crate::props;
use mcrt::glam::Vec2;
use mcrt::sampling::distribution::{
    sample_by_inversion, AliasTable, PiecewiseConstant1D, PiecewiseConstant2D,
};
use mcrt::sampling::mis::{
    balance_heuristic, balance_heuristic_n, power_heuristic, power_heuristic_n,
};
use mcrt::sampling::SamplingError;
use props::{distribution_config as config, float_in, table_len, unit};
use proptest::prelude::*;
use rand::{Rng, SeedableRng};

use mcrt::sampling::ONE_MINUS_EPSILON as ONE_MINUS_EPS;

/// A table with at least one nonzero entry.
fn table(max_len: usize) -> impl Strategy<Value = Vec<f32>> {
    table_len(1..max_len)
}

/// A `(width, height, table)` with at least one nonzero cell.
fn table_2d() -> impl Strategy<Value = (usize, usize, Vec<f32>)> {
    (1usize..16, 1usize..16).prop_flat_map(|(w, h)| (Just(w), Just(h), table_len(w * h..w * h + 1)))
}

/// The index of a nonzero entry, picked by `pick`.
fn nonzero(values: &[f32], pick: prop::sample::Index) -> usize {
    let nz: Vec<usize> = (0..values.len()).filter(|&i| values[i] > 0.0).collect();
    nz[pick.index(nz.len())]
}

fn finite_close(a: f32, b: f32, rel: f32) -> bool {
    a.is_finite() && b.is_finite() && (a - b).abs() <= rel * a.abs().max(b.abs()) + 1e-30
}

proptest! {
    #![proptest_config(config(4096))]

    #[test]
    fn pc1d_samples_are_valid(values in table(200), u in unit()) {
        let d = PiecewiseConstant1D::new(&values).unwrap();
        let (x, pdf, i) = d.sample(u);
        prop_assert!(x.is_finite() && (0.0..1.0).contains(&x), "x = {x}");
        prop_assert!(values[i] > 0.0, "zero bin {i} sampled at u = {u}");
        prop_assert_eq!(d.bin_of(x), Some(i));
        prop_assert!(pdf.is_finite() && pdf > 0.0);
        prop_assert_eq!(pdf, d.pdf(x));
        prop_assert!(finite_close(pdf, values[i] / d.integral(), 1e-5));
        // invert(sample(u)) ≈ u: the error is the CDF's slope times x's rounding.
        let back = d.invert(x);
        let tol = 1e-6 + pdf * 4.0 * f32::EPSILON;
        prop_assert!(back.is_finite() && (back - u).abs() <= tol, "u {u} -> x {x} -> {back}");
    }

    #[test]
    fn pc1d_sample_of_invert_round_trips(values in table(200), pick in any::<prop::sample::Index>(), frac in float_in(0.0, 1.0)) {
        let d = PiecewiseConstant1D::new(&values).unwrap();
        let k = nonzero(&values, pick);
        let x = ((k as f32 + frac) / values.len() as f32).min(1.0f32.next_down());
        let i = d.bin_of(x).unwrap();
        if values[i] == 0.0 {
            return Ok(()); // rounding carried x onto a zero neighbour
        }
        let (y, pdf_y, j) = d.sample(d.invert(x));
        // The error is u's f32 rounding over the CDF's slope; at a bin edge the rounding may
        // land at the adjacent end of the neighbouring bin, hence the smaller slope.
        let tol = 4.0 * f32::EPSILON / d.pdf(x).min(pdf_y) + 2.0 * f32::EPSILON;
        prop_assert!(y.is_finite() && (y - x).abs() <= tol, "x {x} (bin {i}) -> {y} (bin {j})");
    }

    #[test]
    fn pc1d_on_random_intervals(values in table(100), min in float_in(-1e4, 1e4), width in (-3i32..4, float_in(1.0, 10.0)).prop_map(|(e, m)| m * 10f32.powi(e)), u in unit()) {
        let max = min + width;
        let Ok(d) = PiecewiseConstant1D::new_on(&values, min, max) else {
            // Only bins narrower than the f32 spacing are rejected.
            let spacing = min.abs().max(max.abs()) * f32::EPSILON;
            prop_assert!((max - min) / (values.len() as f32) < spacing);
            return Ok(());
        };
        let (x, pdf, i) = d.sample(u);
        prop_assert!(x.is_finite() && x >= min && x < max, "{x} outside [{min}, {max})");
        prop_assert!(values[i] > 0.0);
        prop_assert_eq!(d.bin_of(x), Some(i));
        prop_assert!(pdf.is_finite() && pdf > 0.0 && pdf == d.pdf(x));
        prop_assert!(finite_close(pdf, values[i] / d.integral(), 1e-5));
    }

    #[test]
    fn pc1d_extreme_dynamic_range(
        values in prop::collection::vec(prop_oneof![Just(0.0f32), Just(1e-38f32), Just(1e30f32), float_in(0.0, 1.0)], 1..64),
        u in unit(),
    ) {
        prop_assume!(values.iter().any(|&v| v > 0.0));
        let d = PiecewiseConstant1D::new_on(&values, -3.0, 5.0).unwrap();
        let (x, pdf, i) = d.sample(u);
        prop_assert!(x.is_finite() && (-3.0..5.0).contains(&x));
        prop_assert!(values[i] > 0.0);
        prop_assert!(pdf.is_finite() && pdf > 0.0);
        prop_assert!(d.integral().is_finite());
        let d2 = PiecewiseConstant2D::new(&values, 1, values.len()).unwrap();
        let (p, pdf, [_, y]) = d2.sample_cell(Vec2::new(u, 1.0 - u.max(f32::EPSILON)));
        prop_assert!(p.is_finite() && values[y] > 0.0 && pdf.is_finite() && pdf > 0.0);
        let t = AliasTable::new(&values).unwrap();
        let (k, pmf) = t.sample_with_pmf(u);
        prop_assert!(values[k] > 0.0 && pmf.is_finite() && pmf > 0.0);
    }

    #[test]
    fn pc2d_samples_are_valid((w, h, values) in table_2d(), ux in unit(), uy in unit()) {
        let d = PiecewiseConstant2D::new(&values, w, h).unwrap();
        let u = Vec2::new(ux, uy);
        let (p, pdf, [x, y]) = d.sample_cell(u);
        prop_assert!(p.is_finite() && p.cmpge(Vec2::ZERO).all() && p.cmplt(Vec2::ONE).all());
        prop_assert!(values[y * w + x] > 0.0, "zero cell ({x}, {y}) sampled");
        prop_assert_eq!(d.cell_of(p), Some([x, y]));
        prop_assert!(pdf.is_finite() && pdf > 0.0);
        prop_assert_eq!(pdf, d.pdf(p));
        prop_assert!(finite_close(pdf, values[y * w + x] / d.integral(), 1e-5));
        let mass = d.cell_mass(x, y) as f32 * (w * h) as f32;
        prop_assert!(finite_close(mass, pdf, 1e-5));
        let back = d.invert(p);
        let tol = 1e-6 + pdf * 4.0 * f32::EPSILON * (w * h) as f32;
        prop_assert!(back.is_finite() && (back - u).abs().max_element() <= tol, "{u} -> {p} -> {back}");
    }

    #[test]
    fn pc2d_sample_of_invert_round_trips(
        (w, h, values) in table_2d(),
        pick in any::<prop::sample::Index>(),
        fx in float_in(0.0, 1.0),
        fy in float_in(0.0, 1.0),
    ) {
        let d = PiecewiseConstant2D::new(&values, w, h).unwrap();
        let k = nonzero(&values, pick);
        let below_one = 1.0f32.next_down();
        let px = (((k % w) as f32 + fx) / w as f32).min(below_one);
        let py = (((k / w) as f32 + fy) / h as f32).min(below_one);
        let p = Vec2::new(px, py);
        let [x, y] = d.cell_of(p).unwrap();
        if values[y * w + x] == 0.0 {
            return Ok(()); // rounding carried p onto a zero neighbour
        }
        let (q, _, [_, row]) = d.sample_cell(d.invert(p));
        // The error is u's f32 rounding over the slope of each CDF (see the 1D test).
        let m = d.marginal();
        let tol_y = 4.0 * f32::EPSILON / m.pdf(py).min(m.pdf(q.y)) + 2.0 * f32::EPSILON;
        prop_assert!(q.is_finite() && (q.y - py).abs() <= tol_y, "{p} -> {q}");
        // At a row edge the rounding may switch rows, and u.x then means another row's
        // conditional; within the row, x round trips too.
        if row == y {
            let c = d.conditional(y).unwrap();
            let tol_x = 4.0 * f32::EPSILON / c.pdf(px).min(c.pdf(q.x)) + 2.0 * f32::EPSILON;
            prop_assert!((q.x - px).abs() <= tol_x, "{p} -> {q}");
        }
    }

    #[test]
    fn alias_never_returns_a_zero_weight(weights in table(300), u in unit(), coin in unit()) {
        let t = AliasTable::new(&weights).unwrap();
        let (i, pmf) = t.sample_with_pmf(u);
        prop_assert!(weights[i] > 0.0, "zero weight {i} at u = {u}");
        prop_assert!(pmf.is_finite() && pmf > 0.0 && pmf == t.pmf(i));
        prop_assert!(weights[t.sample_split(Vec2::new(u, coin))] > 0.0);
        let sum: f64 = (0..t.len()).map(|k| t.pmf_f64(k)).sum();
        prop_assert!(sum.is_finite() && (sum - 1.0).abs() < 1e-12);
    }

    #[test]
    fn constructors_reject_bad_entries(
        values in table(50),
        at in any::<prop::sample::Index>(),
        bad in prop_oneof![Just(f32::NAN), Just(f32::INFINITY), Just(f32::NEG_INFINITY), (-30i32..9).prop_map(|e| -(10f32.powi(e)))],
    ) {
        let mut v = values;
        let index = at.index(v.len());
        v[index] = bad;
        let is_entry = |e: SamplingError| matches!(e, SamplingError::InvalidEntry { index: k, .. } if k == index);
        prop_assert!(is_entry(PiecewiseConstant1D::new(&v).unwrap_err()));
        prop_assert!(is_entry(AliasTable::new(&v).unwrap_err()));
        prop_assert!(is_entry(PiecewiseConstant2D::new(&v, v.len(), 1).unwrap_err()));
        let zeros = vec![0.0; v.len()];
        prop_assert_eq!(PiecewiseConstant1D::new(&zeros), Err(SamplingError::ZeroTable));
        prop_assert_eq!(AliasTable::new(&zeros), Err(SamplingError::ZeroTable));
        prop_assert_eq!(PiecewiseConstant2D::new(&zeros, 1, zeros.len()), Err(SamplingError::ZeroTable));
    }

    #[test]
    fn inversion_matches_a_known_inverse(k in 1i32..6, u in 0.0f64..=1.0) {
        // p(x) ∝ x^(k−1) on [0, 2]: x = 2 u^(1/k).
        let x = sample_by_inversion(|x| x.powi(k), |x| f64::from(k) * x.powi(k - 1), 0.0, 2.0, u, 1e-13).unwrap();
        let want = 2.0 * u.powf(1.0 / f64::from(k));
        prop_assert!(x.is_finite() && (x - want).abs() < 1e-9, "{x} vs {want}");
    }

    #[test]
    fn mis_weights_are_in_unit_interval_and_sum_to_one(
        nf in prop_oneof![Just(1.0f32), float_in(0.0, 64.0)],
        ng in prop_oneof![Just(1.0f32), float_in(0.0, 64.0)],
        pf in pdf_value(),
        pg in pdf_value(),
    ) {
        for h in [balance_heuristic, power_heuristic] {
            let (wf, wg) = (h(nf, pf, ng, pg), h(ng, pg, nf, pf));
            prop_assert!(wf.is_finite() && (0.0..=1.0).contains(&wf));
            prop_assert!(wg.is_finite() && (0.0..=1.0).contains(&wg));
            let (f, g) = (nf * pf, ng * pg);
            if pf.is_finite() && pg.is_finite() && (f > 0.0 || g > 0.0) && nf > 0.0 && ng > 0.0 {
                prop_assert!((wf + wg - 1.0).abs() < 1e-6, "{wf} + {wg}");
            }
        }
        let items = [(nf, pf), (ng, pg), (1.0, 0.5)];
        for h in [balance_heuristic_n, power_heuristic_n] {
            let ws: Vec<f32> = (0..3).map(|i| h(i, &items)).collect();
            prop_assert!(ws.iter().all(|w| w.is_finite() && (0.0..=1.0).contains(w)));
            let sum: f32 = ws.iter().sum();
            prop_assert!((sum - 1.0).abs() < 1e-6, "{ws:?}");
        }
    }
}

fn pdf_value() -> impl Strategy<Value = f32> {
    prop_oneof![
        Just(0.0f32),
        Just(f32::INFINITY),
        Just(f32::MAX),
        Just(f32::MIN_POSITIVE / 64.0),
        float_in(0.0, 1e3),
        (-30i32..38).prop_map(|e| 10f32.powi(e)),
    ]
}

#[test]
fn million_bins_one_nonzero() {
    let n = 1_000_000;
    for k in [0, 1, 123_457, n / 2, n - 2, n - 1] {
        let mut v = vec![0.0f32; n];
        v[k] = 0.25;
        let d = PiecewiseConstant1D::new(&v).unwrap();
        for u in [0.0, 1e-7, 0.5, 0.9, ONE_MINUS_EPS] {
            let (x, pdf, i) = d.sample(u);
            assert_eq!(i, k, "u = {u}");
            assert!(x.is_finite() && (0.0..1.0).contains(&x));
            assert_eq!(d.bin_of(x), Some(k));
            assert!(pdf.is_finite() && (pdf - n as f32).abs() <= 1.0);
            // u is not resolved finely enough to come back (the CDF's slope is 10⁶), but
            // the point is: sample(invert(x)) is x to an f32 step.
            let y = d.sample(d.invert(x)).0;
            assert!(
                y.is_finite() && (y - x).abs() <= 2.0 * f32::EPSILON,
                "{x} -> {y}"
            );
        }
        assert!((d.integral() - 0.25e-6).abs() < 1e-12);
        let t = AliasTable::new(&v).unwrap();
        for u in [0.0, 0.3, 0.5, ONE_MINUS_EPS] {
            assert_eq!(t.sample(u), k);
        }
    }
}

#[test]
fn million_cells_one_nonzero_2d() {
    let (w, h) = (1000, 1000);
    for (x, y) in [(0, 0), (999, 999), (17, 640)] {
        let mut v = vec![0.0f32; w * h];
        v[y * w + x] = 3.0;
        let d = PiecewiseConstant2D::new(&v, w, h).unwrap();
        for u in [
            Vec2::ZERO,
            Vec2::splat(0.5),
            Vec2::splat(ONE_MINUS_EPS),
            Vec2::new(0.0, ONE_MINUS_EPS),
        ] {
            let (p, pdf, cell) = d.sample_cell(u);
            assert_eq!(cell, [x, y]);
            assert_eq!(d.cell_of(p), Some([x, y]));
            assert!(pdf.is_finite() && (pdf - 1e6).abs() <= 1.0);
        }
        assert_eq!(d.cell_mass(x, y), 1.0);
    }
}

/// Empirical frequencies against the pmf, for a few fixed seeds: each count within 5
/// binomial standard deviations (a false alarm has probability below 10⁻⁵ per entry).
#[test]
fn alias_frequencies_match_pmf() {
    let weights = [1.0, 0.0, 2.0, 3.0, 0.5, 0.0, 10.0, 0.01, 4.0];
    let t = AliasTable::new(&weights).unwrap();
    let n = 400_000;
    for seed in [1u64, 2, 3] {
        let mut rng = rand_pcg::Pcg32::seed_from_u64(seed);
        let mut counts = [0usize; 9];
        for _ in 0..n {
            counts[t.sample(rng.random::<f32>())] += 1;
        }
        for (i, &c) in counts.iter().enumerate() {
            let p = t.pmf_f64(i);
            let (mean, sd) = (n as f64 * p, (n as f64 * p * (1.0 - p)).sqrt());
            assert!(
                (c as f64 - mean).abs() <= 5.0 * sd + 0.5,
                "seed {seed}, index {i}: {c} vs {mean}"
            );
            if weights[i] == 0.0 {
                assert_eq!(c, 0);
            }
        }
    }
}

/// The same for a 1D and a 2D table: bin frequencies against pmf / cell mass.
#[test]
fn piecewise_frequencies_match_masses() {
    let values = [0.0, 1.0, 2.0, 0.0, 3.0, 0.5];
    let d1 = PiecewiseConstant1D::new(&values).unwrap();
    let d2 = PiecewiseConstant2D::new(&values, 3, 2).unwrap();
    let n = 300_000;
    let mut rng = rand_pcg::Pcg32::seed_from_u64(7);
    let (mut c1, mut c2) = ([0usize; 6], [0usize; 6]);
    for _ in 0..n {
        c1[d1.sample(rng.random::<f32>()).2] += 1;
        let [x, y] = d2.sample_cell(Vec2::new(rng.random(), rng.random())).2;
        c2[y * 3 + x] += 1;
    }
    for i in 0..6 {
        for (c, p) in [(c1[i], d1.pmf_f64(i)), (c2[i], d2.cell_mass(i % 3, i / 3))] {
            let (mean, sd) = (n as f64 * p, (n as f64 * p * (1.0 - p)).sqrt());
            assert!(
                (c as f64 - mean).abs() <= 5.0 * sd + 0.5,
                "bin {i}: {c} vs {mean}"
            );
        }
    }
}

/// A 2D table shaped like a lat-long environment map with a small bright sun: samples land
/// in the sun as often as its mass says, and never in a zero cell (the poles' rows are 0).
#[test]
fn environment_map_with_a_sun() {
    let (w, h) = (512usize, 256usize);
    let mut v = vec![0.0f32; w * h];
    for y in 0..h {
        let sin_theta = (std::f32::consts::PI * (y as f32 + 0.5) / h as f32).sin();
        for x in 0..w {
            let sun = (300..302).contains(&x) && (60..62).contains(&y);
            v[y * w + x] = if y == 0 || y == h - 1 {
                0.0
            } else if sun {
                1e5
            } else {
                0.2
            } * sin_theta;
        }
    }
    let d = PiecewiseConstant2D::new(&v, w, h).unwrap();
    let sun_mass: f64 = [(300, 60), (301, 60), (300, 61), (301, 61)]
        .iter()
        .map(|&(x, y)| d.cell_mass(x, y))
        .sum();
    let mut rng = rand_pcg::Pcg32::seed_from_u64(11);
    let n = 200_000;
    let mut in_sun = 0usize;
    for _ in 0..n {
        let (p, pdf, [x, y]) = d.sample_cell(Vec2::new(rng.random(), rng.random()));
        assert!(v[y * w + x] > 0.0 && pdf.is_finite() && pdf > 0.0 && p.is_finite());
        let sin_theta = (std::f32::consts::PI * p.y).sin();
        let pdf_omega = mcrt::sampling::jacobian::solid_angle_pdf_from_lat_long(pdf, sin_theta);
        assert!(pdf_omega.is_finite() && pdf_omega > 0.0);
        in_sun += usize::from((300..302).contains(&x) && (60..62).contains(&y));
    }
    let (mean, sd) = (
        n as f64 * sun_mass,
        (n as f64 * sun_mass * (1.0 - sun_mass)).sqrt(),
    );
    assert!(
        sun_mass > 0.5 && (in_sun as f64 - mean).abs() <= 5.0 * sd,
        "{in_sun} vs {mean}"
    );
}
