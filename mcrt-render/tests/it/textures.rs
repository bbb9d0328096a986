//! Textures as scene files give them: the committed images decode to the values Mitsuba 3.9.1
//! reads from them, the loader builds what the XML says with Mitsuba's defaults, and a
//! textured material renders the texture where Mitsuba puts it (the whole scene against
//! Mitsuba's image is `tests/it/reference_match.rs`, `textures_match_mitsuba`).

use mcrt::glam::{Vec2, Vec3};
use mcrt_render::description::{BsdfDesc, SceneDescription, Texture, TextureParam};
use mcrt_render::loader::parse_scene;
use mcrt_render::texture::{read_image, FilterType, WrapMode};
use std::path::{Path, PathBuf};
use std::sync::Arc;

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name)
}

/// A pixel's `(x, y)` and its RGB value.
type Pixel = ((usize, usize), [f32; 3]);

fn close(a: Vec3, b: Vec3, tol: f32) -> bool {
    a.is_finite() && (a - b).abs().max_element() <= tol
}

/// Pixels of the three images as Mitsuba 3.9.1 decodes them (nearest lookups at pixel
/// centres, `scripts/make_texture_data.py`): PNG and JPEG through the sRGB curve, EXR as
/// stored. The JPEG decoders may differ by an IDCT rounding step (1/255 before the curve).
#[test]
fn images_decode_as_mitsuba_reads_them() {
    let cases: [(&str, f32, [Pixel; 4]); 3] = [
        (
            "grid.png",
            1e-5,
            [
                ((0, 0), [0.791_298, 0.0, 0.0]),
                ((3, 5), [0.479_32, 0.057_805, 0.027_321]),
                ((15, 15), [0.0, 0.603_828, 0.791_298]),
                ((7, 2), [0.887_923, 0.887_923, 0.887_923]),
            ],
        ),
        (
            "rings.jpg",
            0.01,
            [
                ((0, 0), [0.010_96, 0.291_771, 0.371_238]),
                ((3, 5), [0.434_154, 0.332_451, 0.114_435]),
                ((31, 31), [0.012_287, 0.287_441, 0.366_253]),
                ((7, 2), [0.111_933, 0.226_966, 0.119_539]),
            ],
        ),
        (
            "tiles.exr",
            1e-6,
            [
                ((0, 0), [0.85, 0.3, 0.05]),
                ((3, 5), [0.3, 0.3, 0.8]),
                ((7, 7), [0.85, 0.3, 0.05]),
                ((7, 2), [0.3, 0.3, 0.8]),
            ],
        ),
    ];
    for (file, tol, pixels) in cases {
        let im = read_image(&data(&format!("textures/{file}")), false).unwrap();
        for ((x, y), want) in pixels {
            let got = im.pixels()[y * im.width() as usize + x];
            assert!(
                close(got, Vec3::from(want), tol),
                "{file} ({x}, {y}): {got} vs {want:?}"
            );
        }
    }
    // Mitsuba's means: 0.300187 (PNG), 0.281020 (JPEG), 0.399873 (EXR).
    for (file, mean, tol) in [
        ("grid.png", 0.300_187, 1e-5),
        ("rings.jpg", 0.281_020, 2e-3),
        ("tiles.exr", 0.399_873, 1e-5),
    ] {
        let m = read_image(&data(&format!("textures/{file}")), false)
            .unwrap()
            .mean_luminance();
        assert!(m.is_finite() && (m - mean).abs() <= tol, "{file}: mean {m}");
    }
    // raw: the stored 8-bit values, no curve (pixel (0, 0) of grid.png is 230/255 red).
    let raw = read_image(&data("textures/grid.png"), true).unwrap();
    assert!(
        close(raw.pixels()[0], Vec3::new(230.0 / 255.0, 0.0, 0.0), 1e-6),
        "{}",
        raw.pixels()[0]
    );
}

fn load(xml: &str) -> SceneDescription {
    parse_scene(xml, Some(&data("textures-test.xml")), &[]).unwrap()
}

/// The textured parameters of shape `i`'s material.
fn textures(d: &SceneDescription, i: usize) -> (&BsdfDesc, &[(TextureParam, Texture)]) {
    match &d.shapes[i].bsdf {
        BsdfDesc::Textured { inner, textures } => (inner, textures),
        other => panic!("not textured: {other:?}"),
    }
}

