//! The distributions of `mcrt::sampling::distribution` against masses computed here from the
//! tables they were built from: random tables, tables with zeros, a 10⁶-bin table with one
//! nonzero bin, and a 2D table shaped like an environment map with a small sun. Also the
//! pdf integral, the Jacobian identity and the inverse round trip.

use crate::common;

use common::{chi2, SEED};
use mcrt::glam::Vec2;
use mcrt::sampling::distribution::{
    AliasTable, PiecewiseConstant1D, PiecewiseConstant2D, PiecewiseLinear2D,
    WindowedPiecewiseConstant2D,
};
use mcrt::sampling::warp::{InvertibleWarp, Warp};
use mcrt::sampling::WeightedReservoir;
use mcrt::stats::{
    check_integral, check_inverse, check_jacobian, Discrete, Interval, JacobianCheck, Rectangle,
};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

/// `n` random values in [0, 1), every `zero_every`-th one 0 (`0` for none).
fn random_table(n: usize, zero_every: usize, seed: u64) -> Vec<f32> {
    let mut rng = Pcg64::seed_from_u64(seed);
    (0..n)
        .map(|i| {
            let v: f32 = rng.random();
            if zero_every > 0 && i % zero_every == 0 {
                0.0
            } else {
                v
            }
        })
        .collect()
}

/// Probabilities `v / Σv` in `f64`.
fn normalised(values: &[f32]) -> Vec<f64> {
    let total: f64 = values.iter().map(|&v| f64::from(v)).sum();
    values.iter().map(|&v| f64::from(v) / total).collect()
}

#[test]
fn piecewise_1d_random_tables() {
    for (n, zeros, per_bin) in [
        (7, 0, 8),
        (7, 3, 8),
        (100, 0, 2),
        (1000, 4, 1),
        (1000, 1000, 1),
    ] {
        let values = random_table(n, zeros, SEED + n as u64);
        let d = PiecewiseConstant1D::new(&values).expect("valid table");
        let p = normalised(&values);
        let name = format!("PiecewiseConstant1D-{n}-zeros{zeros}");
        let domain = || Interval::new(0.0, 1.0, n * per_bin);
        let sample = |u: Vec2| d.sample(u.x).0;
        // Against the exact masses of the table's values ...
        chi2(domain(), &name)
            .run_with_masses(sample, |c| p[c / per_bin] / per_bin as f64)
            .assert_passed();
        // ... and against the distribution's own pdf (integrated per cell).
        chi2(domain(), &format!("{name}-pdf"))
            .run(sample, |x| d.pdf(x))
            .assert_passed();
        check_integral(&domain(), |x| d.pdf(x), common::INTEGRAL_TOL).assert_passed();
        check_inverse(sample, |x| Vec2::new(d.invert(x), 0.5), 1, 4096, 1e-4).assert_passed();
    }
}

#[test]
fn piecewise_1d_on_an_interval_and_its_jacobian() {
    let values = [0.5f32, 0.0, 2.0, 1.0, 0.25];
    let d = PiecewiseConstant1D::new_on(&values, -2.0, 3.0).expect("valid table");
    let p = normalised(&values);
    let sample = |u: Vec2| d.sample(u.x).0;
    chi2(Interval::new(-2.0, 3.0, 20), "PiecewiseConstant1D-on")
        .run_with_masses(sample, |c| p[c / 4] / 4.0)
        .assert_passed();
    chi2(Interval::new(-2.0, 3.0, 20), "PiecewiseConstant1D-on-pdf")
        .run(sample, |x| d.pdf(x))
        .assert_passed();
    // x(u) is linear within a bin: pdf · |dx/du| = 1 away from the bin edges.
    check_jacobian(
        sample,
        |x| d.pdf(x),
        JacobianCheck {
            max_skipped: 0.1,
            ..JacobianCheck::default()
        },
    )
    .assert_passed();
}

#[test]
fn piecewise_1d_million_bins_one_nonzero() {
    const N: usize = 1_000_000;
    for k in [0, 123, N / 2, N - 1] {
        let mut values = vec![0.0f32; N];
        values[k] = 3.5;
        let d = PiecewiseConstant1D::new(&values).expect("valid table");
        let sample = |u: Vec2| d.sample(u.x).0;
        let name = format!("PiecewiseConstant1D-1e6-bin{k}");
        // Every sample falls in bin k: one cell spanning exactly the bin (dof 0), nothing
        // outside it.
        let (lo, hi) = (k as f64 / N as f64, (k + 1) as f64 / N as f64);
        let o = chi2(Interval::new(lo, hi, 1), &name).run(sample, |x| d.pdf(x));
        o.assert_passed();
        assert_eq!(o.dof, 0);
        // Within the bin, uniform, where f32 resolves it (near 0: ulp ≪ bin width).
        if k <= 123 {
            chi2(Interval::new(lo, hi, 50), &format!("{name}-zoom"))
                .run(sample, |x| d.pdf(x))
                .assert_passed();
        }
    }
}

