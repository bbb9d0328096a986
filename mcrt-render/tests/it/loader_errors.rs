//! Every kind of loader error: the message names the file, the line and the element, and
//! says what is wrong.

use crate::common;

use common::located::check_located;
use mcrt_render::loader::{load_scene, parse_scene, SceneError, SceneErrorKind};
use std::path::Path;

const FILE: &str = "tests/data/broken-test.xml";

/// Parses `body` inside a scene element whose start tag is on line 1.
fn err(body: &str) -> SceneError {
    let xml = format!("<scene version=\"3.0.0\">\n{body}\n</scene>");
    match parse_scene(&xml, Some(Path::new(FILE)), &[]) {
        Ok(d) => panic!("expected an error, got {d:?}"),
        Err(e) => e,
    }
}

#[test]
fn malformed_xml() {
    let e = err("<shape type=\"cube\">\n<float name=\"x\" value=\"1\">\n</shape>");
    assert!(matches!(e.kind, SceneErrorKind::Xml(_)), "{e}");
    assert!(e.line.is_some_and(|l| l >= 3), "{e}");
    assert!(e.to_string().contains(FILE));
}

#[test]
fn bad_or_missing_version() {
    for (xml, words) in [
        ("<scene version=\"0.6\"/>", "0.6"),
        ("<scene version=\"three\"/>", "three"),
        ("<scene/>", "missing"),
    ] {
        let e = parse_scene(xml, Some(Path::new(FILE)), &[]).unwrap_err();
        assert!(matches!(e.kind, SceneErrorKind::Version(_)), "{e}");
        check_located(&e, FILE, 1, "<scene>", words);
    }
}

#[test]
fn unknown_element_attribute_plugin_and_parameter() {
    let e = err("<shape type=\"cube\">\n<color name=\"x\" value=\"1\"/></shape>");
    assert!(matches!(e.kind, SceneErrorKind::UnknownElement(_)), "{e}");
    check_located(&e, FILE, 3, "<color name=\"x\">", "unknown element <color>");

    let e = err("<shape type=\"cube\" size=\"2\"/>");
    assert!(matches!(e.kind, SceneErrorKind::UnknownAttribute(_)), "{e}");
    check_located(&e, FILE, 2, "<shape type=\"cube\">", "\"size\"");

    let e = err("\n<bsdf type=\"hair\"/>");
    assert!(
        matches!(e.kind, SceneErrorKind::UnknownPlugin { .. }),
        "{e}"
    );
    check_located(
        &e,
        FILE,
        3,
        "<bsdf type=\"hair\">",
        "unknown bsdf plugin type \"hair\"",
    );

    let e = err("<sensor type=\"perspective\">\n<float name=\"fvo\" value=\"40\"/>\n</sensor>");
    assert!(
        matches!(e.kind, SceneErrorKind::UnknownParameter { .. }),
        "{e}"
    );
    check_located(
        &e,
        FILE,
        3,
        "<float name=\"fvo\">",
        "unknown parameter \"fvo\" for sensor \"perspective\"",
    );
}

#[test]
fn wrong_types_and_malformed_values() {
    let e = err("<sensor type=\"perspective\"><string name=\"fov\" value=\"40\"/></sensor>");
    assert!(matches!(e.kind, SceneErrorKind::WrongType { .. }), "{e}");
    check_located(&e, FILE, 2, "<string name=\"fov\">", "must be a <float>");

    let cases = [
        ("<float name=\"fov\" value=\"4o\"/>", "<float name=\"fov\">"),
        (
            "<integer name=\"x\" value=\"1.5\"/>",
            "<integer name=\"x\">",
        ),
        (
            "<boolean name=\"x\" value=\"yes\"/>",
            "<boolean name=\"x\">",
        ),
        ("<rgb name=\"x\" value=\"1, 2\"/>", "<rgb name=\"x\">"),
        (
            "<point name=\"x\" value=\"1 2 nan\"/>",
            "<point name=\"x\">",
        ),
        ("<float name=\"x\" value=\"inf\"/>", "<float name=\"x\">"),
    ];
    for (prop, element) in cases {
        let e = err(&format!("<shape type=\"sphere\">\n{prop}\n</shape>"));
        assert!(matches!(e.kind, SceneErrorKind::Malformed(_)), "{e}");
        check_located(&e, FILE, 3, element, "malformed");
    }
    let e = err("<shape type=\"cube\"><transform name=\"to_world\">\n<matrix value=\"1 0 0\"/>\n</transform></shape>");
    assert!(matches!(e.kind, SceneErrorKind::Malformed(_)), "{e}");
    check_located(&e, FILE, 3, "<matrix>", "16 or 9 values");
}

