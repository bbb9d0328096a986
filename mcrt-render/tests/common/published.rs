//! The render-and-compare check of the published-style scenes (`published_lights.rs`,
//! `published_maps.rs`): a scene under `tests/data/published/DIR/` rendered at [`SPP`]
//! with lights sampled by area, against its Mitsuba reference at [`REFERENCE_SPP`]. No NaN
//! or infinite pixel; a z-test on [`BLOCK`]² block means (blocks brighter than 5% of the
//! image mean) with our per-pixel variance plus the reference's (ours × SPP/REFERENCE_SPP),
//! Šidák-corrected over blocks and channels to a family-wise α = 0.01, each block allowed
//! [`ALLOWANCE`] beyond the noise; the image mean within 1% of the reference plus 3
//! standard errors. Fixed seed.

use mcrt::glam::Vec3;
use mcrt_render::film::{compare_blocks, read_exr};
use mcrt_render::render::{RenderOptions, Renderer, ShapeSampling};
use std::path::PathBuf;
use std::sync::atomic::AtomicBool;

/// Samples per pixel of the references.
pub const REFERENCE_SPP: u32 = 4096;
/// Samples per pixel of our renders.
pub const SPP: u32 = 64;
/// Side of the compared blocks, in pixels.
pub const BLOCK: u32 = 16;
/// Relative difference a block may have beyond the noise.
pub const ALLOWANCE: f64 = 0.01;

/// The file `name` of `tests/data/published/DIR/`.
pub fn data(dir: &str, name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/published")
        .join(dir)
        .join(name)
}

/// Renders `scene` of `tests/data/published/DIR/` and compares it with `reference` there
/// (module docs); `min_blocks` bright blocks at least must be compared.
pub fn check(dir: &str, scene: &str, reference: &str, min_blocks: usize) {
    let desc = mcrt_render::loader::load_scene(&data(dir, scene), &[]).expect("scene loads");
    let opts = RenderOptions {
        spp: Some(SPP),
        seed: Some(2024),
        light_sampling: ShapeSampling::Area,
        ..RenderOptions::default()
    };
    let out = Renderer::new(&desc, &opts)
        .expect("scene builds")
        .render(&|_, _| {}, &AtomicBool::new(false));
    assert_eq!(out.nonfinite_samples, 0, "{scene}: non-finite samples");
    let (w, h) = (out.film.width(), out.film.height());
    let (rw, rh, rf) = read_exr(&data(dir, reference)).expect("reference reads");
    assert_eq!((w, h), (rw, rh), "{scene}: size differs from the reference");
    let img = out.image();
    let var = out.film.variance();
    let scale = SPP as f32 / REFERENCE_SPP as f32;
    let ref_var: Vec<Vec3> = var.iter().map(|v| *v * scale).collect();
    let r = compare_blocks(&img, &var, &rf, Some(&ref_var), w, h, BLOCK, 0.05, 0.01);
    assert_eq!(r.non_finite, 0, "{scene}: NaN or infinite pixels");
    assert!(
        r.blocks >= min_blocks,
        "{scene}: only {} blocks compared",
        r.blocks
    );
    let worst_z = super::blocks::worst_z_beyond(&img, &var, &rf, &ref_var, w, h, BLOCK, ALLOWANCE);
    println!(
        "{scene}: worst |z| beyond 1% {worst_z:.2} (critical {:.2}), worst block {:.1}%, mean ratio {}",
        r.z_critical,
        100.0 * r.worst_relative,
        r.mean_ratio
    );
    assert!(
        worst_z.is_finite() && worst_z <= r.z_critical,
        "{scene}: block z-test fails: worst |z| {worst_z:.2} > {:.2}",
        r.z_critical
    );
    let n = img.len() as f32;
    let ref_mean = rf.iter().copied().sum::<Vec3>() / n;
    let var_mean = var.iter().copied().sum::<Vec3>() / (n * n);
    for c in 0..3 {
        let se = var_mean[c].sqrt() / ref_mean[c];
        let dev = (r.mean_ratio[c] - 1.0).abs();
        assert!(
            dev.is_finite() && se.is_finite() && dev <= 0.01 + 3.0 * se,
            "{scene}: image mean ratio {} (channel {c}: relative standard error {se})",
            r.mean_ratio
        );
    }
}