/// A 256 × 128 latitude–longitude map: a sky brightening toward the zenith (row 0), a black
/// ground (the lower half), and a 2 × 2-texel sun holding about half the power.
fn environment_map() -> (Vec<f32>, usize, usize, [usize; 2]) {
    let (w, h) = (256usize, 128usize);
    let sun = [171usize, 20usize];
    let mut values = vec![0.0f32; w * h];
    let mut sky = 0.0f64;
    for y in 0..h / 2 {
        let theta = (y as f32 + 0.5) / h as f32 * std::f32::consts::PI;
        for x in 0..w {
            let v = (0.2 + 0.8 * theta.cos().max(0.0)) * theta.sin();
            values[y * w + x] = v;
            sky += f64::from(v);
        }
    }
    let sun_value = (sky / 4.0) as f32;
    for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
        values[(sun[1] + dy) * w + sun[0] + dx] = sun_value;
    }
    (values, w, h, sun)
}

#[test]
fn piecewise_2d_environment_map_with_sun() {
    let (values, w, h, sun) = environment_map();
    let d = PiecewiseConstant2D::new(&values, w, h).expect("valid map");
    let p = normalised(&values);
    let sample = |u: Vec2| d.sample_cell(u).0;
    // Cells aligned with texels: exact masses from the values.
    let domain = || Rectangle::new(Vec2::ZERO, Vec2::ONE, w, h);
    chi2(domain(), "PiecewiseConstant2D-envmap")
        .run_with_masses(sample, |c| p[c])
        .assert_passed();
    chi2(domain(), "PiecewiseConstant2D-envmap-pdf")
        .run(sample, |q| d.pdf(q))
        .assert_passed();
    check_integral(&domain(), |q| d.pdf(q), common::INTEGRAL_TOL).assert_passed();
    // Zoom on the sun: uniform within its 2 × 2 texels. Samples elsewhere are "rejected";
    // the pdf restricted to the zoom integrates to the sun's share.
    let (x0, y0) = (sun[0] as f32 / w as f32, sun[1] as f32 / h as f32);
    let (x1, y1) = (x0 + 2.0 / w as f32, y0 + 2.0 / h as f32);
    let inside = |q: Vec2| q.x >= x0 && q.x <= x1 && q.y >= y0 && q.y <= y1;
    let zoom = Rectangle::new(Vec2::new(x0, y0), Vec2::new(x1, y1), 16, 16);
    let o = chi2(zoom, "PiecewiseConstant2D-sun").run_weighted(
        |u| Some(sample(u)).filter(|&q| inside(q)).map(|q| (q, 1.0)),
        |q| if inside(q) { d.pdf(q) } else { 0.0 },
    );
    o.assert_passed();
    assert!(o.integral > 0.45 && o.integral < 0.55, "{}", o.report());
    check_inverse(sample, |q| d.invert(q), 2, 64, 1e-3).assert_passed();
}

#[test]
fn piecewise_2d_small_tables_and_jacobian() {
    let values = random_table(12, 5, SEED + 12);
    let d = PiecewiseConstant2D::new(&values, 4, 3).expect("valid table");
    let p = normalised(&values);
    let sample = |u: Vec2| d.sample_cell(u).0;
    let domain = Rectangle::new(Vec2::ZERO, Vec2::ONE, 4 * 8, 3 * 8);
    chi2(domain, "PiecewiseConstant2D-4x3")
        .run_with_masses(sample, |c| {
            let (cx, cy) = (c % 32, c / 32);
            p[(cy / 8) * 4 + cx / 8] / 64.0
        })
        .assert_passed();
    check_jacobian(
        sample,
        |q| d.pdf(q),
        JacobianCheck {
            max_skipped: 0.2,
            ..JacobianCheck::default()
        },
    )
    .assert_passed();
    check_inverse(sample, |q| d.invert(q), 2, 64, 1e-4).assert_passed();
}

