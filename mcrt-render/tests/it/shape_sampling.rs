//! `Geometry::sample_shape` and `Geometry::shape_pdf` agree, and the solid-angle density is
//! right: for every shape kind and several reference points,
//! - `shape_pdf` at the sampled point (found again by casting a ray) equals the returned pdf;
//! - E[1/pdf · 1{sample visible}] equals the solid angle the shape subtends, computed
//!   independently by casting uniformly distributed rays (both estimates with their standard
//!   errors; the test allows 5 combined standard errors plus 0.5%);
//!
//! both with `ShapeSampling::SolidAngle` and `ShapeSampling::Area` (the default, `Auto`, is one of
//! the two at each point: `tests/it/chi2_lights.rs` checks it where it switches).

use mcrt::glam::{Mat4, Quat, Vec2, Vec3};
use mcrt_render::description::{ShapeDesc, ShapeKind};
use mcrt_render::geometry::{AccelKind, Geometry, Ray, ShapeSampling};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

fn unit_vec(r: &mut Pcg64) -> Vec3 {
    let z = r.random_range(-1.0f32..1.0);
    let phi = r.random_range(0.0f32..std::f32::consts::TAU);
    let s = (1.0 - z * z).max(0.0).sqrt();
    Vec3::new(s * phi.cos(), s * phi.sin(), z)
}

fn u2(r: &mut Pcg64) -> Vec2 {
    Vec2::new(r.random(), r.random())
}

/// Mean and standard error of the mean.
fn mean_se(xs: &[f64]) -> (f64, f64) {
    let n = xs.len() as f64;
    let m = xs.iter().sum::<f64>() / n;
    let v = xs.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (n - 1.0);
    (m, (v / n).sqrt())
}

/// Checks shape 0 of `shapes` seen from `reference`, with both strategies.
fn check(name: &str, shapes: &[ShapeDesc], reference: Vec3, seed: u64) {
    check_with(
        name,
        shapes,
        reference,
        seed,
        ShapeSampling::SolidAngle,
        200_000,
    );
    let area = format!("{name} (area)");
    check_with(
        &area,
        shapes,
        reference,
        seed + 1000,
        ShapeSampling::Area,
        100_000,
    );
}

fn check_with(
    name: &str,
    shapes: &[ShapeDesc],
    reference: Vec3,
    seed: u64,
    how: ShapeSampling,
    n: usize,
) {
    let g = Geometry::new(shapes, None, AccelKind::Bvh)
        .unwrap()
        .with_shape_sampling(how);
    let mut r = Pcg64::seed_from_u64(seed);
    // Solid angle by hit-or-miss over the sphere of directions.
    let hits: Vec<f64> = (0..n)
        .map(|_| {
            let ray = Ray {
                origin: reference,
                dir: unit_vec(&mut r),
            };
            let hit = g.intersect(&ray, f32::INFINITY);
            if hit.is_some_and(|h| h.shape == 0) {
                4.0 * std::f64::consts::PI
            } else {
                0.0
            }
        })
        .collect();
    let (omega, se_omega) = mean_se(&hits);
    // The sampling estimate and the pdf round trip.
    let (mut compared, mut mismatched) = (0usize, 0usize);
    let est: Vec<f64> = (0..n)
        .map(|_| {
            let Some(s) = g.sample_shape(0, reference, r.random(), u2(&mut r)) else {
                return 0.0;
            };
            assert!(s.p.is_finite() && s.n.is_finite(), "{name}: {s:?}");
            assert!(s.pdf.is_finite() && s.pdf > 0.0, "{name}: pdf {}", s.pdf);
            assert!((s.n.length() - 1.0).abs() < 1e-4, "{name}: normal {}", s.n);
            let ray = Ray {
                origin: reference,
                dir: s.p - reference,
            };
            match g.intersect(&ray, f32::INFINITY) {
                Some(h)
                    if h.shape == 0
                        && h.ng.dot(s.n) > 0.999
                        && (h.p - s.p).length() <= 1e-4 * (1.0 + s.p.length()) =>
                {
                    let pdf = g.shape_pdf(0, reference, &h);
                    assert!(pdf.is_finite(), "{name}: shape_pdf {pdf}");
                    compared += 1;
                    // At grazing angles the pdf ∝ 1/cos magnifies the rounding of the
                    // point and its normal (about 10⁻⁴ on a curved shape, whose hit is
                    // projected back onto the surface): compare where it is well
                    // conditioned, allowing that rounding over cos.
                    let cos = (reference - s.p).normalize().dot(s.n).abs();
                    if cos > 0.02 && (pdf - s.pdf).abs() > (2e-3 + 1e-4 / cos) * s.pdf {
                        mismatched += 1;
                    }
                    1.0 / f64::from(s.pdf)
                }
                _ => 0.0,
            }
        })
        .collect();
    let (est, se_est) = mean_se(&est);
    assert!(compared > n / 20, "{name}: only {compared} visible samples");
    assert!(
        mismatched == 0,
        "{name}: shape_pdf differs from the sample's pdf at {mismatched} of {compared} points"
    );
    let tol = 5.0 * (se_omega * se_omega + se_est * se_est).sqrt() + 5e-3 * omega;
    assert!(
        est.is_finite() && (est - omega).abs() <= tol,
        "{name}: E[1/pdf] = {est} ± {se_est}, solid angle {omega} ± {se_omega}"
    );
}

