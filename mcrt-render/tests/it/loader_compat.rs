//! What published Mitsuba scene files use (issue 25), loaded as Mitsuba 3.9.1 loads it:
//! `<path>` folders on the file search path, `focus_distance` and `banner` accepted and
//! ignored, files older than 2.0.0 upgraded, volume textures in materials no shape uses,
//! a non-unit `<rotate>` axis used as given (with a located warning), `sdfgrid` refused by
//! name. Each behaviour was checked against Mitsuba 3.9.1 (`mi.load_file`) on the same
//! files.

use mcrt::glam::{Mat4, Vec3};
use mcrt_render::description::{BsdfDesc, IntegratorDesc, SceneDescription, ShapeKind, Texture};
use mcrt_render::loader::{
    load_scene, parse_scene, parse_scene_with_warnings, SceneError, SceneErrorKind, SceneWarning,
};
use std::path::{Path, PathBuf};

/// A fresh folder holding `files` (name, text), removed when dropped.
struct Folder(PathBuf);

impl Folder {
    fn new(tag: &str, files: &[(&str, &str)]) -> Self {
        let dir = std::env::temp_dir().join(format!("mcrt-compat-{tag}-{}", std::process::id()));
        std::fs::remove_dir_all(&dir).ok();
        for (name, text) in files {
            let p = dir.join(name);
            std::fs::create_dir_all(p.parent().unwrap()).unwrap();
            std::fs::write(p, text).unwrap();
        }
        Self(dir)
    }

    fn load(&self, name: &str) -> Result<SceneDescription, SceneError> {
        load_scene(&self.0.join(name), &[])
    }
}

impl Drop for Folder {
    fn drop(&mut self) {
        std::fs::remove_dir_all(&self.0).ok();
    }
}

const OBJ: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

fn scene(body: &str) -> String {
    format!("<scene version=\"3.0.0\">\n{body}\n</scene>")
}

fn obj(name: &str) -> String {
    format!("<shape type=\"obj\"><string name=\"filename\" value=\"{name}\"/></shape>")
}

fn mesh_file(d: &SceneDescription, i: usize) -> PathBuf {
    match &d.shapes[i].kind {
        ShapeKind::Obj { filename, .. } => filename.clone(),
        k => panic!("not an obj: {k:?}"),
    }
}

/// `<path>`: the last folder declared is tried first, before the scene's own folder; a
/// `<path>` after the shape applies to it too (Mitsuba builds objects after reading).
#[test]
fn path_folders_are_searched_last_declared_first() {
    let f = Folder::new(
        "order",
        &[
            (
                "scene.xml",
                &scene(&format!(
                    "<path value=\"p1\"/>\n{}\n{}\n<path value=\"p2\"/>",
                    obj("x.obj"),
                    obj("only1.obj")
                )),
            ),
            ("x.obj", OBJ),
            ("p1/x.obj", OBJ),
            ("p1/only1.obj", OBJ),
            ("p2/x.obj", OBJ),
        ],
    );
    let d = f.load("scene.xml").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(mesh_file(&d, 0), f.0.join("p2/x.obj"));
    assert_eq!(mesh_file(&d, 1), f.0.join("p1/only1.obj"));
}

/// An included file's own folder resolves its `<include>`s; its meshes and its `<path>`s
/// do not reach the main file's list (as in Mitsuba 3.9.1, whose objects resolve against
/// the main file's resolver).
#[test]
fn included_files_resolve_as_mitsuba() {
    let f = Folder::new(
        "include",
        &[
            ("a.xml", &scene("<include filename=\"sub/b.xml\"/>")),
            ("sub/b.xml", &scene("<include filename=\"c.xml\"/>")),
            (
                "sub/c.xml",
                &scene(&format!("<path value=\"deeper\"/>\n{}", obj("m/x.obj"))),
            ),
            ("sub/deeper/keep.txt", ""),
            ("m/x.obj", OBJ),
            ("sub/m/x.obj", OBJ),
            ("d.xml", &scene("<include filename=\"sub/e.xml\"/>")),
            (
                "sub/e.xml",
                &scene(&format!("<path value=\"../p\"/>\n{}", obj("y.obj"))),
            ),
            ("p/y.obj", OBJ),
        ],
    );
    let d = f.load("a.xml").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(mesh_file(&d, 0), f.0.join("m/x.obj"));
    // The include's <path> is its own: y.obj is not on the main file's list.
    let e = f.load("d.xml").unwrap_err();
    assert!(matches!(e.kind, SceneErrorKind::Io { .. }), "{e}");
    assert_eq!(e.line, Some(3), "{e}");
    assert!(e.to_string().contains("sub/e.xml"), "{e}");
}

