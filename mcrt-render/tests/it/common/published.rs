//! The render-and-compare check of the published-style scenes ([`render_and_compare`], which
//! `published_compat.rs`, `published_instancing.rs`, `published_shading.rs` give their own
//! settings; [`check`] for `published_lights.rs` and `published_maps.rs`): a scene under `tests/data/published/DIR/` rendered at [`SPP`]
//! with lights sampled by area, against its Mitsuba reference at [`REFERENCE_SPP`]. No NaN
//! or infinite pixel; a z-test on [`BLOCK`]² block means (blocks brighter than 5% of the
//! image mean) with our per-pixel variance plus the reference's (ours × SPP/REFERENCE_SPP),
//! Šidák-corrected over blocks and channels to the suite's per-test α (one test of the shared
//! budget, `tests/it/common/suite.rs`: 2.513·10⁻⁵), each block allowed
//! [`ALLOWANCE`] beyond the noise; the image mean within 1% of the reference plus 3
//! standard errors. Fixed seed.

use mcrt::glam::Vec3;
use mcrt_render::description::SceneDescription;
use mcrt_render::film::{compare_blocks, read_exr, BlockReport};
use mcrt_render::render::{RenderOptions, RenderOutput, Renderer, ShapeSampling};
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
    let c = Comparison {
        min_blocks,
        ..Comparison::new(scene, data(dir, reference), SPP, REFERENCE_SPP, 2024)
    };
    render_and_compare(&desc, &c);
}

/// The block z-test alone of a render `out` against `reference` (rendered at
/// `reference_spp`; its variance taken as ours × `spp` / `reference_spp`), 16×16 blocks
/// brighter than 5% of the mean, at least `min_blocks`, at the suite's per-test level: no
/// non-finite sample or pixel, every block within the critical |z|.
pub fn assert_blocks_match(
    what: &str,
    out: &RenderOutput,
    (spp, reference_spp): (u32, u32),
    reference: &[Vec3],
    min_blocks: usize,
) -> BlockReport {
    assert_eq!(out.nonfinite_samples, 0, "{what}: non-finite samples");
    let (w, h) = (out.film.width(), out.film.height());
    let img = out.image();
    let var = out.film.variance();
    let scale = spp as f32 / reference_spp as f32;
    let ref_var: Vec<Vec3> = var.iter().map(|v| *v * scale).collect();
    let alpha = super::per_test_alpha();
    let r = compare_blocks(&img, &var, reference, Some(&ref_var), w, h, 16, 0.05, alpha);
    println!("{what}: {r:?}");
    assert_eq!(r.non_finite, 0, "{what}: NaN or infinite pixels");
    assert!(
        r.blocks >= min_blocks,
        "{what}: only {} blocks compared",
        r.blocks
    );
    assert!(
        r.z_test_passes(),
        "{what}: worst |z| {:.2} > {:.2}",
        r.worst_z,
        r.z_critical
    );
    r
}

/// One render compared with a Mitsuba reference: what to render and how to judge it.
pub struct Comparison<'a> {
    /// The name in messages.
    pub name: &'a str,
    /// The render's options (spp, seed, light sampling, ...).
    pub opts: RenderOptions,
    /// The reference EXR.
    pub reference: PathBuf,
    /// Its samples per pixel (its per-pixel variance is taken as ours × spp / this).
    pub reference_spp: u32,
    /// Side of the compared blocks, in pixels.
    pub block: u32,
    /// Bright blocks that must at least be compared.
    pub min_blocks: usize,
    /// Family-wise level of the block z-test over blocks and channels (the suite's
    /// per-test level, `tests/it/common/suite.rs`).
    pub alpha: f64,
    /// Relative difference a block may have beyond the noise (0: none).
    pub allowance: f64,
}

impl<'a> Comparison<'a> {
    /// `spp` samples with lights sampled by area (as Mitsuba samples them, so the
    /// reference's variance is ours scaled), seed `seed`; [`BLOCK`]² blocks, at least 12,
    /// the suite's per-test α (`tests/it/common/suite.rs`), [`ALLOWANCE`].
    pub fn new(name: &'a str, reference: PathBuf, spp: u32, reference_spp: u32, seed: u64) -> Self {
        Self {
            name,
            opts: RenderOptions {
                spp: Some(spp),
                seed: Some(seed),
                light_sampling: ShapeSampling::Area,
                ..RenderOptions::default()
            },
            reference,
            reference_spp,
            block: BLOCK,
            min_blocks: 12,
            alpha: super::per_test_alpha(),
            allowance: ALLOWANCE,
        }
    }
}

/// Renders `desc` as `c` says and asserts: no non-finite sample or pixel, the reference's
/// size, at least `c.min_blocks` bright blocks (brighter than 5% of the image mean), every
/// block within the z-test's critical value (beyond `c.allowance`), and the image mean
/// within 1% plus 3 standard errors of the reference's. Returns the block report.
pub fn render_and_compare(desc: &SceneDescription, c: &Comparison) -> BlockReport {
    let name = c.name;
    let out = Renderer::new(desc, &c.opts)
        .expect("scene builds")
        .render(&|_, _| {}, &AtomicBool::new(false));
    assert_eq!(out.nonfinite_samples, 0, "{name}: non-finite samples");
    let (w, h) = (out.film.width(), out.film.height());
    let (rw, rh, rf) = read_exr(&c.reference).expect("reference reads");
    assert_eq!((w, h), (rw, rh), "{name}: size differs from the reference");
    let img = out.image();
    let var = out.film.variance();
    let spp = c.opts.spp.expect("a comparison names its spp");
    let scale = spp as f32 / c.reference_spp as f32;
    let ref_var: Vec<Vec3> = var.iter().map(|v| *v * scale).collect();
    let (block, alpha) = (c.block, c.alpha);
    let r = compare_blocks(&img, &var, &rf, Some(&ref_var), w, h, block, 0.05, alpha);
    assert_eq!(r.non_finite, 0, "{name}: NaN or infinite pixels");
    assert!(
        r.blocks >= c.min_blocks,
        "{name}: only {} blocks compared",
        r.blocks
    );
    let worst_z = if c.allowance > 0.0 {
        super::blocks::worst_z_beyond(&img, &var, &rf, &ref_var, w, h, block, c.allowance)
    } else {
        r.worst_z
    };
    println!(
        "{name}: {} blocks, worst |z| beyond {}% {worst_z:.2} (critical {:.2}), worst block \
         {:.1}%, mean ratio {}",
        r.blocks,
        100.0 * c.allowance,
        r.z_critical,
        100.0 * r.worst_relative,
        r.mean_ratio
    );
    assert!(
        worst_z.is_finite() && worst_z <= r.z_critical,
        "{name}: block z-test fails: worst |z| {worst_z:.2} > {:.2}",
        r.z_critical
    );
    let n = img.len() as f32;
    let ref_mean = rf.iter().copied().sum::<Vec3>() / n;
    let var_mean = var.iter().copied().sum::<Vec3>() / (n * n);
    for ch in 0..3 {
        let se = var_mean[ch].sqrt() / ref_mean[ch];
        let dev = (r.mean_ratio[ch] - 1.0).abs();
        assert!(
            dev.is_finite() && se.is_finite() && dev <= 0.01 + 3.0 * se,
            "{name}: image mean ratio {} (channel {ch}: relative standard error {se})",
            r.mean_ratio
        );
    }
    r
}
