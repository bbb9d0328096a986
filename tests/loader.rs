//! The Mitsuba 3 XML loader on the shipped scenes, `$name` substitution and `-D`
//! overrides, and one test per error kind (each message names file, line and element).

use mcrt::glam::{Mat4, Vec3};
use mcrt::scene::cornell_box::{cornell_box, cornell_box_with};
use mcrt::scene::description::{
    BsdfDesc, ConductorFresnel, FilterDesc, FovAxis, IntegratorDesc, MicrofacetKind,
    SceneDescription, ShapeKind,
};
use mcrt::scene::loader::{load_scene, look_at, parse_scene, SceneError, SceneErrorKind};
use std::path::Path;

const CORNELL: &str = "tests/data/cornell-box.xml";
const VEACH: &str = "tests/data/veach-mis.xml";

fn load(path: &str, defines: &[(&str, &str)]) -> SceneDescription {
    let d: Vec<(String, String)> = defines
        .iter()
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect();
    load_scene(Path::new(path), &d).unwrap_or_else(|e| panic!("{e}"))
}

fn assert_mat_close(a: Mat4, b: Mat4, tol: f32) {
    for (x, y) in a.to_cols_array().iter().zip(b.to_cols_array()) {
        assert!(x.is_finite() && y.is_finite(), "{a} vs {b}");
        assert!((x - y).abs() <= tol, "{a} vs {b}");
    }
}

#[test]
fn cornell_box_file_equals_the_scene_built_in_code() {
    let mut parsed = load(CORNELL, &[]);
    assert_eq!(parsed.source.as_deref(), Some(Path::new(CORNELL)));
    parsed.source = None;
    assert_eq!(parsed, cornell_box());
}

#[test]
fn cornell_box_defines_override_defaults() {
    let mut parsed = load(CORNELL, &[("max_depth", "2"), ("spp", "16"), ("res", "32")]);
    parsed.source = None;
    assert_eq!(parsed, cornell_box_with(16, 32, 2));
    assert_eq!(
        parsed.integrator,
        IntegratorDesc::Path {
            max_depth: 2,
            rr_depth: 5
        }
    );
}

#[test]
fn cornell_box_camera() {
    let d = load(CORNELL, &[]);
    assert_eq!(d.sensor.fov, 39.3077);
    assert_eq!(d.sensor.fov_axis, FovAxis::Smaller);
    assert_eq!(d.sensor.film.filter, FilterDesc::Box);
    let expected = Mat4::from_cols_array(&[
        -1., 0., 0., 0., 0., 1., 0., 0., 0., 0., -1., 0., 0., 0., 3.9, 1.,
    ]);
    assert_mat_close(d.sensor.to_world, expected, 1e-6);
}
