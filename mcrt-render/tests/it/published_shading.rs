//! The features behind the shading frame (issue 25) against Mitsuba 3's references, on small
//! scenes in `tests/data/published/shading/` (references: `tests/data/REFERENCES.md`,
//! "Shading frame"): anisotropic rough conductors on a sphere and a turned rectangle, whose
//! highlights follow Mitsuba's shading tangent `dp/du`.
//!
//! Per scene: no non-finite sample or pixel; a z-test on 16×16 block means with the render's
//! own per-pixel variance plus the reference's (ours × spp / reference spp), Šidák-corrected
//! over blocks and channels to the suite's per-test α (one test of `tests/it/common/suite.rs`'s budget per scene); and
//! the image mean within 1% of the reference's plus 3 standard errors. Fixed seed, as
//! `tests/it/reference_match.rs` does.

use crate::common;

use common::published::{data, render_and_compare, Comparison};

/// Renders `scene` at `spp` and compares it with `reference` (rendered at `reference_spp`).
fn check(scene: &str, reference: &str, spp: u32, reference_spp: u32) {
    let desc = mcrt_render::loader::load_scene(&data("shading", scene), &[]).expect("scene loads");
    let reference = data("shading", reference);
    let c = Comparison {
        allowance: 0.0,
        ..Comparison::new(scene, reference, spp, reference_spp, 2024)
    };
    render_and_compare(&desc, &c);
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