/// Defaults (bilinear, repeat, identity to_uv, sRGB decode), a texture declared once and
/// referenced twice by name (decoded once), the stand-in mean in the material's parameter,
/// and textured blend weights and opacities.
#[test]
fn loader_builds_textured_materials() {
    let d = load(
        r#"<scene version="3.0.0">
        <texture type="bitmap" id="grid"><string name="filename" value="textures/grid.png"/></texture>
        <shape type="rectangle"><bsdf type="diffuse"><ref name="reflectance" id="grid"/></bsdf></shape>
        <shape type="rectangle"><bsdf type="roughplastic">
            <ref name="diffuse_reflectance" id="grid"/>
            <texture type="checkerboard" name="specular_reflectance"/>
        </bsdf></shape>
        <shape type="rectangle"><bsdf type="blendbsdf">
            <texture type="checkerboard" name="weight"/>
            <bsdf type="diffuse"/><bsdf type="conductor"/>
        </bsdf></shape>
        <shape type="rectangle"><bsdf type="mask">
            <texture type="bitmap" name="opacity">
                <string name="filename" value="textures/tiles.exr"/>
                <string name="filter_type" value="nearest"/>
                <string name="wrap_mode" value="clamp"/>
            </texture>
            <bsdf type="diffuse"/>
        </bsdf></shape>
    </scene>"#,
    );
    let (inner, t) = textures(&d, 0);
    let Texture::Bitmap(b) = &t[0].1 else {
        panic!()
    };
    assert_eq!(t[0].0, TextureParam::Reflectance);
    assert_eq!((b.filter, b.wrap), (FilterType::Bilinear, WrapMode::Repeat));
    assert_eq!(b.to_uv, mcrt::glam::Affine2::IDENTITY);
    let mean = b.image.mean_luminance();
    assert_eq!(
        *inner,
        BsdfDesc::Diffuse {
            reflectance: mcrt_render::description::Colour::new(Vec3::splat(mean)).unwrap()
        }
    );
    let (inner, t2) = textures(&d, 1);
    let Texture::Bitmap(b2) = &t2[0].1 else {
        panic!()
    };
    assert!(
        Arc::ptr_eq(&b.image, &b2.image),
        "one image for both references"
    );
    assert_eq!(
        t2.iter().map(|x| x.0).collect::<Vec<_>>(),
        [
            TextureParam::DiffuseReflectance,
            TextureParam::SpecularReflectance
        ]
    );
    let BsdfDesc::RoughPlastic {
        diffuse_reflectance,
        specular_reflectance,
        ..
    } = inner
    else {
        panic!()
    };
    assert_eq!(
        (diffuse_reflectance.get(), specular_reflectance.get()),
        (Vec3::splat(mean), Vec3::splat(0.3))
    );
    let (inner, t3) = textures(&d, 2);
    assert!(matches!(inner, BsdfDesc::Blend { weight, .. } if (*weight - 0.3).abs() < 1e-6));
    assert_eq!(t3[0].0, TextureParam::Weight);
    let (inner, t4) = textures(&d, 3);
    let Texture::Bitmap(b4) = &t4[0].1 else {
        panic!()
    };
    assert_eq!((b4.filter, b4.wrap), (FilterType::Nearest, WrapMode::Clamp));
    assert!(matches!(inner, BsdfDesc::Mask { opacity, .. } if (*opacity - 0.399_873).abs() < 1e-5));
    // to_uv: scale then translate, as the 2D affine part.
    let d = load(
        r#"<scene version="3.0.0"><shape type="rectangle"><bsdf type="diffuse">
            <texture type="checkerboard" name="reflectance">
                <rgb name="color0" value="1, 0, 0"/><rgb name="color1" value="0, 0, 1"/>
                <transform name="to_uv"><scale x="2" y="4"/><translate x="0.5"/></transform>
            </texture></bsdf></shape></scene>"#,
    );
    let (_, t) = textures(&d, 0);
    let Texture::Checkerboard(c) = &t[0].1 else {
        panic!()
    };
    let p = c.to_uv.transform_point2(Vec2::new(0.25, 0.25));
    assert!(
        p.is_finite() && (p - Vec2::new(1.0, 1.0)).length() < 1e-6,
        "{p}"
    );
    assert_eq!(t[0].1.eval(Vec2::new(0.1, 0.1)), Vec3::Z);
}
