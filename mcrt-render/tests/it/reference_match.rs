//! The renderer against Mitsuba 3's references (`tests/data/*.exr`, 16384 or 4096 spp, box
//! filter) on the same scene files, at full resolution and low spp (64 for the Cornell box,
//! 128 for the 128×128 material scenes, 32 otherwise) so that it fits CI (about 30 s of
//! CPU).
//! The material scenes are the Cornell box with Mitsuba 3's other BSDFs: rough and thin
//! glass (`cornell-box-glass.xml`), smooth and rough plastic (`cornell-box-plastic.xml`),
//! named conductors (`cornell-box-metals.xml`), a blend and a mask
//! (`cornell-box-blend-mask.xml`), and `principled` (`cornell-box-principled.xml`).
//!
//! For each scene: no NaN or infinite pixel; a z-test on 16×16 block means (for the
//! material scenes 32×32, each allowed 1% beyond the noise: see `check_material_scene`; blocks brighter
//! than 5% of the image mean) with the render's own per-pixel variance plus the reference's
//! (lights are sampled as Mitsuba does, so that is ours × spp / reference spp),
//! Šidák-corrected over blocks and channels to the suite's per-test α (each test one of the
//! shared budget of `tests/it/common/suite.rs`: α = 0.01 over `N_TESTS`); and a bias bound on the image mean: within
//! 1% of the reference plus 3 standard errors. Fixed seed.
//!
//! The strict figures at 1024 spp (every 32×32 block within 3%, image mean within 1%; about
//! 25 minutes, too slow for CI) are a check a person runs: `cargo run --release --example
//! reference_figures -- --spp 1024` prints them and exits non-zero if a bound is exceeded;
//! they are recorded in docs/renderer.md.

use mcrt::glam::Vec3;
use mcrt_render::description::SceneDescription;
use mcrt_render::film::{compare_blocks, read_exr};
use mcrt_render::render::Renderer;
use std::path::PathBuf;
use std::sync::atomic::AtomicBool;

use crate::common;

use common::published::Comparison;

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests")
        .join("data")
        .join(name)
}

fn load(name: &str, defines: &[(&str, &str)]) -> SceneDescription {
    let d: Vec<(String, String)> = defines
        .iter()
        .map(|(k, v)| (k.to_string(), v.to_string()))
        .collect();
    mcrt_render::loader::load_scene(&data(name), &d).expect("scene loads")
}

struct Outcome {
    worst_z: f64,
    z_critical: f64,
    worst_block: f64,
    mean_ratio: Vec3,
    mean_se_rel: Vec3,
}

/// Samples per pixel of each reference (tests/data/REFERENCES.md).
fn reference_spp(reference: &str) -> u32 {
    match reference {
        "cornell-box-direct.exr"
        | "meshes.exr"
        | "tent-crop.exr"
        | "cornell-box-principled.exr" => 4096,
        _ => 16384,
    }
}

/// How blocks are compared: their size, the fewest bright blocks the image must have, and
/// the bias each block may show beyond the noise, relative to the reference.
#[derive(Clone, Copy)]
struct Blocks {
    size: u32,
    min_count: usize,
    allowance: f64,
}

fn run(
    scene: &str,
    defines: &[(&str, &str)],
    reference: &str,
    spp: u32,
    blocks: Blocks,
) -> Outcome {
    let Blocks {
        size: block,
        min_count: min_blocks,
        allowance,
    } = blocks;
    let desc = load(scene, defines);
    // Lights sampled as Mitsuba samples them (rectangles by area, spheres by cone), so the
    // reference's own variance is ours scaled by spp / reference spp. (Solid-angle sampling
    // has up to 300× less variance near the Cornell box's light; the reference's noise
    // would then dominate the test without being counted.)
    let opts = Comparison::new(scene, data(reference), spp, reference_spp(reference), 2024).opts;
    let out = Renderer::new(&desc, &opts)
        .expect("scene builds")
        .render(&|_, _| {}, &AtomicBool::new(false));
    assert_eq!(out.nonfinite_samples, 0, "{scene}: non-finite samples");
    let (w, h) = (out.film.width(), out.film.height());
    let (rw, rh, rf) = read_exr(&data(reference)).expect("reference reads");
    assert_eq!((w, h), (rw, rh), "{scene}: size differs from the reference");
    let img = out.image();
    let var = out.film.variance();
    let scale = spp as f32 / reference_spp(reference) as f32;
    let ref_var: Vec<Vec3> = var.iter().map(|v| *v * scale).collect();
    // One test of the suite's budget (`tests/it/common/suite.rs`), Šidák over blocks and channels.
    let alpha = common::per_test_alpha();
    let r = compare_blocks(&img, &var, &rf, Some(&ref_var), w, h, block, 0.05, alpha);
    assert_eq!(r.non_finite, 0, "{scene}: NaN or infinite pixels");
    assert!(
        r.blocks >= min_blocks,
        "{scene}: only {} blocks compared",
        r.blocks
    );
    let worst_z = if allowance > 0.0 {
        common::blocks::worst_z_beyond(&img, &var, &rf, &ref_var, w, h, block, allowance)
    } else {
        r.worst_z
    };
    let n = img.len() as f32;
    let ref_mean = rf.iter().copied().sum::<Vec3>() / n;
    let var_mean = var.iter().copied().sum::<Vec3>() / (n * n);
    let se = Vec3::new(var_mean.x.sqrt(), var_mean.y.sqrt(), var_mean.z.sqrt()) / ref_mean;
    Outcome {
        worst_z,
        z_critical: r.z_critical,
        worst_block: r.worst_relative,
        mean_ratio: r.mean_ratio,
        mean_se_rel: se,
    }
}