/// A file found nowhere: a located error naming every folder tried, last `<path>` first.
#[test]
fn missing_file_names_every_folder_tried() {
    let f = Folder::new(
        "missing",
        &[
            (
                "scene.xml",
                &scene(&format!(
                    "<path value=\"p1\"/>\n<path value=\"p2\"/>\n{}",
                    obj("none.obj")
                )),
            ),
            ("p1/a", ""),
            ("p2/a", ""),
        ],
    );
    let e = f.load("scene.xml").unwrap_err();
    let msg = e.to_string();
    assert!(matches!(e.kind, SceneErrorKind::Io { .. }), "{msg}");
    assert_eq!(e.line, Some(4), "{msg}");
    assert!(
        msg.contains("none.obj") && msg.contains("scene.xml"),
        "{msg}"
    );
    let cwd = std::env::current_dir().unwrap();
    let tried = [f.0.join("p2"), f.0.join("p1"), f.0.clone(), cwd];
    let at: Vec<usize> = tried
        .iter()
        .map(|p| {
            msg.find(&format!("\"{}\"", p.display()))
                .unwrap_or_else(|| panic!("{} missing in {msg}", p.display()))
        })
        .collect();
    assert!(at.windows(2).all(|w| w[0] < w[1]), "{msg}");
}

/// `<path>` errors: a folder that does not exist, and a `<path>` not directly inside
/// `<scene>` (both located, as Mitsuba refuses them).
#[test]
fn path_errors_are_located() {
    let f = Folder::new(
        "patherr",
        &[
            ("a.xml", &scene("\n<path value=\"nowhere\"/>")),
            (
                "b.xml",
                &scene("<shape type=\"cube\">\n<path value=\".\"/></shape>"),
            ),
            ("c.xml", &scene("<path value=\".\" x=\"1\"/>")),
        ],
    );
    let e = f.load("a.xml").unwrap_err();
    assert_eq!(e.line, Some(3), "{e}");
    assert!(
        e.to_string().contains("nowhere") && e.to_string().contains("folder"),
        "{e}"
    );
    let e = f.load("b.xml").unwrap_err();
    assert!(matches!(e.kind, SceneErrorKind::Misplaced(_)), "{e}");
    assert_eq!(e.line, Some(3), "{e}");
    let e = f.load("c.xml").unwrap_err();
    assert!(matches!(e.kind, SceneErrorKind::UnknownAttribute(_)), "{e}");
}

fn parse(xml: &str) -> Result<SceneDescription, SceneError> {
    parse_scene(xml, Some(Path::new("tests/data/compat-test.xml")), &[])
}

/// `focus_distance` on `perspective` and `banner` on `hdrfilm`: accepted and ignored;
/// `focus_distance` must still be a number (Mitsuba 3 reads it as a float).
#[test]
fn focus_distance_and_banner_are_accepted_and_ignored() {
    let with = parse(&scene(
        "<sensor type=\"perspective\"><float name=\"focus_distance\" value=\"-4\"/>\
         <film type=\"hdrfilm\"><boolean name=\"banner\" value=\"false\"/></film></sensor>",
    ))
    .unwrap_or_else(|e| panic!("{e}"));
    let without = parse(&scene(
        "<sensor type=\"perspective\"><film type=\"hdrfilm\"/></sensor>",
    ))
    .unwrap();
    assert_eq!(with, without);
    let e = parse(&scene(
        "<sensor type=\"perspective\">\n<string name=\"focus_distance\" value=\"far\"/></sensor>",
    ))
    .unwrap_err();
    assert!(matches!(e.kind, SceneErrorKind::WrongType { .. }), "{e}");
    assert_eq!(e.line, Some(3), "{e}");
}