fn with(kind: ShapeKind, m: Mat4) -> ShapeDesc {
    let mut s = ShapeDesc::new(kind);
    s.to_world = m;
    s
}

fn tilted() -> Mat4 {
    Mat4::from_scale_rotation_translation(
        Vec3::new(0.7, 0.3, 1.0),
        Quat::from_axis_angle(Vec3::new(1.0, 2.0, 0.5).normalize(), 0.8),
        Vec3::new(0.2, -0.1, 0.0),
    )
}

#[test]
fn rectangles() {
    let r = vec![with(ShapeKind::Rectangle, tilted())];
    check("rect near", &r, Vec3::new(0.3, 0.2, 0.6), 1);
    check("rect far", &r, Vec3::new(1.0, -2.0, 4.0), 2);
    check("rect behind", &r, Vec3::new(-0.2, 0.1, -0.5), 3);
    let mut flipped = r.clone();
    flipped[0].flip_normals = true;
    check("rect flipped", &flipped, Vec3::new(0.3, 0.2, 0.6), 4);
}

#[test]
fn cubes_and_meshes() {
    let c = vec![with(ShapeKind::Cube, tilted())];
    check("cube near", &c, Vec3::new(0.5, 1.5, 0.9), 5);
    check("cube far", &c, Vec3::new(3.0, 4.0, -5.0), 6);
    // A mesh with triangles of very different sizes, one of zero area.
    let mesh = ShapeDesc::new(ShapeKind::Mesh {
        positions: vec![
            Vec3::ZERO,
            Vec3::X,
            Vec3::Y,
            Vec3::new(1.0, 1.0, 0.3),
            Vec3::new(3.0, 0.0, 1.0),
            Vec3::new(2.0, 2.0, 1.0),
        ],
        normals: vec![],
        indices: vec![[0, 1, 2], [1, 3, 2], [0, 0, 1], [1, 4, 5]],
    });
    check("mesh", &[mesh], Vec3::new(0.8, 0.5, 1.2), 7);
}

#[test]
fn spheres() {
    let s = vec![ShapeDesc::new(ShapeKind::Sphere {
        center: Vec3::new(0.1, 0.2, 0.3),
        radius: 0.5,
    })];
    check("sphere near", &s, Vec3::new(0.1, 0.2, 1.0), 8);
    check("sphere far", &s, Vec3::new(3.0, -2.0, 1.0), 9);
    check("sphere inside", &s, Vec3::new(0.2, 0.1, 0.3), 10);
    let mut scaled = s.clone();
    scaled[0].to_world = Mat4::from_scale_rotation_translation(
        Vec3::splat(2.0),
        Quat::from_rotation_z(0.4),
        Vec3::new(1.0, 0.0, 0.0),
    );
    check("sphere scaled", &scaled, Vec3::new(0.0, 3.0, 1.0), 11);
}

#[test]
fn disks() {
    let d = vec![with(ShapeKind::Disk, tilted())];
    check("disk near", &d, Vec3::new(0.3, 0.2, 0.6), 12);
    check("disk far", &d, Vec3::new(-2.0, 1.0, 3.0), 13);
}

/// Mitsuba 3's `cylinder`, an open tube: from outside (its inner wall seen through an end),
/// far away, and from inside, under a rotation, uniform scale and translation.
#[test]
fn cylinders() {
    let c = vec![with(
        ShapeKind::Cylinder {
            p0: Vec3::new(0.1, -0.3, 0.0),
            p1: Vec3::new(-0.2, 0.4, 0.9),
            radius: 0.35,
        },
        Mat4::from_scale_rotation_translation(
            Vec3::splat(1.3),
            Quat::from_axis_angle(Vec3::new(1.0, 2.0, 0.5).normalize(), 0.8),
            Vec3::new(0.2, -0.1, 0.0),
        ),
    )];
    check("cylinder near", &c, Vec3::new(0.9, 0.3, 1.4), 14);
    check("cylinder far", &c, Vec3::new(-3.0, 2.0, 4.0), 15);
    let inside = c[0].to_world.transform_point3(Vec3::new(0.0, 0.0, 0.4));
    check("cylinder inside", &c, inside, 16);
}

