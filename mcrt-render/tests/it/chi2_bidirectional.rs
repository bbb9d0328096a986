//! The bidirectional estimators' own sampling routines pass the chi-square harness against
//! the densities they state: camera ray directions against `Camera::direction_pdf` (the
//! density and importance of the camera endpoint) and, from one lens point, against
//! `Camera::direction_pdf_from_lens` (the thin lens's), emission directions of an area light and
//! arrival directions of an environment against `Lights::emission_pdf`, and emission points
//! on a sphere light (uniform by area, so their normals are uniform over the sphere).
//!
//! `Lights::sample_emission` takes six sample values; the harness hands out two, so the
//! others are a hash of their bits: a fixed, deterministic function that is uniform and
//! independent of them for the purpose of the test.

use crate::common;

use common::{chi2, sphere};
use mcrt::glam::{Vec2, Vec3};
use mcrt::integrator::SurfacePoint;
use mcrt::stats::Directions;
use mcrt_render::camera::Camera;
use mcrt_render::description::{EmitterDesc, SceneDescription, ShapeDesc, ShapeKind};
use mcrt_render::geometry::{AccelKind, Geometry};
use mcrt_render::light::Lights;

/// A uniform value in [0, 1) from the bits of `u` and a salt (SplitMix64 finaliser).
fn extra(u: Vec2, salt: u64) -> f32 {
    let mut z = (u64::from(u.x.to_bits()) << 32 | u64::from(u.y.to_bits()))
        .wrapping_add(salt.wrapping_mul(0x9e37_79b9_7f4a_7c15));
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^= z >> 31;
    (z >> 40) as f32 / (1u64 << 24) as f32
}

fn extra2(u: Vec2, salt: u64) -> Vec2 {
    Vec2::new(extra(u, salt), extra(u, salt + 1))
}

fn lights_of(desc: &SceneDescription) -> (Geometry, Lights) {
    let geo = Geometry::new(&desc.shapes, None, AccelKind::Bvh).expect("geometry builds");
    let lights = Lights::new(desc, &geo, 4.0).expect("lights build");
    (geo, lights)
}

#[test]
fn camera_ray_directions_follow_the_camera_density() {
    let desc = mcrt_render::cornell_box::cornell_box_with(1, 64, -1);
    // Not square: both tangents matter.
    let film = desc.sensor.film.changed(|f| f.width = 96).unwrap();
    let sensor = desc.sensor.clone().changed(|s| s.film = film).unwrap();
    let cam = Camera::new(&sensor).expect("camera builds");
    let size = Vec2::new(cam.width() as f32, cam.height() as f32);
    // Half the diagonal field of view, with a margin.
    let corner = cam.generate_ray(Vec2::ZERO).dir;
    let half = corner.dot(cam.forward()).clamp(-1.0, 1.0).acos() * 1.05;
    chi2(
        Directions::cap(cam.forward(), half).resolution(48, 64),
        "camera ray directions",
    )
    .run(|u| cam.generate_ray(u * size).dir, |w| cam.direction_pdf(w))
    .assert_passed();
}

/// The thin lens: from one lens point, the directions of rays through uniform film
/// positions follow `Camera::direction_pdf_from_lens` (the density and importance of the
/// lens endpoint).
#[test]
fn thin_lens_ray_directions_follow_the_lens_density() {
    let desc = mcrt_render::cornell_box::cornell_box_with(1, 64, -1);
    let film = desc.sensor.film.changed(|f| f.width = 96).unwrap();
    let mut sensor = desc.sensor.clone().into_inner();
    sensor.film = film;
    sensor.lens = Some(mcrt_render::description::ThinLensDesc {
        aperture_radius: 0.2,
        focus_distance: 2.5,
    });
    let cam = Camera::new(&sensor).expect("camera builds");
    let size = Vec2::new(cam.width() as f32, cam.height() as f32);
    let u_lens = Vec2::new(0.85, 0.3);
    let lens = cam.lens_point(u_lens);
    let corner = cam.generate_ray_through_lens(Vec2::ZERO, u_lens).0.dir;
    let half = corner.dot(cam.forward()).clamp(-1.0, 1.0).acos() * 1.1;
    chi2(
        Directions::cap(cam.forward(), half).resolution(48, 64),
        "thin-lens ray directions",
    )
    .run(
        |u| cam.generate_ray_through_lens(u * size, u_lens).0.dir,
        |w| cam.direction_pdf_from_lens(lens, w),
    )
    .assert_passed();
}