const OLD: &str = r#"<scene version="0.6.0">
    <integrator type="path"><integer name="maxDepth" value="3"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="30"/>
        <string name="fovAxis" value="y"/>
        <float name="focusDistance" value="4"/>
        <transform name="toWorld"><lookAt origin="0 0 5" target="0 0 0" up="0 1 0"/></transform>
        <sampler type="independent"><integer name="sampleCount" value="8"/></sampler>
        <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="8"/></film>
    </sensor>
    <bsdf type="diffuse" id="_mat">
        <texture type="checkerboard" name="diffuseReflectance">
            <float name="uoffset" value="0.25"/><float name="uscale" value="2"/><integer name="vscale" value="3"/>
        </texture>
    </bsdf>
    <shape type="sphere"><ref id="_mat"/></shape>
    <shape type="cube"><bsdf type="roughplastic"><float name="intIOR" value="1.6"/>
        <rgb name="diffuseReflectance" value="0.2"/></bsdf></shape>
</scene>"#;

const NEW: &str = r#"<scene version="3.0.0">
    <integrator type="path"><integer name="max_depth" value="3"/></integrator>
    <sensor type="perspective">
        <float name="fov" value="30"/>
        <string name="fov_axis" value="y"/>
        <transform name="to_world"><lookat origin="0 0 5" target="0 0 0" up="0 1 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="8"/></sampler>
        <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="8"/></film>
    </sensor>
    <bsdf type="diffuse" id="mat">
        <texture type="checkerboard" name="reflectance">
            <transform name="to_uv"><translate x="0.25" y="0"/><scale x="2" y="3"/></transform>
        </texture>
    </bsdf>
    <shape type="sphere"><ref id="mat"/></shape>
    <shape type="cube"><bsdf type="roughplastic"><float name="int_ior" value="1.6"/>
        <rgb name="diffuse_reflectance" value="0.2"/></bsdf></shape>
</scene>"#;

/// A 0.6 file is upgraded as Mitsuba 3 upgrades it and means what its 3.0 spelling means.
/// `to_uv` is S·T: Mitsuba 3.9.1's `to_uv` for this checkerboard is
/// [[2, 0, 0.5], [0, 3, 0], [0, 0, 1]] (`mi.traverse`).
#[test]
fn old_files_are_upgraded() {
    let mut old = parse(OLD).unwrap_or_else(|e| panic!("{e}"));
    let mut new = parse(NEW).unwrap_or_else(|e| panic!("{e}"));
    // The two spellings put the shapes on different lines; the scenes are the same.
    assert_eq!(old.origins.shapes.len(), new.origins.shapes.len());
    old.origins = Default::default();
    new.origins = Default::default();
    assert_eq!(old, new);
    assert_eq!(
        old.integrator,
        IntegratorDesc::Path(mcrt_render::description::PathParams {
            max_depth: 3,
            rr_depth: 5,
            ..Default::default()
        })
    );
    let BsdfDesc::Textured { textures, .. } = &old.shapes[0].bsdf else {
        panic!("{:?}", old.shapes[0].bsdf)
    };
    let Texture::Checkerboard(c) = &textures[0].1 else {
        panic!("{:?}", textures[0].1)
    };
    let m = c.to_uv;
    for (got, want) in [
        (m.matrix2.x_axis.x, 2.0),
        (m.matrix2.y_axis.y, 3.0),
        (m.translation.x, 0.5),
        (m.translation.y, 0.0),
    ] {
        assert!(got.is_finite() && (got - want).abs() < 1e-6, "{m:?}");
    }
}

