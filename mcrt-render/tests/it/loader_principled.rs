//! `<bsdf type="principled">`: Mitsuba 3.9's parameter names and defaults, `specular` or
//! `eta` for the index, a texture on `base_color`, and located errors for values the
//! material cannot take.
//! Its values against Mitsuba's are `tests/it/bsdf_mitsuba_values.rs`.

use mcrt::glam::{Vec2, Vec3};
use mcrt_render::bsdf::{AnyBsdf, PrincipledParams, TexturedBsdf};
use mcrt_render::description::{BsdfDesc, TextureParam};
use mcrt_render::loader::{parse_scene, SceneError, SceneErrorKind};
use std::path::Path;

const FILE: &str = "tests/data/principled-test.xml";

fn parse(bsdf: &str) -> Result<BsdfDesc, SceneError> {
    let xml =
        format!("<scene version=\"3.0.0\">\n<shape type=\"sphere\">\n{bsdf}\n</shape>\n</scene>");
    parse_scene(&xml, Some(Path::new(FILE)), &[]).map(|d| d.shapes[0].bsdf.clone())
}

fn params(bsdf: &str) -> PrincipledParams {
    match parse(bsdf).expect("reads") {
        BsdfDesc::Principled(p) => p,
        other => panic!("not principled: {other:?}"),
    }
}

#[test]
fn defaults_are_mitsubas() {
    let p = params("<bsdf type=\"principled\"/>");
    assert_eq!(p, PrincipledParams::default());
    assert_eq!(p.base_color, Vec3::splat(0.5));
    assert_eq!((p.roughness, p.metallic, p.clearcoat), (0.5, 0.0, 0.0));
    // specular 0.5 is a normal-incidence reflectance of 0.04: index 1.5.
    assert!(p.eta.is_finite() && (p.eta - 1.5).abs() < 1e-5, "{}", p.eta);
    assert_eq!(p.main_specular_sampling_rate, 1.0);
}

#[test]
fn every_parameter_is_read() {
    let p = params(
        "<bsdf type=\"principled\">\
         <rgb name=\"base_color\" value=\"0.1, 0.2, 0.3\"/>\
         <float name=\"roughness\" value=\"0.11\"/><float name=\"anisotropic\" value=\"0\"/>\
         <float name=\"metallic\" value=\"0.13\"/><float name=\"spec_trans\" value=\"0\"/>\
         <float name=\"specular\" value=\"1\"/><float name=\"spec_tint\" value=\"0.14\"/>\
         <float name=\"sheen\" value=\"0.15\"/><float name=\"sheen_tint\" value=\"0.16\"/>\
         <float name=\"flatness\" value=\"0.17\"/><float name=\"clearcoat\" value=\"0.18\"/>\
         <float name=\"clearcoat_gloss\" value=\"0.19\"/>\
         <float name=\"diffuse_reflectance_sampling_rate\" value=\"0.2\"/>\
         <float name=\"main_specular_sampling_rate\" value=\"0.3\"/>\
         <float name=\"clearcoat_sampling_rate\" value=\"0.4\"/></bsdf>",
    );
    let want = PrincipledParams {
        base_color: Vec3::new(0.1, 0.2, 0.3),
        roughness: 0.11,
        anisotropic: 0.0,
        metallic: 0.13,
        spec_trans: 0.0,
        eta: PrincipledParams::eta_from_specular(1.0),
        spec_tint: 0.14,
        sheen: 0.15,
        sheen_tint: 0.16,
        flatness: 0.17,
        clearcoat: 0.18,
        clearcoat_gloss: 0.19,
        diffuse_reflectance_sampling_rate: 0.2,
        main_specular_sampling_rate: 0.3,
        clearcoat_sampling_rate: 0.4,
    };
    assert_eq!(p, want);
    // specular 1 is a normal-incidence reflectance of 0.08.
    let r0 = ((p.eta - 1.0) / (p.eta + 1.0)).powi(2);
    assert!(r0.is_finite() && (r0 - 0.08).abs() < 1e-6, "{r0}");
    let p = params("<bsdf type=\"principled\"><float name=\"eta\" value=\"1.33\"/></bsdf>");
    assert_eq!(p.eta, 1.33);
}