#[test]
fn alias_tables() {
    for (n, zeros) in [(5, 0), (1000, 0), (1000, 3), (100_000, 7)] {
        let weights = random_table(n, zeros, SEED + 7 * n as u64);
        let t = AliasTable::new(&weights).expect("valid weights");
        let p = normalised(&weights);
        let name = format!("AliasTable-{n}-zeros{zeros}");
        chi2(Discrete::new(n), &name)
            .run_with_masses(|u| t.sample(u.x), |i| p[i])
            .assert_passed();
        chi2(Discrete::new(n), &format!("{name}-split"))
            .run_with_masses(|u| t.sample_split(u), |i| p[i])
            .assert_passed();
        // The table's own pmf, against its samples.
        chi2(Discrete::new(n), &format!("{name}-pmf"))
            .run(|u| t.sample(u.x), |i| t.pmf(i))
            .assert_passed();
    }
}

#[test]
fn alias_table_million_entries_one_nonzero() {
    const N: usize = 1_000_000;
    let mut weights = vec![0.0f32; N];
    weights[N - 3] = 0.25;
    let t = AliasTable::new(&weights).expect("valid weights");
    for (tag, split) in [("u", false), ("split", true)] {
        let o = chi2(Discrete::new(N), &format!("AliasTable-1e6-one-{tag}"))
            .run_with_sparse_masses(
                |u| {
                    if split {
                        t.sample_split(u)
                    } else {
                        t.sample(u.x)
                    }
                },
                &[(N - 3, 1.0)],
            );
        o.assert_passed();
        assert_eq!(o.dof, 0);
    }
}

/// The general inversion method on two densities: a smooth bump `p(x) = (π/4) sin(πx/2)` on
/// `[0, 2]`, and a density with a flat zero stretch (bisection territory) and a steep peak.
#[test]
fn inversion_method() {
    use mcrt::sampling::distribution::Inversion1D;
    use std::f64::consts::PI;
    let inv = Inversion1D::new(0.0, 2.0).expect("valid interval");
    let cdf = |x: f64| (1.0 - (PI * x / 2.0).cos()) / 2.0;
    let pdf = |x: f64| PI / 4.0 * (PI * x / 2.0).sin();
    chi2(Interval::new(0.0, 2.0, 200), "Inversion1D-sine")
        .run(
            |u| inv.sample(cdf, pdf, f64::from(u.x)) as f32,
            |x| pdf(f64::from(x)) as f32,
        )
        .assert_passed();
    // p(x) = 0 on [0, 0.5), 2·16·(x − 0.5)^15 on [0.5, 1): CDF (2(x − 0.5))^16.
    let inv = Inversion1D::new(0.0, 1.0).expect("valid interval");
    let cdf = |x: f64| {
        if x < 0.5 {
            0.0
        } else {
            (2.0 * (x - 0.5)).powi(16)
        }
    };
    let pdf = |x: f64| {
        if x < 0.5 {
            0.0
        } else {
            32.0 * (2.0 * (x - 0.5)).powi(15)
        }
    };
    chi2(Interval::new(0.0, 1.0, 400), "Inversion1D-steep")
        .run(
            |u| inv.sample(cdf, pdf, f64::from(u.x)) as f32,
            |x| pdf(f64::from(x)) as f32,
        )
        .assert_passed();
}

/// Weighted reservoir sampling over a stream of 50 random weights (every 6th zero), and the
/// merge of two reservoirs over its halves, against `w / Σw`. The harness's `u` seeds a PCG
/// stream that supplies one uniform number per offered item. 2·10⁵ samples: 10⁷ offers.
#[test]
fn weighted_reservoir() {
    let weights = random_table(50, 6, SEED + 15);
    let p = normalised(&weights);
    let stream =
        |u: Vec2| Pcg64::seed_from_u64(u64::from(u.x.to_bits()) << 32 | u64::from(u.y.to_bits()));
    let single = |u: Vec2| {
        let mut rng = stream(u);
        let mut r = WeightedReservoir::new();
        for (i, &w) in weights.iter().enumerate() {
            r.add(i, w, rng.random());
        }
        r.into_item().unwrap_or(usize::MAX)
    };
    let merged = |u: Vec2| {
        let mut rng = stream(u);
        let (mut a, mut b) = (WeightedReservoir::new(), WeightedReservoir::new());
        for (i, &w) in weights.iter().enumerate() {
            let half = if i < 20 { &mut a } else { &mut b };
            half.add(i, w, rng.random());
        }
        a.merge(b, rng.random());
        a.into_item().unwrap_or(usize::MAX)
    };
    chi2(Discrete::new(50), "WeightedReservoir")
        .samples(200_000)
        .run_with_masses(single, |i| p[i])
        .assert_passed();
    chi2(Discrete::new(50), "WeightedReservoir-merged")
        .samples(200_000)
        .run_with_masses(merged, |i| p[i])
        .assert_passed();
}