/// After the upgrade, errors name the file's own line and the name as the file wrote it.
#[test]
fn errors_after_upgrade_point_into_the_file() {
    let xml = "<scene version=\"0.5.0\">\n<integrator type=\"path\">\n\
               <integer name=\"maxDepht\" value=\"3\"/></integrator></scene>";
    let e = parse(xml).unwrap_err();
    let msg = e.to_string();
    assert!(
        matches!(e.kind, SceneErrorKind::UnknownParameter { .. }),
        "{msg}"
    );
    assert_eq!(e.line, Some(3), "{msg}");
    assert!(
        msg.contains("compat-test.xml") && msg.contains("max_depht"),
        "{msg}"
    );
    assert!(msg.contains("name=\"maxDepht\" in the file"), "{msg}");
}

/// Only the old file is upgraded: a 3.0 file it includes keeps its names (a camelCase
/// name there stays an error), and a 0.5 file included by a 3.0 file is upgraded.
#[test]
fn upgrade_follows_each_files_version() {
    let f = Folder::new(
        "versions",
        &[
            (
                "old.xml",
                "<scene version=\"0.5.0\"><include filename=\"new.xml\"/></scene>",
            ),
            (
                "new.xml",
                "<scene version=\"3.0.0\">\n<integrator type=\"path\">\n\
                 <integer name=\"maxDepth\" value=\"2\"/></integrator></scene>",
            ),
            (
                "top.xml",
                "<scene version=\"3.0.0\"><include filename=\"old2.xml\"/></scene>",
            ),
            (
                "old2.xml",
                "<scene version=\"0.5.0\"><integrator type=\"path\">\
                 <integer name=\"maxDepth\" value=\"2\"/></integrator></scene>",
            ),
        ],
    );
    let e = f.load("old.xml").unwrap_err();
    assert!(
        matches!(e.kind, SceneErrorKind::UnknownParameter { .. }),
        "{e}"
    );
    assert_eq!(e.line, Some(3), "{e}");
    assert!(e.to_string().contains("new.xml"), "{e}");
    let d = f.load("top.xml").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        d.integrator,
        IntegratorDesc::Path(mcrt_render::description::PathParams {
            max_depth: 2,
            rr_depth: 5,
            ..Default::default()
        })
    );
}

const VOLUME_TEXTURE: &str = "<texture type=\"volume\" name=\"reflectance\">\n\
    <volume type=\"gridvolume\" name=\"volume\"><string name=\"filename\" value=\"g.vol\"/></volume>\
    </texture>";

/// A `.vol` header (Mitsuba's grid format, version 3, float32) of a 1×1×1 grid.
fn vol_file() -> Vec<u8> {
    let mut b = b"VOL\x03".to_vec();
    for v in [1u32, 1, 1, 1, 1] {
        b.extend_from_slice(&v.to_le_bytes());
    }
    for v in [0f32, 0., 0., 1., 1., 1., 0.5] {
        b.extend_from_slice(&v.to_le_bytes());
    }
    b
}

