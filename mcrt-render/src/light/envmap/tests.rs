use super::*;
use std::f32::consts::PI;

/// The local direction of map coordinates `(u, v)` (identity `to_world`).
fn dir(u: f32, v: f32) -> Vec3 {
    let (st, ct) = (PI * v).sin_cos();
    let (sp, cp) = (2.0 * PI * u).sin_cos();
    Vec3::new(st * sp, ct, -st * cp)
}

fn close(a: Vec3, b: Vec3, tol: f32) -> bool {
    a.is_finite() && b.is_finite() && (a - b).abs().max_element() <= tol
}

fn lcg(s: &mut u32) -> f32 {
    *s = s.wrapping_mul(747796405).wrapping_add(2891336453);
    (*s >> 8) as f32 / 16_777_216.0
}

fn sun_map() -> EnvMap {
    let (w, h) = (32, 16);
    let mut t = vec![Vec3::splat(0.1); w * h];
    t[5 * w + 20] = Vec3::splat(500.0);
    EnvMap::from_texels(w, h, t, Mat4::from_rotation_y(0.3)).expect("valid map")
}

#[test]
fn halfway_between_column_centres_gives_the_mean_and_wraps() {
    let (a, b) = (Vec3::new(1.0, 2.0, 3.0), Vec3::new(5.0, 0.0, 1.0));
    let m = EnvMap::from_texels(2, 1, vec![a, b], Mat4::IDENTITY).expect("valid map");
    let mean = (a + b) * 0.5;
    for v in [0.1, 0.5, 0.9] {
        assert!(
            close(m.eval(dir(0.25, v)), a, 1e-5),
            "{}",
            m.eval(dir(0.25, v))
        );
        assert!(close(m.eval(dir(0.75, v)), b, 1e-5));
        assert!(close(m.eval(dir(0.5, v)), mean, 1e-5));
        // Across u = 0: from column 1's centre (0.75) to column 0's (1.25).
        assert!(close(m.eval(dir(0.0, v)), mean, 1e-5));
        assert!(close(m.eval(dir(0.125, v)), a * 0.75 + b * 0.25, 1e-5));
        assert!(close(m.eval(dir(0.875, v)), a * 0.25 + b * 0.75, 1e-5));
    }
}

#[test]
fn rows_sit_at_the_poles_and_interpolate_between() {
    // 4 × 2: row 0 is the north pole, row 1 the south pole.
    let t: Vec<Vec3> = (0..8).map(|i| Vec3::splat(i as f32)).collect();
    let m = EnvMap::from_texels(4, 2, t.clone(), Mat4::IDENTITY).expect("valid map");
    let centre = |x: usize| (x as f32 + 0.5) / 4.0;
    for x in 0..4 {
        let mid = (t[x] + t[4 + x]) * 0.5;
        assert!(close(m.eval(dir(centre(x), 0.5)), mid, 1e-4));
        let quarter = t[x] * 0.75 + t[4 + x] * 0.25;
        assert!(close(m.eval(dir(centre(x), 0.25)), quarter, 1e-4));
    }
    // Halfway between column 3 and column 0 (wrapping) and halfway in v: the four's mean.
    let four = (t[3] + t[0] + t[7] + t[4]) * 0.25;
    assert!(close(m.eval(dir(0.0, 0.5)), four, 1e-4));
}

#[test]
fn a_constant_map_stays_constant_and_nothing_is_nan() {
    let c = Vec3::new(0.3, 0.6, 0.9);
    let m = EnvMap::from_texels(7, 5, vec![c; 35], Mat4::from_rotation_z(0.7)).expect("map");
    let mut s = 7u32;
    for _ in 0..500 {
        let d = dir(lcg(&mut s), lcg(&mut s));
        assert!(close(m.eval(d), c, 1e-5), "{}", m.eval(d));
    }
    let m = sun_map();
    let edges = [
        Vec3::Y,
        -Vec3::Y,
        Vec3::NEG_Z,
        Vec3::new(-1e-7, 0.0, -1.0),
        Vec3::new(1e-7, 0.0, -1.0),
        Vec3::new(-1e-30, 1.0, 0.0),
        Vec3::ZERO,
        Vec3::NAN,
    ];
    for d in edges {
        for r in [Mat4::IDENTITY, Mat4::from_rotation_y(-0.3)] {
            let d = r.transform_vector3(d);
            assert!(m.eval(d).is_finite(), "{d}");
            assert!(m.pdf(d).is_finite() && m.pdf(d) >= 0.0, "{d}");
        }
    }
    for u in [
        Vec2::ZERO,
        Vec2::splat(1.0 - 2f32.powi(-24)),
        Vec2::new(0.0, 0.999_999),
    ] {
        if let Some((d, l, pdf)) = m.sample(u) {
            assert!(d.is_finite() && l.is_finite() && pdf.is_finite() && pdf > 0.0);
        }
    }
}

