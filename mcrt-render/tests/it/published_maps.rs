//! Issue 25's shading-frame adapters against Mitsuba 3.9.1's references
//! (`tests/data/published/maps/*.exr`, 4096 spp, box filter; `tests/data/REFERENCES.md`,
//! "Normal and bump maps"): `normalmap` (a turned floor under `twosided`, a sphere),
//! `bumpmap` (a bilinear height field on a turned floor and on a sphere, its normal from
//! the gradient and `dp/du`, `dp/dv`), and textured roughness (`alpha` on `roughconductor`
//! and `roughdielectric`, a textured `alpha_u` with a constant `alpha_v`). Each scene is
//! 96×96, rendered here at 64 spp with lights sampled by area as Mitsuba samples them (a
//! few seconds of CPU each). Rendered without the maps (flat normals, no bumps, a constant
//! α = 0.3), each scene misses its reference by 10–130% in several blocks, so the tests
//! see the features.
//!
//! As `tests/it/reference_match.rs` does: no NaN or infinite pixel; a z-test on 16×16 block
//! means (blocks brighter than 5% of the image mean) with our per-pixel variance plus the
//! reference's (ours × spp / 4096), Šidák-corrected over blocks and channels to the
//! suite's per-test α (`tests/it/common/suite.rs`), each block allowed 1% beyond the noise (8-bit textures
//! interpolated in single precision by both renderers); and the image mean within 1% of
//! the reference plus 3 standard errors. Fixed seed. One statistical test per scene.

use crate::common;

use common::published;

/// The file `name` of `tests/data/published/maps/`.
fn data(name: &str) -> std::path::PathBuf {
    published::data("maps", name)
}

/// Renders `scene` and compares it with `reference` (`common/published.rs`); `min_blocks`
/// bright blocks at least must be compared.
fn check(scene: &str, reference: &str, min_blocks: usize) {
    published::check("maps", scene, reference, min_blocks);
}

/// `normalmap`: tangent-space domes on a floor turned about its normal (its frame built on
/// `dp/du`, under `twosided`) and on a sphere.
#[test]
fn normal_maps_match_mitsuba() {
    check("normalmap.xml", "normalmap.exr", 25);
}

/// `bumpmap`: a grey height field at scale 0.25 on a turned floor (over `diffuse`, under
/// `twosided`) and tiled on a sphere (over `roughconductor`).
#[test]
fn bump_maps_match_mitsuba() {
    check("bumpmap.xml", "bumpmap.exr", 25);
}

/// Textured roughness: `alpha` from a bitmap on a `roughconductor` floor and a
/// `roughdielectric` sphere, and a textured `alpha_u` with a constant `alpha_v`.
#[test]
fn textured_roughness_matches_mitsuba() {
    check("rough-texture.xml", "rough-texture.exr", 25);
}

/// Parses `body` inside a scene whose file sits beside the maps' textures; the error's
/// line (the scene's start tag is line 1), the element it names and words of its message.
fn refused(body: &str, line: u32, element: &str, words: &str) {
    let xml = format!("<scene version=\"3.0.0\">\n{body}\n</scene>");
    let file = data("refusals.xml");
    let e = match mcrt_render::loader::parse_scene(&xml, Some(&file), &[]) {
        Ok(_) => panic!("expected an error for {body}"),
        Err(e) => e,
    };
    let msg = e.to_string();
    assert_eq!(e.line, Some(line), "{msg}");
    assert!(
        msg.contains("refusals.xml") && msg.contains(element),
        "{msg}"
    );
    assert!(msg.contains(words), "{msg}");
}

/// The maps' and textured roughness's refusals name file, line and element, and say what
/// is wrong (Mitsuba 3.9.1 refuses the same, at load or when rendering).
#[test]
fn map_refusals_are_located() {
    let bitmap = |name: &str| {
        format!(
            "<texture type=\"bitmap\" name=\"{name}\"><string name=\"filename\" \
             value=\"domes.png\"/></texture>"
        )
    };
    let cases = [
        (
            "<bsdf type=\"normalmap\">\n<bsdf type=\"diffuse\"/></bsdf>".to_string(),
            2,
            "<bsdf type=\"normalmap\">",
            "needs a texture named \"normalmap\"",
        ),
        (
            format!("<bsdf type=\"normalmap\">\n{}<bsdf type=\"diffuse\"/></bsdf>", bitmap("bump")),
            3,
            "<texture type=\"bitmap\" name=\"bump\">",
            "a texture named \"bump\" in a normalmap",
        ),
        (
            "<bsdf type=\"normalmap\">\n<rgb name=\"normalmap\" value=\"0.5, 0.5, 1\"/>\
             <bsdf type=\"diffuse\"/></bsdf>"
                .to_string(),
            3,
            "<rgb name=\"normalmap\">",
            "normalmap",
        ),
        (
            format!(
                "<bsdf type=\"normalmap\">{}\n<bsdf type=\"diffuse\"/><bsdf type=\"diffuse\"/></bsdf>",
                bitmap("normalmap")
            ),
            2,
            "<bsdf type=\"normalmap\">",
            "exactly one nested BSDF",
        ),
        (
            "<bsdf type=\"bumpmap\">\n<texture type=\"checkerboard\"/><bsdf type=\"diffuse\"/></bsdf>"
                .to_string(),
            3,
            "<texture type=\"checkerboard\">",
            "must be a bitmap",
        ),
        (
            format!(
                "<bsdf type=\"bumpmap\">{}\n{}<bsdf type=\"diffuse\"/></bsdf>",
                bitmap("a"),
                bitmap("b")
            ),
            3,
            "<texture type=\"bitmap\" name=\"b\">",
            "a second texture in a bumpmap",
        ),
        (
            "<bsdf type=\"bumpmap\">\n<bsdf type=\"diffuse\"/></bsdf>".to_string(),
            2,
            "<bsdf type=\"bumpmap\">",
            "bumpmap needs one texture (the height field), found none",
        ),
        (
            format!(
                "<bsdf type=\"roughconductor\">{}\n<float name=\"alpha_u\" value=\"0.1\"/></bsdf>",
                bitmap("alpha")
            ),
            3,
            "<float name=\"alpha_u\">",
            "give either alpha or both alpha_u and alpha_v",
        ),
    ];
    for (body, line, element, words) in cases {
        refused(&body, line, element, words);
    }
    // Accepted: a textured alpha_v with a number for alpha_u, on roughdielectric.
    let xml = format!(
        "<scene version=\"3.0.0\"><bsdf type=\"roughdielectric\" id=\"glass\">{}\
         <float name=\"alpha_u\" value=\"0.1\"/></bsdf></scene>",
        bitmap("alpha_v")
    );
    mcrt_render::loader::parse_scene(&xml, Some(&data("accepted.xml")), &[])
        .expect("a textured alpha_v with a constant alpha_u loads");
}
