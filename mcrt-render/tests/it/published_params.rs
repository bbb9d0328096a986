//! Issue 24's worked example: `hide_emitters` on `guided` (one entry in its list of
//! definitions, `param_defs/integrator.rs`, and its use in `render/estimator.rs`).
//!
//! - The loader reads it (it was an unknown parameter of `guided` before).
//! - `tests/data/published/integrators/hide-emitters.xml` (the Cornell box under a sky,
//!   64×64) with its `path` replaced by `guided`, against Mitsuba 3.9.1's image of the file
//!   (its `path` with `hide_emitters`, 16384 spp; the guided path tracer's image is the path
//!   tracer's up to noise): the sky's pixels exactly black (they are bright when the
//!   parameter is not honoured), and a z-test on 16×16 block means with the render's own
//!   per-pixel variance plus the reference's (ours scaled by the final pass's spp / 16384), as
//!   `tests/it/published_integrators.rs` does, at the suite's per-test level (Šidák over the
//!   suite's budget, `tests/it/common/suite.rs`). One statistical test. Fixed seed.

use crate::common;

use common::published::{assert_blocks_match, Comparison};
use mcrt::glam::Vec3;
use mcrt_render::description::{IntegratorDesc, SceneDescription};
use mcrt_render::film::read_exr;
use mcrt_render::render::Renderer;
use std::path::PathBuf;
use std::sync::atomic::AtomicBool;

fn scene_file() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/published/integrators/hide-emitters.xml")
}

/// `hide-emitters.xml` with its integrator element replaced by `integrator`.
fn with_integrator(integrator: &str) -> SceneDescription {
    let path = scene_file();
    let xml = std::fs::read_to_string(&path).expect("scene reads");
    let (start, end) = (
        xml.find("<integrator")
            .expect("the scene has an integrator"),
        xml.find("</integrator>").expect("closed") + "</integrator>".len(),
    );
    let xml = format!("{}{integrator}{}", &xml[..start], &xml[end..]);
    mcrt_render::loader::parse_scene(&xml, Some(&path), &[]).expect("scene parses")
}

#[test]
fn guided_reads_hide_emitters() {
    let hidden = with_integrator(
        r#"<integrator type="guided"><boolean name="hide_emitters" value="true"/></integrator>"#,
    );
    match *hidden.integrator {
        IntegratorDesc::Guided(p) => assert!(p.hide_emitters),
        other => panic!("{other:?}"),
    }
    let shown = with_integrator(r#"<integrator type="guided"/>"#);
    assert!(!shown.integrator.hide_emitters());
}

#[test]
fn guided_hides_emitters_as_mitsubas_path_does() {
    // Guided to the end (`min_gain` 0), and with the default `min_gain`, under which this
    // small image's guide promises too little after three passes and the rest is path
    // traced: both images combine their passes into the reference's.
    for (min_gain, stops) in [("0", false), ("1.6", true)] {
        guided_hides_emitters_with(min_gain, stops);
    }
}

fn guided_hides_emitters_with(min_gain: &str, stops: bool) {
    let desc = with_integrator(&format!(
        r#"<integrator type="guided"><boolean name="hide_emitters" value="true"/><float name="min_gain" value="{min_gain}"/></integrator>"#
    ));
    // The options of the reference comparisons (64 spp, lights by area, seed 2024).
    let c = Comparison::new(
        "guided, hide_emitters",
        scene_file().with_extension("exr"),
        64,
        16384,
        2024,
    );
    let out = Renderer::new(&desc, &c.opts)
        .expect("scene builds")
        .render(&|_, _| {}, &AtomicBool::new(false));
    let g = out.guiding.expect("guided reports its training");
    assert!(g.passes >= 2 && g.final_spp >= 16, "{g:?}");
    assert_eq!(g.unguided_final.is_some(), stops, "{g:?}");
    assert_eq!(out.nonfinite_samples, 0, "non-finite samples");
    let (rw, rh, reference) = read_exr(&c.reference).expect("reference reads");
    let (w, h) = (out.film.width(), out.film.height());
    assert_eq!((w, h), (rw, rh));
    let img = out.image();
    // Where Mitsuba sees only the hidden sky, so do we: exactly black.
    let sky: Vec<usize> = (0..reference.len())
        .filter(|&i| reference[i] == Vec3::ZERO)
        .collect();
    assert!(sky.len() > 100, "the view shows the sky");
    assert!(sky.iter().all(|&i| img[i] == Vec3::ZERO));
    // The variance is the combined image's; the reference's is taken as ours scaled by the
    // final pass's share of the reference's samples (conservative: the image holds more).
    assert_blocks_match(c.name, &out, (g.final_spp, c.reference_spp), &reference, 4);
}
