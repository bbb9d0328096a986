use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::*;

/// `[0,2] × [0,3]`, pdf 1/6 per unit area.
struct ScaledSquare;
impl Warp for ScaledSquare {
    type Point = Vec2;
    fn sample(&self, u: Vec2) -> Vec2 {
        Vec2::new(2.0 * u.x, 3.0 * u.y)
    }
    fn pdf(&self, _: Vec2) -> f32 {
        1.0 / 6.0
    }
}

/// The seeds' polar disk map, r = √u₁, pdf 1/π per unit area.
struct PolarDisk;
impl Warp for PolarDisk {
    type Point = Vec2;
    fn sample(&self, u: Vec2) -> Vec2 {
        let (s, c) = (2.0 * PI * u.y).sin_cos();
        u.x.sqrt() * Vec2::new(c, s)
    }
    fn pdf(&self, p: Vec2) -> f32 {
        if p.length_squared() <= 1.0 {
            1.0 / PI
        } else {
            0.0
        }
    }
}

/// The seeds' wrong disk map r = u₁, paired with the uniform pdf.
struct WrongDisk;
impl Warp for WrongDisk {
    type Point = Vec2;
    fn sample(&self, u: Vec2) -> Vec2 {
        let (s, c) = (2.0 * PI * u.y).sin_cos();
        u.x * Vec2::new(c, s)
    }
    fn pdf(&self, _: Vec2) -> f32 {
        1.0 / PI
    }
}

/// Uniform sphere, z = 1 − 2u₁, pdf 1/4π per unit solid angle.
struct Sphere;
impl Warp for Sphere {
    type Point = Vec3;
    fn sample(&self, u: Vec2) -> Vec3 {
        let z = 1.0 - 2.0 * u.x;
        let r = (1.0 - z * z).max(0.0).sqrt();
        let (s, c) = (2.0 * PI * u.y).sin_cos();
        Vec3::new(r * c, r * s, z)
    }
    fn pdf(&self, _: Vec3) -> f32 {
        0.25 / PI
    }
}

fn grid() -> impl Iterator<Item = Vec2> {
    (1..20).flat_map(|i| (1..20).map(move |j| Vec2::new(i as f32 / 20.0, j as f32 / 20.0)))
}

#[test]
fn identity_holds_for_correct_warps() {
    let h = DEFAULT_JACOBIAN_STEP;
    for u in grid() {
        for err in [
            jacobian_identity_error(&ScaledSquare, u, h),
            jacobian_identity_error(&PolarDisk, u, h),
            jacobian_identity_error(&Sphere, u, h),
        ] {
            let err = err.expect("u is inside the stencil's reach");
            assert!(err.is_finite() && err < 1e-3, "u = {u}: error {err}");
        }
    }
}

#[test]
fn identity_fails_for_a_wrong_pdf() {
    let worst = grid()
        .filter_map(|u| jacobian_identity_error(&WrongDisk, u, DEFAULT_JACOBIAN_STEP))
        .fold(0.0_f64, f64::max);
    assert!(worst > 0.5, "the wrong disk passed: {worst}");
}

#[test]
fn jacobian_values_and_edges() {
    let j = numerical_jacobian(&ScaledSquare, Vec2::new(0.5, 0.5), DEFAULT_JACOBIAN_STEP).unwrap();
    assert!(j.is_finite() && (j - 6.0).abs() < 6e-4, "{j}");
    let j = numerical_jacobian(&Sphere, Vec2::new(0.3, 0.6), DEFAULT_JACOBIAN_STEP).unwrap();
    assert!(j.is_finite() && (j - 4.0 * std::f64::consts::PI).abs() < 1e-3);
    for u in [
        Vec2::new(0.0, 0.5),
        Vec2::new(0.5, 0.9999),
        Vec2::new(1e-4, 0.5),
    ] {
        assert_eq!(numerical_jacobian(&PolarDisk, u, 1e-3), None);
    }
    assert_eq!(numerical_jacobian(&PolarDisk, Vec2::splat(0.5), 0.0), None);
    assert_eq!(
        numerical_jacobian(&PolarDisk, Vec2::splat(0.5), f64::NAN),
        None
    );
    let seam = |p: Vec2| (p.x - p.y).abs() < 0.01;
    let near = numerical_jacobian_excluding(&PolarDisk, Vec2::new(0.5, 0.505), 1e-3, seam);
    assert_eq!(near, None);
    let far = numerical_jacobian_excluding(&PolarDisk, Vec2::new(0.5, 0.7), 1e-3, seam);
    assert!(far.is_some());
}

