//! Unit tests of light sampling: the plans chosen once give the same samples as sampling the
//! light's shape through the geometry.

use super::{positive_finite, toward_area_light, Light, LightSample, Lights, SamplePlan};
use crate::geometry::{AccelKind, Geometry, ShapeSampling};
use glam::{Vec2, Vec3};
use mcrt::integrator::SurfacePoint;
use mcrt::sampling::Frame;

/// A light sample through the geometry's shape sampling (the general path).
fn through_geometry(
    geo: &Geometry,
    shape: u32,
    radiance: Vec3,
    from: Vec3,
    (u_pick, u): (f32, Vec2),
) -> Option<LightSample> {
    let s = geo.sample_shape(shape, from, u_pick, u)?;
    toward_area_light(s, radiance, from, 1.0)
}

fn cornell(sampling: ShapeSampling) -> (Geometry, Lights) {
    let desc = crate::cornell_box::cornell_box();
    let geo = Geometry::new(&desc.shapes, None, AccelKind::Bvh)
        .unwrap()
        .with_shape_sampling(sampling);
    let lights = Lights::new(&desc, &geo, 10.0).unwrap();
    (geo, lights)
}

fn point(p: Vec3) -> SurfacePoint {
    SurfacePoint {
        p,
        ng: Vec3::Y,
        frame: Frame::from_normal(Vec3::Y),
        t: 1.0,
        shape: 0,
        prim: 0,
        uv: Vec2::ZERO,
        instance: 0,
    }
}

fn close(a: f32, b: f32, rel: f32) -> bool {
    a.is_finite() && b.is_finite() && (a - b).abs() <= rel * a.abs().max(b.abs())
}

/// The precomputed rectangle gives the same direction, distance and density as sampling
/// the shape through the geometry, and its density is what `pdf_hit` reports for the
/// point a ray in that direction hits.
#[test]
fn fast_rectangle_matches_geometry_sampling() {
    let (geo, lights) = cornell(ShapeSampling::Area);
    let (i, shape, radiance) = lights
        .lights()
        .iter()
        .enumerate()
        .find_map(|(i, l)| match *l {
            Light::Area { shape, radiance } => Some((i, shape, radiance)),
            _ => None,
        })
        .unwrap();
    assert_eq!(lights.plan, SamplePlan::LoneRectangleByArea);
    assert!(lights.rectangles[i].is_some());
    let froms = [
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(-0.9, 0.5, 0.3),
        Vec3::new(0.7, 1.5, -0.8),
    ];
    let mut checked = 0;
    for from in froms {
        let sp = point(from);
        for k in 0..64 {
            let u = Vec2::new((k % 8) as f32 / 8.0 + 0.03, (k / 8) as f32 / 8.0 + 0.05);
            let fast = lights.sample(&geo, &sp, Vec2::new(0.4, 0.6), u);
            let slow = through_geometry(&geo, shape, radiance, from, (0.6, u));
            let (Some(f), Some(s)) = (fast, slow) else {
                assert_eq!(fast.is_some(), slow.is_some(), "{from} {u}");
                continue;
            };
            assert!((f.wi - s.wi).length() < 1e-5 && close(f.dist, s.dist, 1e-5));
            assert!(close(f.pdf, s.pdf, 1e-4), "{} vs {}", f.pdf, s.pdf);
            assert_eq!(f.radiance, radiance);
            let p = from + f.wi * f.dist;
            let mut hit = point(p);
            (hit.ng, hit.shape) = (geo.rectangle_sampler(shape).unwrap().normal(), shape);
            let back = lights.pdf_hit(&geo, &sp, &hit);
            assert!(close(back, f.pdf, 1e-4), "{back} vs {}", f.pdf);
            checked += 1;
        }
    }
    assert!(checked > 100, "{checked}");
}

/// Shading points over the whole Cornell box, on the ceiling (behind the light), in and
/// next to the light's plane, and on the light.
fn box_points() -> Vec<Vec3> {
    let mut v = Vec::new();
    for i in 0..6 {
        for j in 0..7 {
            for k in 0..6 {
                let y = [0.0, 0.4, 0.98, 0.99, 0.990001, 0.995, 1.0][j];
                v.push(Vec3::new(-1.0 + 0.4 * i as f32, y, -1.0 + 0.4 * k as f32));
            }
        }
    }
    v.extend([Vec3::new(0.0, 0.99, 0.0), Vec3::new(0.1, 0.99, -0.05)]);
    v
}

/// With solid-angle sampling the light's own path (a frame built once, points clearly
/// behind skipped) gives exactly the geometry's sample, bit for bit, everywhere.
#[test]
fn solid_angle_sampling_is_the_geometrys_bit_for_bit() {
    let (geo, lights) = cornell(ShapeSampling::SolidAngle);
    let Light::Area { shape, radiance } = lights.lights()[0] else {
        panic!("the Cornell box's light is an area light");
    };
    let (mut some, mut none) = (0, 0);
    for from in box_points() {
        let sp = point(from);
        for k in 0..25 {
            let u = Vec2::new((k % 5) as f32 / 5.0 + 0.07, (k / 5) as f32 / 5.0 + 0.11);
            let got = lights.sample(&geo, &sp, Vec2::new(0.5, 0.5), u);
            let want = through_geometry(&geo, shape, radiance, from, (0.5, u));
            assert_eq!(got, want, "from {from} u {u}");
            if let Some(s) = got {
                assert!(s.pdf.is_finite() && s.pdf > 0.0 && s.wi.is_finite());
                some += 1;
            } else {
                none += 1;
            }
        }
    }
    assert!(some > 1000 && none > 500, "{some} samples, {none} rejected");
}

