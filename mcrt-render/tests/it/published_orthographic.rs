//! Issue 25's `orthographic` sensor (Mitsuba 3's): a render against Mitsuba 3.9.1's
//! reference, and the loader's located errors for what it refuses.
//!
//! The render (`tests/data/published/orthographic/spheres.xml`, 96 × 64, box filter;
//! reference at 4096 spp, `tests/data/REFERENCES.md`, "Published-scene features:
//! orthographic") is compared as `tests/it/published_lights.rs` compares its scenes
//! (`common/published.rs`: block z-tests Šidák-corrected to the suite's per-test α, and the
//! image mean): one statistical test.

use crate::common;

use common::located::check_located;
use mcrt_render::description::{IntegratorKind, Projection};
use mcrt_render::loader::{parse_scene, SceneError, SceneErrorKind};
use mcrt_render::render::{RenderOptions, Renderer};
use std::path::Path;

const FILE: &str = "tests/data/ortho-test.xml";

/// A scaled orthographic view of spheres on a checkerboard floor, lit by a rectangle and
/// a dim sky, on a non-square film.
#[test]
fn an_orthographic_view_matches_mitsuba() {
    common::published::check("orthographic", "spheres.xml", "spheres.exr", 15);
}

/// A scene with the sensor `sensor` (its start tag on line 3) and the integrator `integrator`
/// (line 2).
fn scene(integrator: &str, sensor: &str) -> String {
    format!("<scene version=\"3.0.0\">\n{integrator}\n{sensor}\n</scene>")
}

fn err(xml: &str) -> SceneError {
    match parse_scene(xml, Some(Path::new(FILE)), &[]) {
        Ok(d) => panic!("expected an error, got {:?}", d.sensor),
        Err(e) => e,
    }
}

const ORTHO: &str = "<sensor type=\"orthographic\">\n<float name=\"near_clip\" value=\"0.5\"/>\n\
                     <float name=\"focus_distance\" value=\"3\"/>\n</sensor>";

#[test]
fn the_orthographic_sensor_loads_with_its_parameters() {
    let d = parse_scene(
        &scene("<integrator type=\"path\"/>", ORTHO),
        Some(Path::new(FILE)),
        &[],
    )
    .unwrap();
    assert_eq!(d.sensor.projection, Projection::Orthographic);
    assert_eq!(d.sensor.near_clip, 0.5);
    assert_eq!(d.sensor.far_clip, 1e4);
    assert!(d.sensor.lens.is_none());
    // `moment` around `path` and `guided` render it.
    for integrator in [
        "<integrator type=\"moment\"><integrator type=\"path\"/></integrator>",
        "<integrator type=\"guided\"/>",
        "<integrator type=\"direct\"/>",
    ] {
        parse_scene(&scene(integrator, ORTHO), None, &[]).unwrap();
    }
}

/// `bdpt`, `mlt` and `ptracer` connect light paths to the camera: refused at the sensor,
/// naming both and the integrator's line, in either order in the file.
#[test]
fn integrators_that_connect_to_the_camera_are_refused_with_it() {
    for ty in ["bdpt", "mlt", "ptracer"] {
        let integrator = format!("<integrator type=\"{ty}\"/>");
        let e = err(&scene(&integrator, ORTHO));
        assert!(matches!(e.kind, SceneErrorKind::Unsupported(_)), "{e}");
        check_located(
            &e,
            FILE,
            3,
            "<sensor type=\"orthographic\">",
            &format!("integrator \"{ty}\" (line 2)"),
        );
        // The sensor first (line 2), the integrator after it (line 6).
        let xml = format!("<scene version=\"3.0.0\">\n{ORTHO}\n{integrator}\n</scene>");
        let e = err(&xml);
        check_located(
            &e,
            FILE,
            2,
            "<sensor type=\"orthographic\">",
            &format!("integrator \"{ty}\" (line 6)"),
        );
    }
    // Overriding the integrator on the command line fails when the render is set up.
    let d = parse_scene(&scene("<integrator type=\"path\"/>", ORTHO), None, &[]).unwrap();
    for kind in [
        IntegratorKind::Bdpt,
        IntegratorKind::Mlt,
        IntegratorKind::Ptracer,
    ] {
        let opts = RenderOptions {
            integrator: Some(kind),
            ..RenderOptions::default()
        };
        let msg = match Renderer::new(&d, &opts) {
            Ok(_) => panic!("{kind:?} renders an orthographic camera"),
            Err(e) => e.to_string(),
        };
        assert!(msg.contains("orthographic"), "{msg}");
    }
}

/// Bad or foreign parameters: located errors naming the parameter.
#[test]
fn bad_parameters_are_located() {
    let bad = |params: &str| {
        err(&scene(
            "<integrator type=\"path\"/>",
            &format!("<sensor type=\"orthographic\">\n{params}\n</sensor>"),
        ))
    };
    let e = bad("<float name=\"near_clip\" value=\"-1\"/>");
    check_located(&e, FILE, 4, "near_clip", "must be positive");
    let e = bad("<float name=\"near_clip\" value=\"5\"/><float name=\"far_clip\" value=\"2\"/>");
    check_located(&e, FILE, 4, "<float name=\"near_clip\">", "below far_clip");
    // The perspective camera's and the thin lens's parameters are unknown here (as in
    // Mitsuba 3, which reports them unreferenced).
    for p in ["fov", "aperture_radius"] {
        let e = bad(&format!("<float name=\"{p}\" value=\"1\"/>"));
        assert!(
            matches!(e.kind, SceneErrorKind::UnknownParameter { .. }),
            "{e}"
        );
        check_located(
            &e,
            FILE,
            4,
            &format!("<float name=\"{p}\">"),
            "orthographic",
        );
    }
    let e = bad("<transform name=\"to_world\"><scale x=\"0\"/></transform>");
    check_located(&e, FILE, 4, "to_world", "to_world");
}