/// A volume texture in a material no shape uses, and a top-level `<volume>`, load (as in
/// Mitsuba 3.9.1); the same material on a shape is a located error, as is a missing grid
/// file, and a `<medium>` stays one.
#[test]
fn unused_volume_textures_are_accepted() {
    let dir = std::env::temp_dir().join(format!("mcrt-compat-vol-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("g.vol"), vol_file()).unwrap();
    let at = dir.join("scene.xml");
    let load = |body: &str| parse_scene(&scene(body), Some(&at), &[]);
    let unused = format!("<bsdf type=\"diffuse\" id=\"m\">\n{VOLUME_TEXTURE}</bsdf>");
    let d = load(&format!(
        "{unused}\n<volume type=\"gridvolume\" id=\"v\"><string name=\"filename\" value=\"g.vol\"/></volume>\n\
         <texture type=\"volume\" id=\"t\"><ref name=\"volume\" id=\"v\"/></texture>\n<shape type=\"cube\"/>"
    ))
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(d.shapes.len(), 1);
    let e = load(&format!(
        "{unused}\n<shape type=\"cube\"><ref id=\"m\"/></shape>"
    ))
    .unwrap_err();
    assert!(matches!(e.kind, SceneErrorKind::Unsupported(_)), "{e}");
    assert_eq!(e.line, Some(3), "{e}");
    assert!(e.to_string().contains("volume"), "{e}");
    let e = load(&unused.replace("g.vol", "none.vol")).unwrap_err();
    assert!(matches!(e.kind, SceneErrorKind::Io { .. }), "{e}");
    assert_eq!(e.line, Some(4), "{e}");
    let e = load(&unused.replace("g.vol", "scene.xml")).unwrap_err();
    assert!(
        e.to_string().contains("not found") || e.to_string().contains(".vol"),
        "{e}"
    );
    let e = load("<medium type=\"homogeneous\" id=\"fog\"/>").unwrap_err();
    assert!(matches!(e.kind, SceneErrorKind::Unsupported(_)), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

/// `sdfgrid` is refused by name.
#[test]
fn sdfgrid_is_refused_by_name() {
    let e = parse(&scene("\n<shape type=\"sdfgrid\"/>")).unwrap_err();
    assert!(matches!(e.kind, SceneErrorKind::Unsupported(_)), "{e}");
    assert_eq!(e.line, Some(3), "{e}");
    assert!(e.to_string().contains("sdfgrid"), "{e}");
}

fn to_world(xml_ops: &str) -> (Mat4, Vec<SceneWarning>) {
    let (d, w) = parse_scene_with_warnings(
        &scene(&format!(
            "<shape type=\"cube\"><transform name=\"to_world\">\n{xml_ops}</transform></shape>"
        )),
        Some(Path::new("tests/data/compat-test.xml")),
        &[],
    )
    .unwrap_or_else(|e| panic!("{e}"));
    (d.shapes[0].to_world, w)
}

/// A non-unit `<rotate>` axis is used as given, as Mitsuba 3.9.1 does, with a located
/// warning. Mitsuba's matrices, `mi.ScalarTransform4f().rotate(axis, angle).matrix`:
/// axis (0, 1, 1), 30° → [[0.866025, −0.5, 0.5], [0.5, 1, 0.133975], [−0.5, 0.133975, 1]];
/// axis (0, 2, 0), 90° → [[0, 0, 2], [0, 4, 0], [−2, 0, 0]].
#[test]
fn non_unit_rotate_axis_matches_mitsuba_and_warns() {
    let cases: [(&str, [[f32; 3]; 3]); 2] = [
        (
            "<rotate x=\"0\" y=\"1\" z=\"1\" angle=\"30\"/>",
            [
                [0.866025, -0.5, 0.5],
                [0.5, 1.0, 0.133975],
                [-0.5, 0.133975, 1.0],
            ],
        ),
        (
            "<rotate y=\"2\" angle=\"90\"/>",
            [[0.0, 0.0, 2.0], [0.0, 4.0, 0.0], [-2.0, 0.0, 0.0]],
        ),
    ];
    for (op, want) in cases {
        let (m, warnings) = to_world(op);
        for (r, row) in want.iter().enumerate() {
            for (c, w) in row.iter().enumerate() {
                let got = m.col(c)[r];
                assert!(got.is_finite() && (got - w).abs() < 1e-5, "{op}: {m:?}");
            }
        }
        assert_eq!(warnings.len(), 1, "{op}");
        let w = warnings[0].to_string();
        assert_eq!(warnings[0].line, Some(3), "{w}");
        assert!(
            w.contains("compat-test.xml") && w.contains("not unit length"),
            "{w}"
        );
        assert!(w.contains("<rotate>") && w.contains("warning"), "{w}");
    }
    // A unit axis: a rotation, no warning.
    let (m, warnings) = to_world("<rotate x=\"0\" y=\"0.6\" z=\"0.8\" angle=\"70\"/>");
    assert!(warnings.is_empty(), "{warnings:?}");
    let r = Mat4::from_axis_angle(Vec3::new(0.0, 0.6, 0.8), 70f32.to_radians());
    assert!(m.abs_diff_eq(r, 1e-6), "{m:?}");
}