/// A point reported clearly behind the light gets no sample from any strategy; points
/// in front or in the plane are never reported.
#[test]
fn surely_behind_only_where_every_sample_is_rejected() {
    let (geo, lights) = cornell(ShapeSampling::SolidAngle);
    assert_eq!(lights.plan, SamplePlan::LoneRectangleBySolidAngle);
    let (r, radiance) = lights.lone_rectangle().unwrap();
    let Light::Area { shape, .. } = lights.lights()[0] else {
        panic!("the Cornell box's light is an area light");
    };
    let mut behind = 0;
    for from in box_points() {
        let in_front_or_plane = from.y <= 0.990001;
        if !r.surely_behind(from) {
            continue;
        }
        assert!(!in_front_or_plane, "{from}");
        behind += 1;
        for k in 0..25 {
            let u = Vec2::new((k % 5) as f32 / 5.0 + 0.07, (k / 5) as f32 / 5.0 + 0.11);
            let by_area = r.sample(ShapeSampling::Area, from, u);
            let by_area = by_area.and_then(|s| toward_area_light(s, radiance, from, 1.0));
            assert!(by_area.is_none(), "{from} {u}");
            let slow = through_geometry(&geo, shape, radiance, from, (0.5, u));
            assert!(slow.is_none(), "{from} {u}");
        }
    }
    assert!(behind >= 72, "{behind} points behind");
}

/// `u_pick` is read only with a light on a triangle mesh (the choice among several lights
/// reuses `u.x`).
#[test]
fn light_choice_is_drawn_only_when_read() {
    use crate::description::{EmitterDesc, ShapeKind};
    let (_, lights) = cornell(ShapeSampling::Area);
    assert!(!lights.reads_pick(), "one rectangle light");
    let mut desc = crate::cornell_box::cornell_box();
    let i = desc
        .shapes
        .iter()
        .position(|s| s.emitter.is_some())
        .unwrap();
    let light = desc.shapes[i].clone();
    desc.shapes[i] = light.clone().changed(|s| s.kind = ShapeKind::Cube).unwrap();
    let geo = Geometry::new(&desc.shapes, None, AccelKind::Bvh).unwrap();
    assert!(
        Lights::new(&desc, &geo, 10.0).unwrap().reads_pick(),
        "a cube light"
    );
    desc.shapes[i] = light;
    let point = EmitterDesc::Point {
        position: Vec3::Y,
        intensity: crate::description::Colour::WHITE,
    };
    desc.emitters
        .push(crate::description::Checked::new(point).unwrap());
    let geo = Geometry::new(&desc.shapes, None, AccelKind::Bvh).unwrap();
    assert!(
        !Lights::new(&desc, &geo, 10.0).unwrap().reads_pick(),
        "two lights"
    );
}

/// The bit test is `0 < x < ∞` exactly, at the edges of every class.
#[test]
fn positive_finite_is_the_float_comparison() {
    let edges = [
        0.0,
        -0.0,
        f32::from_bits(1),
        -f32::from_bits(1),
        f32::MIN_POSITIVE,
        1.0,
        f32::MAX,
        -f32::MAX,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
        -f32::NAN,
        f32::from_bits(0x7fc0_0001),
    ];
    for x in edges {
        assert_eq!(positive_finite(x), x > 0.0 && x < f32::INFINITY, "{x:?}");
    }
    for bits in (0..=u32::MAX).step_by(65_521) {
        let x = f32::from_bits(bits);
        assert_eq!(
            positive_finite(x),
            x > 0.0 && x < f32::INFINITY,
            "{bits:#x}"
        );
    }
}

/// The irradiance at a point of the Cornell box's floor, `E[L·|cos θ|/p]` over a 4-D grid of
/// sample values (8 strata per dimension, so `u_pick.y`, which chooses among candidates, is
/// independent of the rest), with `m` resampling candidates over the light BVH.
fn floor_irradiance(m: u32) -> f64 {
    let desc = crate::cornell_box::cornell_box();
    let geo = Geometry::new(&desc.shapes, None, AccelKind::Bvh).unwrap();
    let mut lights = Lights::with_bvh(&desc, &geo, 10.0, super::LightBvhUse::Always).unwrap();
    assert_eq!(lights.set_light_candidates(m), m > 1);
    let from = point(Vec3::new(0.3, -0.99, -0.2));
    let s = |k: usize| (k as f32 + 0.5) / 8.0;
    let mut sum = 0.0f64;
    for k in 0..8 * 8 * 8 * 8 {
        let u_pick = Vec2::new(s(k % 8), s(k / 8 % 8));
        let u = Vec2::new(s(k / 64 % 8), s(k / 512));
        if let Some(ls) = lights.sample(&geo, &from, u_pick, u) {
            let e = ls.radiance.x * ls.wi.dot(Vec3::Y).abs() / ls.pdf;
            assert!(e.is_finite());
            sum += f64::from(e);
        }
    }
    sum / 4096.0
}

/// Resampling is on only where the BVH chooses and every light is a rectangle or a split
/// mesh, and its estimate of the irradiance agrees with one BVH sample's (a contribution
/// weight without the `1/M` would be off by a factor `M`).
#[test]
fn resampled_light_samples_keep_the_irradiance() {
    let (_, mut plain) = cornell(ShapeSampling::Auto);
    assert!(!plain.set_light_candidates(4)); // one light: no BVH
    let one = floor_irradiance(1);
    assert!(one.is_finite() && one > 0.0);
    for m in [2, 4, 8] {
        let e = floor_irradiance(m);
        assert!(close(e as f32, one as f32, 0.02), "M = {m}: {e} vs {one}");
    }
}