#[test]
fn undefined_parameter_and_reference() {
    let e = err(
        "<integrator type=\"path\">\n<integer name=\"max_depth\" value=\"$depth\"/></integrator>",
    );
    assert!(
        matches!(e.kind, SceneErrorKind::UndefinedParameter(_)),
        "{e}"
    );
    check_located(&e, FILE, 3, "<integer name=\"max_depth\">", "$depth");

    let e = err("<shape type=\"cube\">\n<ref id=\"nowhere\"/></shape>");
    assert!(
        matches!(e.kind, SceneErrorKind::UndefinedReference(_)),
        "{e}"
    );
    check_located(&e, FILE, 3, "<ref id=\"nowhere\">", "nowhere");

    let e = err("<shape type=\"cube\" id=\"c\"/>\n<shape type=\"cube\"><ref id=\"c\"/></shape>");
    assert!(
        matches!(e.kind, SceneErrorKind::UndefinedReference(_)),
        "{e}"
    );
    check_located(&e, FILE, 3, "<ref id=\"c\">", "not a <bsdf>");

    let e = err("<bsdf type=\"diffuse\" id=\"a\"/>\n<bsdf type=\"diffuse\" id=\"a\"/>");
    assert!(matches!(e.kind, SceneErrorKind::DuplicateId(_)), "{e}");
    check_located(&e, FILE, 3, "id=\"a\"", "duplicate id \"a\"");
}

#[test]
fn missing_or_unreadable_files() {
    let e = load_scene(Path::new("tests/data/no-such-scene.xml"), &[]).unwrap_err();
    assert!(matches!(e.kind, SceneErrorKind::Io { .. }), "{e}");
    assert!(e.to_string().contains("no-such-scene.xml"), "{e}");

    let e = err("<shape type=\"obj\">\n<string name=\"filename\" value=\"missing.obj\"/></shape>");
    assert!(matches!(e.kind, SceneErrorKind::Io { .. }), "{e}");
    check_located(&e, FILE, 2, "<shape type=\"obj\">", "missing.obj");

    let e = err("<emitter type=\"envmap\">\n<string name=\"filename\" value=\"cornell-box.xml\"/></emitter>");
    assert!(matches!(e.kind, SceneErrorKind::Io { .. }), "{e}");
    check_located(
        &e,
        FILE,
        2,
        "<emitter type=\"envmap\">",
        "not an OpenEXR file",
    );
}

