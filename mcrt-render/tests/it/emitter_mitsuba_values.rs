//! The spot, directional and environment-map emitters and the thin-lens sensor against
//! Mitsuba 3's own values (`tests/data/mitsuba-emitter-values.txt`, written by
//! `scripts/mitsuba_emitter_values.py` from the same scene fragments this test loads):
//!
//! - spot and directional lights: from points around them, the direction toward the light
//!   and the radiance arriving (a spot's intensity times its falloff over the squared
//!   distance; zero outside its cone), through the loader and [`Lights::sample`];
//! - environment maps, with and without a `to_world` rotation: the radiance seen along
//!   directions over the sphere ([`Lights::environment`]);
//! - the thin lens: the ray for a film sample and an aperture sample, origin and direction
//!   ([`Camera::generate_ray_through_lens`]).

use mcrt::glam::{Vec2, Vec3};
use mcrt::integrator::SurfacePoint;
use mcrt::sampling::Frame;
use mcrt_render::accel::AccelKind;
use mcrt_render::camera::Camera;
use mcrt_render::description::SceneDescription;
use mcrt_render::geometry::Geometry;
use mcrt_render::light::Lights;
use mcrt_render::loader::parse_scene;
use std::path::PathBuf;

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests")
        .join("data")
        .join(name)
}

/// One case of the file: its name, its scene fragment and its value lines.
struct Case {
    name: String,
    fragment: String,
    rows: Vec<(char, Vec<f32>)>,
}

fn cases() -> Vec<Case> {
    let text = std::fs::read_to_string(data("mitsuba-emitter-values.txt")).expect("values");
    let mut out: Vec<Case> = Vec::new();
    for line in text.lines().filter(|l| !l.starts_with('#')) {
        if let Some(rest) = line.strip_prefix("case ") {
            let (name, fragment) = rest.split_once(" | ").expect("case NAME | fragment");
            out.push(Case {
                name: name.to_string(),
                fragment: fragment.to_string(),
                rows: Vec::new(),
            });
        } else if let Some((kind, nums)) = line.split_once(' ') {
            let v = nums
                .split(' ')
                .map(|x| x.parse().expect("number"))
                .collect();
            let case = out.last_mut().expect("a case first");
            case.rows.push((kind.chars().next().expect("kind"), v));
        }
    }
    assert!(out.len() >= 10, "cases read: {}", out.len());
    out
}

fn load(case: &Case) -> SceneDescription {
    let xml = format!("<scene version=\"3.0.0\">{}</scene>", case.fragment);
    // The fragment's file names resolve against tests/data, as the script's do.
    parse_scene(&xml, Some(&data("fragment.xml")), &[]).expect("fragment loads")
}

fn v3(v: &[f32]) -> Vec3 {
    Vec3::new(v[0], v[1], v[2])
}

/// `|a − b| ≤ rel·max(|b|) + abs`, with a finite `a`.
fn close(a: Vec3, b: Vec3, rel: f32, abs: f32) -> bool {
    let err = (a - b).abs().max_element();
    a.is_finite() && err <= rel * b.abs().max_element() + abs
}

fn lights(desc: &SceneDescription) -> (Geometry, Lights) {
    let geo = Geometry::new(&desc.shapes, None, AccelKind::Bvh).expect("geometry");
    let lights = Lights::new(desc, &geo, 1.0).expect("lights");
    (geo, lights)
}

#[test]
fn spot_and_directional_lights_match_mitsuba() {
    let mut checked = (0, 0);
    for case in cases()
        .iter()
        .filter(|c| c.name.starts_with("spot") || c.name.starts_with("directional"))
    {
        let (geo, lights) = lights(&load(case));
        for (_, row) in &case.rows {
            let (p, wi, want) = (v3(&row[0..3]), v3(&row[3..6]), v3(&row[6..9]));
            let sp = SurfacePoint::new(p, Vec3::Z, Frame::from_normal(Vec3::Z));
            let got = lights.sample(&geo, &sp, Vec2::splat(0.5), Vec2::splat(0.5));
            if want == Vec3::ZERO {
                let r = got.map_or(Vec3::ZERO, |s| s.radiance);
                assert!(
                    r == Vec3::ZERO,
                    "{}: at {p} radiance {r}, Mitsuba 0",
                    case.name
                );
                checked.1 += 1;
                continue;
            }
            let s = got.unwrap_or_else(|| panic!("{}: no sample at {p}", case.name));
            assert!(
                s.delta && s.pdf == 1.0,
                "{}: a delta light's sample",
                case.name
            );
            assert!(
                close(s.wi, wi, 0.0, 2e-5),
                "{}: at {p} wi {} vs {wi}",
                case.name,
                s.wi
            );
            assert!(
                close(s.radiance, want, 2e-4, 0.0),
                "{}: at {p} radiance {} vs Mitsuba's {want}",
                case.name,
                s.radiance
            );
            checked.0 += 1;
        }
    }
    // Both lit points and points outside the spot cones were compared.
    assert!(checked.0 >= 100 && checked.1 >= 10, "{checked:?}");
}

#[test]
fn environment_maps_with_and_without_rotation_match_mitsuba() {
    let mut n = 0;
    for case in cases().iter().filter(|c| c.name.starts_with("envmap")) {
        let (_, lights) = lights(&load(case));
        for (_, row) in &case.rows {
            let (d, want) = (v3(&row[0..3]), v3(&row[3..6]));
            let got = lights.environment(d);
            assert!(
                close(got, want, 1e-4, 1e-6),
                "{}: along {d} radiance {got} vs Mitsuba's {want}",
                case.name
            );
            n += 1;
        }
    }
    assert_eq!(n, 80);
}

#[test]
fn thin_lens_rays_match_mitsuba() {
    let mut n = 0;
    for case in cases().iter().filter(|c| c.name.starts_with("thinlens")) {
        let desc = load(case);
        assert!(desc.sensor.lens.is_some(), "{}: a thin lens", case.name);
        let cam = Camera::new(&desc.sensor).expect("camera");
        let size = Vec2::new(cam.width() as f32, cam.height() as f32);
        for (_, row) in &case.rows {
            let (film, aperture) = (Vec2::new(row[0], row[1]), Vec2::new(row[2], row[3]));
            let (o, d) = (v3(&row[4..7]), v3(&row[7..10]));
            let (ray, _) = cam.generate_ray_through_lens(film * size, aperture);
            assert!(
                close(ray.origin, o, 1e-5, 1e-5),
                "{}: film {film} lens {aperture}: origin {} vs Mitsuba's {o}",
                case.name,
                ray.origin
            );
            assert!(
                close(ray.dir, d, 0.0, 1e-5),
                "{}: film {film} lens {aperture}: direction {} vs Mitsuba's {d}",
                case.name,
                ray.dir
            );
            n += 1;
        }
    }
    assert_eq!(n, 32);
}