#[test]
fn extreme_sample_values_stay_finite() {
    let shapes = vec![
        with(ShapeKind::Rectangle, tilted()),
        with(ShapeKind::Cube, tilted()),
        with(ShapeKind::Disk, tilted()),
        ShapeDesc::new(ShapeKind::Sphere {
            center: Vec3::ZERO,
            radius: 1.0,
        }),
        ShapeDesc::new(ShapeKind::Cylinder {
            p0: Vec3::ZERO,
            p1: Vec3::Z,
            radius: 1.0,
        }),
    ];
    let g = Geometry::new(&shapes, None, AccelKind::Bvh).unwrap();
    let edge = [0.0, 0.5, 1.0 - 2f32.powi(-24)];
    for shape in 0..5 {
        for reference in [Vec3::new(0.3, 2.0, 3.0), Vec3::new(0.0, 0.0, 0.1)] {
            for &a in &edge {
                for &b in &edge {
                    for &c in &edge {
                        if let Some(s) = g.sample_shape(shape, reference, a, Vec2::new(b, c)) {
                            assert!(s.p.is_finite() && s.n.is_finite());
                            assert!(s.pdf.is_finite() && s.pdf > 0.0);
                        }
                    }
                }
            }
        }
    }
    // Out-of-range shape index: no sample, zero area.
    assert!(g
        .sample_shape(9, Vec3::ZERO, 0.5, Vec2::splat(0.5))
        .is_none());
    assert_eq!(g.shape_area(9), 0.0);
}

#[test]
fn areas() {
    let shapes = vec![
        ShapeDesc::new(ShapeKind::Rectangle),
        ShapeDesc::new(ShapeKind::Cube),
        ShapeDesc::new(ShapeKind::Disk),
        ShapeDesc::new(ShapeKind::Sphere {
            center: Vec3::ZERO,
            radius: 2.0,
        }),
        with(ShapeKind::Disk, Mat4::from_scale(Vec3::new(2.0, 3.0, 5.0))),
        // Radius 0.5 × 2, length 3 × 2 (the scale along the axis too): 2π · 1 · 6.
        with(
            ShapeKind::Cylinder {
                p0: Vec3::ZERO,
                p1: Vec3::new(0.0, 3.0, 0.0),
                radius: 0.5,
            },
            Mat4::from_scale(Vec3::splat(2.0)),
        ),
    ];
    let g = Geometry::new(&shapes, None, AccelKind::Bvh).unwrap();
    let pi = std::f32::consts::PI;
    for (i, want) in [4.0, 24.0, pi, 16.0 * pi, 6.0 * pi, 12.0 * pi]
        .into_iter()
        .enumerate()
    {
        let a = g.shape_area(i as u32);
        assert!(
            a.is_finite() && (a - want).abs() < 1e-4 * want,
            "shape {i}: {a} vs {want}"
        );
    }
}

/// Where the spherical warps apply, every sample has the same density 1/Ω (times the
/// triangle's choice probability for meshes).
#[test]
fn solid_angle_sampling_gives_constant_pdf() {
    let light = with(
        ShapeKind::Rectangle,
        Mat4::from_cols_array(&[
            0.23, 0., 0., 0., 0., 0., 0.19, 0., 0., -0.19, 0., 0., 0., 0.99, 0.01, 1.,
        ]),
    );
    let one_triangle = ShapeDesc::new(ShapeKind::Mesh {
        positions: vec![
            Vec3::new(-1.0, 1.0, -1.0),
            Vec3::new(1.0, 1.0, -1.0),
            Vec3::new(0.0, 1.0, 1.0),
        ],
        normals: vec![],
        indices: vec![[0, 2, 1]],
    });
    let ball = ShapeDesc::new(ShapeKind::Sphere {
        center: Vec3::new(0.0, 0.5, 0.0),
        radius: 0.2,
    });
    let g = Geometry::new(&[light, one_triangle, ball], None, AccelKind::Bvh)
        .unwrap()
        .with_shape_sampling(ShapeSampling::SolidAngle);
    let reference = Vec3::new(0.3, -1.0, 0.2);
    let mut r = Pcg64::seed_from_u64(20);
    for shape in 0..3 {
        let pdfs: Vec<f32> = (0..2000)
            .filter_map(|_| g.sample_shape(shape, reference, r.random(), u2(&mut r)))
            .map(|s| s.pdf)
            .collect();
        assert_eq!(pdfs.len(), 2000);
        let (lo, hi) = pdfs
            .iter()
            .fold((f32::INFINITY, 0.0f32), |(a, b), &p| (a.min(p), b.max(p)));
        assert!(lo.is_finite() && hi.is_finite() && lo > 0.0);
        assert!(hi / lo - 1.0 < 1e-4, "shape {shape}: pdf from {lo} to {hi}");
    }
}

#[test]
fn sheared_rectangle_falls_back_to_area_sampling() {
    let mut m = tilted();
    m.y_axis += m.x_axis * 0.5; // shear: the edges are no longer orthogonal
    let r = vec![with(ShapeKind::Rectangle, m)];
    check("rect sheared", &r, Vec3::new(0.3, 0.2, 0.9), 21);
}