fn check_low_spp(scene: &str, defines: &[(&str, &str)], reference: &str, spp: u32) {
    let blocks = Blocks {
        size: 16,
        min_count: 21,
        allowance: 0.0,
    };
    check_blocks(scene, defines, reference, spp, blocks);
}

/// The block test for the 128×128 material scenes, whose specular parts cast caustics that
/// a path tracer finds only by BSDF sampling: their rare, bright samples skew block means
/// at test sample counts (below the mean, mostly, with a variance estimate too small), so
/// that a pure z-test fails for many seeds even on 32×32 blocks at 256 spp. So 32×32 blocks
/// at 128 spp, each allowed 1% beyond the noise, as the bidirectional tests allow
/// (`tests/it/bidirectional.rs`): a bias above about 3% of a block still fails (σ of a block
/// is about 0.4%), and `tests/it/bsdf_mitsuba_values.rs` checks the materials themselves to
/// 10⁻³. (Over seeds 1, 2, 3 and 2024, the worst block is then at most 1.5 σ beyond the
/// allowance.)
fn check_material_scene(scene: &str, reference: &str) {
    let blocks = Blocks {
        size: 32,
        min_count: 12,
        allowance: 0.01,
    };
    check_blocks(scene, &[], reference, 128, blocks);
}

fn check_blocks(scene: &str, defines: &[(&str, &str)], reference: &str, spp: u32, blocks: Blocks) {
    let o = run(scene, defines, reference, spp, blocks);
    let block = blocks.size;
    println!(
        "{scene} {defines:?}: worst |z| {:.2} (critical {:.2}), worst {block}×{block} block {:.1}%, mean ratio {}",
        o.worst_z,
        o.z_critical,
        100.0 * o.worst_block,
        o.mean_ratio
    );
    assert!(
        o.worst_z.is_finite() && o.worst_z <= o.z_critical,
        "{scene}: block z-test fails: worst |z| {:.2} > {:.2}",
        o.worst_z,
        o.z_critical
    );
    for c in 0..3 {
        let dev = (o.mean_ratio[c] - 1.0).abs();
        assert!(
            dev.is_finite() && dev <= 0.01 + 3.0 * o.mean_se_rel[c],
            "{scene}: image mean ratio {} (relative standard error {})",
            o.mean_ratio,
            o.mean_se_rel
        );
    }
}

#[test]
fn cornell_box_matches_mitsuba() {
    check_low_spp("cornell-box.xml", &[], "cornell-box.exr", 64);
}

#[test]
fn cornell_box_direct_matches_mitsuba() {
    check_low_spp(
        "cornell-box.xml",
        &[("max_depth", "2")],
        "cornell-box-direct.exr",
        32,
    );
}

#[test]
fn veach_mis_matches_mitsuba() {
    check_low_spp("veach-mis.xml", &[], "veach-mis.exr", 32);
}

#[test]
fn rough_and_thin_glass_match_mitsuba() {
    check_material_scene("cornell-box-glass.xml", "cornell-box-glass.exr");
}

#[test]
fn smooth_and_rough_plastic_match_mitsuba() {
    check_material_scene("cornell-box-plastic.xml", "cornell-box-plastic.exr");
}

#[test]
fn named_conductors_match_mitsuba() {
    check_material_scene("cornell-box-metals.xml", "cornell-box-metals.exr");
}

#[test]
fn blend_and_mask_match_mitsuba() {
    check_material_scene("cornell-box-blend-mask.xml", "cornell-box-blend-mask.exr");
}

/// `principled`: a gold metal box, a clearcoated blue sphere with sheen, a back wall with
/// tinted specular and a rough, flat floor with sheen (reference at 4096 spp).
#[test]
fn principled_matches_mitsuba() {
    check_material_scene("cornell-box-principled.xml", "cornell-box-principled.exr");
}

/// Textures (`textures.xml`): a checkerboard floor through a top-level `<texture>` and
/// `<ref name>`, a PNG wall tiled by `to_uv`, an EXR box (nearest, mirror), a JPEG sphere
/// (rough plastic, rotated), a checkerboard blend weight. On 16×16 blocks (64, so that a
/// texture in the wrong place or orientation shows; each allowed 1% as the material
/// scenes).
#[test]
fn textures_match_mitsuba() {
    let blocks = Blocks {
        size: 16,
        min_count: 48,
        allowance: 0.01,
    };
    check_blocks("textures.xml", &[], "textures.exr", 128, blocks);
}

/// PLY (binary little and big endian, ASCII) and `serialized` meshes, smooth shading from
/// the file's normals and from computed ones, face normals, `<include>` and spectral
/// colours (reference: `scripts/make_mesh_data.py --render`).
#[test]
fn mesh_files_match_mitsuba() {
    check_low_spp("meshes.xml", &[], "meshes.exr", 64);
}

/// The tent filter and a crop window (80 × 64 of 128 × 128): 8×8 blocks.
#[test]
fn tent_filter_and_crop_window_match_mitsuba() {
    check_blocks(
        "tent-crop.xml",
        &[],
        "tent-crop.exr",
        64,
        Blocks {
            size: 8,
            min_count: 21,
            allowance: 0.0,
        },
    );
}

/// A spot light (cutoff 30°, beam 18°, aimed by a `lookat`) and a directional light
/// (`direction`) in an open box: the falloff cone and hard shadows (issue 16).
#[test]
fn spot_and_directional_lights_match_mitsuba() {
    check_low_spp("spot-directional.xml", &[], "spot-directional.exr", 64);
}

/// A thin-lens sensor (aperture 0.12, focus 4.2) over spheres lit by an environment map
/// turned by a `to_world` of two rotations (issue 16).
#[test]
fn thin_lens_and_rotated_envmap_match_mitsuba() {
    check_low_spp("thinlens.xml", &[], "thinlens.exr", 64);
}