#[test]
fn sample_pdf_and_eval_agree() {
    let m = sun_map();
    let mut s = 1u32;
    let mut n = 0;
    for _ in 0..2000 {
        let u = Vec2::new(lcg(&mut s), lcg(&mut s));
        let Some((d, l, pdf)) = m.sample(u) else {
            continue;
        };
        n += 1;
        let p2 = m.pdf(d);
        assert!(pdf.is_finite() && p2.is_finite() && pdf > 0.0);
        assert!((pdf - p2).abs() <= 1e-3 * pdf, "{pdf} vs {p2}");
        let e = m.eval(d);
        assert!(close(l, e, 1e-3 * e.max_element().max(1.0)), "{l} vs {e}");
    }
    assert!(n > 1900, "{n} samples");
}

#[test]
fn pdf_integrates_to_one() {
    let m = sun_map();
    let (nt, np) = (400, 800);
    let mut sum = 0.0f64;
    for i in 0..nt {
        let th = (i as f32 + 0.5) * PI / nt as f32;
        for j in 0..np {
            let ph = (j as f32 + 0.5) * 2.0 * PI / np as f32;
            let d = Vec3::new(th.sin() * ph.cos(), th.sin() * ph.sin(), th.cos());
            sum += (m.pdf(d) * th.sin()) as f64;
        }
    }
    let integral = sum * (PI as f64 / nt as f64) * (2.0 * PI as f64 / np as f64);
    assert!(
        integral.is_finite() && (integral - 1.0).abs() < 0.01,
        "{integral}"
    );
}

#[test]
fn pdf_is_positive_wherever_the_interpolated_radiance_is() {
    // One lit texel in a black map: its light spreads to the neighbouring texels' area.
    let (w, h) = (16, 9);
    let mut t = vec![Vec3::ZERO; w * h];
    t[4 * w + 15] = Vec3::new(0.0, 0.0, 1.0); // the last column: spreads across u = 0
    let m = EnvMap::from_texels(w, h, t, Mat4::IDENTITY).expect("valid map");
    let (mut lit, mut dark) = (0, 0);
    for i in 0..200 {
        for j in 0..400 {
            let d = dir((j as f32 + 0.5) / 400.0, (i as f32 + 0.5) / 200.0);
            let (l, pdf) = (m.eval(d), m.pdf(d));
            assert!(l.is_finite() && pdf.is_finite());
            if l.max_element() > 0.0 {
                lit += 1;
                assert!(pdf > 0.0, "radiance {l} with pdf 0 at {d}");
            } else if pdf == 0.0 {
                dark += 1;
            }
        }
    }
    // The light covers two rows of cells by two columns, and the density stays on it.
    assert!(lit > 0 && dark > 70_000, "{lit} lit, {dark} dark");
}

#[test]
fn integral_matches_quadrature_of_the_lookup() {
    let (w, h) = (6, 4);
    let mut s = 3u32;
    let t: Vec<Vec3> = (0..w * h)
        .map(|_| Vec3::new(lcg(&mut s), lcg(&mut s), lcg(&mut s)) * 4.0)
        .collect();
    let m = EnvMap::from_texels(w, h, t, Mat4::from_rotation_x(1.1)).expect("valid map");
    let to_world = Mat4::from_rotation_x(1.1);
    let (nt, np) = (600, 600);
    let mut sum = 0.0f64;
    for i in 0..nt {
        let v = (i as f32 + 0.5) / nt as f32;
        for j in 0..np {
            let d = to_world.transform_vector3(dir((j as f32 + 0.5) / np as f32, v));
            let l = m.eval(d);
            sum += f64::from(l.x + l.y + l.z) / 3.0 * f64::from((PI * v).sin());
        }
    }
    let quad = sum * 2.0 * (PI as f64).powi(2) / (nt * np) as f64;
    let got = f64::from(m.integral());
    assert!(
        got.is_finite() && (got - quad).abs() < 1e-4 * quad,
        "{got} vs {quad}"
    );
    let c = EnvMap::from_texels(5, 3, vec![Vec3::splat(2.0); 15], Mat4::IDENTITY).unwrap();
    let four_pi_c = 8.0 * std::f64::consts::PI;
    assert!((f64::from(c.integral()) - four_pi_c).abs() < 1e-5 * four_pi_c);
}

