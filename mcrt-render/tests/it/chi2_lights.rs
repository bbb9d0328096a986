//! The light samplers as the renderer composes them pass the chi-square harness: directions
//! from a shading point toward an emitting shape, drawn with `Geometry::sample_shape` and
//! checked against `Geometry::shape_pdf` (per steradian) — a sphere by its cone, the Cornell
//! box's rectangle light by spherical rectangle and by area, a cube (a 12-triangle mesh: a
//! triangle by area, then a spherical triangle), a disk and a cylinder by area.
//!
//! A sample counts only if its point is what a ray from the reference toward it hits first:
//! points on the far side of the cube are hidden by its near side (the renderer's shadow ray
//! finds them occluded), so they go to the harness's rejected cell, whose expected mass is
//! `1 − ∫ pdf`; `shape_pdf` of the first hit must account for all the rest.
//!
//! `sample_shape` takes three sample values (one picks a mesh triangle); the harness hands
//! out two, so the third is a hash of their bits: a fixed, deterministic function that is
//! uniform and independent of them for the purpose of the test.

use crate::common;

use common::chi2;
use mcrt::glam::{Mat4, Vec2, Vec3};
use mcrt::stats::Directions;
use mcrt_render::accel::AccelKind;
use mcrt_render::description::{ShapeDesc, ShapeKind};
use mcrt_render::geometry::{Geometry, Ray, ShapeSampling};

/// A uniform value in [0, 1) from the bits of `u` (SplitMix64 finaliser).
fn third_value(u: Vec2) -> f32 {
    let mut z = (u64::from(u.x.to_bits()) << 32 | u64::from(u.y.to_bits()))
        .wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^= z >> 31;
    (z >> 40) as f32 / (1u64 << 24) as f32
}

/// The cap of directions from `reference` that holds the shape's bounding sphere, with a
/// margin.
fn cap_toward(geometry: &Geometry, reference: Vec3) -> Directions {
    let (centre, radius) = geometry.bounding_sphere();
    let to = centre - reference;
    let half = (radius / to.length()).clamp(0.0, 1.0).asin();
    Directions::cap(to.normalize(), (1.3 * half).min(std::f32::consts::PI))
        .resolution(48, 64)
        .refinement(1.0)
}

/// Runs the chi-square test of shape 0 of `geometry` seen from `reference`.
fn check(name: &str, geometry: &Geometry, reference: Vec3) {
    let first_hit = |w: Vec3| {
        let ray = Ray {
            origin: reference,
            dir: w,
        };
        geometry
            .intersect(&ray, f32::INFINITY)
            .filter(|hit| hit.shape == 0)
    };
    let sample = |u: Vec2| {
        let s = geometry.sample_shape(0, reference, third_value(u), u)?;
        let to = s.p - reference;
        let w = to.normalize();
        // Hidden: the shape itself lies in front of the point. (A grazing sample on a sphere's
        // rim may miss in f32; it still counts, in its cell.)
        let hidden = first_hit(w).is_some_and(|hit| hit.t < (1.0 - 1e-4) * to.length());
        (!hidden).then_some((w, 1.0))
    };
    let pdf = |w: Vec3| first_hit(w).map_or(0.0, |hit| geometry.shape_pdf(0, reference, &hit));
    chi2(cap_toward(geometry, reference), name)
        .run_weighted(sample, pdf)
        .assert_passed();
}

fn geometry(kind: ShapeKind, to_world: Mat4, sampling: ShapeSampling) -> Geometry {
    let mut shape = ShapeDesc::new(kind);
    shape.to_world = to_world;
    Geometry::new(&[shape], None, AccelKind::Bvh)
        .expect("valid shape")
        .with_shape_sampling(sampling)
}

/// The Cornell box's light, seen from a point on the floor.
fn cornell_light(sampling: ShapeSampling) -> Geometry {
    let m = Mat4::from_cols_array_2d(&[
        [0.23, 0.0, 0.0, 0.0],
        [0.0, 0.0, 0.19, 0.0],
        [0.0, -0.19, 0.0, 0.0],
        [0.0, 0.99, 0.01, 1.0],
    ]);
    geometry(ShapeKind::Rectangle, m, sampling)
}

#[test]
fn rectangle_light_by_solid_angle_and_by_area() {
    let floor = Vec3::new(0.3, -0.99, 0.2);
    check(
        "light-rectangle-solid-angle",
        &cornell_light(ShapeSampling::SolidAngle),
        floor,
    );
    check(
        "light-rectangle-area",
        &cornell_light(ShapeSampling::Area),
        floor,
    );
    // The default chooses per point: the floor is far (by area), a point just below the
    // light near (by solid angle).
    let auto = cornell_light(ShapeSampling::Auto);
    check("light-rectangle-auto-far", &auto, floor);
    check(
        "light-rectangle-auto-near",
        &auto,
        Vec3::new(0.1, 0.9, 0.05),
    );
}

#[test]
fn sphere_light_by_its_cone() {
    let sphere = ShapeKind::Sphere {
        center: Vec3::new(1.25, 4.2, -1.0),
        radius: 0.45,
    };
    let g = geometry(sphere, Mat4::IDENTITY, ShapeSampling::SolidAngle);
    check("light-sphere-near", &g, Vec3::new(0.0, 2.0, 0.5));
    check("light-sphere-far", &g, Vec3::new(0.0, -2.5, 10.0));
}

#[test]
fn cube_light_by_triangle_choice_and_spherical_triangles() {
    let m = Mat4::from_scale_rotation_translation(
        Vec3::new(0.3, 0.2, 0.4),
        mcrt::glam::Quat::from_rotation_y(0.4),
        Vec3::new(0.0, 1.0, 0.0),
    );
    for (tag, sampling) in [
        ("solid-angle", ShapeSampling::SolidAngle),
        ("area", ShapeSampling::Area),
    ] {
        let g = geometry(ShapeKind::Cube, m, sampling);
        check(&format!("light-cube-{tag}"), &g, Vec3::new(0.8, -0.5, 0.9));
    }
    // `Auto` from a point where 4 of the 12 triangles are near (by solid angle) and the
    // other 8 far (by area): one shape, both strategies, one density.
    let g = geometry(ShapeKind::Cube, m, ShapeSampling::Auto);
    check("light-cube-auto-mixed", &g, Vec3::new(1.0, 0.6, 1.0));
}

#[test]
fn disk_light_by_area() {
    let m = Mat4::from_scale_rotation_translation(
        Vec3::splat(0.5),
        mcrt::glam::Quat::from_rotation_x(std::f32::consts::FRAC_PI_2),
        Vec3::new(0.0, 1.0, 0.0),
    );
    let g = geometry(ShapeKind::Disk, m, ShapeSampling::SolidAngle);
    check("light-disk", &g, Vec3::new(0.4, -0.5, 0.3));
}

/// Mitsuba 3's `cylinder` (an open tube), sampled uniformly by area, from a point outside
/// where the near wall hides most of the far one and the inner wall shows through an open
/// end.
#[test]
fn cylinder_light_by_area() {
    let m = Mat4::from_rotation_x(0.7) * Mat4::from_translation(Vec3::new(0.0, 0.5, 0.0));
    let kind = ShapeKind::Cylinder {
        p0: Vec3::new(0.0, 0.0, -0.5),
        p1: Vec3::new(0.2, 0.1, 0.8),
        radius: 0.4,
    };
    let g = geometry(kind, m, ShapeSampling::SolidAngle);
    check("light-cylinder", &g, Vec3::new(1.2, -0.6, 1.6));
}
