//! The Mitsuba 3 XML loader on the shipped scenes, `$name` substitution and `-D`
//! overrides, and one test per error kind (each message names file, line and element).

use mcrt::glam::{Mat4, Vec3};
use mcrt_render::cornell_box::{cornell_box, cornell_box_with};
use mcrt_render::description::{
    BsdfDesc, ConductorFresnel, EmitterDesc, FilterDesc, FovAxis, IntegratorDesc, Microfacet,
    MicrofacetKind, Roughness, SamplerKind, SceneDescription, ShapeKind, ThinLensDesc,
};
use mcrt_render::loader::{load_scene, look_at, parse_scene, SceneError, SceneErrorKind};
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
    parsed.origins = Default::default();
    assert_eq!(parsed, cornell_box());
}

#[test]
fn cornell_box_defines_override_defaults() {
    let mut parsed = load(CORNELL, &[("max_depth", "2"), ("spp", "16"), ("res", "32")]);
    parsed.source = None;
    parsed.origins = Default::default();
    assert_eq!(parsed, cornell_box_with(16, 32, 2));
    assert_eq!(
        parsed.integrator,
        IntegratorDesc::Path(mcrt_render::description::PathParams {
            max_depth: 2,
            rr_depth: 5,
            ..Default::default()
        })
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

#[test]
fn veach_plates_are_ggx_mirrors_of_rising_roughness() {
    let d = load(VEACH, &[]);
    assert_eq!(d.shapes.len(), 11);
    for (i, alpha) in [0.005f32, 0.02, 0.05, 0.1].into_iter().enumerate() {
        let s = &d.shapes[i];
        assert_eq!(s.id.as_deref(), Some(format!("plate{i}").as_str()));
        assert_eq!(s.kind, ShapeKind::Rectangle);
        assert_eq!(
            s.bsdf,
            BsdfDesc::RoughConductor {
                microfacet: Microfacet::new(
                    MicrofacetKind::Ggx,
                    Roughness::new(alpha).expect("a roughness")
                ),
                fresnel: ConductorFresnel::Perfect,
                specular_reflectance: mcrt_render::description::Colour::WHITE,
            }
        );
        assert!(s.emitter.is_none());
    }
    let m = d.shapes[0].to_world;
    assert_eq!(
        m.row(1),
        mcrt::glam::Vec4::new(0., 0.048321, 0.996133, -1.9)
    );
}

#[test]
fn veach_sphere_lights() {
    let d = load(VEACH, &[]);
    let expected = [
        (-3.75, 0.05, 300.0),
        (-1.25, 0.15, 33.3333),
        (1.25, 0.45, 3.7037),
        (3.75, 1.0, 0.75),
    ];
    for (i, (x, r, l)) in expected.into_iter().enumerate() {
        let s = &d.shapes[4 + i];
        assert_eq!(
            s.kind,
            ShapeKind::Sphere {
                center: Vec3::new(x, 4.2, -1.0),
                radius: r
            }
        );
        assert_eq!(s.emitter.map(|e| e.radiance.get()), Some(Vec3::splat(l)));
        assert_eq!(s.to_world, Mat4::IDENTITY);
        // An emitting shape without a BSDF gets Mitsuba 3's black diffuse.
        assert_eq!(
            s.bsdf,
            BsdfDesc::Diffuse {
                reflectance: mcrt_render::description::Colour::new(Vec3::ZERO).unwrap()
            }
        );
    }
    let fill = &d.shapes[10];
    assert_eq!(fill.id.as_deref(), Some("fill"));
    assert_eq!(
        fill.emitter.map(|e| e.radiance.get()),
        Some(Vec3::splat(1.2))
    );
    // A shape without a BSDF and without an emitter gets Mitsuba's default: diffuse 0.5.
    let plain = parse(
        r#"<scene version="3.0.0"><shape type="sphere"/></scene>"#,
        &[],
    )
    .unwrap();
    assert_eq!(plain.shapes[0].bsdf, BsdfDesc::default());
}

#[test]
fn veach_walls_compose_transforms_in_mitsuba_order() {
    let d = load(VEACH, &[]);
    let wall = BsdfDesc::Diffuse {
        reflectance: mcrt_render::description::Colour::new(Vec3::splat(0.4)).unwrap(),
    };
    let back = &d.shapes[8];
    assert_eq!(back.id.as_deref(), Some("back"));
    assert_eq!(back.bsdf, wall);
    // scale, then translate: T · S.
    let expected = Mat4::from_translation(Vec3::new(0.0, 0.0, -4.0))
        * Mat4::from_scale(Vec3::new(20.0, 10.0, 1.0));
    assert_mat_close(back.to_world, expected, 0.0);
    assert_eq!(
        back.to_world.transform_point3(Vec3::new(1., 1., 0.)),
        Vec3::new(20., 10., -4.)
    );
    let floor = &d.shapes[9];
    // The rectangle's +z normal is rotated to +y, and the floor sits at y = −2.5.
    let n = floor.to_world.transform_vector3(Vec3::Z);
    assert!((n.normalize() - Vec3::Y).length() < 1e-6, "{n}");
    let c = floor.to_world.transform_point3(Vec3::new(1.0, 1.0, 0.0));
    assert!((c - Vec3::new(20.0, -2.5, -20.0)).length() < 1e-5, "{c}");
}

#[test]
fn veach_camera() {
    let d = load(VEACH, &[]);
    assert_eq!(d.sensor.fov, 40.0);
    assert_eq!(d.sensor.fov_axis, FovAxis::X);
    assert_eq!((d.sensor.film.width, d.sensor.film.height), (384, 256));
    assert_eq!(d.sensor.near_clip, 0.01);
    assert_eq!(d.sensor.far_clip, 1e4);
    let m = look_at(Vec3::new(0., 2., 15.), Vec3::new(0., 1., 0.), Vec3::Y).unwrap();
    assert_eq!(d.sensor.to_world, m);
    let dir = m.transform_vector3(Vec3::Z);
    let expected = Vec3::new(0.0, -1.0, -15.0).normalize();
    assert!((dir - expected).length() < 1e-6);
    // Mitsuba's camera: +x is the image's left, so for a camera looking down −z it is −x.
    assert!((m.transform_vector3(Vec3::X) - Vec3::NEG_X).length() < 1e-6);
    assert_eq!(d.sensor.sampler.sample_count, 64);
    let d = load(VEACH, &[("spp", "7")]);
    assert_eq!(d.sensor.sampler.sample_count, 7);
}

fn parse(xml: &str, defines: &[(&str, &str)]) -> Result<SceneDescription, SceneError> {
    let d: Vec<(String, String)> = defines
        .iter()
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect();
    parse_scene(xml, Some(Path::new("tests/data/inline.xml")), &d)
}

#[test]
fn substitution_works_in_any_attribute_and_defines_win() {
    let xml = r#"<scene version="3.0.0">
        <default name="kind" value="diffuse"/>
        <default name="r" value="0.25"/>
        <default name="rr" value="0.75"/>
        <shape type="sphere"><bsdf type="$kind"><rgb name="reflectance" value="$r, $rr, $r"/></bsdf></shape>
    </scene>"#;
    let d = parse(xml, &[]).unwrap();
    let refl = |d: &SceneDescription| d.shapes[0].bsdf.clone();
    assert_eq!(
        refl(&d),
        BsdfDesc::Diffuse {
            reflectance: mcrt_render::description::Colour::new(Vec3::new(0.25, 0.75, 0.25))
                .unwrap()
        }
    );
    let d = parse(xml, &[("r", "0.5"), ("kind", "diffuse")]).unwrap();
    assert_eq!(
        refl(&d),
        BsdfDesc::Diffuse {
            reflectance: mcrt_render::description::Colour::new(Vec3::new(0.5, 0.75, 0.5)).unwrap()
        }
    );
    // A define the file neither declares nor uses is refused (a misspelt -D is never
    // silently ignored), naming the file and the parameters it declares.
    let e = parse(xml, &[("r", "0.5"), ("unused", "1")]).unwrap_err();
    assert!(matches!(e.kind, SceneErrorKind::UnknownDefine(_)), "{e}");
    let msg = e.to_string();
    assert!(msg.starts_with("tests/data/inline.xml: "), "{msg}");
    assert!(
        msg.contains("-D unused=1") && msg.contains("kind, r, rr"),
        "{msg}"
    );
    // A define that only a `$name` uses (no <default>) is a parameter.
    let uses = r#"<scene version="3.0.0"><shape type="sphere"><float name="radius" value="$rad"/></shape></scene>"#;
    assert!(parse(uses, &[("rad", "2")]).is_ok());
    assert!(parse(uses, &[("rad", "2"), ("ra", "1")]).is_err());
}

#[test]
fn transform_elements() {
    let xml = r#"<scene version="3.0.0"><shape type="cube"><transform name="to_world">
        <translate value="1, 2, 3"/><rotate y="1" angle="90"/><scale value="2"/>
        <matrix value="1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1"/>
    </transform></shape></scene>"#;
    let m = parse(xml, &[]).unwrap().shapes[0].to_world;
    // Each later element applies after: p ↦ 2 · R_y(90°) · (p + (1, 2, 3)).
    let p = m.transform_point3(Vec3::ZERO);
    assert!((p - Vec3::new(6.0, 4.0, -2.0)).length() < 1e-5, "{p}");
}

#[test]
fn materials_emitters_and_integrators() {
    let xml = r#"<scene version="3.0.0">
        <integrator type="direct"><integer name="shading_samples" value="3"/>
            <integer name="bsdf_samples" value="2"/></integrator>
        <sensor type="perspective"><film type="hdrfilm"><integer name="width" value="8"/>
            <integer name="height" value="4"/><string name="pixel_format" value="rgba"/></film>
            <sampler type="ldsampler"><integer name="sample_count" value="16"/>
            <integer name="seed" value="9"/></sampler></sensor>
        <bsdf type="twosided" id="two"><bsdf type="conductor">
            <rgb name="eta" value="0.2, 0.9, 1.1"/><rgb name="k" value="3.9, 2.4, 2.2"/></bsdf></bsdf>
        <shape type="disk"><ref id="two"/></shape>
        <shape type="rectangle"><bsdf type="dielectric"><string name="int_ior" value="water"/>
            <float name="ext_ior" value="1"/></bsdf><boolean name="flip_normals" value="true"/></shape>
        <shape type="obj"><string name="filename" value="cornell-box.xml"/></shape>
        <emitter type="point"><point name="position" value="1, 2, 3"/><rgb name="intensity" value="5"/></emitter>
        <emitter type="envmap"><string name="filename" value="veach-mis.exr"/><float name="scale" value="2"/></emitter>
    </scene>"#;
    let d = parse(xml, &[]).unwrap();
    // A scene has at most one environment emitter (a second is a located error, as in
    // Mitsuba 3): the constant one is read on its own.
    let constant = r#"<scene version="3.0.0">
        <emitter type="constant"><rgb name="radiance" value="0.5"/></emitter></scene>"#;
    assert_eq!(parse(constant, &[]).unwrap().emitters.len(), 1);
    assert_eq!(
        d.integrator,
        IntegratorDesc::Direct(mcrt_render::description::DirectParams {
            shading_samples: 3,
            emitter_samples: 3,
            bsdf_samples: 2,
            ..Default::default()
        })
    );
    assert_eq!((d.sensor.film.width, d.sensor.film.height), (8, 4));
    assert_eq!(d.sensor.film.filter, FilterDesc::Gaussian { stddev: 0.5 });
    assert_eq!(d.sensor.sampler.sample_count, 16);
    assert_eq!(d.sensor.sampler.seed, 9);
    let BsdfDesc::TwoSided(inner) = &d.shapes[0].bsdf else {
        panic!("{:?}", d.shapes[0].bsdf)
    };
    assert!(matches!(
        **inner,
        BsdfDesc::Conductor {
            fresnel: ConductorFresnel::Complex { .. },
            ..
        }
    ));
    assert!(
        matches!(d.shapes[1].bsdf, BsdfDesc::Dielectric { int_ior, ext_ior, .. }
        if int_ior == 1.333 && ext_ior == 1.0)
    );
    assert!(d.shapes[1].flip_normals);
    let ShapeKind::Obj {
        filename,
        face_normals,
        ..
    } = &d.shapes[2].kind
    else {
        panic!()
    };
    assert_eq!(filename, Path::new("tests/data/cornell-box.xml"));
    assert!(!face_normals);
    assert_eq!(d.emitters.len(), 2);
}

/// Mitsuba 3's other BSDFs with their defaults (each checked against Mitsuba itself with
/// `mi.traverse`: plastic's η = 1.49 / 1.000277 = 1.48959, roughdielectric's η = 1.50418,
/// Beckmann α = 0.1), and a named conductor.
#[test]
fn mitsuba3_materials_and_their_defaults() {
    let xml = r#"<scene version="3.0.0">
        <shape type="sphere"><bsdf type="plastic"/></shape>
        <shape type="sphere"><bsdf type="roughplastic"><string name="distribution" value="ggx"/>
            <float name="alpha" value="0.3"/><boolean name="nonlinear" value="true"/>
            <boolean name="sample_visible" value="false"/></bsdf></shape>
        <shape type="sphere"><bsdf type="roughdielectric"/></shape>
        <shape type="sphere"><bsdf type="thindielectric"><string name="int_ior" value="water"/></bsdf></shape>
        <shape type="sphere"><bsdf type="conductor"><string name="material" value="Au"/></bsdf></shape>
        <shape type="sphere"><bsdf type="mask"><bsdf type="blendbsdf">
            <float name="weight" value="0.25"/><bsdf type="diffuse"/><bsdf type="plastic"/>
        </bsdf></bsdf></shape>
    </scene>"#;
    let d = parse(xml, &[]).unwrap();
    let (air, one, half) = (1.000277, Vec3::ONE, Vec3::splat(0.5));
    assert_eq!(
        d.shapes[0].bsdf,
        BsdfDesc::Plastic {
            int_ior: mcrt_render::description::Ior::new(1.49).unwrap(),
            ext_ior: mcrt_render::description::Ior::new(air).unwrap(),
            diffuse_reflectance: mcrt_render::description::Colour::new(half).unwrap(),
            specular_reflectance: mcrt_render::description::Colour::new(one).unwrap(),
            nonlinear: false,
        }
    );
    assert_eq!(
        d.shapes[1].bsdf,
        BsdfDesc::RoughPlastic {
            microfacet: Microfacet {
                sample_visible: false,
                ..Microfacet::new(
                    MicrofacetKind::Ggx,
                    Roughness::new(0.3).expect("a roughness")
                )
            },
            int_ior: mcrt_render::description::Ior::new(1.49).unwrap(),
            ext_ior: mcrt_render::description::Ior::new(air).unwrap(),
            diffuse_reflectance: mcrt_render::description::Colour::new(half).unwrap(),
            specular_reflectance: mcrt_render::description::Colour::new(one).unwrap(),
            nonlinear: true,
        }
    );
    assert_eq!(
        d.shapes[2].bsdf,
        BsdfDesc::RoughDielectric {
            microfacet: Microfacet::new(MicrofacetKind::Beckmann, Roughness::DEFAULT),
            int_ior: mcrt_render::description::Ior::new(1.5046).unwrap(),
            ext_ior: mcrt_render::description::Ior::new(air).unwrap(),
            specular_reflectance: mcrt_render::description::Colour::new(one).unwrap(),
            specular_transmittance: mcrt_render::description::Colour::new(one).unwrap(),
        }
    );
    assert_eq!(
        d.shapes[3].bsdf,
        BsdfDesc::ThinDielectric {
            int_ior: mcrt_render::description::Ior::new(1.333).unwrap(),
            ext_ior: mcrt_render::description::Ior::new(air).unwrap(),
            specular_reflectance: mcrt_render::description::Colour::new(one).unwrap(),
            specular_transmittance: mcrt_render::description::Colour::new(one).unwrap(),
        }
    );
    let BsdfDesc::Conductor {
        fresnel: ConductorFresnel::Complex { eta, k },
        ..
    } = d.shapes[4].bsdf
    else {
        panic!("{:?}", d.shapes[4].bsdf)
    };
    let want = (
        Vec3::new(0.143036, 0.375307, 1.44205),
        Vec3::new(3.983, 2.38556, 1.60336),
    );
    let err = (eta.get() - want.0)
        .abs()
        .max((k.get() - want.1).abs())
        .max_element();
    assert!(err.is_finite() && err < 1e-5, "{eta} {k}");
}

#[test]
fn cornell_box_direct_lighting_define() {
    let mut parsed = load(CORNELL, &[("max_depth", "2")]);
    parsed.source = None;
    parsed.origins = Default::default();
    assert_eq!(parsed, cornell_box_with(64, 256, 2));
}

#[test]
fn obj_shapes_resolve_against_the_scene_folder_and_read() {
    let dir = std::env::temp_dir().join(format!("mcrt-loader-obj-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("meshes")).unwrap();
    let obj = "# a quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1 4//1\n";
    std::fs::write(dir.join("meshes/quad.obj"), obj).unwrap();
    let scene = r#"<scene version="3.0.0"><shape type="obj">
        <string name="filename" value="meshes/quad.obj"/>
        <boolean name="face_normals" value="true"/>
    </shape></scene>"#;
    std::fs::write(dir.join("scene.xml"), scene).unwrap();
    let d = load_scene(&dir.join("scene.xml"), &[]).unwrap();
    let ShapeKind::Obj {
        filename,
        face_normals,
        ..
    } = &d.shapes[0].kind
    else {
        panic!("{:?}", d.shapes[0].kind)
    };
    assert!(*face_normals);
    assert_eq!(filename, &dir.join("meshes/quad.obj"));
    let mesh = mcrt_render::mesh_file::obj::read_obj(filename).unwrap();
    assert_eq!(mesh.indices, vec![[0, 1, 2], [0, 2, 3]]);
    assert_eq!(mesh.normals, vec![Vec3::Z; 4]);
    let missing = mcrt_render::mesh_file::obj::read_obj(&dir.join("nope.obj")).unwrap_err();
    assert!(missing.to_string().contains("nope.obj"), "{missing}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn mesh_scene_with_include_spectra_tent_and_crop() {
    let d = load("tests/data/meshes.xml", &[]);
    // Six shapes from the included room, then four mesh files.
    assert_eq!(d.shapes.len(), 10);
    assert_eq!(d.shapes[0].id.as_deref(), Some("light"));
    assert!(matches!(
        &d.shapes[7].kind,
        ShapeKind::Serialized {
            shape_index: 1,
            face_normals: false,
            ..
        }
    ));
    assert!(matches!(
        &d.shapes[8].kind,
        ShapeKind::Ply {
            face_normals: true,
            ..
        }
    ));
    // Spectra as Mitsuba 3.9.1 reads them back (`mi.traverse`, scalar_rgb): the green
    // wall's reflectance and the light's radiance.
    let close = |a: Vec3, b: [f32; 3]| {
        let e = (a - Vec3::from(b)).abs().max_element();
        e.is_finite() && e < 1e-4
    };
    let BsdfDesc::Diffuse { reflectance } = d.shapes[4].bsdf else {
        panic!("{:?}", d.shapes[4].bsdf)
    };
    assert!(
        close(reflectance.get(), [0.0353889, 0.404299, 0.107332]),
        "{reflectance}"
    );
    let radiance = d.shapes[0].emitter.expect("the light").radiance;
    assert!(
        close(radiance.get(), [20.383, 13.091, 8.59723]),
        "{radiance}"
    );
    let t = load("tests/data/tent-crop.xml", &[]);
    let film = t.sensor.film;
    assert_eq!(film.filter, FilterDesc::Tent { radius: 1.5 });
    let w = film.window();
    assert_eq!(
        (w.offset_x, w.offset_y, w.width, w.height),
        (24, 40, 80, 64)
    );
    // Mitsuba's defaults: a tent of radius 1; a crop window reaching to the film's edge.
    let x = parse_scene(
        r#"<scene version="3.0.0"><sensor type="perspective"><film type="hdrfilm">
           <integer name="width" value="10"/><integer name="crop_offset_x" value="4"/>
           <rfilter type="tent"/></film></sensor></scene>"#,
        None,
        &[],
    )
    .unwrap();
    let f = x.sensor.film;
    assert_eq!(f.filter, FilterDesc::Tent { radius: 1.0 });
    assert_eq!((f.window().width, f.window().height), (6, 576));
}

/// Spot and directional emitters and the thinlens sensor with Mitsuba 3's defaults (checked
/// against Mitsuba 3.9.1 itself: a spot's cutoff 20° and beam ¾ of the cutoff, a directional
/// light travelling along +z of its `to_world`, a thin lens focused at 10⁴ whose
/// `aperture_radius` is required), and the parameters given.
#[test]
fn spot_directional_and_thinlens_with_their_defaults() {
    let xml = r#"<scene version="3.0.0">
        <sensor type="thinlens"><float name="aperture_radius" value="0.2"/></sensor>
        <emitter type="spot"/>
        <emitter type="spot"><float name="cutoff_angle" value="40"/></emitter>
        <emitter type="spot"><float name="cutoff_angle" value="40"/><float name="beam_width" value="5"/>
            <rgb name="intensity" value="1, 2, 3"/>
            <transform name="to_world"><translate x="1"/></transform></emitter>
        <emitter type="directional"/>
        <emitter type="directional"><vector name="direction" x="0" y="-3" z="0"/>
            <rgb name="irradiance" value="2"/></emitter>
        <emitter type="directional"><transform name="to_world"><rotate x="1" angle="90"/></transform></emitter>
    </scene>"#;
    let d = parse(xml, &[]).unwrap();
    assert_eq!(
        d.sensor.lens,
        Some(ThinLensDesc {
            aperture_radius: 0.2,
            focus_distance: 1e4
        })
    );
    let spot = |i: usize| match &*d.emitters[i] {
        EmitterDesc::Spot {
            intensity,
            cutoff_angle,
            beam_width,
            to_world,
        } => (intensity.get(), *cutoff_angle, *beam_width, *to_world),
        e => panic!("{e:?}"),
    };
    assert_eq!(spot(0), (Vec3::ONE, 20.0, 15.0, Mat4::IDENTITY));
    assert_eq!((spot(1).1, spot(1).2), (40.0, 30.0));
    let (i, c, b, m) = spot(2);
    assert_eq!((i, c, b), (Vec3::new(1.0, 2.0, 3.0), 40.0, 5.0));
    assert_eq!(m.transform_point3(Vec3::ZERO), Vec3::X);
    let directional = |i: usize| match &*d.emitters[i] {
        EmitterDesc::Directional {
            irradiance,
            direction,
        } => (irradiance.get(), *direction),
        e => panic!("{e:?}"),
    };
    assert_eq!(directional(3), (Vec3::ONE, Vec3::Z));
    assert_eq!(directional(4), (Vec3::splat(2.0), Vec3::NEG_Y));
    // Rotating +z by 90° about x gives −y.
    let (_, dir) = directional(5);
    assert!((dir - Vec3::NEG_Y).length() < 1e-6, "{dir}");
    // A perspective sensor has no lens.
    let p = parse(
        r#"<scene version="3.0.0"><sensor type="perspective"/></scene>"#,
        &[],
    )
    .unwrap();
    assert_eq!(p.sensor.lens, None);
}

/// Without `fov`, Mitsuba 3's sensors take `focal_length` (default 50 mm on a 36 × 24 mm
/// frame, a diagonal field of view); `fov_axis="diagonal"` is read too. The horizontal
/// fields of view Mitsuba 3.9.1 reports (`x_fov`) for the same elements.
#[test]
fn field_of_view_from_focal_length_and_diagonal_as_mitsuba() {
    let cases = [
        ("perspective", 768, 576, "", 38.1848),
        ("perspective", 64, 80, "", 30.2495),
        (
            "thinlens",
            4,
            4,
            r#"<float name="aperture_radius" value="0.1"/>"#,
            34.0221,
        ),
        (
            "perspective",
            100,
            100,
            r#"<string name="focal_length" value="35mm"/>"#,
            47.2163,
        ),
        (
            "perspective",
            64,
            80,
            r#"<string name="focal_length" value="20"/>"#,
            68.0947,
        ),
        (
            "perspective",
            64,
            80,
            r#"<float name="fov" value="30"/><string name="fov_axis" value="diagonal"/>"#,
            19.0049,
        ),
    ];
    for (ty, w, h, params, want) in cases {
        let xml = format!(
            r#"<scene version="3.0.0"><sensor type="{ty}">{params}<film type="hdrfilm">
            <integer name="width" value="{w}"/><integer name="height" value="{h}"/></film>
            </sensor></scene>"#
        );
        let s = parse(&xml, &[]).unwrap().sensor;
        assert_eq!(s.fov_axis, FovAxis::X, "{params}");
        assert!(
            s.fov.is_finite() && (s.fov - want).abs() < 1e-3,
            "{ty} {w}x{h} {params}: fov {} vs Mitsuba's {want}",
            s.fov
        );
    }
    let both = r#"<scene version="3.0.0"><sensor type="perspective"><float name="fov" value="30"/>
        <string name="focal_length" value="35mm"/></sensor></scene>"#;
    let e = parse(both, &[]).unwrap_err().to_string();
    assert!(e.contains("focal_length cannot both be given"), "{e}");
}

/// Mitsuba's `multijitter` maps to the correlated multi-jittered sampler; `jitter = false`
/// (centred values), which no sampler here renders, is an error that names the line.
#[test]
fn multijitter_maps_to_the_cmj_sampler() {
    let scene = |sampler: &str| {
        format!(
            "<scene version=\"3.0.0\"><sensor type=\"perspective\">\n{sampler}\n</sensor></scene>"
        )
    };
    let xml =
        scene(r#"<sampler type="multijitter"><integer name="sample_count" value="5"/></sampler>"#);
    let d = parse(&xml, &[]).unwrap();
    assert_eq!(d.sensor.sampler.kind, SamplerKind::MultiJitter);
    assert_eq!(d.sensor.sampler.sample_count, 5);
    let xml =
        scene(r#"<sampler type="multijitter"><boolean name="jitter" value="false"/></sampler>"#);
    let e = parse(&xml, &[]).unwrap_err().to_string();
    assert!(
        e.contains("inline.xml") && e.contains("line 2") && e.contains("jitter"),
        "{e}"
    );
}

/// Mitsuba's `orthogonal` (strength 2) loads and renders with the correlated multi-jittered
/// sampler at Mitsuba's count (the square of a prime: 64 → 121); another strength is an
/// error that names the line.
#[test]
fn orthogonal_maps_to_the_cmj_sampler_with_a_prime_square_count() {
    let scene = |sampler: &str| {
        format!(
            "<scene version=\"3.0.0\"><sensor type=\"perspective\">\n{sampler}\n</sensor></scene>"
        )
    };
    let xml = scene(
        r#"<sampler type="orthogonal"><integer name="sample_count" value="64"/>
           <integer name="strength" value="2"/><boolean name="jitter" value="true"/></sampler>"#,
    );
    let d = parse(&xml, &[]).unwrap();
    assert_eq!(d.sensor.sampler.kind, SamplerKind::Orthogonal);
    let s = mcrt::sampling::sampler::AnySampler::by_name("orthogonal", 64, 0)
        .unwrap()
        .unwrap();
    assert_eq!(mcrt::sampling::sampler::Sampler::samples_per_pixel(&s), 121);
    let xml = scene(
        r#"<sampler type="orthogonal">
           <integer name="strength" value="3"/></sampler>"#,
    );
    let e = parse(&xml, &[]).unwrap_err().to_string();
    assert!(
        e.contains("inline.xml") && e.contains("line 3") && e.contains("strength 3"),
        "{e}"
    );
}

/// A shape's `<ref>` may name an area emitter declared by id, before or after the shape (as
/// Mitsuba 3 reads `variants_cbox_spectral.xml`); the declaration alone adds no light, and a
/// `<ref>` to a BSDF beside it still works.
#[test]
fn a_shape_may_refer_to_an_area_emitter_declared_by_id() {
    let d = parse(
        r#"<scene version="3.0.0">
            <bsdf type="diffuse" id="white"/>
            <shape type="rectangle"><ref id="light"/><ref id="white"/></shape>
            <emitter type="area" id="light"><rgb name="radiance" value="2, 3, 4"/></emitter>
            <emitter type="area" id="unused"><rgb name="radiance" value="1"/></emitter>
            <shape type="disk"><ref id="light"/></shape>
        </scene>"#,
        &[],
    )
    .expect("loads");
    assert_eq!(d.shapes.len(), 2);
    assert!(d.emitters.is_empty(), "{:?}", d.emitters);
    for s in &d.shapes {
        let e = s.emitter.as_ref().expect("the shape emits");
        assert_eq!(e.radiance.get(), Vec3::new(2.0, 3.0, 4.0));
    }
    assert!(matches!(d.shapes[0].bsdf, BsdfDesc::Diffuse { .. }));
    // A bad declared emitter is an error even where no shape uses it.
    let e = parse(
        r#"<scene version="3.0.0">
            <emitter type="area" id="bad"><rgb name="radiance" value="-1"/></emitter>
        </scene>"#,
        &[],
    )
    .unwrap_err();
    assert_eq!(e.line, Some(2), "{e}");
}