#[test]
fn row_weights_cover_the_sphere() {
    for h in [1, 2, 3, 8, 101] {
        let s: f64 = row_weights(h).iter().sum();
        assert!(s.is_finite() && (s - 2.0).abs() < 1e-12, "{h}: {s}");
        assert!(row_weights(h).iter().all(|&w| w > 0.0));
    }
}

#[test]
fn bad_sizes_are_errors_not_panics() {
    assert!(EnvMap::from_texels(0, 3, vec![], Mat4::IDENTITY).is_err());
    assert!(EnvMap::from_texels(2, 2, vec![Vec3::ONE; 3], Mat4::IDENTITY).is_err());
    // A black map (or scale 0) is a black environment, and so is one that sanitises to 0.
    let nan = vec![Vec3::new(1.0, f32::NAN, 2.0), Vec3::splat(f32::INFINITY)];
    for texels in [vec![Vec3::ZERO; 2], nan] {
        let m = EnvMap::from_texels(2, 1, texels, Mat4::IDENTITY).expect("black map");
        assert_eq!(m.integral(), 0.0);
        assert_eq!(m.eval(dir(0.25, 0.5)), Vec3::ZERO);
    }
    let odd = vec![Vec3::new(-1.0, 0.5, 2.0), Vec3::splat(f32::INFINITY)];
    let m = EnvMap::from_texels(2, 1, odd, Mat4::IDENTITY).expect("sanitised");
    assert!(close(
        m.eval(dir(0.25, 0.5)),
        Vec3::new(0.0, 0.5, 2.0),
        1e-6
    ));
    assert!(close(m.eval(dir(0.75, 0.5)), Vec3::ZERO, 0.0));
}

/// `(mean, relative standard deviation)` of `f(radiance, pdf)` over the map's samples for a
/// 256 × 256 grid of `u` (cell centres).
fn sample_stats(m: &EnvMap, f: impl Fn(Vec3, f32) -> f64) -> (f64, f64) {
    let n = 256;
    let (mut s, mut s2) = (0.0f64, 0.0f64);
    for i in 0..n {
        for j in 0..n {
            let u = Vec2::new((j as f32 + 0.5) / n as f32, (i as f32 + 0.5) / n as f32);
            let (_, l, pdf) = m.sample(u).expect("a sample");
            let x = f(l, pdf);
            s += x;
            s2 += x * x;
        }
    }
    let k = (n * n) as f64;
    let mean = s / k;
    (mean, (s2 / k - mean * mean).max(0.0).sqrt() / mean)
}

fn lum_over_pdf(l: Vec3, pdf: f32) -> f64 {
    f64::from(luminance(l)) / f64::from(pdf)
}

#[test]
fn pdf_is_proportional_to_luminance_at_the_vertices() {
    let (w, h) = (12, 10);
    let mut s = 11u32;
    let t: Vec<Vec3> = (0..w * h)
        .map(|_| Vec3::new(lcg(&mut s), lcg(&mut s), lcg(&mut s)) * 3.0 + 0.01)
        .collect();
    let m = EnvMap::from_texels(w, h, t, Mat4::IDENTITY).expect("valid map");
    let ratio = |x: usize, y: usize| {
        let d = dir((x as f32 + 0.5) / w as f32, y as f32 / (h - 1) as f32);
        m.pdf(d) / luminance(m.eval(d))
    };
    let first = ratio(0, 1);
    assert!(first.is_finite() && first > 0.0);
    for y in 1..h - 1 {
        for x in 0..w {
            let r = ratio(x, y);
            assert!(
                r.is_finite() && (r - first).abs() < 1e-4 * first,
                "({x}, {y}): {r} vs {first}"
            );
        }
    }
}

