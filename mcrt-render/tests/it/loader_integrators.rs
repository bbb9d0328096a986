//! The loader on the integrator features of issue 25: `hide_emitters` on every integrator,
//! `ptracer` with Mitsuba 3's parameters, `moment` around `path` or `direct`, and located
//! errors for what is refused (an outer integrator other than `moment`, a nested one that
//! does not sample per pixel, several nested ones).

use crate::common;

use common::located::check_located;
use mcrt_render::description::{IntegratorDesc, MomentDesc, SceneDescription};
use mcrt_render::loader::{parse_scene, SceneError};
use std::path::Path;

const FILE: &str = "tests/data/integrators-test.xml";

fn scene(body: &str) -> String {
    format!("<scene version=\"3.0.0\">\n{body}\n</scene>")
}

fn load(body: &str) -> SceneDescription {
    parse_scene(&scene(body), Some(Path::new(FILE)), &[]).expect("scene loads")
}

fn err(body: &str) -> SceneError {
    match parse_scene(&scene(body), Some(Path::new(FILE)), &[]) {
        Ok(d) => panic!("expected an error, got {d:?}"),
        Err(e) => e,
    }
}

#[test]
fn hide_emitters_is_read_on_every_integrator() {
    for ty in ["path", "direct", "bdpt", "mlt", "ptracer", "guided"] {
        let shown = load(&format!("<integrator type=\"{ty}\"/>"));
        assert!(!shown.integrator.hide_emitters(), "{ty}");
        let hidden = load(&format!(
            "<integrator type=\"{ty}\"><boolean name=\"hide_emitters\" value=\"true\"/></integrator>"
        ));
        assert!(hidden.integrator.hide_emitters(), "{ty}");
        assert_eq!(hidden.integrator.kind().name(), ty);
    }
    assert!(!load("").integrator.hide_emitters());
}

#[test]
fn ptracer_reads_mitsubas_parameters() {
    let d = load(
        "<integrator type=\"ptracer\"><integer name=\"max_depth\" value=\"8\"/>\n\
         <integer name=\"rr_depth\" value=\"3\"/><integer name=\"samples_per_pass\" value=\"4\"/>\n\
         </integrator>",
    );
    assert_eq!(
        d.integrator,
        IntegratorDesc::Ptracer(mcrt_render::description::PtracerParams {
            max_depth: 8,
            rr_depth: 3,
            samples_per_pass: 4,
            ..Default::default()
        })
    );
    assert_eq!(
        load("<integrator type=\"ptracer\"/>").integrator,
        IntegratorDesc::Ptracer(mcrt_render::description::PtracerParams {
            max_depth: -1,
            rr_depth: 5,
            ..Default::default()
        })
    );
    let e = err(
        "<integrator type=\"ptracer\">\n<integer name=\"max_depth\" value=\"-2\"/></integrator>",
    );
    check_located(&e, FILE, 3, "<integer name=\"max_depth\">", "max_depth");
    let e = err("<integrator type=\"ptracer\">\n<float name=\"sigma\" value=\"1\"/></integrator>");
    check_located(&e, FILE, 3, "sigma", "sigma");
}

#[test]
fn moment_wraps_path_or_direct_and_is_named_after_it() {
    let d = load(
        "<integrator type=\"moment\">\n<integrator type=\"path\" name=\"nested\">\
         <integer name=\"max_depth\" value=\"4\"/>\
         <boolean name=\"hide_emitters\" value=\"true\"/></integrator></integrator>",
    );
    assert_eq!(
        d.integrator,
        IntegratorDesc::Path(mcrt_render::description::PathParams {
            max_depth: 4,
            hide_emitters: true,
            ..Default::default()
        })
    );
    assert!(d.integrator.hide_emitters());
    assert_eq!(
        d.moment,
        Some(MomentDesc {
            name: "nested".into(),
            more: Vec::new(),
        })
    );
    // Unnamed, it is Mitsuba's first automatic name.
    let d = load("<integrator type=\"moment\"><integrator type=\"direct\"/></integrator>");
    assert_eq!(d.moment.map(|m| m.name).as_deref(), Some("_arg_0"));
    assert!(load("<integrator type=\"path\"/>").moment.is_none());
}