#[test]
fn area_light_emission_directions_are_cosine_distributed() {
    let desc = mcrt_render::cornell_box::cornell_box();
    let (geo, lights) = lights_of(&desc);
    let world = geo.bounding_sphere();
    let probe = lights
        .sample_emission(
            &geo,
            world,
            Vec2::splat(0.5),
            Vec2::splat(0.5),
            Vec2::splat(0.5),
        )
        .expect("the light emits");
    let n = probe.point.ng;
    let light = probe.light;
    chi2(
        Directions::cap(n, std::f32::consts::FRAC_PI_2).resolution(48, 64),
        "area light emission directions",
    )
    .run_weighted(
        |u| {
            let es = lights.sample_emission(&geo, world, extra2(u, 1), extra2(u, 3), u)?;
            Some((es.dir, 1.0))
        },
        |w| lights.emission_pdf(&geo, world, light, &probe.point, w).1,
    )
    .assert_passed();
}

#[test]
fn environment_emission_directions_follow_their_density() {
    let mut desc = mcrt_render::cornell_box::cornell_box();
    for s in &mut desc.shapes {
        *s = s.clone().changed(|s| s.emitter = None).unwrap();
    }
    desc.emitters.push(
        mcrt_render::description::Checked::new(EmitterDesc::Constant {
            radiance: mcrt_render::description::Colour::WHITE,
        })
        .unwrap(),
    );
    let (geo, lights) = lights_of(&desc);
    let world = geo.bounding_sphere();
    let env = lights.environment_index().expect("an environment");
    let nowhere = bare(Vec3::ZERO);
    chi2(sphere(), "environment emission arrival directions")
        .run_weighted(
            |u| {
                let es = lights.sample_emission(&geo, world, extra2(u, 5), u, extra2(u, 7))?;
                // The ray starts on the disk one radius out along the arrival direction.
                let back = (es.point.p - world.0).dot(-es.dir);
                (back > 0.99 * world.1).then_some((-es.dir, 1.0))
            },
            |w| lights.emission_pdf(&geo, world, env, &nowhere, -w).0,
        )
        .assert_passed();
}

#[test]
fn sphere_light_emission_points_are_uniform_by_area() {
    let centre = Vec3::new(0.3, -0.2, 0.5);
    let radius = 0.7;
    let mut s = ShapeDesc::new(ShapeKind::Sphere {
        center: centre,
        radius,
    });
    s.emitter = Some(mcrt_render::description::AreaEmitterDesc {
        radiance: mcrt_render::description::Colour::WHITE,
    });
    let desc = SceneDescription {
        shapes: vec![s]
            .into_iter()
            .map(|x| mcrt_render::description::Checked::new(x).unwrap())
            .collect(),
        ..SceneDescription::default()
    };
    let (geo, lights) = lights_of(&desc);
    let world = geo.bounding_sphere();
    chi2(sphere(), "sphere light emission points")
        .run_weighted(
            |u| {
                let es = lights.sample_emission(&geo, world, extra2(u, 9), u, extra2(u, 11))?;
                let n = (es.point.p - centre) / radius;
                (es.point.ng.dot(n) > 0.999).then_some((n.normalize(), 1.0))
            },
            // Per unit area 1/(4πr²); per steradian of the normal, times r².
            |_| {
                let (pdf_pos, _) = lights.emission_pdf(&geo, world, 0, &bare(centre), Vec3::Z);
                pdf_pos * radius * radius
            },
        )
        .assert_passed();
}

/// A surface point with only a position (the densities tested do not read the rest).
fn bare(p: Vec3) -> SurfacePoint {
    SurfacePoint {
        p,
        ng: Vec3::Z,
        frame: mcrt::sampling::Frame::from_normal(Vec3::Z),
        t: 0.0,
        shape: 0,
        prim: 0,
        uv: Vec2::ZERO,
        instance: 0,
    }
}
