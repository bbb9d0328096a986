//! The features behind the shading frame (issue 25) against Mitsuba 3's references, on small
//! scenes in `tests/data/published/shading/` (references: `tests/data/REFERENCES.md`,
//! "Shading frame"): anisotropic rough conductors on a sphere and a turned rectangle, whose
//! highlights follow Mitsuba's shading tangent `dp/du`.
//!
//! Per scene: no non-finite sample or pixel; a z-test on 16×16 block means with the render's
//! own per-pixel variance plus the reference's (ours × spp / reference spp), Šidák-corrected
//! over blocks and channels to a family-wise α = 0.01 (one statistical test per scene); and
//! the image mean within 1% of the reference's plus 3 standard errors. Fixed seed, as
//! `tests/reference_match.rs` does.

use mcrt::glam::Vec3;
use mcrt_render::film::{compare_blocks, read_exr};
use mcrt_render::render::{RenderOptions, Renderer, ShapeSampling};
use std::path::PathBuf;
use std::sync::atomic::AtomicBool;

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/published/shading")
        .join(name)
}

/// Renders `scene` at `spp` and compares it with `reference` (rendered at `reference_spp`).
fn check(scene: &str, reference: &str, spp: u32, reference_spp: u32) {
    let desc = mcrt_render::loader::load_scene(&data(scene), &[]).expect("scene loads");
    let opts = RenderOptions {
        spp: Some(spp),
        seed: Some(2024),
        light_sampling: ShapeSampling::Area,
        ..RenderOptions::default()
    };
    let out = Renderer::new(&desc, &opts)
        .expect("scene builds")
        .render(&|_, _| {}, &AtomicBool::new(false));
    assert_eq!(out.nonfinite_samples, 0, "{scene}: non-finite samples");
    let (w, h) = (out.film.width(), out.film.height());
    let (rw, rh, rf) = read_exr(&data(reference)).expect("reference reads");
    assert_eq!((w, h), (rw, rh), "{scene}: size differs from the reference");
    let img = out.image();
    let var = out.film.variance();
    let scale = spp as f32 / reference_spp as f32;
    let ref_var: Vec<Vec3> = var.iter().map(|v| *v * scale).collect();
    let r = compare_blocks(&img, &var, &rf, Some(&ref_var), w, h, 16, 0.05, 0.01);
    assert_eq!(r.non_finite, 0, "{scene}: NaN or infinite pixels");
    assert!(r.blocks >= 12, "{scene}: only {} blocks compared", r.blocks);
    assert!(
        r.worst_z.is_finite() && r.worst_z <= r.z_critical,
        "{scene}: worst block z {:.2} > {:.2} (worst relative {:.3})",
        r.worst_z,
        r.z_critical,
        r.worst_relative
    );
    let n = img.len() as f32;
    let ref_mean = rf.iter().copied().sum::<Vec3>() / n;
    let var_mean = var.iter().copied().sum::<Vec3>() / (n * n);
    for c in 0..3 {
        let (ratio, se) = (r.mean_ratio[c], var_mean[c].sqrt() / ref_mean[c]);
        assert!(
            ratio.is_finite() && se.is_finite() && (ratio - 1.0).abs() <= 0.01 + 3.0 * se,
            "{scene}: channel {c} mean ratio {ratio} (se {se})"
        );
    }
}

#[test]
fn anisotropic_rough_conductors_follow_mitsubas_tangent() {
    check(
        "anisotropic-conductor.xml",
        "anisotropic-conductor.exr",
        128,
        4096,
    );
}