#[test]
fn light_sampling_of_a_smooth_map_has_almost_no_variance() {
    // Luminance smooth in u and v, so that within a cell it is nearly bilinear in (u, v)
    // times sin θ: the sampled density follows it, and L/p is nearly constant. (The former
    // piecewise-constant sampling over cells weighted by their largest corner: 5.6·10⁻² for
    // this 64 × 32 map.)
    let (w, h) = (64, 32);
    let t: Vec<Vec3> = (0..w * h)
        .map(|k| {
            let u = ((k % w) as f32 + 0.5) / w as f32;
            let v = (k / w) as f32 / (h - 1) as f32;
            Vec3::splat(1.0 + 0.5 * (2.0 * PI * u).cos() + 0.3 * v)
        })
        .collect();
    let m = EnvMap::from_texels(w, h, t, Mat4::from_rotation_x(0.2)).expect("valid map");
    let (mean, rel) = sample_stats(&m, lum_over_pdf);
    let want = f64::from(luminance(Vec3::splat(m.integral())));
    assert!(
        mean.is_finite() && (mean - want).abs() < 1e-3 * want,
        "{mean} vs {want}"
    );
    assert!(rel.is_finite() && rel < 1e-3, "relative std of L/p: {rel}");
    // A uniform map (every vertex alike, so only sin θ's interpolation remains).
    let m = EnvMap::from_texels(16, 33, vec![Vec3::ONE; 16 * 33], Mat4::IDENTITY).unwrap();
    let (mean, rel) = sample_stats(&m, lum_over_pdf);
    assert!((mean - 4.0 * f64::from(PI)).abs() < 1e-3 * mean, "{mean}");
    assert!(rel.is_finite() && rel < 1e-3, "relative std of L/p: {rel}");
}

#[test]
fn a_bright_pole_over_a_black_row_is_sampled_with_a_bounded_ratio() {
    // Only the north pole row is lit: its light fills the pole cells, and the pole vertices
    // carry the density there.
    let (w, h) = (8, 16);
    let mut t = vec![Vec3::ZERO; w * h];
    t[..w].fill(Vec3::new(2.0, 1.0, 0.5));
    let m = EnvMap::from_texels(w, h, t, Mat4::IDENTITY).expect("valid map");
    let (mean, _) = sample_stats(&m, lum_over_pdf);
    let mut worst = 0.0f64;
    let n = 256;
    for i in 0..n {
        for j in 0..n {
            let u = Vec2::new((j as f32 + 0.5) / n as f32, (i as f32 + 0.5) / n as f32);
            let (_, l, pdf) = m.sample(u).expect("a sample");
            worst = worst.max(lum_over_pdf(l, pdf));
        }
    }
    assert!(
        worst.is_finite() && worst < 3.2 * mean,
        "{worst} vs mean {mean}"
    );
    for v in [0.0, 1e-3, 0.5 / (h - 1) as f32] {
        let d = dir(0.3, v);
        assert!(
            m.pdf(d) > 0.0 && m.pdf(d).is_finite(),
            "v = {v}: {}",
            m.pdf(d)
        );
    }
}

#[test]
fn samples_at_the_edges_of_the_square_have_a_density() {
    let mut t = vec![Vec3::splat(0.5); 6 * 12];
    t[5 * 6 + 2] = Vec3::splat(80.0);
    let maps = [
        EnvMap::from_texels(6, 12, t, Mat4::IDENTITY).unwrap(),
        EnvMap::from_texels(3, 1, vec![Vec3::ONE; 3], Mat4::IDENTITY).unwrap(),
        EnvMap::from_texels(5, 2, vec![Vec3::X; 10], Mat4::IDENTITY).unwrap(),
    ];
    let top = 1.0 - 2f32.powi(-24);
    for m in &maps {
        for u in [
            Vec2::ZERO,
            Vec2::new(0.3, 0.0),
            Vec2::new(0.0, top),
            Vec2::splat(top),
            Vec2::new(top, 0.5),
        ] {
            let (d, l, pdf) = m.sample(u).expect("a sample");
            assert!(
                d.is_finite() && l.is_finite() && pdf.is_finite() && pdf > 0.0,
                "{u}"
            );
            assert!(l.max_element() > 0.0, "{u}: {l}");
        }
    }
}