#[test]
fn unsupported_and_misplaced() {
    let cases: [(&str, u32, &str, &str); 26] = [
        ("<bsdf type=\"twosided\">\n<bsdf type=\"dielectric\"/></bsdf>",
            2, "<bsdf type=\"twosided\">", "lets light through"),
        ("<bsdf type=\"blendbsdf\"><bsdf type=\"diffuse\"/>\n<bsdf type=\"diffuse\"/></bsdf>",
            2, "<bsdf type=\"blendbsdf\">", "needs a \"weight\""),
        ("<bsdf type=\"mask\">\n<float name=\"opacity\" value=\"1.5\"/><bsdf type=\"diffuse\"/></bsdf>",
            2, "<bsdf type=\"mask\">", "[0, 1]"),
        ("<bsdf type=\"mask\" id=\"m\">\n<ref id=\"m\"/></bsdf>",
            2, "<bsdf type=\"mask\" id=\"m\">", "nest more than 16"),
        ("<bsdf type=\"conductor\">\n<string name=\"material\" value=\"Gold\"/></bsdf>",
            3, "<string name=\"material\">", "\"Gold\" is not a known conductor"),
        ("<bsdf type=\"roughconductor\"><string name=\"material\" value=\"Au\"/>\n<rgb name=\"eta\" value=\"1\"/></bsdf>",
            3, "<rgb name=\"eta\">", "cannot be given with material \"Au\""),
        ("<bsdf type=\"roughplastic\"><float name=\"alpha_u\" value=\"0.1\"/>\n<float name=\"alpha_v\" value=\"0.2\"/></bsdf>",
            2, "<float name=\"alpha_u\">", "anisotropy"),
        ("<bsdf type=\"plastic\"><boolean name=\"nonlinear\" value=\"true\"/>\n<rgb name=\"diffuse_reflectance\" value=\"1.2, 0.5, 0.5\"/></bsdf>",
            3, "<rgb name=\"diffuse_reflectance\">", "diverge"),
        ("<integrator type=\"moment\"><integrator type=\"path\" name=\"a\"/>\n<integrator type=\"direct\" name=\"a\"/></integrator>",
            3, "<integrator type=\"direct\"", "a second integrator named \"a\""),
        ("<sensor type=\"perspective\"><float name=\"fov\" value=\"30\"/>\n<string name=\"fov_axis\" value=\"z\"/></sensor>",
            3, "<string name=\"fov_axis\">", "\"z\" is not supported"),
        ("<sensor type=\"perspective\">\n<string name=\"focal_length\" value=\"35cm\"/></sensor>",
            3, "<string name=\"focal_length\">", "not a positive length in mm"),
        ("<bsdf type=\"roughconductor\"><float name=\"alpha_u\" value=\"0.1\"/>\n<float name=\"alpha_v\" value=\"-0.2\"/></bsdf>",
            3, "<float name=\"alpha_v\">", "[0, 10]"),
        ("<emitter type=\"area\"/>", 2, "<emitter type=\"area\">", "inside a <shape>"),
        ("<shape type=\"cube\"><emitter type=\"point\"/></shape>", 2, "<emitter type=\"point\">", "only \"area\""),
        ("<shape type=\"cube\">\n<texture type=\"bitmap\"/></shape>", 3, "<texture type=\"bitmap\">", "inside a <shape>"),
        ("<shape type=\"cube\"><translate x=\"1\"/></shape>", 2, "<translate>", "outside a <transform>"),
        ("<shape type=\"sphere\"><float name=\"radius\" value=\"-1\"/></shape>", 2, "<float name=\"radius\">", "positive"),
        ("<emitter type=\"spot\">\n<float name=\"cutoff_angle\" value=\"0\"/></emitter>",
            3, "<float name=\"cutoff_angle\">", "(0, 180]"),
        ("<emitter type=\"spot\">\n<float name=\"beam_width\" value=\"-2\"/></emitter>",
            3, "<float name=\"beam_width\">", "non-negative"),
        ("<emitter type=\"spot\">\n<transform name=\"to_world\"><scale x=\"2\"/></transform></emitter>",
            3, "<transform name=\"to_world\">", "uniform scale"),
        ("<emitter type=\"directional\"><vector name=\"direction\" value=\"0, 1, 0\"/>\n<transform name=\"to_world\"/></emitter>",
            2, "<vector name=\"direction\">", "cannot both be given"),
        ("<emitter type=\"directional\">\n<vector name=\"direction\" value=\"0, 0, 0\"/></emitter>",
            3, "<vector name=\"direction\">", "non-zero"),
        ("<emitter type=\"envmap\"><string name=\"filename\" value=\"sky.exr\"/>\n<transform name=\"to_world\"><scale value=\"2\"/></transform></emitter>",
            3, "<transform name=\"to_world\">", "must be a rotation"),
        ("<shape type=\"cube\"><emitter type=\"spot\"/></shape>", 2, "<emitter type=\"spot\">", "only \"area\""),
        ("<sensor type=\"thinlens\">\n<float name=\"fov\" value=\"30\"/></sensor>",
            2, "<sensor type=\"thinlens\">", "aperture_radius"),
        ("<sensor type=\"thinlens\"><float name=\"aperture_radius\" value=\"0.1\"/>\n<float name=\"focus_distance\" value=\"-1\"/></sensor>",
            3, "<float name=\"focus_distance\">", "positive"),
    ];
    for (body, line, element, words) in cases {
        let e = err(body);
        check_located(&e, FILE, line, element, words);
    }
}