/// `PiecewiseLinear2D` against its own bilinear pdf (integrated per cell): a random 9 × 7
/// grid with zeros, and a 65 × 33 map shaped like an environment map (a sky, a black ground
/// and one bright vertex, the sun, whose bilinear footprint is a 2 × 2-cell pyramid). Also the
/// Jacobian identity and the inverse round trip. 2·10⁵ samples each.
#[test]
fn piecewise_linear_2d() {
    let random = random_table(63, 5, SEED + 21);
    let (w, h) = (65, 33);
    let mut sky = vec![0.0f32; w * h];
    for y in h / 2..h {
        for x in 0..w {
            sky[y * w + x] = 0.2 + (y - h / 2) as f32 / h as f32;
        }
    }
    sky[(h * 3 / 4) * w + w / 3] = 3000.0;
    for (name, values, width, height) in [
        ("PiecewiseLinear2D-9x7", random, 9, 7),
        ("PiecewiseLinear2D-sky-sun", sky, w, h),
    ] {
        let d = PiecewiseLinear2D::new(&values, width, height).expect("valid grid");
        chi2(Rectangle::unit_square(64), name)
            .samples(200_000)
            .run_warp(&d)
            .assert_passed();
        // A step of 2⁻¹¹: near a vertex of value ~10⁻², the map's second derivative jumps
        // across grid lines and a step of 2⁻⁹ leaves a truncation error of several percent
        // (pdf · J → 1 as the step shrinks: 1.014 at 10⁻³, 1.0003 at 10⁻⁴).
        let settings = JacobianCheck {
            step: 1.0 / 2048.0,
            ..JacobianCheck::default()
        };
        check_jacobian(|u| d.sample(u), |p| d.pdf(p), settings).assert_passed();
        check_inverse(|u| d.sample(u), |p| d.invert(p), 2, 64, 1e-4).assert_passed();
    }
}

/// `WindowedPiecewiseConstant2D`: a random 8 × 6 table with zeros seen through a window that
/// cuts cells on every side, and the environment map of `piecewise_2d_environment_map_with_sun`
/// through a small window around its sun (a portal); each against its own pdf over the window
/// (48 × 48 cells), with the Jacobian identity and the round trip. 2·10⁵ samples each.
#[test]
fn windowed_piecewise_constant_2d() {
    let (env, w, h, sun) = environment_map();
    let random = random_table(48, 4, SEED + 23);
    let sun_at = Vec2::new(sun[0] as f32 / w as f32, sun[1] as f32 / h as f32);
    let cases = [
        (
            "Windowed-8x6",
            random,
            8,
            6,
            Vec2::new(0.13, 0.05),
            Vec2::new(0.71, 0.9),
        ),
        (
            "Windowed-envmap-portal",
            env,
            w,
            h,
            sun_at - 0.02,
            sun_at + 0.03,
        ),
    ];
    for (name, values, width, height, min, max) in cases {
        let d = WindowedPiecewiseConstant2D::new(&values, width, height).expect("valid table");
        let win = d.window(min, max).expect("window with mass");
        chi2(Rectangle::new(min, max, 48, 48), name)
            .samples(200_000)
            .run_warp(&win)
            .assert_passed();
        // Seams at every column and row edge, where the slope of the piecewise-linear map
        // jumps: a stencil straddling one mixes two slopes, which the h-against-2h test does
        // not always see when they are close. A step of 2⁻¹¹ keeps such stencils rare; up to
        // 20 % of the lattice may be skipped (as for `PiecewiseConstant2D`).
        let settings = JacobianCheck {
            step: 1.0 / 2048.0,
            max_skipped: 0.2,
            ..JacobianCheck::default()
        };
        let j = check_jacobian(|u| win.sample(u), |p| win.pdf(p), settings);
        assert!(j.passed(), "{name}: {}", j.report());
        check_inverse(|u| win.sample(u), |p| win.invert(p), 2, 64, 1e-4).assert_passed();
    }
}
