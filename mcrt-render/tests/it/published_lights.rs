//! Issue 25's light and shape features against Mitsuba 3.9.1's references
//! (`tests/data/published/lights/*.exr`, 4096 spp, box filter; `tests/data/REFERENCES.md`,
//! "Published-scene features: lights"): the `cylinder` shape, Radiance RGBE (`.hdr`)
//! images as environment map and bitmap, textured `area` emission, the textured `spot` and
//! the `projector`. Each scene is 96×96, rendered here at 64 spp with lights sampled by
//! area as Mitsuba samples them (a few seconds of CPU each).
//!
//! As `tests/it/reference_match.rs` does: no NaN or infinite pixel; a z-test on 16×16 block
//! means (blocks brighter than 5% of the image mean) with our per-pixel variance plus the
//! reference's (ours × spp / 4096), Šidák-corrected over blocks and channels to the
//! suite's per-test α (`tests/it/common/suite.rs`), each block allowed 1% beyond the noise (the textures' and
//! the `.hdr` sun's small bright features skew block means at 64 spp, as in
//! `textures_match_mitsuba`); and the image mean within 1% of the reference plus 3
//! standard errors. Fixed seed. One statistical test per scene.

use crate::common;

use common::published;

/// Renders `scene` and compares it with `reference` (`common/published.rs`); `min_blocks`
/// bright blocks at least must be compared.
fn check(scene: &str, reference: &str, min_blocks: usize) {
    published::check("lights", scene, reference, min_blocks);
}

/// `cylinder`: a tilted checkerboard tube given by `p0`, `p1`, `radius` and a `to_world`,
/// an emitting thin cylinder scaled along its axis, a flipped-normal tube.
#[test]
fn cylinders_match_mitsuba() {
    check("cylinder.xml", "cylinder.exr", 20);
}

/// Radiance RGBE files: an `envmap` (rotated, scaled, with a sun) and a `bitmap` floor.
#[test]
fn rgbe_envmap_and_bitmap_match_mitsuba() {
    check("hdr.xml", "hdr.exr", 30);
}

/// Textured `area` emission: a checkerboard `radiance` on a rectangle and a PNG (through
/// `<ref name="radiance">`) on a cube, seen directly and lighting the floor.
#[test]
fn textured_area_emission_matches_mitsuba() {
    check("textured-area.xml", "textured-area.exr", 20);
}

/// A `spot` with a `texture` and a `projector` (its image, `scale`, `fov` along `y`).
#[test]
fn textured_spot_and_projector_match_mitsuba() {
    check("spot-projector.xml", "spot-projector.exr", 20);
}