#[test]
fn duplicate_parameter_and_second_sensor() {
    let e = err("<shape type=\"sphere\"><float name=\"radius\" value=\"1\"/>\n<float name=\"radius\" value=\"2\"/></shape>");
    assert!(
        matches!(e.kind, SceneErrorKind::DuplicateParameter(_)),
        "{e}"
    );
    check_located(&e, FILE, 3, "<float name=\"radius\">", "given twice");
    let e = err("<sensor type=\"perspective\"/>\n<sensor type=\"perspective\"/>");
    check_located(
        &e,
        FILE,
        3,
        "<sensor type=\"perspective\">",
        "second <sensor>",
    );
}

#[test]
fn bidirectional_integrators_read_and_refuse_with_locations() {
    let ok = |body: &str| {
        let xml = format!("<scene version=\"3.0.0\">\n{body}\n</scene>");
        parse_scene(&xml, Some(Path::new(FILE)), &[]).expect("loads")
    };
    use mcrt_render::description::IntegratorDesc;
    assert_eq!(
        ok("<integrator type=\"bdpt\"><integer name=\"max_depth\" value=\"8\"/></integrator>")
            .integrator,
        IntegratorDesc::Bdpt(mcrt_render::description::BdptParams {
            max_depth: 8,
            rr_depth: 5,
            ..Default::default()
        })
    );
    let m = ok(
        "<integrator type=\"mlt\"><integer name=\"chains\" value=\"10\"/>\
                <float name=\"sigma\" value=\"0.02\"/></integrator>",
    )
    .integrator
    .into_inner();
    assert!(
        matches!(m, IntegratorDesc::Mlt(p) if p.chains == 10 && p.max_depth == 5 && p.sigma == 0.02),
        "{m:?}"
    );
    for (body, element, words) in [
        (
            "<integrator type=\"bdpt\"><integer name=\"rr_depth\" value=\"0\"/></integrator>",
            "rr_depth",
            "rr_depth",
        ),
        (
            "<integrator type=\"mlt\"><float name=\"large_step_prob\" value=\"0\"/></integrator>",
            "large_step_prob",
            "(0, 1]",
        ),
        (
            "<integrator type=\"mlt\"><float name=\"sigma\" value=\"-1\"/></integrator>",
            "sigma",
            "positive",
        ),
        (
            "<integrator type=\"mlt\"><integer name=\"max_depth\" value=\"-1\"/></integrator>",
            "max_depth",
            "max_depth",
        ),
        (
            "<integrator type=\"mlt\"><integer name=\"chains\" value=\"5000\"/>\
             <integer name=\"bootstrap_samples\" value=\"100\"/></integrator>",
            "bootstrap_samples",
            "chains",
        ),
    ] {
        let e = err(body);
        check_located(&e, FILE, 2, element, words);
    }
}