/// Mitsuba 3 accepts several nested integrators: the first gives the image; each is named
/// by its `name` attribute or `_arg_N`, `N` counting the unnamed ones (as Mitsuba 3.9.1's
/// `aov_names()` shows).
#[test]
fn several_nested_integrators_are_read_in_file_order() {
    let d = load(
        "<integrator type=\"moment\"><integrator type=\"path\"/><integrator type=\"direct\"/>\
         <integrator type=\"path\" name=\"c\"><integer name=\"max_depth\" value=\"2\"/></integrator>\
         <integrator type=\"direct\"/></integrator>",
    );
    assert_eq!(
        d.integrator.kind(),
        mcrt_render::description::IntegratorKind::Path
    );
    let m = d.moment.expect("moment is read");
    assert_eq!(m.name, "_arg_0");
    let more: Vec<(&str, Option<i32>)> = m
        .more
        .iter()
        .map(|n| (n.name.as_str(), n.integrator.max_depth()))
        .collect();
    let kinds: Vec<&str> = m.more.iter().map(|n| n.integrator.kind().name()).collect();
    assert_eq!(more[0].0, "_arg_1");
    assert_eq!(more[1], ("c", Some(2)));
    assert_eq!(more[2].0, "_arg_2");
    assert_eq!(kinds, ["direct", "path", "direct"]);
}

#[test]
fn what_moment_cannot_hold_is_a_located_error() {
    let e = err("<integrator type=\"moment\">\n<integrator type=\"bdpt\"/></integrator>");
    check_located(
        &e,
        FILE,
        3,
        "<integrator type=\"bdpt\">",
        "only \"path\" and \"direct\"",
    );
    let e = err("<integrator type=\"moment\">\n<integrator type=\"moment\"/></integrator>");
    check_located(
        &e,
        FILE,
        3,
        "<integrator type=\"moment\">",
        "inside \"moment\"",
    );
    // Several nested integrators are read (`several_nested_integrators_are_read_in_file_order`);
    // two of one name would give their channels one name.
    let e = err("<integrator type=\"moment\"><integrator type=\"path\" name=\"a\"/>\n<integrator type=\"path\" name=\"a\"/></integrator>");
    check_located(
        &e,
        FILE,
        3,
        "<integrator type=\"path\"",
        "a second integrator named \"a\" in \"moment\" (the first is on line 2)",
    );
    let e = err("<integrator type=\"moment\">\n</integrator>");
    check_located(
        &e,
        FILE,
        2,
        "<integrator type=\"moment\">",
        "at least one nested",
    );
    let e = err("<integrator type=\"moment\">\n<bsdf type=\"diffuse\"/></integrator>");
    check_located(&e, FILE, 3, "<bsdf type=\"diffuse\">", "cannot be nested");
    let e = err("<integrator type=\"moment\"><integrator type=\"path\"/>\n<integer name=\"x\" value=\"1\"/></integrator>");
    check_located(&e, FILE, 3, "<integer name=\"x\">", "x");
    // A nested integrator's own parameters are checked where they are.
    let e = err("<integrator type=\"moment\"><integrator type=\"path\">\n<integer name=\"rr_depth\" value=\"0\"/></integrator></integrator>");
    check_located(&e, FILE, 3, "<integer name=\"rr_depth\">", "rr_depth");
}

#[test]
fn an_outer_integrator_we_do_not_support_is_named() {
    for ty in ["aov", "stokes"] {
        let e = err(&format!(
            "<integrator type=\"{ty}\">\n<integrator type=\"path\"/></integrator>"
        ));
        check_located(
            &e,
            FILE,
            2,
            &format!("<integrator type=\"{ty}\">"),
            "only \"moment\"",
        );
    }
    // An unknown one with something nested: the outer element is named, not the inner.
    let e = err("<integrator type=\"volpathmis\">\n<integrator type=\"path\"/></integrator>");
    check_located(
        &e,
        FILE,
        2,
        "<integrator type=\"volpathmis\">",
        "volpathmis",
    );
    // A known integrator still refuses a nested one where it stands.
    let e = err("<integrator type=\"path\">\n<integrator type=\"path\"/></integrator>");
    check_located(
        &e,
        FILE,
        3,
        "<integrator type=\"path\">",
        "cannot be nested here",
    );
}