#[test]
fn conversions_round_trip_and_stay_finite() {
    let p = solid_angle_pdf_from_area(0.5, 4.0, -0.5);
    assert!(p.is_finite() && (p - 4.0).abs() < 1e-6);
    let back = area_pdf_from_solid_angle(p, 4.0, -0.5);
    assert!(back.is_finite() && (back - 0.5).abs() < 1e-6);
    assert_eq!(solid_angle_pdf_from_area(1.0, 1.0, 0.0), 0.0);
    assert_eq!(
        solid_angle_pdf_from_area(f32::MAX, f32::MAX, 1e-30),
        f32::MAX
    );
    assert_eq!(area_pdf_from_solid_angle(1.0, 0.0, 1.0), 0.0);
    assert_eq!(solid_angle_pdf_from_area(f32::NAN, 1.0, 1.0), 0.0);
    let s = spherical_pdf_from_solid_angle(2.0, 0.5);
    assert!((s - 1.0).abs() < 1e-7 && (solid_angle_pdf_from_spherical(s, 0.5) - 2.0).abs() < 1e-7);
    assert_eq!(solid_angle_pdf_from_spherical(1.0, 0.0), 0.0);
    let q = polar_pdf_from_cartesian(1.0 / PI, 0.5);
    assert!(
        (q - 0.5 / PI).abs() < 1e-7 && (cartesian_pdf_from_polar(q, 0.5) - 1.0 / PI).abs() < 1e-7
    );
    assert_eq!(cartesian_pdf_from_polar(1.0, 0.0), 0.0);
    // A uniform lat-long map (p(u, v) = 1) is the uniform sphere.
    let (theta, sin) = (1.0_f32, 1.0_f32.sin());
    let w = solid_angle_pdf_from_lat_long(1.0, sin);
    assert!(w.is_finite() && (w * 2.0 * PI * PI * theta.sin() - 1.0).abs() < 1e-6);
}

#[test]
fn closures_lines_and_categories() {
    let j = numerical_jacobian_of(|u: Vec2| 3.0 * u.x, Vec2::new(0.5, 0.5), 1e-3).unwrap();
    assert!(j.is_finite() && (j - 3.0).abs() < 1e-4, "{j}");
    // Only u.x moves for a line: u.y may sit on the square's edge.
    assert!(numerical_jacobian_of(|u: Vec2| u.x, Vec2::new(0.5, 0.0), 1e-3).is_some());
    assert_eq!(
        numerical_jacobian_of(|_: Vec2| 2usize, Vec2::splat(0.5), 1e-3),
        None
    );
    assert_eq!(
        numerical_jacobian_of(|_: Vec2| Vec2::NAN, Vec2::splat(0.5), 1e-3),
        None
    );
}

/// A stencil point that leaves `[0,1)` only once rounded to `f32` is refused: the map is
/// never evaluated at `u = 1`.
#[test]
fn stencil_is_checked_after_rounding() {
    let u = Vec2::new(1.0 - 2f32.powi(-11), 0.5);
    let h = 2f64.powi(-11) - 2f64.powi(-30);
    assert!(f64::from(u.x) + h < 1.0 && ((f64::from(u.x) + h) as f32) == 1.0);
    let refuse_one = |v: Vec2| {
        assert!(v.x < 1.0, "evaluated at u = {v}");
        v
    };
    assert_eq!(numerical_jacobian_of(refuse_one, u, h), None);
}