/// Writes `files` (name, text) into a fresh folder and loads the first.
fn load_files(tag: &str, files: &[(&str, &str)]) -> Result<(), SceneError> {
    let dir = std::env::temp_dir().join(format!("mcrt-loader-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text) in files {
        std::fs::write(dir.join(name), text).unwrap();
    }
    let r = load_scene(&dir.join(files[0].0), &[]).map(|_| ());
    std::fs::remove_dir_all(&dir).ok();
    r
}

#[test]
fn include_errors_name_the_file_they_are_in() {
    let scene = |body: &str| format!("<scene version=\"3.0.0\">\n{body}\n</scene>");
    // A missing file: located at the <include>.
    let e = load_files(
        "inc-missing",
        &[("a.xml", &scene("<include filename=\"nope.xml\"/>"))],
    )
    .unwrap_err();
    assert!(matches!(e.kind, SceneErrorKind::Io { .. }), "{e}");
    assert_eq!(e.line, Some(2), "{e}");
    assert!(e.to_string().contains("nope.xml"), "{e}");
    // A cycle: a.xml → b.xml → a.xml.
    let a = scene("<include filename=\"b.xml\"/>");
    let b = scene("\n<include filename=\"a.xml\"/>");
    let e = load_files("inc-cycle", &[("a.xml", &a), ("b.xml", &b)]).unwrap_err();
    assert!(e.to_string().contains("includes itself"), "{e}");
    assert!(e.to_string().contains("b.xml, line 3"), "{e}");
    // An error inside an included file names that file and its line; parameters defined
    // before the include are known inside it.
    let a = scene("<default name=\"r\" value=\"2\"/>\n<include filename=\"b.xml\"/>");
    let b = scene("<shape type=\"sphere\"><float name=\"radius\" value=\"$r\"/></shape>\n<shape type=\"teapot\"/>");
    let e = load_files("inc-inner", &[("a.xml", &a), ("b.xml", &b)]).unwrap_err();
    assert!(
        matches!(e.kind, SceneErrorKind::UnknownPlugin { .. }),
        "{e}"
    );
    assert!(e.to_string().contains("b.xml, line 3"), "{e}");
    let e = load_files(
        "inc-attr",
        &[("a.xml", &scene("<include file=\"b.xml\"/>"))],
    )
    .unwrap_err();
    assert!(matches!(e.kind, SceneErrorKind::UnknownAttribute(_)), "{e}");
    assert!(e.to_string().contains("a.xml, line 2"), "{e}");
    let e = load_files(
        "inc-root",
        &[
            ("a.xml", &scene("<include filename=\"b.xml\"/>")),
            ("b.xml", "<shape type=\"cube\"/>"),
        ],
    )
    .unwrap_err();
    assert!(e.to_string().contains("must be <scene>"), "{e}");
}

#[test]
fn spectrum_crop_tent_and_mesh_file_errors() {
    let e = err(
        "<bsdf type=\"diffuse\">\n<spectrum name=\"reflectance\" value=\"500:1, 400:2\"/></bsdf>",
    );
    assert!(matches!(e.kind, SceneErrorKind::Malformed(_)), "{e}");
    check_located(
        &e,
        FILE,
        3,
        "<spectrum name=\"reflectance\">",
        "wavelengths must increase",
    );
    let e =
        err("<bsdf type=\"diffuse\">\n<spectrum name=\"reflectance\" filename=\"x.spd\"/></bsdf>");
    assert!(matches!(e.kind, SceneErrorKind::Unsupported(_)), "{e}");
    let film = |extra: &str| {
        err(&format!(
            "<sensor type=\"perspective\"><film type=\"hdrfilm\">\n\
             <integer name=\"width\" value=\"64\"/>{extra}</film></sensor>"
        ))
    };
    let e = film(
        "<integer name=\"crop_offset_x\" value=\"40\"/><integer name=\"crop_width\" value=\"30\"/>",
    );
    assert!(matches!(e.kind, SceneErrorKind::InvalidValue(_)), "{e}");
    assert!(e.to_string().contains("crop_width"), "{e}");
    let e = film("<integer name=\"crop_offset_y\" value=\"-1\"/>");
    assert!(e.to_string().contains("crop_offset_y"), "{e}");
    let e = film("<rfilter type=\"tent\"><float name=\"radius\" value=\"0\"/></rfilter>");
    assert!(e.to_string().contains("radius"), "{e}");
    let e = err("<shape type=\"ply\">\n<string name=\"filename\" value=\"missing.ply\"/></shape>");
    check_located(&e, FILE, 2, "<shape type=\"ply\">", "missing.ply");
    let e = err("<shape type=\"serialized\">\n<string name=\"filename\" value=\"meshes/shapes.serialized\"/>\n<integer name=\"shape_index\" value=\"-1\"/></shape>");
    check_located(&e, FILE, 4, "<integer name=\"shape_index\">", "outside");
}

/// Textures: files that are missing or not images, unknown modes and plugins, textures
/// where none is taken, on parameters a material lacks, or given twice.
#[test]
fn texture_errors() {
    let bitmap = |params: &str| {
        format!(
            "<bsdf type=\"diffuse\">\n<texture type=\"bitmap\" name=\"reflectance\">{params}</texture></bsdf>"
        )
    };
    let file = |f: &str| format!("<string name=\"filename\" value=\"{f}\"/>");
    let e = err(&bitmap(&file("missing.png")));
    assert!(matches!(e.kind, SceneErrorKind::Io { .. }), "{e}");
    check_located(
        &e,
        FILE,
        3,
        "<texture type=\"bitmap\" name=\"reflectance\">",
        "missing.png",
    );
    let e = err(&bitmap(&file("cornell-box.xml")));
    assert!(matches!(e.kind, SceneErrorKind::Io { .. }), "{e}");
    check_located(
        &e,
        FILE,
        3,
        "<texture type=\"bitmap\"",
        "not a PNG, JPEG or OpenEXR image",
    );
    let e = err(&bitmap(""));
    check_located(
        &e,
        FILE,
        3,
        "<texture type=\"bitmap\"",
        "needs a \"filename\"",
    );

    // A PNG cut short after its header: located, never a panic.
    let dir = std::env::temp_dir().join(format!("mcrt-texture-errors-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let png = std::fs::read("tests/data/textures/grid.png").unwrap();
    let cut = dir.join("cut.png");
    std::fs::write(&cut, &png[..60]).unwrap();
    let e = err(&bitmap(&file(cut.to_str().unwrap())));
    check_located(&e, FILE, 3, "<texture type=\"bitmap\"", "PNG");
    let jpg = std::fs::read("tests/data/textures/rings.jpg").unwrap();
    let cut = dir.join("cut.jpg");
    std::fs::write(&cut, &jpg[..jpg.len() / 3]).unwrap();
    let e = err(&bitmap(&file(cut.to_str().unwrap())));
    check_located(&e, FILE, 3, "<texture type=\"bitmap\"", "JPEG");
    // A PNG whose header claims 10⁵ × 10⁵ pixels: refused before any pixel is allocated.
    let huge = dir.join("huge.png");
    std::fs::write(&huge, png_header(100_000, 100_000)).unwrap();
    let e = err(&bitmap(&file(huge.to_str().unwrap())));
    check_located(
        &e,
        FILE,
        3,
        "<texture type=\"bitmap\"",
        "more than the 67108864 a texture may have",
    );
    // An EXR whose header claims 10⁵ × 10⁵ pixels, as a texture and as an environment map:
    // refused from the header, before the decoder allocates the layer.
    let huge = dir.join("huge.exr");
    std::fs::write(&huge, exr_claiming(100_000, 100_000)).unwrap();
    let e = err(&bitmap(&file(huge.to_str().unwrap())));
    check_located(
        &e,
        FILE,
        3,
        "<texture type=\"bitmap\"",
        "100000 × 100000 pixels is more than the 67108864 allowed",
    );
    let e = mcrt_render::light::EnvMap::load(&huge, 1.0, glam::Mat4::IDENTITY).unwrap_err();
    assert!(
        e.contains("100000 × 100000 pixels is more than the 67108864 allowed"),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).unwrap();

    let grid = file("textures/grid.png");
    let cases: [(String, u32, &str, &str); 12] = [
        (bitmap(&format!("{grid}\n<string name=\"wrap_mode\" value=\"tile\"/>")),
            4, "<string name=\"wrap_mode\">", "\"tile\" is not repeat, mirror or clamp"),
        (bitmap(&format!("{grid}\n<string name=\"filter_type\" value=\"cubic\"/>")),
            4, "<string name=\"filter_type\">", "\"cubic\" is not bilinear or nearest"),
        ("<bsdf type=\"diffuse\">\n<texture type=\"noise\" name=\"reflectance\"/></bsdf>".into(),
            3, "<texture type=\"noise\"", "unknown texture plugin type \"noise\""),
        ("<bsdf type=\"diffuse\">\n<texture type=\"checkerboard\"/></bsdf>".into(),
            3, "<texture type=\"checkerboard\">", "missing attribute \"name"),
        ("<bsdf type=\"conductor\">\n<texture type=\"checkerboard\" name=\"reflectance\"/></bsdf>".into(),
            3, "<texture type=\"checkerboard\" name=\"reflectance\">", "unknown parameter \"reflectance\" for bsdf \"conductor\""),
        // (`roughconductor` and `roughdielectric` take a textured `alpha` since issue 25;
        // Mitsuba 3.9.1's `roughplastic` does not.)
        ("<bsdf type=\"roughplastic\">\n<texture type=\"checkerboard\" name=\"alpha\"/></bsdf>".into(),
            3, "<texture type=\"checkerboard\" name=\"alpha\">", "a texture for \"alpha\""),
        ("<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.5\"/>\n<texture type=\"checkerboard\" name=\"reflectance\"/></bsdf>".into(),
            3, "<texture type=\"checkerboard\"", "\"reflectance\" given twice"),
        // (An area emitter's `radiance` takes a texture since issue 25; a point light's
        // `intensity` does not.)
        ("<emitter type=\"point\">\n<texture type=\"checkerboard\" name=\"intensity\"/></emitter>".into(),
            3, "<texture type=\"checkerboard\" name=\"intensity\">", "a texture for \"intensity\" here"),
        ("<texture type=\"checkerboard\">\n<texture type=\"checkerboard\" name=\"color0\"/></texture>".into(),
            3, "<texture type=\"checkerboard\" name=\"color0\">", "a texture for \"color0\" here"),
        ("<bsdf type=\"twosided\">\n<texture type=\"checkerboard\" name=\"reflectance\"/><bsdf type=\"diffuse\"/></bsdf>".into(),
            3, "<texture type=\"checkerboard\"", "a texture for \"reflectance\" here"),
        ("<texture type=\"checkerboard\" id=\"t\"/>\n<shape type=\"cube\"><ref id=\"t\"/></shape>".into(),
            3, "<ref id=\"t\">", "not a <bsdf>"),
        ("<bsdf type=\"diffuse\">\n<ref name=\"reflectance\" id=\"nothing\"/></bsdf>".into(),
            3, "<ref", "no object has id \"nothing\""),
    ];
    for (body, line, element, words) in cases {
        let e = err(&body);
        check_located(&e, FILE, line, element, words);
    }
}

/// A valid 2 × 2 EXR whose data and display windows are then rewritten to claim `w × h`
/// pixels (the chunk table and pixels stay those of 2 × 2).
fn exr_claiming(w: i32, h: i32) -> Vec<u8> {
    let path = std::env::temp_dir().join(format!("mcrt-exr-claiming-{}.exr", std::process::id()));
    mcrt_render::film::write_exr(&path, 2, 2, &[glam::Vec3::ONE; 4]).unwrap();
    let mut bytes = std::fs::read(&path).unwrap();
    std::fs::remove_file(&path).ok();
    for name in [&b"dataWindow\0box2i\0"[..], &b"displayWindow\0box2i\0"[..]] {
        let at = bytes
            .windows(name.len())
            .position(|x| x == name)
            .expect("a window attribute")
            + name.len()
            + 4;
        bytes[at + 8..at + 12].copy_from_slice(&(w - 1).to_le_bytes());
        bytes[at + 12..at + 16].copy_from_slice(&(h - 1).to_le_bytes());
    }
    bytes
}

/// The signature, a valid IHDR chunk (8-bit RGB) of a PNG of `w × h` pixels, an empty
/// IDAT and IEND.
fn png_header(w: u32, h: u32) -> Vec<u8> {
    fn crc32(bytes: &[u8]) -> u32 {
        let mut c = !0u32;
        for &b in bytes {
            c ^= u32::from(b);
            for _ in 0..8 {
                c = if c & 1 == 1 {
                    0xedb8_8320 ^ (c >> 1)
                } else {
                    c >> 1
                };
            }
        }
        !c
    }
    let mut ihdr = b"IHDR".to_vec();
    ihdr.extend(w.to_be_bytes());
    ihdr.extend(h.to_be_bytes());
    ihdr.extend([8, 2, 0, 0, 0]);
    let mut out = b"\x89PNG\r\n\x1a\n".to_vec();
    for chunk in [ihdr, b"IDAT".to_vec(), b"IEND".to_vec()] {
        out.extend((chunk.len() as u32 - 4).to_be_bytes());
        out.extend(&chunk);
        out.extend(crc32(&chunk).to_be_bytes());
    }
    out
}