#[test]
fn base_color_takes_a_texture() {
    let desc = parse(
        "<bsdf type=\"principled\"><texture type=\"checkerboard\" name=\"base_color\">\
         <rgb name=\"color0\" value=\"0.8, 0.1, 0.1\"/><rgb name=\"color1\" value=\"0.1, 0.1, 0.8\"/>\
         </texture></bsdf>",
    )
    .expect("reads");
    let BsdfDesc::Textured { textures, .. } = &desc else {
        panic!("not textured: {desc:?}");
    };
    assert_eq!(textures[0].0, TextureParam::BaseColor);
    let t = TexturedBsdf::from_desc(&desc).expect("valid");
    let colour = |uv| match t.at(uv).bsdf {
        AnyBsdf::Principled(p) => p.params.base_color,
        other => panic!("not principled: {other:?}"),
    };
    let (a, b) = (colour(Vec2::new(0.25, 0.25)), colour(Vec2::new(0.75, 0.25)));
    assert!(a.is_finite() && (a - Vec3::new(0.8, 0.1, 0.1)).abs().max_element() < 1e-6);
    assert!(b.is_finite() && (b - Vec3::new(0.1, 0.1, 0.8)).abs().max_element() < 1e-6);
}

/// Checks that the error is an invalid value at `line` naming the file and `words`.
fn check(bsdf: &str, line: u32, words: &str) {
    let e = parse(bsdf).expect_err("refused");
    let msg = e.to_string();
    assert!(matches!(e.kind, SceneErrorKind::InvalidValue(_)), "{msg}");
    assert_eq!(e.line, Some(line), "{msg}");
    assert!(msg.contains(FILE) && msg.contains(words), "{msg}");
}

#[test]
fn bad_values_are_refused_where_they_are() {
    let one = |name: &str, v: &str| {
        format!("<bsdf type=\"principled\">\n<float name=\"{name}\" value=\"{v}\"/></bsdf>")
    };
    // The parameter's own line (the <bsdf> is on line 3).
    check(
        &one("spec_trans", "1.5"),
        4,
        "\"spec_trans\" must be in [0, 1]",
    );
    check(
        &one("roughness", "1.5"),
        4,
        "\"roughness\" must be in [0, 1]",
    );
    check(&one("metallic", "-0.1"), 4, "\"metallic\"");
    check(
        &one("anisotropic", "1.5"),
        4,
        "\"anisotropic\" must be in [0, 1]",
    );
    check(&one("eta", "0"), 4, "\"eta\" must be finite and > 0");
    check(
        &one("specular", "13"),
        4,
        "\"specular\" must lie in [0, 12.5)",
    );
    check(
        &one("clearcoat_sampling_rate", "-1"),
        4,
        "clearcoat_sampling_rate",
    );
    check(
        "<bsdf type=\"principled\">\n<rgb name=\"base_color\" value=\"0.5, -1, 0\"/></bsdf>",
        4,
        "\"base_color\"",
    );
    check(
        "<bsdf type=\"principled\"><float name=\"eta\" value=\"1.5\"/>\n\
         <float name=\"specular\" value=\"0.5\"/></bsdf>",
        4,
        "\"specular\" cannot be given with \"eta\"",
    );
}

/// A transmitting principled lets light through, so `twosided` refuses it (as Mitsuba 3
/// refuses any nested material with transmission); without transmission it may be wrapped.
#[test]
fn twosided_takes_principled_without_transmission_only() {
    let wrap = |st: &str| {
        parse(&format!(
            "<bsdf type=\"twosided\"><bsdf type=\"principled\">\
             <float name=\"spec_trans\" value=\"{st}\"/></bsdf></bsdf>"
        ))
    };
    assert!(matches!(wrap("0").expect("reads"), BsdfDesc::TwoSided(_)));
    let e = wrap("0.5").expect_err("refused");
    assert!(matches!(e.kind, SceneErrorKind::InvalidValue(_)), "{e}");
}

#[test]
fn unknown_parameters_and_principledthin_are_refused() {
    let e = parse("<bsdf type=\"principled\"><float name=\"subsurface\" value=\"0.5\"/></bsdf>")
        .expect_err("refused");
    assert!(
        matches!(e.kind, SceneErrorKind::UnknownParameter { .. }),
        "{e}"
    );
    let e = parse("<bsdf type=\"principledthin\"/>").expect_err("refused");
    assert!(
        matches!(e.kind, SceneErrorKind::UnknownPlugin { .. }),
        "{e}"
    );
}
